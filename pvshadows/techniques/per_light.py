"""What the shadow-map techniques share: one map per light, read through the filters."""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Callable, Iterator
from typing import ClassVar, Generic, TypeVar

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import only_translates
from pvshadows.gl.actor_buffers import ActorBuffers
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.capabilities import image_copies_supported
from pvshadows.gl.caster_batch import CasterBatch
from pvshadows.gl.caster_draws import CasterDraws
from pvshadows.gl.transmittance_textures import TransmittanceTexture
from pvshadows.model.plan import Cast
from pvshadows.model.report import PassReport
from pvshadows.model.settings import ShadowSettings
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.triangles import vtk_id
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext, LightFrame, Releasable
from pvshadows.techniques.filtering import FilterBindings, lookup_shading
from pvshadows.techniques.still_casters import DepthStep, MapT, StillCasters, TargetT, depth_steps
from pvshadows.techniques.translucent import Companion


class LightState(ABC):
    """What a technique keeps for one light between frames: its map and the map's companion.

    A subclass (a dataclass) holds ``companion``, ``still``, ``planned``
    and ``key`` as fields, default ``None``, and ``frame``, and says in
    :meth:`release_map` how its map is released.
    """

    #: The transmittance companion of its map, when some of its casters are translucent.
    companion: Companion | None
    #: The cast the map was last brought up to date for.
    planned: Cast | None
    #: What the map was last drawn from (``None`` when it holds nothing to read).
    key: tuple | None
    #: The frame it was last drawn in.
    frame: int
    #: Which casters a redraw draws over a still map (``None`` where maps cannot be copied).
    still: StillCasters | None

    @abstractmethod
    def release_map(self) -> None:
        """Release the light's map."""

    def release(self) -> None:
        """Release the map, its companion and its still map."""
        self.release_map()
        self.drop_companion()
        if self.still is not None:
            self.still.release()

    def drop_companion(self) -> None:
        """Release the transmittance companion, if any."""
        if self.companion is not None:
            self.companion.release()
            self.companion = None


StateT = TypeVar("StateT", bound=LightState)
PassT = TypeVar("PassT", bound=Releasable)


#: Lists of casters whose gathered rows :class:`DrawnRows` keeps at most.
KEPT_DRAWN_LISTS = 64
#: Casters from which a translating view adds to their matrices instead of multiplying
#: them: fewer are multiplied as fast, and the float32 copy kept for adding would cost a
#: list gathered at every frame (an actor moving) more than it saves.
ADD_FROM = 100


class DrawnRows:
    """What depth passes draw of lists of casters, gathered once per list and snapshot.

    A light drawn again, its casters the same list on the same snapshot (it
    moved, the camera did), multiplies only their matrices by its new view;
    their buffers, model matrices, sides to cull and batch rows are gathered
    once. A view that only translates (a spot's or a point light's) moves
    the affine matrices of :data:`ADD_FROM` or more casters by adding to
    their last column: the same float32 columns as the product, without
    it. The latest :data:`KEPT_DRAWN_LISTS` lists are kept.

    Examples
    --------
    >>> from pvshadows.techniques.per_light import DrawnRows
    >>> DrawnRows().gathered
    0
    """

    def __init__(self) -> None:
        self._kept: dict[int, tuple] = {}
        #: Lists gathered since this object was made (a list drawn again is not).
        self.gathered = 0

    def draws(
        self,
        casters: list[ActorState],
        world_to_light: np.ndarray,
        snapshot: Snapshot,
        buffers: ActorBuffers,
        settings: ShadowSettings,
    ) -> CasterDraws:
        """Return what a depth pass draws of some casters of a snapshot, in one batched product.

        Parameters
        ----------
        casters : list of ActorState
            The casters to draw, all of ``snapshot``.
        world_to_light : numpy.ndarray
            ``(4, 4)`` world to the light's space.
        snapshot : Snapshot
            This frame's actors: their stacked model matrices.
        buffers : ActorBuffers
            The casters' triangles on the GPU.
        settings : ShadowSettings
            The light's settings: with ``cull_front=True`` each caster's
            :attr:`~pvshadows.scene.actor_state.ActorState.cull_side` is culled.

        Returns
        -------
        CasterDraws
            Their buffers, ``world_to_light @ model_matrix``, sides to cull and
            rows in the snapshot's batch of small casters.
        """
        every, batch = buffers.of_casters(snapshot), buffers.batch_of(snapshot)
        kept = self._kept.get(id(casters))
        if (
            kept is None
            or kept[0] is not casters
            or kept[1] is not snapshot
            or kept[2] is not every
            or kept[3] is not batch
            or kept[4] != settings.cull_front
        ):
            gathered = _gather(casters, snapshot, every, batch, settings.cull_front)
            kept = (casters, snapshot, every, batch, settings.cull_front, gathered)
            if len(self._kept) >= KEPT_DRAWN_LISTS:
                del self._kept[next(iter(self._kept))]
            self._kept[id(casters)] = kept
            self.gathered += 1
        drawn, columns, culls, in_batch = kept[5]
        return CasterDraws(drawn, columns.to_light(world_to_light), culls, batch, in_batch)


class _ModelColumns:
    """Casters' model matrices by columns, ready to be taken to a light's space each frame.

    ``columns`` is ``(n, 4, 4)`` float64, each model matrix transposed
    (:attr:`~pvshadows.scene.snapshot.Snapshot.caster_model_columns`).
    """

    def __init__(self, columns: np.ndarray) -> None:
        self.columns = columns
        affine = (
            len(columns) >= ADD_FROM
            and not columns[:, :3, 3].any()
            and bool((columns[:, 3, 3] == 1.0).all())
        )
        # Affine matrices in float32, and their translations in float64 to add to.
        self._affine = (
            (np.asarray(columns, dtype=np.float32), np.ascontiguousarray(columns[:, 3, :3]))
            if affine
            else None
        )

    def to_light(self, world_to_light: np.ndarray) -> np.ndarray:
        """Return each ``world_to_light @ model`` by columns, ``(n, 4, 4)`` float32.

        Worked out in float64 and rounded once, as GL reads it; a
        translation is added to the models' translations, which gives the
        product's very numbers.
        """
        if self._affine is not None and only_translates(world_to_light):
            still, origins = self._affine
            moved = still.copy()
            np.add(origins, world_to_light[:3, 3], out=moved[:, 3, :3], casting="same_kind")
            return moved
        # Every caster's world_to_light @ model, transposed, in one product of 2-D arrays.
        product = self.columns.reshape(-1, 4) @ world_to_light.T
        return product.reshape(-1, 4, 4).astype(np.float32)


def _gather(
    casters: list[ActorState],
    snapshot: Snapshot,
    every: list,
    batch: CasterBatch | None,
    cull_front: bool,
) -> tuple[list, _ModelColumns, list[str | None], np.ndarray | None]:
    """Return the casters' buffers, model matrices' columns, sides to cull and batch rows."""
    rows = None if casters is snapshot.casters else snapshot.caster_rows(casters).tolist()
    drawn = every if rows is None else [every[row] for row in rows]
    columns = snapshot.caster_model_columns
    if rows is not None:
        columns = columns[rows]
    culls: list[str | None] = [None] * len(casters)
    if cull_front:  # only then: finding whether a caster is closed reads its triangles
        sides = snapshot.caster_sides
        culls = sides if rows is None else [sides[row] for row in rows]
    in_batch = None if batch is None else batch.rows if rows is None else batch.rows[rows]
    return drawn, _ModelColumns(columns), culls, in_batch


class PerLightMaps(ABC, Generic[StateT, PassT]):
    """Keeps one :class:`LightState` per light and the filters' textures.

    Subclasses set ``name``, fill ``self._states`` keyed by
    ``vtk_id(light)``, set ``self._pass`` to the pass that draws their maps,
    and say how a map is reported reused, how the camera's view reaches the
    light's space, and what else must hold for a light to be taken again.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the maps.
    """

    name: ClassVar[str]

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._filters = FilterBindings(window)
        self._states: dict[str, StateT] = {}
        self._pass: PassT | None = None
        self._shadings: dict[tuple, LightShading] = {}
        #: Whether a redraw may draw its moving casters over a still map (it copies it).
        self._still_maps = image_copies_supported(opengl_for(window))
        #: Casters handed to the depth passes since this object was made.
        self.casters_drawn = 0
        #: What the depth passes draw of each list of casters, gathered once per snapshot.
        self.drawn_rows = DrawnRows()

    def _still_casters(self, make_map: Callable[[], MapT]) -> StillCasters[MapT] | None:
        """Return a new light's :class:`StillCasters`, ``None`` where maps cannot be copied."""
        return StillCasters(make_map) if self._still_maps else None

    def _drawn_steps(
        self,
        still: StillCasters[MapT] | None,
        key: tuple,
        casters: list[ActorState],
        target: TargetT,
        world_to_light: np.ndarray,
        context: FrameContext,
        settings: ShadowSettings,
    ) -> Iterator[tuple[DepthStep[TargetT, MapT], CasterDraws]]:
        """Yield each depth pass of a redraw into ``target`` with what it draws.

        ``key`` is the map's key, its casters' keys last (:func:`depth_steps`
        compares the rest as the view); the casters drawn are counted in
        :attr:`casters_drawn`.
        """
        snapshot, buffers = context.snapshot, context.buffers
        serials = snapshot.for_casters(snapshot.caster_serials, casters)
        for step in depth_steps(still, key[:-1], casters, key[-1], serials, target):
            self.casters_drawn += len(step.casters)
            draws = self.drawn_rows.draws(step.casters, world_to_light, snapshot, buffers, settings)
            yield step, draws

    def _lookup_shading(
        self,
        kind: str,
        plan: Cast,
        *,
        has_map: bool,
        translucent: bool = False,
        texture: str = "",
    ) -> LightShading:
        """Return :func:`lookup_shading` for a light, the same object while nothing changed.

        Frames then hand the receivers' edits the same shadings, compared by identity.
        """
        key = (kind, plan.vtk_index, plan.settings, has_map, translucent, texture)
        shading = self._shadings.get(key)
        if shading is None:
            shading = lookup_shading(
                kind,
                plan.vtk_index,
                plan.settings,
                has_map=has_map,
                translucent=translucent,
                texture=texture,
            )
            self._shadings[key] = shading
        return shading

    def again(
        self, plan: Cast, context: FrameContext, last: LightFrame, same_view: bool
    ) -> LightFrame | None:
        """Return a light's last :class:`LightFrame`, seen from this frame's camera.

        A map holds while its cast is the one it was drawn for
        (:meth:`_still_right`) and what else the technique asks holds
        (:meth:`_holds_again`); only the view-to-light matrix follows the
        camera.

        Parameters
        ----------
        plan : Cast
            The light's cast, the one ``last`` was made for.
        context : FrameContext
            This frame's camera.
        last : LightFrame
            What the light was given last frame.
        same_view : bool
            Whether the camera is last frame's.

        Returns
        -------
        LightFrame or None
            The reused pass, last frame's shading and textures, and its entry;
            ``None`` when the light must be brought up to date.
        """
        state = self._states.get(plan.key)
        if state is None or not self._still_right(state, plan):
            return None
        if not self._holds_again(state, plan, context, same_view):
            return None
        if same_view and last.again:
            return last  # its reused passes' report as well: nothing in it changed
        entry = last.entry
        if not same_view:
            entry = entry.seen_from(self._view_to_light(state, plan, context))
        return LightFrame(self._reused(state), last.shading, entry, last.samplers, again=True)

    @abstractmethod
    def _reused(self, state: StateT) -> list[PassReport]:
        """Return the report of a light's map reused as it is."""

    @abstractmethod
    def _view_to_light(self, state: StateT, plan: Cast, context: FrameContext) -> np.ndarray:
        """Return the ``(4, 4)`` matrix from this frame's view coordinates to the light's space."""

    @abstractmethod
    def _holds_again(
        self, state: StateT, plan: Cast, context: FrameContext, same_view: bool
    ) -> bool:
        """Whether what a light whose map is still right was given last frame holds in this one.

        ``same_view`` tells whether the camera is last frame's.

        A technique that notes which lights each frame binds notes the light.
        """

    @staticmethod
    def _still_right(state: LightState | None, plan: Cast) -> bool:
        """Whether a light's map was last brought up to date for this very cast and holds casters.

        The planner hands the same cast again only while the light, its
        casters and what they are drawn from are as they were, so the map,
        drawn then, is right still. A map with a transmittance companion is
        brought up to date again: the companion keeps its own key.
        """
        return (
            state is not None
            and state.planned is plan
            and state.key is not None
            and state.companion is None
        )

    def companion_of(self, light: vtk.vtkLight) -> TransmittanceTexture | None:
        """Return the transmittance companion kept for a light, if any (for tests and debugging)."""
        state = self._states.get(vtk_id(light))
        return state.companion.texture if state is not None and state.companion else None

    def end_frame(self) -> None:
        """Nothing to let go of: the maps stay bound on the receivers' units."""

    def keep_only(self, plans: list[Cast]) -> None:
        """Release the maps of lights that no longer use this technique.

        Parameters
        ----------
        plans : list of Cast
            This frame's casts.
        """
        states = self._states
        held = 0
        for plan in plans:  # a count first: most frames release nothing
            if plan.technique == self.name and plan.key in states:
                held += 1
        if held < len(states):
            alive = {p.key for p in plans if p.technique == self.name}
            for key in set(states) - alive:
                states.pop(key).release()
        if len(self._shadings) > 4 * max(len(self._states), 1):
            self._shadings.clear()

    def release(self) -> None:
        """Release every map, the pass's programs and the filters' textures."""
        self.keep_only([])
        self._shadings.clear()
        if self._pass is not None:
            self._pass.release()
        self._filters.release()
