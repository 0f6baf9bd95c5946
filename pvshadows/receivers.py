"""The shader edits and uniforms of every actor of one renderer, kept up to date cheaply.

Each frame the receivers need the edits of the lights that shadow them and
the uniforms those lights' techniques return; bystanders need only the probe
switch. Both are sent to VTK only where they changed: replacements are
rebuilt for an actor only when its state or the lights' shadings changed
(and built once per distinct set of lights, not once per actor), and a
uniform whose value did not change is not set again. So a frame where only
the camera moved sets the camera-dependent uniforms and nothing else, and a
frame where nothing changed makes no VTK call here at all.
"""

from __future__ import annotations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.shading import (
    PROBE_UNIFORM,
    LightShading,
    ShaderEdits,
    bystander_replacements,
    receiver_replacements,
    uniform_setter,
)
from pvshadows.snapshot import ActorState, Snapshot

#: The state kept for a bystander that receives as points or lines (no triangles).
_LIT_POINTS = "lit points"


def _same(a: object, b: object) -> bool:
    if a is b:
        return True
    if isinstance(a, np.ndarray) and isinstance(b, np.ndarray):
        return a.shape == b.shape and bool((a == b).all())
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray) or type(a) is not type(b):
        return False
    return bool(a == b)


def _signature(pbr: bool, lights: list[LightShading]) -> tuple:
    return (
        pbr,
        tuple(
            (
                light.vtk_index,
                light.visibility,
                tuple(sorted(light.samplers.items())),
                light.needs,
                light.sources,
                light.defines,
            )
            for light in lights
        ),
    )


class ReceiverEdits:
    """Owns the :class:`~pvshadows.shading.ShaderEdits` of one renderer's actors.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.receivers import ReceiverEdits
    >>> from pvshadows.shading import PROBE_UNIFORM, LightShading
    >>> from pvshadows.snapshot import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> _ = pl.add_mesh(pv.Sphere())
    >>> snapshot = SceneReader(lambda actor: "an actor").read(pl.renderer)
    >>> edits = ReceiverEdits()
    >>> edits.update(snapshot, [LightShading(0, "1.0")], {PROBE_UNIFORM: -1, "pvsLevel": 0.5})
    >>> edits.update(snapshot, [LightShading(0, "1.0")], {PROBE_UNIFORM: -1, "pvsLevel": 0.5})
    >>> edits.uniform_calls
    2
    """

    def __init__(self) -> None:
        self._edits: dict[str, ShaderEdits] = {}
        self._uniforms: dict[str, vtk.vtkUniforms] = {}
        self._states: dict[str, ActorState | str | None] = {}
        self._replacements: dict[tuple, list[tuple[str, str]]] = {}
        self._bystander = bystander_replacements()
        self._snapshot: Snapshot | None = None
        self._shadings: list[LightShading] = []
        self._values: dict[str, object] = {}
        self._receiving: list[vtk.vtkUniforms] = []
        self._standing: list[vtk.vtkUniforms] = []
        #: Uniform values handed to VTK since this object was made (one per actor and uniform).
        self.uniform_calls = 0
        #: Times an actor's replacements were worked out again.
        self.edited = 0

    def update(
        self,
        snapshot: Snapshot,
        shadings: list[LightShading],
        uniforms: dict[str, object],
        light_space: list[LightShading] | None = None,
        lit_points: set[str] | None = None,
    ) -> None:
        """Bring every actor's edits and uniforms to this frame's.

        Parameters
        ----------
        snapshot : Snapshot
            This frame's actors.
        shadings : list of LightShading
            How receivers read each shadowed light.
        uniforms : dict
            Uniform values every receiver gets (including the probe switch,
            which bystanders get too).
        light_space : list of LightShading, optional
            The shadings of lights whose lookups work at any fragment
            (shadow maps): points and lines without triangles read these.
        lit_points : set of str, optional
            Keys of the bystanders VTK lights without triangles (points as
            spheres, lines as tubes): they receive ``light_space``.
        """
        light_space = light_space or []
        lit_points = lit_points or set()
        same_lights = shadings == self._shadings
        if self._values.keys() == uniforms.keys():
            changed = {n: v for n, v in uniforms.items() if not _same(self._values[n], v)}
        else:
            changed = None
        if snapshot is self._snapshot and same_lights and changed == {}:
            return
        setters = [uniform_setter(n, v) for n, v in (changed or {}).items()]
        probe = [s for n, s in zip(changed or {}, setters, strict=True) if n == PROBE_UNIFORM]
        self._values = dict(uniforms)
        if snapshot is self._snapshot and same_lights and changed is not None:
            # Only values changed (the camera moved, say): set just those, on every actor.
            for targets, chosen in ((self._receiving, setters), (self._standing, probe)):
                for uniforms_of_actor in targets:
                    for setter in chosen:
                        setter(uniforms_of_actor)
                self.uniform_calls += len(targets) * len(chosen)
            return
        touched = set()
        for state in snapshot.receivers:
            key = state.key()[0]
            touched.add(key)
            known = key in self._states and self._states[key] is not None
            if not (known and same_lights and self._states[key] is state):
                lights = [s.for_actor(key) for s in shadings]
                self._edits_of(state.actor, key).apply(self._replacements_for(state.actor, lights))
                self.edited += 1
            self._send(state.actor, key, known and changed is not None, setters, uniforms)
            self._states[key] = state
        for actor in snapshot.bystanders:
            key = actor.__this__
            touched.add(key)
            if key in lit_points:
                known = self._states.get(key) == _LIT_POINTS
                if not (known and same_lights):
                    lights = [s.for_actor(key) for s in light_space]
                    replacements = receiver_replacements(actor, lights, triangles=False)
                    self._edits_of(actor, key).apply(replacements)
                    self.edited += 1
                self._send(actor, key, known and changed is not None, setters, uniforms)
                self._states[key] = _LIT_POINTS
                continue
            known = key in self._states and self._states[key] is None
            if not known:
                self._edits_of(actor, key).apply(self._bystander)
            probe_only = {PROBE_UNIFORM: uniforms[PROBE_UNIFORM]}
            self._send(actor, key, known and changed is not None, probe, probe_only)
            self._states[key] = None
        for key in set(self._edits) - touched:
            self._forget(key)
        self._snapshot, self._shadings = snapshot, list(shadings)
        self._receiving = [self._uniforms[s.key()[0]] for s in snapshot.receivers]
        self._receiving += [self._uniforms[key] for key in lit_points]
        self._standing = [
            self._uniforms[a.__this__] for a in snapshot.bystanders if a.__this__ not in lit_points
        ]

    def _send(
        self, actor: vtk.vtkActor, key: str, only_changed: bool, setters: list, values: dict
    ) -> None:
        if only_changed:
            uniforms = self._uniforms[key]
            for setter in setters:
                setter(uniforms)
            self.uniform_calls += len(setters)
            return
        self._edits_of(actor, key).set_uniforms(values)
        self._uniforms[key] = actor.GetShaderProperty().GetFragmentCustomUniforms()
        self.uniform_calls += len(values)

    def _replacements_for(
        self, actor: vtk.vtkActor, lights: list[LightShading]
    ) -> list[tuple[str, str]]:
        pbr = actor.GetProperty().GetInterpolation() == vtk.VTK_PBR
        signature = _signature(pbr, lights)
        if signature not in self._replacements:
            self._replacements[signature] = receiver_replacements(actor, lights)
        return self._replacements[signature]

    def _edits_of(self, actor: vtk.vtkActor, key: str) -> ShaderEdits:
        if key not in self._edits:
            self._edits[key] = ShaderEdits(actor)
        return self._edits[key]

    def _forget(self, key: str) -> None:
        self._edits.pop(key).remove()
        self._uniforms.pop(key, None)
        self._states.pop(key, None)

    def clear(self) -> list[str]:
        """Take every edit and uniform off every actor; return what could not be taken off.

        Every actor is tried, even after one fails, so a fault leaves as few
        edited shaders behind as it can.
        """
        troubles = []
        for key in list(self._edits):
            edits = self._edits[key]
            try:
                self._forget(key)
            except Exception as error:
                troubles.append(
                    f"removing the edits of {edits.actor.GetClassName()}: "
                    f"{type(error).__name__}: {error}"
                )
            self._edits.pop(key, None)
            self._uniforms.pop(key, None)
            self._states.pop(key, None)
        self._snapshot, self._shadings, self._values = None, [], {}
        self._receiving, self._standing = [], []
        self._replacements.clear()
        return troubles
