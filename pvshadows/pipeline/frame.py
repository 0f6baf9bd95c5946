"""Runs pvshadows inside one renderer's frames.

A renderer ``StartEvent`` observer runs before VTK draws anything: it reads
the scene, asks the planner what each light does, brings the shadow maps up
to date, binds them, and sets every receiver's shader edits and uniforms. An
``EndEvent`` observer frees the texture units and reads the passes' GPU
times into :attr:`RendererShadows.last_frame`.
"""

from __future__ import annotations

import time
import traceback
import warnings
from collections.abc import Callable
from functools import partial
from pathlib import Path

from pvshadows import _vtk as vtk
from pvshadows.gl.actor_buffers import ActorBuffers
from pvshadows.gl.buffers import forget_pointer_records
from pvshadows.gl.frame_block import FrameBlock, LightEntry
from pvshadows.gl.sampler_units import SamplerUnits
from pvshadows.gl.texture_units import park_active_unit
from pvshadows.gl.timing import PassTimer
from pvshadows.model.plan import Cast, LightPlan
from pvshadows.model.report import FrameFailure, FrameReport, LightReport
from pvshadows.model.settings import ShadowSettings
from pvshadows.pipeline.plan_memo import PlanMemo
from pvshadows.pipeline.planner import plan_frame
from pvshadows.pipeline.reach import ReachCache
from pvshadows.scene.impostors import LIGHT_SPACE_TECHNIQUES, lit_without_triangles
from pvshadows.scene.light_kit import KeyLights
from pvshadows.scene.reader import SceneReader
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.triangles import vtk_id
from pvshadows.scene.view import FrameView
from pvshadows.shaders.edits import ReceiverEdits
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques import TECHNIQUE_CLASSES
from pvshadows.techniques.base import FrameContext, LightFrame, Technique
from pvshadows.techniques.volume import VolumeTechnique


class RendererShadows:
    """Shadows for the lights and actors of one renderer.

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer.
    settings_for : callable
        Returns a light's settings, or ``None`` when it casts no shadow, given
        the light and (keyword ``keys``) the frame's
        :class:`~pvshadows.scene.light_kit.KeyLights`.
    reader : SceneReader
        Reads the actors and their roles each frame.
    """

    def __init__(
        self,
        renderer: vtk.vtkRenderer,
        settings_for: Callable[..., ShadowSettings | None],
        reader: SceneReader,
    ) -> None:
        self.renderer = renderer
        self._settings_for = settings_for
        self._reader = reader
        self._observers = [
            renderer.AddObserver(vtk.vtkCommand.StartEvent, self._on_start),
            renderer.AddObserver(vtk.vtkCommand.EndEvent, self._on_end),
        ]
        self._edits = ReceiverEdits()
        self._warned: set[tuple[str, str]] = set()
        #: What each spot light reached, kept between frames (``reach.tests`` counts cone tests).
        self.reach = ReachCache()
        #: Warnings of volume lights already given: open casters, forced z-pass (one each).
        self.warned_open: set[tuple] = set()
        #: Each light's last plan, kept while its inputs hold (``memo.planned`` counts replans).
        self.memo = PlanMemo()
        self._window: vtk.vtkOpenGLRenderWindow | None = None
        self._window_parts: tuple = ()
        self._timer: PassTimer | None = None
        self._buffers: ActorBuffers | None = None
        self._block: FrameBlock | None = None
        self._units: SamplerUnits | None = None
        self._techniques: dict[str, Technique] = {}
        self._frame = 0
        self._active: list[Technique] = []
        self.probe_index = -1
        self.plans: list[LightPlan] = []
        self.snapshot: Snapshot | None = None
        self.last_frame = FrameReport()
        #: The exception that made the last frame draw without shadows, else ``None``.
        self.error: Exception | None = None
        #: What the frame is doing, for the report of a frame that fails: in words, or
        #: the light being brought up to date (put in words only then).
        self._where: str | LightPlan = ""
        self._building = FrameReport()
        #: Let techniques draw debug overlays (``draw_debug``) over the finished frame.
        self.show_debug = False
        self._context: FrameContext | None = None
        #: Each shadowed light's cast, camera and :class:`LightFrame` of the last frame, by
        #: VTK light index: a light whose technique says they hold is not brought up again.
        self._kept: dict[int, tuple[Cast, FrameView, LightFrame]] = {}
        #: Lights whose last frame's :class:`LightFrame` was taken again, over all frames.
        self.lights_kept = 0

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
        window = vtk.vtkRenderer.GetRenderWindow(self.renderer)
        if self._window is window:
            return
        self._window = window
        # Held only so that their Python wrappers live on: the passes ask the window for
        # them many times a frame, and VTK makes a wrapper afresh (looking its class up
        # by name) for an object that Python no longer holds.
        self._window_parts = (
            window.GetState(),
            window.GetTextureUnitManager(),
            window.GetShaderCache(),
        )
        self._timer = PassTimer(window)
        self._buffers = ActorBuffers(window)
        self._block = FrameBlock(window)
        self._units = self._edits.units = SamplerUnits(window)
        self._techniques = {}
        self._kept = {}

    def _extrudes_on_gpu(self) -> bool:
        volume = self.technique("volume")
        assert isinstance(volume, VolumeTechnique)
        return volume.can_extrude_on_gpu()

    def _on_start(self, renderer: vtk.vtkRenderer, event: str) -> None:
        started = time.thread_time()
        self._frame += 1
        self._where = "reading the scene"
        self._building = FrameReport(frame=self._frame)
        try:
            self._run_frame()
            self.error = None
        except Exception as error:
            self._fail(error)
        self._building.cpu_ms = (time.thread_time() - started) * 1e3

    def _run_frame(self) -> None:
        self._start_gl()
        assert self._buffers is not None and self._timer is not None  # made by _start_gl
        renderer = self.renderer
        # VTK's own methods, called on the class: PyVista's wrappers check every attribute
        vtk.vtkRenderer.UpdateLightsGeometryToFollowCamera(renderer)
        snapshot = self._reader.read(renderer)
        last = self._context.view if self._context is not None else None
        view = FrameView.of(renderer, last)
        self._where = "planning"
        keys = KeyLights()  # the light kit's key light, looked for once this frame
        plans = plan_frame(
            renderer,
            snapshot,
            partial(self._settings_for, keys=keys),
            self.reach,
            view,
            self.warned_open,
            self.memo,
            self._extrudes_on_gpu,
            keys,
        )
        context = FrameContext(
            self._window,
            renderer,
            vtk.vtkRenderer.GetActiveCamera(renderer),
            snapshot,
            self._frame,
            self._buffers,
            self._timer,
            view,
        )
        self._context = context
        report = self._building
        uniforms: dict[str, object] = {}
        entries: dict[int, LightEntry] = {}
        shadings = []
        light_space: list[LightShading] = []
        self._active = []
        kept, self._kept = self._kept, {}
        casts = []
        for plan in plans:
            light_report = LightReport(
                plan.index, plan.kind.value, plan.technique, notes=plan.notes
            )
            report.lights.append(light_report)
            cast = plan.cast
            if cast is None:
                continue
            casts.append(cast)
            self._where = plan
            technique = self.technique(cast.technique)
            lit = self._light_frame(technique, cast, context, kept.get(cast.vtk_index))
            self._kept[cast.vtk_index] = (cast, view, lit)
            light_report.passes = lit.passes
            shadings.append(lit.shading)
            entries[cast.vtk_index] = lit.entry
            if cast.technique in LIGHT_SPACE_TECHNIQUES:
                light_space.append(lit.shading)
            if technique not in self._active:
                self._active.append(technique)
            uniforms.update(lit.samplers)
        impostors = self._impostors(snapshot)
        if impostors:
            self._note_impostors(plans, impostors)
        for light_report, plan in zip(report.lights, plans, strict=True):
            light_report.notes = list(plan.notes)
        self._where = "keeping only this frame's maps"
        for technique in self._techniques.values():
            technique.keep_only(casts)
        if snapshot is not self.snapshot and snapshot.parent is None:
            self._buffers.keep_only(snapshot.actors)
        self._where = "receiver shader edits"
        assert self._block is not None  # made by _start_gl
        screen_masks = len(light_space) < len(entries)
        self._block.update(entries, self.probe_index, self._viewport(context, screen_masks))
        lit_points = {vtk_id(actor) for actor in impostors} if light_space else set()
        self._edits.update(snapshot, shadings, uniforms, light_space, lit_points, view.planes)
        assert self._units is not None  # made by _start_gl
        self._units.bind(uniforms)
        park_active_unit(self._window)
        self.plans, self.snapshot, self.last_frame = plans, snapshot, report

    def _light_frame(
        self,
        technique: Technique,
        cast: Cast,
        context: FrameContext,
        kept: tuple[Cast, FrameView, LightFrame] | None,
    ) -> LightFrame:
        """Bring one light up to date, or take last frame's if its technique says it holds."""
        if kept is not None and kept[0] is cast:
            lit = technique.again(cast, context, kept[2], kept[1] is context.view)
            if lit is not None:
                self.lights_kept += 1
                return lit
        passes = technique.update(cast, context)
        shading = technique.shading(cast)
        entry = LightEntry(cast.settings.strength)
        for lookup in shading.needs:
            if lookup.vtk_index == cast.vtk_index:
                entry.taps = lookup.taps
        samplers = technique.activate(cast, context, entry)
        return LightFrame(passes, shading, entry, samplers)

    @staticmethod
    def _viewport(context: FrameContext, screen_masks: bool) -> tuple[float, float, float, float]:
        """Return where the renderer draws in the window, when some light reads a screen mask."""
        if not screen_masks:
            return (0.0, 0.0, 1.0, 1.0)
        target = context.target()
        (x0, y0), (width, height) = target.origin, target.size
        return (float(x0), float(y0), float(width), float(height))

    def _impostors(self, snapshot: Snapshot) -> list[vtk.vtkActor]:
        """Return the receiving bystanders VTK lights without triangles (points, lines)."""
        if not snapshot.bystanders:
            return []
        receiving = self._reader.receiving
        return [
            actor
            for actor in snapshot.bystanders
            if receiving.get(vtk_id(actor), True) and lit_without_triangles(actor)
        ]

    def _note_impostors(self, plans: list[LightPlan], impostors: list[vtk.vtkActor]) -> None:
        """Say under each shadowed light what the actors without triangles do."""
        listed = ", ".join(self._reader.name_of(actor) for actor in impostors)
        for plan in plans:
            if plan.technique is None:
                continue
            if plan.technique in LIGHT_SPACE_TECHNIQUES:
                plan.notes.append(
                    f"points or lines without triangles receive, cast nothing: {listed}"
                )
            else:
                plan.notes.append(
                    f"points or lines without triangles stay lit by this {plan.technique} light "
                    f"(its mask covers triangles only) and cast nothing: {listed}"
                )

    def _fail(self, error: Exception) -> None:
        """Draw this frame unshadowed: undo every edit, drop every map, say so once per fault.

        Nothing raised here leaves the VTK observer: a clean-up step that
        fails too is named in the report instead.
        """
        self.error = error
        where = f"{_in_words(self._where)}{_raised_in(error)}"
        troubles = self._undo()
        failure = FrameFailure(self._frame, where, f"{type(error).__name__}: {error}", troubles)
        previous = self.last_frame.failure
        if previous is not None and previous.same_fault(failure):
            failure.repeats = previous.repeats + 1
        report = self._building
        for light in report.lights:
            light.technique, light.passes = None, []
        report.failure = failure
        self.plans, self.last_frame = [], report
        if failure.repeats == 1:
            warnings.warn(f"pvshadows drew {failure}", stacklevel=1)

    def _undo(self) -> list[str]:
        """Leave receivers' shaders as VTK built them and release the maps; return what failed."""
        troubles = []
        steps = [(f"ending the frame of {type(t).__name__}", t.end_frame) for t in self._active]
        steps += [(f"releasing {type(t).__name__}", t.release) for t in self._techniques.values()]
        if self._timer is not None:
            steps.append(("collecting GPU times", self._timer.collect))
        for what, step in steps:
            try:
                step()
            except Exception as error:
                troubles.append(f"{what}: {type(error).__name__}: {error}")
        troubles += self._edits.clear()
        if self._units is not None:
            self._units.release()
        self.memo.forget()
        self._active = []
        self._techniques = {}
        self._kept = {}
        self._context = None
        return troubles

    def _on_end(self, renderer: vtk.vtkRenderer, event: str) -> None:
        if self.error is not None:
            return
        started = time.thread_time()
        try:
            self._finish_frame()
        except Exception as error:
            self._fail(error)
        self.last_frame.cpu_ms += (time.thread_time() - started) * 1e3

    def _finish_frame(self) -> None:
        if self.show_debug and self.probe_index < 0 and self._context is not None:
            self._where = "drawing the debug overlay"
            for technique in self._active:
                draw = getattr(technique, "draw_debug", None)
                if draw is not None:
                    draw(self._context)
        self._where = "the end of the frame"
        for technique in self._active:
            technique.end_frame()
        self._active = []
        if self._units is not None:
            self._units.end_frame()
        if self._timer is not None:
            self._timer.collect()
        self._report_receivers()

    def _report_receivers(self) -> None:
        """Name in ``last_frame`` (and warn once) each receiver whose edits failed this frame."""
        for key, (actor, problem) in self._edits.problems().items():
            name = self._reader.name_of(actor)
            self.last_frame.receivers.append(f"{name}: {problem}")
            if (key, problem) not in self._warned:
                self._warned.add((key, problem))
                warnings.warn(f"pvshadows: receiver {name}: {problem}", stacklevel=1)

    def _clear_edits(self) -> None:
        self._edits.clear()

    def detach(self) -> None:
        """Remove the observers and every shader edit, and release GPU resources."""
        for tag in self._observers:
            self.renderer.RemoveObserver(tag)
        self._observers = []
        self._reader.release(self.renderer)
        self._clear_edits()
        window = self._window
        if window is not None and window.GetInitialized():
            window.MakeCurrent()
            for technique in self._techniques.values():
                technique.release()
            if self._buffers is not None:
                self._buffers.release()
            if self._timer is not None:
                self._timer.release()
            if self._block is not None:
                self._block.release()
            if self._units is not None:
                self._units.release()
            forget_pointer_records()
        self._techniques.clear()
        self._window = None
        self._window_parts = ()


def _in_words(where: str | LightPlan) -> str:
    """Return what a frame was doing, e.g. ``"light 0 (spot, map)"`` for the light it was at."""
    if isinstance(where, str):
        return where
    assert where.cast is not None  # only a light that casts is brought up to date
    return f"light {where.index} ({where.kind.value}, {where.cast.technique})"


def _raised_in(error: Exception) -> str:
    """Return where in pvshadows ``error`` was raised, e.g. ``" in CubeDepthPass.render"``."""
    package = str(Path(__file__).parents[1])
    inside = [
        frame
        for frame, _ in traceback.walk_tb(error.__traceback__)
        if frame.f_code.co_filename.startswith(package)
    ]
    return f" in {inside[-1].f_code.co_qualname}" if inside else ""
