"""Pixel-exact hard shadows from stencil shadow volumes, for every kind of light.

Per frame and light, in a framebuffer of pvshadows' own the size of the
viewport (:mod:`pvshadows.gl.mask_target`):

1. a depth pre-pass of every visible actor with the camera's projection (once
   per frame, shared by all lights; skipped when the camera and actors did
   not change);
2. every closed caster's shadow volume — silhouette extruded to infinity
   (``w = 0``; with a parallel projection, to a finite distance beyond the
   scene), with light and dark caps for z-fail — counted in the 8-bit
   stencil, z-pass when the camera is outside every volume and z-fail
   otherwise (:mod:`pvshadows.pipeline.volume_zmode`), with depth clamping, in batches
   of at most 255 bodies;
3. the count turned into the light's *shadow mask* (1 lit, 0 in a volume).

Receivers read the mask at their own pixel (``gl_FragCoord``) and multiply
it by a facing test, so only that light's diffuse and specular are removed
and ambient light stays everywhere.

Extrusion runs on the GPU (``extrude="gpu"``: a geometry shader fed
``GL_TRIANGLES_ADJACENCY`` from pvshadows' own index buffer, built once per
mesh with :func:`pvshadows.geometry.silhouette.adjacency_indices`; VTK's own mapper
draws plain triangles and is not involved) or on the CPU (``extrude="cpu"``:
:func:`pvshadows.geometry.silhouette.volume_geometry`, vectorised numpy, rebuilt only
when the light or the caster moved).

Casters must be closed (:mod:`pvshadows.geometry.volume_casters`). An open caster
either raises (``on_open="raise"``) or casts its shadow from a shadow map
instead (``on_open="fallback"``): the light's visibility is then the volume
mask times that map's lookup over the open casters only
(:mod:`pvshadows.techniques.volume_fallback`). Preparing casters is
:mod:`pvshadows.techniques.volume_meshes`; where the light stands against them
(on a face, inside one) is :mod:`pvshadows.techniques.volume_light`.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.silhouette import volume_geometry
from pvshadows.geometry.transforms import column_major
from pvshadows.geometry.volume_casters import VolumeMesh
from pvshadows.gl.buffers import IndexedBuffers
from pvshadows.gl.caster_draws import CasterDraws
from pvshadows.gl.frame_block import LightEntry
from pvshadows.gl.mask_target import MaskTexture, VolumeTarget
from pvshadows.gl.volume_batch import VolumeBatch, batchable
from pvshadows.model.plan import Cast, VolumeCast
from pvshadows.model.report import PassReport
from pvshadows.passes.volume_stencil import (
    VolumeDraw,
    VolumePasses,
    VolumeRows,
    stencil_sides,
)
from pvshadows.scene.actor_state import ActorState, hides_what_is_behind
from pvshadows.scene.render_target import tiled_viewport
from pvshadows.scene.snapshot import ALL_ACTORS, Snapshot
from pvshadows.scene.triangles import ActorTriangles, vtk_id
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext, LightFrame
from pvshadows.techniques.screen_mask import held_for, mask_holds, mask_shading, mask_uniforms
from pvshadows.techniques.volume_draws import (
    DepthActors,
    KeptDraws,
    lights_in_models,
)
from pvshadows.techniques.volume_fallback import Fallback, OpenCasterFallbacks, combine_shadings
from pvshadows.techniques.volume_light import (
    finite_reach,
)
from pvshadows.techniques.volume_meshes import (
    translucent_batches,
)

#: Colour of the volumes drawn by ``pl.shadows.show_volumes(True)``.
OVERLAY_COLOUR = (1.0, 0.55, 0.1, 0.22)


@dataclass
class _CpuVolume:
    key: tuple
    buffers: IndexedBuffers
    starts: dict[str, np.ndarray]
    bases: dict[str, int]
    seconds: float


@dataclass
class _LightState:
    mask: MaskTexture
    key: tuple | None = None
    frame: int = -1
    zmode: str = ""
    draws: list[VolumeDraw] = field(default_factory=list)
    #: What the last count's draws read (for ``show_volumes``).
    rows: VolumeRows | None = None
    fallback: Fallback | None = None
    #: What the mask was last right for: the cast, snapshot, view, target size and
    #: hidden-line removal (:meth:`VolumeTechnique.again` compares them).
    held: tuple | None = None
    #: The last count's draws, whatever the camera and, extruded on the GPU, the light.
    drawn: KeptDraws | None = None
    #: Closed casters, and their keys and transmittances (part of the mask's key).
    closed_key: tuple = (None, ())
    #: The small volumes of its closed casters in one vertex array, if enough.
    batch: VolumeBatch | None = None

    def batch_for(
        self, window: vtk.vtkOpenGLRenderWindow, meshes: list[VolumeMesh | None]
    ) -> VolumeBatch | None:
        """Return the light's batch of these volume meshes: the kept one while it holds them."""
        if self.batch is not None and self.batch.holds(meshes):
            return self.batch
        if self.batch is not None:
            self.batch.release()
        self.batch = VolumeBatch(window, meshes) if any(batchable(meshes)) else None
        return self.batch

    def release(self) -> None:
        """Release the mask and the batch."""
        self.mask.release()
        if self.batch is not None:
            self.batch.release()
            self.batch = None


class VolumeTechnique:
    """Keeps the shadow masks of the lights that use volumes, and the casters' volume data.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the framebuffer, masks and buffers.
    """

    name: ClassVar[str] = "volume"

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._passes = VolumePasses(window)
        self._target: VolumeTarget | None = None
        self._lights: dict[str, _LightState] = {}
        self._meshes: dict[str, tuple[ActorTriangles, IndexedBuffers]] = {}
        self._cpu: dict[tuple[str, str], _CpuVolume] = {}
        self._depth_key: tuple | None = None
        self._depth_frame = -1
        #: Per snapshot: every actor's part of a mask's key; and, per hidden-line
        #: removal too, the actors the depth pre-pass draws and their keys.
        self._actors_of: tuple = (None, ())
        self._depth_of = DepthActors(None, False, None, (), np.zeros((0, 4, 4)), [], [], None, [])
        self._fallbacks = OpenCasterFallbacks(window)
        self._context: FrameContext | None = None
        #: The volume casts of the last :meth:`keep_only`.
        self._kept_for: tuple[Cast, ...] = ()
        #: The closed casters of the last volume draws built, with their model
        #: matrices and the inverses stacked (:meth:`_stacked`).
        self._stacks: tuple = ((), np.zeros((0, 4, 4)), np.zeros((0, 4, 4)))

    # -- per light ------------------------------------------------------------------------

    def update(self, plan: VolumeCast, context: FrameContext) -> list[PassReport]:
        """Bring the light's shadow mask up to date for this frame.

        Parameters
        ----------
        plan : Cast
            The light's cast (technique ``"volume"``).
        context : FrameContext
            This frame's renderer, camera, actors, buffers and timer.

        Returns
        -------
        list of PassReport
            The passes run, reused or skipped. What the light casts and how it
            counts (closed casters, enclosing caster, z-pass or z-fail, open
            casters' fallback) is the planner's :class:`~pvshadows.model.plan.VolumePlan`.
        """
        self._context = context
        width, height = context.viewport_size()
        hidden = bool(vtk.vtkRenderer.GetUseHiddenLineRemoval(context.renderer))
        light_id = plan.key
        if width < 1 or height < 1:
            dropped = self._lights.pop(light_id, None)
            if dropped is not None:
                dropped.release()
            return [PassReport("shadow volumes", "skipped", "the viewport has no pixels")]
        self._ensure_target(width, height)
        state = self._lights.get(light_id)
        if state is None:
            state = self._lights[light_id] = _LightState(MaskTexture(self._window, width, height))
        volume = plan.volume
        closed, light, zmode, extrude = volume.closed, volume.light, volume.zmode, volume.extrude
        reports: list[PassReport] = []
        state.fallback = volume.fallback
        state.held = (*held_for(plan, context), hidden)
        if volume.enclosing is not None:
            key: tuple = ("inside", plan.pose.key(), volume.enclosing.key())
            if key != state.key:
                assert self._target is not None
                self._passes.fill(self._target, state.mask, 0.0)
                state.key, state.frame, state.draws, state.zmode = key, context.frame, [], ""
                reports.append(PassReport("shadow mask", "run", "all in shadow (light enclosed)"))
            else:
                reports.append(PassReport("shadow mask", "reused", "light still enclosed"))
            return reports + self._fallbacks.update(state.fallback, context)
        camera = context.view.world_to_clip
        key = (
            plan.pose.key(),
            zmode,
            extrude,
            camera.tobytes(),
            (width, height),
            self._actors_key(context.snapshot),
            hidden,
            self._closed_key(state, plan),
        )
        if key == state.key:
            reports.append(_reused(state, extrude))
            return reports + self._fallbacks.update(state.fallback, context)
        if self._depth_frame != context.frame:
            reports.append(self._depth_pass(context, camera, width, height))
        reach = finite_reach(context, light)
        if reach:
            plan.notes.append("parallel projection: volumes end beyond the scene, not at infinity")
        drawn = state.drawn
        if drawn is not None and drawn.holds(plan, closed, zmode, reach, extrude):
            if drawn.closed is not closed:
                drawn.take(closed, *self._stacked(closed))
            reports.extend(_cpu_reused(closed, extrude))
        else:
            plan_batches, passing = translucent_batches(closed)
            models, inverses = self._stacked(closed)
            lights = lights_in_models(inverses, light)
            draws, built = self._volume_draws(
                plan, closed, plan_batches, models, lights, zmode, extrude, reach
            )
            reports.extend(built)
            meshes = [mesh if extrude == "gpu" else None for _, mesh in closed]
            volume_batch = state.batch_for(self._window, meshes)
            sides = [stencil_sides(batch, volume_batch) for batch in draws]
            reaches = np.zeros(len(closed))
            for draw in (d for group in draws for d in group):
                reaches[draw.row] = draw.extrude_to
            drawn = state.drawn = KeptDraws(
                plan, closed, zmode, reach, extrude, plan_batches, passing, draws, sides,
                models, inverses, reaches, light, lights,
            )  # fmt: skip
        rows = drawn.rows(camera, light)
        bodies = drawn.bodies
        record = PassReport(
            f"stencil count ({zmode}, {extrude} extrusion)",
            "run",
            f"{len(closed)} closed casters, {sum(bodies)} bodies in {len(bodies)} batch(es)"
            if closed
            else "no closed caster: mask all lit",
        )
        assert self._target is not None
        with context.timer.measure(record):
            self._passes.count(
                self._target, state.mask, drawn.sides, rows, zmode, drawn.passing, state.batch
            )
        reports.append(record)
        state.key, state.frame, state.zmode = key, context.frame, zmode
        state.draws, state.rows = drawn.every, rows
        return reports + self._fallbacks.update(state.fallback, context)

    def _actors_key(self, snapshot: Snapshot) -> tuple:
        """Return each actor's key and whether its faces are drawn (per snapshot).

        A snapshot that follows the last one patches its replaced actors' parts.
        """
        kept = self._actors_of
        if kept[0] is snapshot:
            return kept[1]
        if kept[0] is not None and snapshot.parent is kept[0]:
            parts = list(kept[1])
            for row, state in snapshot.patches(ALL_ACTORS):
                parts[row] = (*state.key(), state.faces_drawn)
            key = tuple(parts)
        else:
            key = tuple((*a.key(), a.faces_drawn) for a in snapshot.actors)
        self._actors_of = (snapshot, key)
        return key

    @staticmethod
    def _closed_key(state: _LightState, plan: VolumeCast) -> tuple:
        """Return a cast's closed casters' keys and transmittances (per list of closed casters)."""
        closed = plan.volume.closed
        if state.closed_key[0] is not closed:
            state.closed_key = (closed, tuple((*c.key(), c.transmittance) for c, _ in closed))
        return state.closed_key[1]

    def _depth_actors(self, context: FrameContext) -> DepthActors:
        """Return what the depth pre-pass draws: the actors that hide what is behind them.

        Worked out once per snapshot, hidden-line removal and batch of
        small casters.
        """
        snapshot, buffers = context.snapshot, context.buffers
        hidden = bool(vtk.vtkRenderer.GetUseHiddenLineRemoval(context.renderer))
        batch = buffers.batch_of(snapshot)
        kept = self._depth_of
        if kept.snapshot is snapshot and kept.hidden == hidden and kept.batch is batch:
            return kept
        follows = kept.snapshot is not None and snapshot.parent is kept.snapshot
        patched = None
        if follows and kept.hidden == hidden and kept.batch is batch:
            patched = kept.patched(snapshot, context.renderer, buffers)
        if patched is None:
            actors = [a for a in snapshot.actors if hides_what_is_behind(a, context.renderer)]
            number = {id(a): n for n, a in enumerate(actors)}
            rows = None
            if batch is not None:
                among = snapshot.caster_rows_among(actors)
                rows = np.where(among >= 0, batch.rows[among], -1)
            patched = DepthActors(
                snapshot,
                hidden,
                batch,
                tuple(a.key() for a in actors),
                np.array([a.model_matrix() for a in actors]).reshape(-1, 4, 4),
                [buffers.get(a) for a in actors],
                [None] * len(actors),
                rows,
                [number.get(id(a), -1) for a in snapshot.actors],
            )
        self._depth_of = patched
        return patched

    def _ensure_target(self, width: int, height: int) -> None:
        if self._target is not None and self._target.size == (width, height):
            return
        if self._target is not None:
            self._target.release()
        for state in self._lights.values():
            state.release()
        self._lights.clear()
        self._target = VolumeTarget(self._window, width, height)
        self._depth_key, self._depth_frame = None, -1

    def _depth_pass(
        self, context: FrameContext, camera: np.ndarray, width: int, height: int
    ) -> PassReport:
        self._depth_frame = context.frame
        depth = self._depth_actors(context)
        key = (camera.tobytes(), (width, height), depth.keys)
        if key == self._depth_key:
            return PassReport(
                "volume depth pre-pass", "reused", "camera and actors unchanged: depth still right"
            )
        columns = column_major(camera @ depth.models).reshape(-1, 4, 4)
        draws = CasterDraws(depth.buffers, columns, depth.culls, depth.batch, depth.rows)
        self._depth_key = key
        assert self._target is not None
        return self._passes.depth(self._target, draws, context.timer)

    def _volume_draws(
        self,
        plan: Cast,
        closed: list[tuple[ActorState, VolumeMesh]],
        plan_batches: list[list[tuple]],
        models: np.ndarray,
        lights: np.ndarray,
        zmode: str,
        extrude: str,
        reach: float,
    ) -> tuple[list[list[VolumeDraw]], list[PassReport]]:
        """Each batch's draws, and a report of the CPU rebuild (``extrude="cpu"``).

        Draw ``number`` reads row ``number`` of the closed casters' matrices
        (``models``, stacked) and of ``lights``, the light in each one's frame.
        ``reach`` is 0 to extrude to infinity, or how far (world units) to
        extrude volumes for a parallel projection.
        """
        ranges_of: dict[int, list[tuple[int, int]]] = {}
        for batch in plan_batches:
            for number, first, end in batch:
                ranges_of.setdefault(number, []).append((first, end))
        per_caster: list[list[VolumeDraw]] = []
        rebuilt, reused, seconds = 0, 0, 0.0
        for number, (caster, mesh) in enumerate(closed):
            model = models[number]
            light_model, mirrored = lights[number], caster.mirrored
            # Model units that are at least `reach` world units in every direction.
            extrude_to = (
                reach / np.linalg.svd(model[:3, :3], compute_uv=False)[-1] if reach else 0.0
            )
            if extrude == "gpu":
                buffers = self._mesh_buffers(caster, mesh)
                draws = []
                for first, end in ranges_of[number]:
                    a, b = int(mesh.body_starts[first]), int(mesh.body_starts[end])
                    span = (6 * a, 6 * (b - a), "all")
                    draws.append(VolumeDraw(buffers, "gpu", number, mirrored, [span], extrude_to))
            else:
                volume = self._cpu_volume(plan, caster, mesh, light_model, extrude_to)
                if volume.seconds:
                    rebuilt += 1
                    seconds += volume.seconds
                else:
                    reused += 1
                draws = []
                for s, e in ranges_of[number]:
                    pieces = []
                    for piece in ("sides", "light", "dark"):
                        if zmode == "zpass" and piece != "sides":
                            continue
                        starts = volume.starts[piece]
                        first = volume.bases[piece] + int(starts[s])
                        pieces.append((3 * first, 3 * int(starts[e] - starts[s]), piece))
                    draws.append(VolumeDraw(volume.buffers, "cpu", number, mirrored, pieces))
            per_caster.append(draws)
        reports = []
        if extrude == "cpu" and closed:
            status = "run" if rebuilt else "reused"
            report = PassReport(
                "silhouettes and volumes (cpu)",
                status,
                f"{rebuilt} rebuilt, {reused} reused (light and caster unchanged); CPU time",
            )
            report.ms = seconds * 1e3 if rebuilt else None
            reports.append(report)
        taken = [0] * len(per_caster)
        grouped = []
        for batch in plan_batches:
            group = []
            for number, _, _ in batch:
                group.append(per_caster[number][taken[number]])
                taken[number] += 1
            grouped.append(group)
        return grouped, reports

    def _mesh_buffers(self, caster: ActorState, mesh: VolumeMesh) -> IndexedBuffers:
        key = vtk_id(caster.actor)
        cached = self._meshes.get(key)
        if cached is not None and cached[0] is caster.triangles:
            return cached[1]
        if cached is not None:
            cached[1].release()
        buffers = IndexedBuffers(self._window, mesh.points, mesh.adjacency_rows)
        self._meshes[key] = (caster.triangles, buffers)
        return buffers

    def _cpu_volume(
        self,
        plan: Cast,
        caster: ActorState,
        mesh: VolumeMesh,
        light_model: np.ndarray,
        extrude_to: float,
    ) -> _CpuVolume:
        cache_key = (plan.key, vtk_id(caster.actor))
        key = (id(caster.triangles), caster.triangles.version, light_model.tobytes(), extrude_to)
        cached = self._cpu.get(cache_key)
        if cached is not None and cached.key == key:
            cached.seconds = 0.0
            return cached
        start = time.perf_counter()
        shining = light_model.copy()
        if shining[3] == 0.0:
            shining[:3] = -shining[:3]
        geometry = volume_geometry(mesh.points, mesh.triangles, mesh.adjacency, shining)
        n = len(mesh.points)
        positions = geometry.positions
        if extrude_to:
            away = mesh.points - shining[:3] if shining[3] else np.broadcast_to(shining[:3], (n, 3))
            length = np.linalg.norm(away, axis=1, keepdims=True)
            positions = positions.copy()
            positions[n:, :3] = mesh.points + away * (extrude_to / np.maximum(length, 1e-300))
            positions[n:, 3] = 1.0
        body = mesh.point_body
        sides = geometry.sides
        side_body = body[sides[:, 0] % n]
        order = np.argsort(side_body, kind="stable")
        sides, side_body = sides[order], side_body[order]
        pieces = {
            "sides": (sides, side_body),
            "light": (geometry.light_cap, body[geometry.light_cap[:, 0]]),
            "dark": (geometry.dark_cap, body[geometry.dark_cap[:, 0] - n]),
        }
        bodies = np.arange(mesh.n_bodies + 1)
        starts, bases, rows, base = {}, {}, [], 0
        for name, (triangles, owner) in pieces.items():
            starts[name] = np.searchsorted(owner, bodies, side="left")
            bases[name] = base
            rows.append(triangles)
            base += len(triangles)
        seconds = time.perf_counter() - start
        if cached is not None:
            cached.buffers.release()
        volume = _CpuVolume(
            key,
            IndexedBuffers(self._window, positions, np.concatenate(rows)),
            starts,
            bases,
            seconds,
        )
        self._cpu[cache_key] = volume
        return volume

    def shading(self, plan: Cast) -> LightShading:
        """Return how receivers read this light's mask (and fallback map).

        Parameters
        ----------
        plan : Cast
            The light's cast.

        Returns
        -------
        LightShading
            The mask lookup, times the fallback's lookup when open casters
            cast from a shadow map.
        """
        own = mask_shading(plan.vtk_index)
        state = self._lights.get(plan.key)
        if state is None:
            return LightShading(plan.vtk_index, "1.0")  # nothing counted this frame (no pixels)
        if state.fallback is None:
            return own
        name, subplan = state.fallback
        return combine_shadings(own, self._fallbacks.technique(name).shading(subplan))

    def again(
        self, plan: Cast, context: FrameContext, last: LightFrame, same_view: bool
    ) -> LightFrame | None:
        """Return a light's last :class:`LightFrame` while its mask is last frame's.

        The mask counts the closed casters' volumes against the scene's depth
        seen from the camera, so it holds for the very cast it was made for
        (the planner hands that again only while the light and its casters
        hold, and chooses the same z-mode for the same view), the same
        snapshot of the actors, the same view and render target and the same
        hidden-line removal. A light whose open casters cast from a fallback
        map is brought up to date: that map's technique decides.

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
            Last frame's shading, textures and entry, the mask reported
            reused; ``None`` when the mask must be brought up to date.
        """
        state = self._lights.get(plan.key)
        if not same_view or state is None or state.fallback is not None or state.held is None:
            return None
        hidden = bool(vtk.vtkRenderer.GetUseHiddenLineRemoval(context.renderer))
        if not mask_holds(state.held, plan, context) or state.held[4] != hidden:
            return None
        self._context = context
        if last.again:
            return last  # its reused pass's report as well: nothing in it changed
        assert isinstance(plan, VolumeCast)  # what the volume technique is given
        reused = (
            PassReport("shadow mask", "reused", "light still enclosed")
            if plan.volume.enclosing is not None
            else _reused(state, plan.volume.extrude)
        )
        return LightFrame([reused], last.shading, last.entry, last.samplers, again=True)

    def activate(self, plan: Cast, context: FrameContext, entry: LightEntry) -> dict[str, object]:
        """Fill the light's block entry (facing test, a fallback's map); return its textures.

        Parameters
        ----------
        plan : Cast
            The light's cast.
        context : FrameContext
            This frame's renderer and camera.
        entry : LightEntry
            The light's entry of the frame's uniform block, which the open
            casters' fallback fills too.

        Returns
        -------
        dict
            The mask's and the fallback's textures, by uniform name.
        """
        state = self._lights.get(plan.key)
        if state is None:
            return {}
        uniforms = mask_uniforms(plan, context, state.mask, entry)
        if state.fallback is not None:
            name, subplan = state.fallback
            uniforms.update(self._fallbacks.technique(name).activate(subplan, context, entry))
        return uniforms

    def _stacked(
        self, closed: list[tuple[ActorState, VolumeMesh]]
    ) -> tuple[np.ndarray, np.ndarray]:
        """Return the closed casters' model matrices and their inverses, ``(n, 4, 4)`` each.

        Stacked again only for other caster states than the last call's: a
        light that moves over the same casters multiplies the same stacks.
        """
        states = self._stacks[0]
        if len(states) != len(closed) or any(
            c is not kept for (c, _), kept in zip(closed, states, strict=True)
        ):
            casters = [c for c, _ in closed]
            self._stacks = (
                tuple(casters),
                np.array([c.model_matrix() for c in casters]).reshape(-1, 4, 4),
                np.array([c.model_inverse for c in casters]).reshape(-1, 4, 4),
            )
        return self._stacks[1], self._stacks[2]

    def end_frame(self) -> None:
        """End the frame of the open casters' fallback techniques."""
        self._fallbacks.end_frame()

    def draw_debug(self, context: FrameContext) -> None:
        """Draw this frame's volumes translucent over the finished frame (``show_volumes``).

        Parameters
        ----------
        context : FrameContext
            The frame's context (its renderer's viewport).
        """
        target = tiled_viewport(context.renderer)
        (x0, y0), (width, height) = target.origin, target.size
        for state in self._lights.values():
            if state.draws and state.rows is not None:
                viewport = (x0, y0, width, height)
                self._passes.overlay(state.draws, state.rows, viewport, OVERLAY_COLOUR)

    def mask_of(self, light: vtk.vtkLight) -> MaskTexture | None:
        """Return the mask kept for a light, if any (for tests and debugging)."""
        state = self._lights.get(vtk_id(light))
        return state.mask if state else None

    def can_extrude_on_gpu(self) -> bool:
        """Return whether this window compiles the geometry shader that extrudes volumes.

        Returns
        -------
        bool
            Asked by the planner for lights whose settings want it (tried
            once per window).
        """
        return self._passes.can_extrude_on_gpu()

    def zmode_of(self, light: vtk.vtkLight) -> str | None:
        """Return the counting used for a light in its last update: ``"zpass"`` or ``"zfail"``."""
        state = self._lights.get(vtk_id(light))
        return state.zmode if state else None

    def keep_only(self, plans: list[Cast]) -> None:
        """Release the masks of lights that no longer use volumes, and unused volume data.

        Parameters
        ----------
        plans : list of Cast
            This frame's casts: casts of the same lights over the same
            actors as the last call's (a frame in which only the camera,
            the lights or some casters moved) leave nothing to release, and
            their casters are not listed again.
        """
        using = [p for p in plans if p.technique == self.name]
        kept, self._kept_for = self._kept_for, tuple(using)
        if len(using) == len(kept) and all(map(_same_casters, using, kept)):
            return
        self._release_unused(using)

    def _release_unused(self, using: list[Cast]) -> None:
        """Release what none of ``using`` (volume casts) needs."""
        alive = {p.key for p in using}
        for key in set(self._lights) - alive:
            self._lights.pop(key).release()
        casters = {vtk_id(c.actor) for p in using for c in p.casters}
        for mesh_key in set(self._meshes) - casters:
            self._meshes.pop(mesh_key)[1].release()
        for cpu_key in [k for k in self._cpu if k[0] not in alive or k[1] not in casters]:
            self._cpu.pop(cpu_key).buffers.release()
        self._fallbacks.keep_only([s.fallback[1] for s in self._lights.values() if s.fallback])
        if not self._lights and self._target is not None:
            self._target.release()
            self._target = None

    def release(self) -> None:
        """Release every framebuffer, mask, buffer and program."""
        self._kept_for = ()
        self._release_unused([])
        self._fallbacks.release()
        self._passes.release()


def _same_casters(cast: Cast, before: Cast) -> bool:
    """Tell whether two volume casts are of the same light over the same actors."""
    if not isinstance(cast, VolumeCast) or not isinstance(before, VolumeCast):
        return cast is before
    if cast.key != before.key:
        return False
    now, then = cast.casters, before.casters
    return now is then or (
        len(now) == len(then) and all(a.actor is b.actor for a, b in zip(now, then, strict=True))
    )


def _cpu_reused(closed: list, extrude: str) -> list[PassReport]:
    """Return the report of CPU volumes all kept, worded as ``_volume_draws`` words it."""
    if extrude != "cpu" or not closed:
        return []
    return [
        PassReport(
            "silhouettes and volumes (cpu)",
            "reused",
            f"0 rebuilt, {len(closed)} reused (light and caster unchanged); CPU time",
        )
    ]


def _reused(state: _LightState, extrude: str) -> PassReport:
    """Return the report of a light's stencil count whose mask is still right."""
    return PassReport(
        f"stencil count ({state.zmode}, {extrude} extrusion)",
        "reused",
        f"camera, light and actors unchanged since frame {state.frame}: mask still right",
    )
