"""The shader edits and uniforms of every actor of one renderer, kept up to date cheaply.

Each frame the receivers need the edits of the lights that shadow them and
the uniforms those lights' techniques return (packed into the arrays of each
group of lights, :func:`pvshadows.shaders.shading.receiver_uniforms`): only
their samplers, since everything else they read is in the frame's uniform
block. The samplers read texture units reserved for them
(:class:`~pvshadows.gl.sampler_units.SamplerUnits`), written into the
receivers' source where the context allows: then receivers have no custom
uniform at all, which VTK would set again at every draw. Bystanders need
only the edit that blacks them out in probe frames, and no uniform. Both are
sent to VTK only where they changed: replacements and packed uniforms are
worked out once per distinct set of lights an actor shows (its *signature*),
not once per actor; replacements are rebuilt for an actor only when its
state, its signature or the lights' shadings changed; and a uniform whose
value did not change is not set again.
So a frame where only the camera or a light moved, or nothing changed, makes
no VTK call here at all.

A receiver whose shader variant refused the edits, or in whose compiled
program some edits did not land, tells this object through its
:class:`~pvshadows.shaders.landing.LandingCheck` (no per-frame watch over every
receiver): the next frame applies its edits again (a refused variant is then
left as VTK built it) and :meth:`ReceiverEdits.problems` names it.
"""

from __future__ import annotations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.sampler_units import SamplerUnits
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import Snapshot
from pvshadows.shaders.landing_views import WaitingChecks, Watchers
from pvshadows.shaders.shading import (
    LightShading,
    ShaderEdits,
    bystander_replacements,
    receiver_replacements,
    receiver_uniforms,
    uniform_setter,
)

#: The state kept for a bystander that receives as points or lines (no triangles).
_LIT_POINTS = "lit points"


def _same_values(a: dict[str, object], b: dict[str, object]) -> bool:
    if a.keys() != b.keys():
        return False
    # a loop, not all() over a generator: this runs every frame
    for name, value in a.items():
        if value is not b[name] and not _same(value, b[name]):
            return False
    return True


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
    """Owns the :class:`~pvshadows.shaders.shading.ShaderEdits` of one renderer's actors.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.shaders.edits import ReceiverEdits
    >>> from pvshadows.shaders.shading import LightShading
    >>> from pvshadows.scene.reader import SceneReader
    >>> pl = pv.Plotter(off_screen=True)
    >>> _ = pl.add_mesh(pv.Sphere())
    >>> snapshot = SceneReader(lambda actor: "an actor").read(pl.renderer)
    >>> edits = ReceiverEdits()
    >>> edits.update(snapshot, [LightShading(0, "1.0")], {"pvsMask0": 3})
    >>> edits.update(snapshot, [LightShading(0, "1.0")], {"pvsMask0": 3})
    >>> edits.uniform_calls
    1
    """

    def __init__(self) -> None:
        #: The units samplers read; ``None``: the uniforms' values are units already.
        self.units: SamplerUnits | None = None
        self._edits: dict[str, ShaderEdits] = {}
        self._uniforms: dict[str, vtk.vtkUniforms] = {}
        self._states: dict[str, ActorState | str | None] = {}
        self._signature_of: dict[str, tuple] = {}
        self._lights_of: dict[tuple, list[LightShading]] = {}
        self._replacements: dict[tuple, list[tuple[str, str]]] = {}
        self._sent: dict[tuple, dict[str, object]] = {}
        self._members: dict[tuple, list[vtk.vtkUniforms]] = {}
        self._bystander = bystander_replacements()
        self._snapshot: Snapshot | None = None
        self._shadings: list[LightShading] = []
        self._lit_points: set[str] = set()
        self._flagged: set[str] = set()
        #: Receivers whose programs cannot be watched yet (no OpenGL mapper before a first draw).
        self.waiting = WaitingChecks()
        #: The receiver whose mapper is watched for each shader variant and edits.
        self._watchers = Watchers()
        #: The lights' uniform values of the last frame (nothing to send when they are the same).
        self._given: dict[str, object] = {}
        self._problems: dict[str, str] = {}
        #: Uniform values handed to VTK since this object was made (one per actor and uniform).
        self.uniform_calls = 0
        #: Times an actor's replacements were worked out again.
        self.edited = 0
        #: Actors brought up to date one by one (new or changed, or every actor when
        #: the lights' lookups changed); the others take changed values by kind.
        self.received = 0

    def update(
        self,
        snapshot: Snapshot,
        shadings: list[LightShading],
        uniforms: dict[str, object],
        light_space: list[LightShading] | None = None,
        lit_points: set[str] | None = None,
        planes: np.ndarray | None = None,
    ) -> None:
        """Bring every actor's edits and uniforms to this frame's.

        Parameters
        ----------
        snapshot : Snapshot
            This frame's actors.
        shadings : list of LightShading
            How receivers read each shadowed light.
        uniforms : dict
            Every light's uniform values by name that receivers read
            themselves: their samplers' textures
            (:class:`~pvshadows.gl.sampler_units.TextureBinding`, or units
            where :attr:`units` is ``None``).
        light_space : list of LightShading, optional
            The shadings of lights whose lookups work at any fragment
            (shadow maps): points and lines without triangles read these.
        lit_points : set of str, optional
            Keys of the bystanders VTK lights without triangles (points as
            spheres, lines as tubes): they receive ``light_space``.
        planes : numpy.ndarray, optional
            ``(6, 4)`` the view's frustum planes: a receiver whose program is
            not watched yet is tried again only where the view meets it
            (every frame when not given).
        """
        light_space = light_space or []
        lit_points = lit_points or set()
        self._watchers.hand_over_unseen(planes)
        self.waiting.try_in_view(planes)
        flagged, self._flagged = self._flagged, set()
        same = (
            snapshot is self._snapshot
            and shadings == self._shadings
            and lit_points == self._lit_points
            and not flagged
        )
        values_kept = _same_values(uniforms, self._given)
        if same:
            if not values_kept:
                self._send_changed(uniforms)
                self._given = dict(uniforms)
            return
        self._given = dict(uniforms)
        # With the same lights, a receiver whose state is last frame's keeps its edits
        # and takes only the uniform values that changed, with the others of its kind:
        # a frame costs the actors that changed, not every receiver.
        lights_kept = shadings == self._shadings and lit_points == self._lit_points
        previous = self._snapshot
        if (
            lights_kept
            and not flagged
            and previous is not None
            and snapshot.parent is previous
            and snapshot.bystanders is previous.bystanders
            and self._update_replaced(snapshot, shadings, uniforms, values_kept)
        ):
            return
        fresh: dict[tuple, dict[str, object]] = {}
        touched = set()
        members: dict[tuple, list[vtk.vtkUniforms]] = {}
        kept: dict[tuple, list[vtk.vtkUniforms]] = {}
        for state in snapshot.receivers:
            key = state.key()[0]
            touched.add(key)
            if lights_kept and key not in flagged and self._states.get(key) is state:
                signature = self._signature_of[key]
                members.setdefault(signature, []).append(self._uniforms[key])
                kept.setdefault(signature, []).append(self._uniforms[key])
                continue
            lights = [s.for_actor(key) for s in shadings]
            self._receive(state.actor, key, state, lights, True, flagged, uniforms, fresh)
            members.setdefault(self._signature_of[key], []).append(self._uniforms[key])
        for signature, targets in kept.items():
            fresh[signature] = self._send_to(signature, targets, uniforms, fresh.get(signature))
        for actor in snapshot.bystanders:
            key = actor.__this__
            touched.add(key)
            if key in lit_points:
                lights = [s.for_actor(key) for s in light_space]
                self._receive(actor, key, _LIT_POINTS, lights, False, flagged, uniforms, fresh)
                members.setdefault(self._signature_of[key], []).append(self._uniforms[key])
                continue
            if not (key in self._states and self._states[key] is None) or key in flagged:
                edits = self._edits_of(actor, key)
                edits.apply(self._bystander)
                edits.set_uniforms({})
                self._uniforms.pop(key, None)
            self._states[key] = None
            self._signature_of.pop(key, None)
        for key in set(self._edits) - touched:
            self._forget(key)
        self._sent.update(fresh)
        for signature in set(self._sent) - set(members):
            self._sent.pop(signature)
            self._lights_of.pop(signature, None)
        self._members = members
        self._snapshot, self._shadings, self._lit_points = snapshot, list(shadings), lit_points
        if self.units is not None:
            self.units.keep_marked()

    def _update_replaced(
        self,
        snapshot: Snapshot,
        shadings: list[LightShading],
        uniforms: dict[str, object],
        values_kept: bool,
    ) -> bool:
        """Bring only the receivers replaced since the last snapshot up to date.

        Every other receiver keeps its edits and takes the changed values by
        kind (none when ``values_kept``: the uniforms are last frame's).
        Returns ``False``, before touching that receiver, when one of them
        would change kind (then the whole frame's path runs).
        """
        fresh: dict[tuple, dict[str, object]] = {}
        for row in snapshot.replaced:
            state = snapshot.actors[row]
            if not state.receiver:
                continue
            key = state.key()[0]
            lights = [s.for_actor(key) for s in shadings]
            pbr = state.actor.GetProperty().GetInterpolation() == vtk.VTK_PBR
            if self._signature_of.get(key) != (True, *_signature(pbr, lights)):
                return False
            if self._moved_only(key, state):
                # its edits and its place among its kind's receivers are as they were
                self._states[key] = state
                continue
            self._receive(state.actor, key, state, lights, True, set(), uniforms, fresh)
        if fresh or not values_kept:
            for signature, targets in self._members.items():
                fresh[signature] = self._send_to(signature, targets, uniforms, fresh.get(signature))
            self._sent.update(fresh)
        self._snapshot = snapshot
        return True

    def _moved_only(self, key: str, state: ActorState) -> bool:
        """Whether a receiver differs from the state its edits were made for only in its place.

        Its edits follow its kind (its signature) alone, so an actor that
        moved, its triangles and style as they were, keeps them; one whose
        edits wait for a program to check is brought up to date in full (the
        wait follows its bounds).
        """
        before = self._states.get(key)
        edits = self._edits.get(key)
        return (
            isinstance(before, ActorState)
            and before.actor is state.actor
            and before.triangles is state.triangles
            and before.faces_drawn == state.faces_drawn
            and edits is not None
            and edits.check.attached
        )

    def _receive(
        self,
        actor: vtk.vtkActor,
        key: str,
        state: ActorState | str,
        lights: list[LightShading],
        triangles: bool,
        flagged: set[str],
        uniforms: dict[str, object],
        fresh: dict[tuple, dict[str, object]],
    ) -> None:
        """Bring one receiver's edits and uniforms up to date (a full frame's path)."""
        self.received += 1
        pbr = actor.GetProperty().GetInterpolation() == vtk.VTK_PBR
        signature = (triangles, *_signature(pbr, lights))
        packed = None
        if signature not in fresh:
            self._lights_of[signature] = lights
            packed = receiver_uniforms(lights, uniforms)
            fresh[signature] = self._values(packed)
        values = fresh[signature]
        same_edits = (
            self._states.get(key) is state
            and self._signature_of.get(key) == signature
            and key not in flagged
        )
        edits = self._edits_of(actor, key)
        if not same_edits:
            if packed is None:
                packed = receiver_uniforms(lights, uniforms)
            edits.apply(self._replacements_for(actor, signature, lights, packed))
            if not edits.check.attached:  # ``apply`` tried to attach it just now
                bounds = state.bounds if isinstance(state, ActorState) else None
                self.waiting.wait(key, edits.check, bounds)
            self.edited += 1
            self._note_problem(key)
        previous = self._sent.get(signature) if self._signature_of.get(key) == signature else None
        if key in self._uniforms and previous is not None and previous.keys() == values.keys():
            changed = [n for n, v in values.items() if not _same(previous[n], v)]
            for name in changed:
                uniform_setter(name, values[name])(self._uniforms[key])
            self.uniform_calls += len(changed)
        else:
            edits.set_uniforms(values)
            self._uniforms[key] = actor.GetShaderProperty().GetFragmentCustomUniforms()
            self.uniform_calls += len(values)
        self._states[key] = state
        self._signature_of[key] = signature

    def _send_changed(self, uniforms: dict[str, object]) -> None:
        """Set only the uniform values that changed, once converted per signature."""
        for signature, targets in self._members.items():
            self._sent[signature] = self._send_to(signature, targets, uniforms)

    def _send_to(
        self,
        signature: tuple,
        targets: list[vtk.vtkUniforms],
        uniforms: dict[str, object],
        values: dict[str, object] | None = None,
    ) -> dict[str, object]:
        """Give receivers of one signature the values that changed since last sent; return all.

        ``values`` are the signature's values this frame when already converted.
        """
        if values is None:
            values = self._values(receiver_uniforms(self._lights_of[signature], uniforms))
        previous = self._sent[signature]
        if previous.keys() == values.keys():
            changed = [n for n, v in values.items() if not _same(previous[n], v)]
        else:
            changed = list(values)
        if not changed:  # the common case (an actor moved): no walk over every receiver
            return values
        setters = [uniform_setter(name, values[name]) for name in changed]
        for target in targets:
            for setter in setters:
                setter(target)
        self.uniform_calls += len(targets) * len(setters)
        return values

    def _values(self, packed: dict[str, object]) -> dict:
        """Return the uniforms VTK sets on a receiver, from its :func:`receiver_uniforms`."""
        if self.units is None:
            return packed
        if self.units.binding:  # the samplers' units are in the source
            units = self.units.first_units(packed)
            return {name: value for name, value in packed.items() if name not in units}
        return self.units.units_of(packed)

    def _replacements_for(
        self,
        actor: vtk.vtkActor,
        signature: tuple,
        lights: list[LightShading],
        packed: dict[str, object],
    ) -> list[tuple[str, str]]:
        """Return the edits of a receiver of ``signature``, once per signature and units.

        ``packed`` is its :func:`receiver_uniforms`.
        """
        units = None
        if self.units is not None and self.units.binding:
            units = self.units.first_units(packed)
        key = (signature, tuple(sorted(units.items())) if units is not None else None)
        if key not in self._replacements:
            self._replacements[key] = receiver_replacements(
                actor, lights, triangles=signature[0], units=units
            )
        return self._replacements[key]

    def _edits_of(self, actor: vtk.vtkActor, key: str) -> ShaderEdits:
        if key not in self._edits:
            edits = ShaderEdits(actor, self._watchers)
            edits.check.notify = lambda: self._flagged.add(key)
            self._edits[key] = edits
        return self._edits[key]

    def of(self, key: str) -> ShaderEdits | None:
        """Return the edits kept for the actor ``key``, or ``None`` when it has none.

        Parameters
        ----------
        key : str
            The actor's :func:`pvshadows.scene.triangles.vtk_id`.

        Returns
        -------
        ShaderEdits or None
            What pvshadows put on the actor's shader property.
        """
        return self._edits.get(key)

    def _note_problem(self, key: str) -> None:
        problem = self._edits[key].problem
        if problem is None:
            self._problems.pop(key, None)
        else:
            self._problems[key] = problem

    def problems(self) -> dict[str, tuple[vtk.vtkActor, str]]:
        """Return the receivers that show fewer shadows than asked, and why.

        Returns
        -------
        dict
            Actor key to ``(actor, why)``: its shader variant refused the
            edits (drawn as VTK built it), or some edits did not land in the
            program VTK compiled.
        """
        for key in self._flagged:
            if key in self._edits:
                self._note_problem(key)
        if not self._problems:
            return {}
        return {key: (self._edits[key].actor, why) for key, why in self._problems.items()}

    def _forget(self, key: str) -> None:
        self.waiting.forget(key)
        self._problems.pop(key, None)
        self._signature_of.pop(key, None)
        self._uniforms.pop(key, None)
        self._states.pop(key, None)
        self._edits.pop(key).remove()

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
        self._snapshot, self._shadings, self._lit_points = None, [], set()
        self._members, self._sent, self._lights_of = {}, {}, {}
        self._replacements.clear()
        self._flagged.clear()
        return troubles
