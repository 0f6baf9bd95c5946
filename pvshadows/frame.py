"""Runs pvshadows inside one renderer's frames.

A renderer ``StartEvent`` observer runs before VTK draws anything: it reads
the scene, asks the planner what each light does, brings the shadow maps up
to date, binds them, and sets every receiver's shader edits and uniforms. An
``EndEvent`` observer frees the texture units and reads the passes' GPU
times into :attr:`RendererShadows.last_frame`.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable

import vtk

from pvshadows.gl.actor_buffers import ActorBuffers
from pvshadows.gl.timing import PassTimer
from pvshadows.planner import LightPlan, plan_frame
from pvshadows.report import FrameReport, LightReport
from pvshadows.scene import vtk_id
from pvshadows.settings import ShadowSettings
from pvshadows.shading import (
    PROBE_UNIFORM,
    ShaderEdits,
    bystander_replacements,
    receiver_replacements,
    receiver_uniforms,
)
from pvshadows.snapshot import SceneReader, Snapshot
from pvshadows.techniques import TECHNIQUE_CLASSES
from pvshadows.techniques.base import FrameContext, Technique


class RendererShadows:
    """Shadows for the lights and actors of one renderer.

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer.
    settings_for : callable
        Returns a light's settings, or ``None`` when it casts no shadow.
    reader : SceneReader
        Reads the actors and their roles each frame.
    """

    def __init__(
        self,
        renderer: vtk.vtkRenderer,
        settings_for: Callable[[vtk.vtkLight], ShadowSettings | None],
        reader: SceneReader,
    ) -> None:
        self.renderer = renderer
        self._settings_for = settings_for
        self._reader = reader
        self._observers = [
            renderer.AddObserver(vtk.vtkCommand.StartEvent, self._on_start),
            renderer.AddObserver(vtk.vtkCommand.EndEvent, self._on_end),
        ]
        self._edits: dict[str, ShaderEdits] = {}
        self._warned: set[tuple[str, str]] = set()
        self._window: vtk.vtkOpenGLRenderWindow | None = None
        self._timer: PassTimer | None = None
        self._buffers: ActorBuffers | None = None
        self._techniques: dict[str, Technique] = {}
        self._frame = 0
        self._active: list[Technique] = []
        self.probe_index = -1
        self.plans: list[LightPlan] = []
        self.snapshot: Snapshot | None = None
        self.last_frame = FrameReport()
        self.error: Exception | None = None
        #: Let techniques draw debug overlays (``draw_debug``) over the finished frame.
        self.show_debug = False
        self._context: FrameContext | None = None

    def technique(self, name: str) -> Technique:
        """Return the object running technique ``name`` in this renderer.

        Parameters
        ----------
        name : str
            Technique name, e.g. ``"cubemap"``.

        Returns
        -------
        Technique
            The technique's state (its maps), created on first use.
        """
        if name not in self._techniques:
            self._techniques[name] = TECHNIQUE_CLASSES[name](self._window)
        return self._techniques[name]

    def _start_gl(self) -> None:
        window = self.renderer.GetRenderWindow()
        if self._window is window:
            return
        self._window = window
        self._timer = PassTimer(window)
        self._buffers = ActorBuffers(window)
        self._techniques = {}

    def _on_start(self, renderer: vtk.vtkRenderer, event: str) -> None:
        try:
            self._run_frame()
            self.error = None
        except Exception as error:
            self.error = error
            self._clear_edits()
            warnings.warn(f"pvshadows drew this frame without shadows: {error}", stacklevel=1)

    def _run_frame(self) -> None:
        self._start_gl()
        self._frame += 1
        renderer = self.renderer
        renderer.UpdateLightsGeometryToFollowCamera()
        snapshot = self._reader.read(renderer)
        plans = plan_frame(renderer, snapshot, self._settings_for)
        context = FrameContext(
            self._window,
            renderer,
            renderer.GetActiveCamera(),
            snapshot,
            self._frame,
            self._buffers,
            self._timer,
        )
        self._context = context
        report = FrameReport()
        uniforms: dict[str, object] = {PROBE_UNIFORM: self.probe_index}
        shadings = []
        self._active = []
        for plan in plans:
            light_report = LightReport(
                plan.index, plan.kind.value, plan.technique, notes=plan.notes
            )
            report.lights.append(light_report)
            if plan.technique is None:
                continue
            technique = self.technique(plan.technique)
            light_report.passes = technique.update(plan, context)
            shadings.append(technique.shading(plan))
            uniforms.update(technique.activate(plan, context))
            if technique not in self._active:
                self._active.append(technique)
        for technique in self._techniques.values():
            technique.keep_only(plans)
        self._buffers.keep_only(snapshot.actors)
        self._apply_edits(snapshot, shadings, uniforms)
        self.plans, self.snapshot, self.last_frame = plans, snapshot, report

    def _apply_edits(self, snapshot: Snapshot, shadings: list, uniforms: dict) -> None:
        touched = set()
        for state in snapshot.receivers:
            edits = self._edits_of(state.actor)
            key = vtk_id(state.actor)
            shown = [s.for_actor(key) for s in shadings]
            edits.apply(receiver_replacements(state.actor, shown))
            edits.set_uniforms(receiver_uniforms(shown, uniforms))
            touched.add(vtk_id(state.actor))
        for actor in snapshot.bystanders:
            edits = self._edits_of(actor)
            edits.apply(bystander_replacements())
            edits.set_uniforms({PROBE_UNIFORM: self.probe_index})
            touched.add(vtk_id(actor))
        for key in set(self._edits) - touched:
            self._edits.pop(key).remove()

    def _edits_of(self, actor: vtk.vtkActor) -> ShaderEdits:
        key = vtk_id(actor)
        if key not in self._edits:
            self._edits[key] = ShaderEdits(actor)
        return self._edits[key]

    def _on_end(self, renderer: vtk.vtkRenderer, event: str) -> None:
        if self.show_debug and self.probe_index < 0 and self._context is not None:
            for technique in self._active:
                draw = getattr(technique, "draw_debug", None)
                try:
                    if draw is not None:
                        draw(self._context)
                except Exception as error:
                    warnings.warn(
                        f"pvshadows could not draw its debug overlay: {error}", stacklevel=1
                    )
        for technique in self._active:
            technique.deactivate()
        self._active = []
        if self._timer is not None:
            self._timer.collect()
        self._report_receivers()

    def _report_receivers(self) -> None:
        """Name in ``last_frame`` (and warn once) each receiver whose edits failed this frame."""
        for key, edits in self._edits.items():
            problem = edits.problem
            if problem is None:
                continue
            name = getattr(edits.actor, "name", None) or key
            self.last_frame.receivers.append(f"{name}: {problem}")
            if (key, problem) not in self._warned:
                self._warned.add((key, problem))
                warnings.warn(f"pvshadows: receiver {name}: {problem}", stacklevel=1)

    def _clear_edits(self) -> None:
        for edits in self._edits.values():
            edits.remove()
        self._edits.clear()

    def detach(self) -> None:
        """Remove the observers and every shader edit, and release GPU resources."""
        for tag in self._observers:
            self.renderer.RemoveObserver(tag)
        self._observers = []
        self._clear_edits()
        window = self._window
        if window is not None and window.GetInitialized():
            window.MakeCurrent()
            for technique in self._techniques.values():
                technique.release()
            self._buffers.release()
            self._timer.release()
        self._techniques.clear()
        self._window = None
