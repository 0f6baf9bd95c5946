"""Planar projected shadows: the casters flattened onto one receiving plane.

The cheapest technique, for every kind of light, and exact on the plane it
serves. Per frame and light:

1. the planner chooses the receiving plane (:func:`pvshadows.scene.planes.choose_plane`):
   an actor named with ``pl.shadows.set_receiver(actor, plane=True)``, or
   else a flat receiver found on its own (the largest, if several), and
   oriented so that the light is on its positive side;
2. every caster on the light's side of the plane is drawn through the
   flattening matrix ``(plane . light) I - light plane^T``
   (:func:`pvshadows.scene.planes.flattening`) and the camera's projection into
   the light's *mask*, a screen-space texture the size of the viewport,
   cleared to 1 (lit) and written 0 (:mod:`pvshadows.passes.planar_mask`).

Only the plane reads the mask, at its own pixel (``gl_FragCoord``), times a
facing test. The mask is binary: overlapping flattened triangles never
darken a pixel twice, as with a stencil test, and the shadow ends where the
plane ends, with no depth test against it and so no z-fighting at any scale.
The matrices are composed in float64 around each caster's centre, so a plane
a million units from the origin is as sharp as one at it.

Objects do not shadow each other with planar shadows: every other receiver
of the light gets its facing test only. The mask is screen-space, so it is
drawn again whenever the camera, the light, the plane or a caster moved,
and reused otherwise.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from itertools import compress
from typing import ClassVar

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.geometry.transforms import column_major
from pvshadows.gl.buffers import IndexedBuffers
from pvshadows.gl.caster_batch import CasterBatch
from pvshadows.gl.caster_draws import CasterDraws
from pvshadows.gl.frame_block import LightEntry
from pvshadows.gl.mask_target import MaskTexture
from pvshadows.model.plan import Cast, PlanarCast
from pvshadows.model.report import PassReport
from pvshadows.passes.planar_mask import FLAT_VECTORS, PlanarMaskPass
from pvshadows.pipeline.reach import same_objects
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.planes import PlaneChoice, facing, flattening
from pvshadows.scene.triangles import vtk_id
from pvshadows.scene.view import FrameView
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext, LightFrame
from pvshadows.techniques.screen_mask import (
    facing_shading,
    held_for,
    mask_holds,
    mask_shading,
    mask_uniforms,
)

_PASS = "planar mask"


@dataclass
class _LightState:
    mask: MaskTexture
    key: tuple | None = None
    frame: int = -1
    plane_actor: str | None = None
    #: What the mask was last brought up to date for (the cast, snapshot, view and
    #: target size) and the notes that said about it (:meth:`PlanarTechnique.again`).
    held: tuple | None = None
    #: The cast last drawn, with its light, its plane facing the light, the casters
    #: that may cast onto it flattened (:class:`FlatCasters`) and their keys and
    #: transmittances: the camera changes none of it.
    flattened: tuple | None = None
    #: The casters last tested and on which snapshot, which may cast, those
    #: between the plane and the light, their keys, and their gathering for the pass.
    between: tuple | None = None


def may_cast_boxes(bounds: np.ndarray, plane: np.ndarray, light: np.ndarray) -> np.ndarray:
    """Return whether any part of each caster lies between the plane and the light's height.

    Over a box a plane's height is greatest and least at corners found axis
    by axis: every caster is tested at once from its world bounds.

    Parameters
    ----------
    bounds : numpy.ndarray
        ``(n, 2, 3)`` min and max corners.
    plane : numpy.ndarray
        ``(4,)`` the plane, positive on the light's side.
    light : numpy.ndarray
        ``(4,)`` the homogeneous light.

    Returns
    -------
    numpy.ndarray
        ``(n,)`` bool, ``False`` for bounds wholly under the plane or
        wholly beyond a positional light's height above it.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.techniques.planar import may_cast_boxes
    >>> boxes = np.array([[[0, 0, 1.0], [1, 1, 2]], [[0, 0, -2.0], [1, 1, -1]]])
    >>> may_cast_boxes(boxes, np.array([0, 0, 1.0, 0]), np.array([0, 0, 5.0, 1])).tolist()
    [True, False]
    """
    heights = np.asarray(bounds, dtype=np.float64).reshape(-1, 2, 3) * plane[:3]
    highest = heights.max(axis=1).sum(axis=1) + plane[3]
    casts = highest > 0.0
    if light[3] != 0.0:
        casts &= heights.min(axis=1).sum(axis=1) + plane[3] < float(plane @ light)
    return casts


def _camera_sees_unlit_side(view: FrameView, plane: np.ndarray) -> bool:
    # VTK's own methods, called on the class: PyVista's wrappers check every attribute
    camera = view.stamp[0]
    if vtk.vtkCamera.GetParallelProjection(camera):
        return float(np.dot(plane[:3], vtk.vtkCamera.GetDirectionOfProjection(camera))) > 0.0
    return float(plane @ np.append(vtk.vtkCamera.GetPosition(camera), 1.0)) < 0.0


def flatten_models(
    models: np.ndarray, plane: np.ndarray, light: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Return casters flattened onto the plane from the light, whatever the camera.

    Each caster is drawn in a frame centred on its own centre ``o``: the
    plane and the light are moved there before they are multiplied, and
    :meth:`FlatCasters.to_clip` moves the camera's view there too, so no
    matrix handed to the GPU holds the scene's distance from the origin.
    All in float64, every caster at once.

    Parameters
    ----------
    models : numpy.ndarray
        ``(n, 4, 4)`` from each caster's (centred) model coordinates to world.
    plane : numpy.ndarray
        ``(4,)`` the world plane, positive on the light's side, ``|n| = 1``.
    light : numpy.ndarray
        ``(4,)`` the homogeneous world light.

    Returns
    -------
    centres : numpy.ndarray
        ``(n, 3)`` each world centre ``o``.
    flats : numpy.ndarray
        ``(n, 4, 4)`` from model coordinates to the flattened point, moved by ``-o``.
    planes_model : numpy.ndarray
        ``(n, 4)`` the plane in model coordinates (signed distance in world units).
    flat_ws : numpy.ndarray
        ``(n, 4)`` the flattened point's ``w`` as a function of the model point.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.techniques.planar import flatten_models
    >>> from pvshadows.geometry.transforms import translation
    >>> ground, bulb = np.array([0, 0, 1.0, 0]), np.array([0, 0, 4.0, 1])
    >>> centres, flats, planes, ws = flatten_models(translation([1, 0, 2])[None], ground, bulb)
    >>> p = translation(centres[0]) @ flats[0] @ [0, 0, 0, 1.0]
    >>> (p[:3] / p[3]).tolist(), float(planes[0] @ [0, 0, 0, 1.0])
    ([2.0, 0.0, 0.0], 2.0)
    """
    centres = models[:, :3, 3] / models[:, 3, 3:4]
    # translation(-o) @ model: the first three rows less o times the last
    local = models.copy()
    local[:, :3, :] -= centres[:, :, None] * models[:, 3:4, :]
    # translation(o).T @ plane: the plane's offset moved by n . o
    planes_local = np.repeat(plane[None], len(models), axis=0)
    planes_local[:, 3] += centres @ plane[:3]
    # translation(-o w) @ light: a positional light moved by -o, a direction kept
    lights_local = np.repeat(light[None], len(models), axis=0)
    lights_local[:, :3] -= centres * (light[3] * light[3])
    flats = flattening(planes_local, lights_local) @ local
    planes_model = np.einsum("nji,nj->ni", local, planes_local)
    return centres, flats, planes_model, flats[:, 3].copy()


@dataclass(frozen=True)
class FlatCasters:
    """The casters of one cast flattened onto its plane (:func:`flatten_models`), once per cast.

    Neither the camera nor the viewport changes them: a camera move only
    composes the camera's matrices with them again (:meth:`to_clip`).

    Attributes
    ----------
    casters : list of ActorState
        The casters, in order.
    centres : numpy.ndarray
        ``(n, 3)`` each caster's world centre.
    flats : numpy.ndarray
        ``(n, 4, 4)`` each caster's flattening, from its model coordinates.
    planes_model : numpy.ndarray
        ``(n, 4)`` the plane in each caster's model coordinates.
    flat_ws : numpy.ndarray
        ``(n, 4)`` each flattened point's ``w`` as a function of the model point.
    """

    casters: list[ActorState]
    centres: np.ndarray
    flats: np.ndarray
    planes_model: np.ndarray
    flat_ws: np.ndarray
    #: The batch :meth:`gathered` last answered for, the buffers and the rows
    #: (shared by the flattenings of the very same casters).
    _gathered: list = field(default_factory=list, repr=False, compare=False)

    @classmethod
    def of(
        cls,
        casters: list[ActorState],
        plane: np.ndarray,
        light: np.ndarray,
        gathered: list | None = None,
    ) -> FlatCasters:
        """Flatten every caster onto ``plane`` from ``light``.

        Parameters
        ----------
        casters : list of ActorState
            The casters.
        plane : numpy.ndarray
            ``(4,)`` the world plane, positive on the light's side, ``|n| = 1``.
        light : numpy.ndarray
            ``(4,)`` the homogeneous world light.
        gathered : list, optional
            The :meth:`gathered` of an earlier flattening of the very same
            casters, shared; a new one by default.

        Returns
        -------
        FlatCasters
            Their flattenings, stacked.
        """
        models = np.array([caster.model_matrix() for caster in casters]).reshape(-1, 4, 4)
        flattened = flatten_models(models, plane, light)
        return cls(casters, *flattened, [] if gathered is None else gathered)

    @cached
    def vectors(self) -> tuple[tuple[str, np.ndarray], ...]:
        """Each caster's :data:`~pvshadows.passes.planar_mask.FLAT_VECTORS`, float32."""
        through = np.zeros((len(self.casters), 4), dtype=np.float32)
        through[:, 0] = [caster.transmittance for caster in self.casters]
        values = (self.planes_model, self.flat_ws, through)
        arrays = [np.ascontiguousarray(v, dtype=np.float32).reshape(-1, 4) for v in values]
        return tuple(zip(FLAT_VECTORS, arrays, strict=True))

    def gathered(
        self, context: FrameContext
    ) -> tuple[list[IndexedBuffers], CasterBatch | None, np.ndarray | None]:
        """Return the casters' buffers, the snapshot's batch and their rows in it.

        Gathered once per batch (which only its casters' changes replace).
        """
        snapshot, buffers = context.snapshot, context.buffers
        batch = buffers.batch_of(snapshot)
        kept = self._gathered
        if kept and kept[0] is batch:
            return kept[1], batch, kept[2]
        drawn: list[IndexedBuffers] = [buffers.get(caster) for caster in self.casters]
        rows = None if batch is None else batch.rows[snapshot.caster_rows(self.casters)]
        self._gathered[:] = [batch, drawn, rows]
        return drawn, batch, rows

    def to_clip(self, world_to_clip: np.ndarray) -> np.ndarray:
        """Return each caster's matrix from model to clip coordinates, in float64.

        Parameters
        ----------
        world_to_clip : numpy.ndarray
            ``(4, 4)`` the camera's projection times its world-to-view matrix.

        Returns
        -------
        numpy.ndarray
            ``(n, 4, 4)``: the camera's matrix moved to each caster's centre
            (composed in float64, so that its offset from the origin cancels
            there, before anything is rounded to float32), then its flattening.

        Examples
        --------
        >>> import numpy as np
        >>> from pvshadows.techniques.planar import FlatCasters, flatten_models
        >>> from pvshadows.geometry.transforms import translation
        >>> ground, bulb = np.array([0, 0, 1.0, 0]), np.array([0, 0, 4.0, 1])
        >>> flats = FlatCasters([], *flatten_models(translation([1, 0, 2])[None], ground, bulb))
        >>> p = flats.to_clip(np.eye(4))[0] @ [0, 0, 0, 1.0]
        >>> (p[:3] / p[3]).tolist()
        [2.0, 0.0, 0.0]
        """
        moved = np.repeat(world_to_clip[None], len(self.centres), axis=0)
        # The camera's matrix times a translation to the centre: only its last column changes.
        moved[:, :, 3] = self.centres @ world_to_clip[:, :3].T + world_to_clip[:, 3]
        return moved @ self.flats


def flat_draws(
    flats: FlatCasters, context: FrameContext, rows_per_chunk: Callable[[int], int]
) -> CasterDraws:
    """Return what the planar pass draws of the casters, seen from this frame's camera.

    Parameters
    ----------
    flats : FlatCasters
        The casters, flattened onto the plane.
    context : FrameContext
        The frame (camera, actors, actor buffers).
    rows_per_chunk : callable
        Given the batch's rows per chunk, the batched program's
        (:meth:`~pvshadows.passes.planar_mask.PlanarMaskPass.chunk`).

    Returns
    -------
    CasterDraws
        Their buffers, matrices through the flattening to the camera's clip
        space and :data:`~pvshadows.passes.planar_mask.FLAT_VECTORS`; their
        rows in the snapshot's batch of small casters, where it has one.
    """
    buffers, batch, rows = flats.gathered(context)
    to_clip = column_major(flats.to_clip(context.view.world_to_clip)).reshape(-1, 4, 4)
    chunk = 0 if batch is None else rows_per_chunk(batch.chunk)
    culls = [None] * len(buffers)
    return CasterDraws(buffers, to_clip, culls, batch, rows, flats.vectors, chunk)


class PlanarTechnique:
    """Keeps the screen-space planar-shadow mask of each light that uses ``planar``.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the masks and the framebuffer.
    """

    name: ClassVar[str] = "planar"

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._pass = PlanarMaskPass(window)
        self._lights: dict[str, _LightState] = {}

    def _state(self, plan: Cast, width: int, height: int) -> _LightState:
        key = plan.key
        state = self._lights.get(key)
        if state is not None and state.mask.size != (width, height):
            self._lights.pop(key).mask.release()
            state = None
        if state is None:
            state = self._lights[key] = _LightState(MaskTexture(self._window, width, height))
        return state

    def update(self, plan: PlanarCast, context: FrameContext) -> list[PassReport]:
        """Bring the light's mask up to date for this frame.

        Parameters
        ----------
        plan : Cast
            The light's cast (technique ``"planar"``).
        context : FrameContext
            This frame's renderer, camera, actors, buffers and timer.

        Returns
        -------
        list of PassReport
            The mask pass, run, reused or skipped. The receiving plane is the
            planner's (``plan.plane``).
        """
        said = len(plan.notes)
        reports = self._update(plan, context)
        state = self._lights.get(plan.key)
        if state is not None:
            state.held = (*held_for(plan, context), tuple(plan.notes[said:]))
        return reports

    def _update(self, plan: PlanarCast, context: FrameContext) -> list[PassReport]:
        receivers = context.snapshot.receivers
        choice = plan.plane
        width, height = context.viewport_size()
        if width < 1 or height < 1:
            state = self._lights.pop(plan.key, None)
            if state is not None:
                state.mask.release()
            return [PassReport(_PASS, "skipped", "the viewport has no pixels")]
        state = self._state(plan, width, height)
        state.plane_actor = None
        if choice.actor is None:
            return [PassReport(_PASS, "skipped", "no receiving plane")]
        state.plane_actor = vtk_id(choice.actor.actor)
        others = [r.name for r in receivers if r is not choice.actor]
        if others:
            plan.notes.append(
                "objects do not shadow each other with planar shadows: "
                f"no shadow from this light falls on {', '.join(others)}"
            )
        return self._draw(plan, context, state, choice)

    @staticmethod
    def _between(
        plan: Cast,
        context: FrameContext,
        state: _LightState,
        choice: PlaneChoice,
        plane: np.ndarray,
        light: np.ndarray,
    ) -> tuple[list[ActorState], tuple, list]:
        """Return the casters between the plane and the light, their keys and gathering.

        Tested all at once over their stacked bounds (:func:`may_cast_boxes`);
        the same casters as last time (a light that moved a little) are the
        very list, keys and :meth:`FlatCasters.gathered` of last time.
        """
        assert choice.actor is not None
        casters, plane_actor = plan.casters, choice.actor.actor
        casts = may_cast_boxes(context.snapshot.bounds_of(casters), plane, light)
        kept = state.between
        if (
            kept is not None
            and kept[1] is context.snapshot
            and np.array_equal(kept[2], casts)
            and (kept[0] is casters or same_objects(kept[0], casters))
        ):
            return kept[3], kept[4], kept[5]
        between = [c for c in compress(casters, casts.tolist()) if c.actor is not plane_actor]
        keys = tuple((*c.key(), c.transmittance) for c in between)
        state.between = (casters, context.snapshot, casts, between, keys, [])
        return between, keys, state.between[5]

    def _draw(
        self, plan: Cast, context: FrameContext, state: _LightState, choice: PlaneChoice
    ) -> list[PassReport]:
        assert choice.actor is not None and choice.plane is not None
        kept = state.flattened
        if kept is not None and kept[0] is plan:
            light, plane = kept[1], kept[2]
        else:
            kept = None
            light = plan.pose.homogeneous()
            plane = facing(choice.plane, light)
        name = choice.actor.name
        if not plane @ light > 0.0:
            plan.notes.append(f"the light lies in the plane of {name}: it only grazes it")
            return [PassReport(_PASS, "skipped", "the light lies in the plane")]
        if _camera_sees_unlit_side(context.view, plane):
            plan.notes.append(
                f"the camera sees the side of {name} that faces away from the light: "
                "it is unlit, nothing to flatten"
            )
            return [PassReport(_PASS, "skipped", "the camera sees the plane's unlit side")]
        if kept is None:
            between, keys, gathered = self._between(plan, context, state, choice, plane, light)
            kept = state.flattened = (
                plan,
                light,
                plane,
                FlatCasters.of(between, plane, light, gathered),
                keys,
            )
        flats = kept[3]
        casters = flats.casters
        if not casters:
            if state.key != ("lit",):
                self._pass.fill_lit(state.mask)
                state.key = ("lit",)
            return [
                PassReport(_PASS, "skipped", f"no caster between the light and {name}: all lit")
            ]
        key = (
            choice.actor.key(),
            plane.tobytes(),
            plan.pose.key(),
            context.view.world_to_clip.tobytes(),
            state.mask.size,
            kept[4],
        )
        if key == state.key:
            return [_reused(state)]
        record = PassReport(
            _PASS, "run", f"{len(casters)} of {len(plan.casters)} casters flattened onto {name}"
        )
        draws = flat_draws(flats, context, self._pass.chunk)
        with context.timer.measure(record):
            self._pass.draw(state.mask, draws)
        state.key, state.frame = key, context.frame
        return [record]

    def shading(self, plan: Cast) -> LightShading:
        """Return how receivers read this light: the plane its mask, the others facing only.

        Parameters
        ----------
        plan : Cast
            The light's cast.

        Returns
        -------
        LightShading
            The mask lookup for the receiving plane (:attr:`LightShading.only_on`),
            with a facing test for every other receiver.
        """
        facing_only = facing_shading(plan.vtk_index)
        state = self._lights.get(plan.key)
        if state is None or state.plane_actor is None:
            return facing_only
        return mask_shading(
            plan.vtk_index, only_on=frozenset({state.plane_actor}), elsewhere=facing_only
        )

    def again(
        self, plan: Cast, context: FrameContext, last: LightFrame, same_view: bool
    ) -> LightFrame | None:
        """Return a light's last :class:`LightFrame` while its mask is last frame's.

        The mask is the casters flattened onto the plan's plane and seen from
        the camera: it holds for the very cast it was drawn for, the same
        snapshot of the actors, the same view and the same render target.
        What the technique noted about the light then is noted again.

        Parameters
        ----------
        plan : Cast
            The light's cast, the one ``last`` was made for.
        context : FrameContext
            This frame's camera and actors.
        last : LightFrame
            What the light was given last frame.
        same_view : bool
            Whether the camera is last frame's.

        Returns
        -------
        LightFrame or None
            Last frame's shading, textures and entry, a mask drawn then
            reported reused; ``None`` when the mask must be brought up to date.
        """
        state = self._lights.get(plan.key)
        if not same_view or state is None or state.held is None:
            return None
        if not mask_holds(state.held, plan, context):
            return None
        plan.notes.extend(state.held[4])
        if last.again:
            return last  # its reports as well: nothing in them changed
        passes = [_reused(state) if p.status == "run" else p for p in last.passes]
        return LightFrame(passes, last.shading, last.entry, last.samplers, again=True)

    def activate(self, plan: Cast, context: FrameContext, entry: LightEntry) -> dict[str, object]:
        """Fill the light's block entry (the facing test's light); return its mask's texture.

        Parameters
        ----------
        plan : Cast
            The light's cast.
        context : FrameContext
            This frame's renderer and camera.
        entry : LightEntry
            The light's entry of the frame's uniform block.

        Returns
        -------
        dict
            The mask's texture by uniform name (none without a plane).
        """
        state = self._lights.get(plan.key)
        if state is None or state.plane_actor is None:
            return mask_uniforms(plan, context, None, entry)
        return mask_uniforms(plan, context, state.mask, entry)

    def end_frame(self) -> None:
        """Nothing to let go of: the masks stay bound on the receivers' units."""

    def mask_of(self, light: vtk.vtkLight) -> MaskTexture | None:
        """Return the mask kept for a light, if any (for tests and debugging)."""
        state = self._lights.get(vtk_id(light))
        return state.mask if state else None

    def keep_only(self, plans: list[Cast]) -> None:
        """Release the masks of lights that no longer use planar shadows.

        Parameters
        ----------
        plans : list of Cast
            This frame's casts.
        """
        alive = {p.key for p in plans if p.technique == self.name}
        for key in set(self._lights) - alive:
            self._lights.pop(key).mask.release()

    def release(self) -> None:
        """Release every mask, the framebuffer and the program."""
        self.keep_only([])
        self._pass.release()


def _reused(state: _LightState) -> PassReport:
    """Return the report of a light's mask that is still right."""
    return PassReport(
        _PASS,
        "reused",
        f"camera, light, plane and casters unchanged since frame {state.frame}; "
        "the mask is screen-space, so a moving camera redraws it",
    )
