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
(:data:`FALLBACK_TECHNIQUES`).
"""

from __future__ import annotations

import time
import warnings
import weakref
from dataclasses import dataclass, field, fields, replace
from typing import ClassVar

import numpy as np
import pyvista as pv

from pvshadows import _vtk as vtk
from pvshadows.geometry.closed import OpenMeshError
from pvshadows.geometry.silhouette import volume_geometry
from pvshadows.geometry.volume_casters import (
    VolumeMesh,
    batches,
    prepare_volume_mesh,
    winding_number,
)
from pvshadows.gl.buffers import IndexedBuffers
from pvshadows.gl.mask_target import MaskTexture, VolumeTarget
from pvshadows.model.plan import LightPlan
from pvshadows.model.report import PassReport
from pvshadows.passes.volume_stencil import DepthDraw, VolumeDraw, VolumePasses
from pvshadows.pipeline.volume_zmode import choose_zmode
from pvshadows.scene.lights import LightKind
from pvshadows.scene.render_target import tiled_viewport
from pvshadows.scene.snapshot import ActorState, Snapshot
from pvshadows.scene.triangles import ActorTriangles, vtk_id
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext, Technique

#: The technique that casts the shadows of open casters (``on_open="fallback"``),
#: per kind of light. A name that is not (yet) a registered technique serving
#: that kind of light leaves open casters without shadows from such lights,
#: with a warning naming them.
FALLBACK_TECHNIQUES = {
    LightKind.POINT: "cubemap",
    LightKind.SPOT: "cubemap",
    LightKind.DIRECTIONAL: "map",
}

#: Colour of the volumes drawn by ``pl.shadows.show_volumes(True)``.
OVERLAY_COLOUR = (1.0, 0.55, 0.1, 0.22)

_HOW = {
    "repaired": "a closed surface after repair (welding, rewinding or closing small holes)",
    "two-sided sheet": "a two-sided slab of zero thickness (it is a flat open sheet)",
}

_PREPARED: dict[int, tuple[weakref.ref, VolumeMesh | OpenMeshError]] = {}


def _reason(error: OpenMeshError) -> str:
    return str(error).split("cannot be made closed: ", 1)[-1]


def prepared_mesh(triangles: ActorTriangles, name: str) -> VolumeMesh:
    """Return an actor's surface made ready for shadow volumes, once per version of its data.

    Parameters
    ----------
    triangles : ActorTriangles
        The actor's triangles (the result is kept as long as they live).
    name : str
        How messages name the actor.

    Returns
    -------
    VolumeMesh
        Closed and outward wound, in the frame of ``triangles.points``.

    Raises
    ------
    OpenMeshError
        When it is open and cannot be closed; the message names the actor.
    """
    entry = _PREPARED.get(id(triangles))
    if entry is None or entry[0]() is not triangles:
        try:
            result: VolumeMesh | OpenMeshError = prepare_volume_mesh(
                triangles.points, triangles.triangles, name
            )
        except OpenMeshError as error:
            result = OpenMeshError(
                f"{name} is not a closed surface and cannot be closed ({_reason(error)}), "
                "so it cannot cast a shadow volume"
            )
        key = id(triangles)
        _PREPARED[key] = (weakref.ref(triangles), result)
        weakref.finalize(triangles, _PREPARED.pop, key, None)
        entry = _PREPARED[key]
    if isinstance(entry[1], OpenMeshError):
        raise entry[1]
    return entry[1]


def require_closed(casters: list[tuple[str, ActorTriangles]]) -> None:
    """Raise for the first caster that cannot cast a shadow volume (``on_open="raise"``).

    Parameters
    ----------
    casters : list of (str, ActorTriangles)
        Each caster's name and triangles.

    Raises
    ------
    ValueError
        Naming the actor and what is wrong, and what to do.
    """
    for name, triangles in casters:
        try:
            prepared_mesh(triangles, name)
        except OpenMeshError as error:
            msg = (
                f"{error}. With on_open='raise' every caster of a volume light must be "
                "closed: close the mesh, use on_open='fallback' (it then casts from a shadow "
                "map), or pl.shadows.set_caster(actor, False)"
            )
            raise OpenMeshError(msg) from None


def translucent_batches(
    closed: list[tuple[ActorState, VolumeMesh]],
) -> tuple[list[list[tuple]], list[float]]:
    """Batch the closed casters: opaque ones together, each translucent one on its own.

    Parameters
    ----------
    closed : list of tuple
        ``(caster, volume mesh)`` in drawing order.

    Returns
    -------
    batches : list of list of tuple
        As :func:`pvshadows.geometry.volume_casters.batches`: opaque casters first.
    passing : list of float
        Per batch, the light its shadow lets through: 0 for opaque casters,
        ``(1 - opacity)`` squared for a translucent closed caster (a shadow
        ray crosses two of its surfaces), ``1 - opacity`` for a flat sheet.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from pvshadows.techniques.volume import translucent_batches
    >>> glass = SimpleNamespace(transmittance=0.5)
    >>> stone = SimpleNamespace(transmittance=0.0)
    >>> body = SimpleNamespace(n_bodies=1, how="closed")
    >>> translucent_batches([(glass, body), (stone, body)])
    ([[(1, 0, 1)], [(0, 0, 1)]], [0.0, 0.25])
    """
    through = [caster.transmittance for caster, _ in closed]
    counts = [mesh.n_bodies for _, mesh in closed]
    result = batches([c if t == 0.0 else 0 for c, t in zip(counts, through, strict=True)])
    passing = [0.0] * len(result)
    for number, (t, (_, mesh)) in enumerate(zip(through, closed, strict=True)):
        if t > 0.0:
            own = batches([0] * number + [counts[number]])
            result += own
            passing += [t if mesh.how == "two-sided sheet" else t * t] * len(own)
    return result, passing


def combine_shadings(first: LightShading, second: LightShading) -> LightShading:
    """Return one light's shading whose visibility is the product of two.

    Parameters
    ----------
    first, second : LightShading
        Two lookups of the same light (e.g. a volume mask and a cube map).

    Returns
    -------
    LightShading
        Visibility ``(first) * (second)``; samplers merged, every other
        field (sources, defines, ...) concatenated without repeats.

    Examples
    --------
    >>> from pvshadows.shaders.shading import LightShading
    >>> from pvshadows.techniques.volume import combine_shadings
    >>> both = combine_shadings(LightShading(0, "a", sources=("x",)), LightShading(0, "b"))
    >>> both.visibility, both.sources
    ('(a) * (b)', ('x',))
    """
    merged = {}
    for item in fields(LightShading):
        a, b = getattr(first, item.name), getattr(second, item.name)
        if item.name == "vtk_index":
            merged[item.name] = a
        elif item.name == "visibility":
            merged[item.name] = f"({a}) * ({b})"
        elif isinstance(a, tuple):
            merged[item.name] = tuple(dict.fromkeys((*a, *b)))
        elif isinstance(a, dict) or hasattr(a, "items"):
            merged[item.name] = {**a, **b}
        else:
            merged[item.name] = a
    return LightShading(**merged)


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
    fallback: tuple[str, LightPlan] | None = None


def _homogeneous_light(plan: LightPlan) -> np.ndarray:
    """Return the light in world coordinates: (position, 1), or (direction towards it, 0)."""
    assert plan.pose is not None
    if plan.kind is LightKind.DIRECTIONAL:
        return np.array([*(-plan.pose.direction), 0.0])
    return np.array([*plan.pose.position, 1.0])


#: A light this close to a caster's face plane (fraction of the caster's size) lies in it.
ON_SURFACE = 1e-6
#: How far such a light is moved off the face for its volumes (fraction of the caster's size).
OFF_SURFACE = 1e-5


def _off_surfaces(
    light: np.ndarray, closed: list[tuple[ActorState, VolumeMesh]], notes: list[str]
) -> np.ndarray:
    """Move a point light lying in the plane of a caster's face a hair off it, outwards.

    A face in the light's plane is neither lit nor unlit, and the silhouette
    edges around it come out inconsistent: whole volumes go missing. Cast
    from 1e-5 of the caster's size outside every such face, the shadows
    differ from the exact ones by far less than a pixel.
    """
    if light[3] == 0.0:
        return light
    position = light[:3]
    push = np.zeros(3)
    for caster, mesh in closed:
        lo, hi = caster.bounds
        size = float(np.linalg.norm(hi - lo))
        if np.any(position < lo - ON_SURFACE * size) or np.any(position > hi + ON_SURFACE * size):
            continue
        model = caster.model_matrix()
        points = mesh.points @ model[:3, :3].T + model[:3, 3]
        corners = points[mesh.triangles]
        normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        length = np.linalg.norm(normals, axis=1)
        keep = length > 0.0
        unit = normals[keep] / length[keep, None]
        distance = np.einsum("ij,ij->i", unit, position - corners[keep, 0])
        touching = np.abs(distance) <= ON_SURFACE * size
        if touching.any():
            notes.append(
                f"the light lies in the plane of a face of {caster.name}: its volumes are cast "
                f"from {OFF_SURFACE:g} of its size off that face"
            )
            push += OFF_SURFACE * size * unit[touching].sum(axis=0) / max(touching.sum(), 1)
    if not push.any():
        return light
    return np.array([*(position + push), 1.0])


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
        self._fallbacks: dict[str, Technique] = {}
        self._warned: set[tuple] = set()
        self._context: FrameContext | None = None

    # -- per light ------------------------------------------------------------------------

    def update(self, plan: LightPlan, context: FrameContext) -> list[PassReport]:
        """Bring the light's shadow mask up to date for this frame.

        Parameters
        ----------
        plan : LightPlan
            The light's plan (technique ``"volume"``).
        context : FrameContext
            This frame's renderer, camera, actors, buffers and timer.

        Returns
        -------
        list of PassReport
            The passes run, reused or skipped; ``plan.notes`` gets the
            z-pass/z-fail decision and what happened to open casters.

        Raises
        ------
        OpenMeshError
            With ``on_open="raise"``, for a caster that is not closed.
        """
        self._context = context
        width, height = context.viewport_size()
        light_id = vtk_id(plan.light)
        if width < 1 or height < 1:
            dropped = self._lights.pop(light_id, None)
            if dropped is not None:
                dropped.mask.release()
            return [PassReport("shadow volumes", "skipped", "the viewport has no pixels")]
        self._ensure_target(width, height)
        state = self._lights.get(light_id)
        if state is None:
            state = self._lights[light_id] = _LightState(MaskTexture(self._window, width, height))
        settings = plan.settings
        assert settings is not None and plan.pose is not None
        closed, open_casters = self._split_casters(plan)
        reports: list[PassReport] = []
        state.fallback = self._plan_fallback(plan, open_casters)
        light = _off_surfaces(_homogeneous_light(plan), closed, plan.notes)
        enclosing = self._enclosing_caster(light, closed)
        while enclosing is not None and _holds_the_rest(enclosing, closed, context.snapshot):
            plan.notes.append(
                f"the light and every other receiver are inside {enclosing.name}: it shadows "
                "none of them, so it casts no volume"
            )
            closed = [(c, m) for c, m in closed if c is not enclosing]
            enclosing = self._enclosing_caster(light, closed)
        if enclosing is not None:
            plan.notes.append(
                f"the light is inside {enclosing.name}: everything outside it is in its shadow"
            )
            key: tuple = ("inside", plan.pose.key(), enclosing.key())
            if key != state.key:
                assert self._target is not None
                self._passes.fill(self._target, state.mask, 0.0)
                state.key, state.frame, state.draws, state.zmode = key, context.frame, [], ""
                reports.append(PassReport("shadow mask", "run", "all in shadow (light enclosed)"))
            else:
                reports.append(PassReport("shadow mask", "reused", "light still enclosed"))
            return reports + self._fallback_update(state, context)
        for caster, mesh in closed:
            if mesh.how != "closed":
                plan.notes.append(f"{caster.name} counted as {_HOW[mesh.how]}")
        extrude = settings.extrude
        if extrude == "gpu" and not self._passes.can_extrude_on_gpu():
            extrude = "cpu"
            plan.notes.append("the extruding geometry shader does not compile here: cpu extrusion")
        zmode, why = choose_zmode(
            settings.zmode, light, context.renderer, [(c.name, c.bounds) for c, _ in closed]
        )
        plan.notes.append(f"{zmode}: {why}")
        camera = _projection(context.renderer)
        key = (
            plan.pose.key(),
            zmode,
            extrude,
            camera.tobytes(),
            (width, height),
            tuple(c.key() for c in context.snapshot.actors),
            tuple((*c.key(), c.transmittance) for c, _ in closed),
        )
        if key == state.key:
            reports.append(
                PassReport(
                    f"stencil count ({zmode}, {extrude} extrusion)",
                    "reused",
                    f"camera, light and actors unchanged since frame {state.frame}: "
                    "mask still right",
                )
            )
            return reports + self._fallback_update(state, context)
        if self._depth_frame != context.frame:
            reports.append(self._depth_pass(context, camera, width, height))
        plan_batches, passing = translucent_batches(closed)
        reach = _finite_reach(context, light)
        if reach:
            plan.notes.append("parallel projection: volumes end beyond the scene, not at infinity")
        draws, built = self._volume_draws(
            plan, closed, plan_batches, camera, light, zmode, extrude, reach
        )
        reports.extend(built)
        bodies = [sum(e - s for _, s, e in batch) for batch in plan_batches]
        record = PassReport(
            f"stencil count ({zmode}, {extrude} extrusion)",
            "run",
            f"{len(closed)} closed casters, {sum(bodies)} bodies in {len(bodies)} batch(es)"
            if closed
            else "no closed caster: mask all lit",
        )
        assert self._target is not None
        with context.timer.measure(record):
            self._passes.count(self._target, state.mask, draws, zmode, passing)
        reports.append(record)
        state.key, state.frame, state.zmode = key, context.frame, zmode
        state.draws = [draw for batch in draws for draw in batch]
        return reports + self._fallback_update(state, context)

    def _ensure_target(self, width: int, height: int) -> None:
        if self._target is not None and self._target.size == (width, height):
            return
        if self._target is not None:
            self._target.release()
        for state in self._lights.values():
            state.mask.release()
        self._lights.clear()
        self._target = VolumeTarget(self._window, width, height)
        self._depth_key, self._depth_frame = None, -1

    def _split_casters(
        self, plan: LightPlan
    ) -> tuple[list[tuple[ActorState, VolumeMesh]], list[ActorState]]:
        closed, open_casters = [], []
        for caster in plan.casters:
            if abs(np.linalg.det(caster.matrix[:3, :3])) == 0.0:
                plan.notes.append(f"{caster.name} is scaled flat to nothing: it casts no shadow")
                continue
            try:
                closed.append((caster, prepared_mesh(caster.triangles, caster.name)))
            except OpenMeshError as error:
                assert plan.settings is not None
                if plan.settings.on_open == "raise":
                    require_closed([(caster.name, caster.triangles)])
                    raise error  # pragma: no cover - require_closed raised already
                open_casters.append(caster)
        return closed, open_casters

    def _plan_fallback(
        self, plan: LightPlan, open_casters: list[ActorState]
    ) -> tuple[str, LightPlan] | None:
        if not open_casters:
            return None
        from pvshadows.model.plan import SERVES
        from pvshadows.techniques import TECHNIQUE_CLASSES

        name = FALLBACK_TECHNIQUES.get(plan.kind)
        usable = name in TECHNIQUE_CLASSES and plan.kind in SERVES.get(name, ())
        names = ", ".join(c.name for c in open_casters)
        if usable:
            plan.notes.append(f"open casters cast from a {name} shadow map instead: {names}")
        else:
            plan.notes.append(
                f"open casters cast no shadow from this {plan.kind.value} light "
                f"(no shadow-map fallback for it yet): {names}"
            )
        for caster in open_casters:
            warned = (vtk_id(caster.actor), caster.triangles.version, plan.kind, usable)
            if warned in self._warned:
                continue
            self._warned.add(warned)
            reason = _open_reason(caster)
            then = (
                f"it casts its shadow from a {name} shadow map instead"
                if usable
                else f"it casts no shadow from {plan.kind.value} lights until a shadow-map "
                "fallback serves them"
            )
            warnings.warn(f"pvshadows: {reason}; {then}", stacklevel=2)
        if not usable:
            return None
        assert name is not None
        return name, replace(plan, casters=open_casters, technique=name, notes=[])

    def _fallback_update(self, state: _LightState, context: FrameContext) -> list[PassReport]:
        if state.fallback is None:
            return []
        name, subplan = state.fallback
        technique = self._fallback(name)
        reports = technique.update(subplan, context)
        for report in reports:
            report.name = f"fallback {report.name}"
        return reports

    def _fallback(self, name: str) -> Technique:
        if name not in self._fallbacks:
            from pvshadows.techniques import TECHNIQUE_CLASSES

            self._fallbacks[name] = TECHNIQUE_CLASSES[name](self._window)
        return self._fallbacks[name]

    def _enclosing_caster(
        self, light: np.ndarray, closed: list[tuple[ActorState, VolumeMesh]]
    ) -> ActorState | None:
        if light[3] == 0.0:
            return None
        position = light[:3]
        for caster, mesh in closed:
            lo, hi = caster.bounds
            if np.any(position < lo) or np.any(position > hi) or mesh.how == "two-sided sheet":
                continue
            model = np.linalg.solve(caster.model_matrix(), np.append(position, 1.0))
            if winding_number(mesh.points, mesh.triangles, model[:3] / model[3]) > 0.5:
                return caster
        return None

    def _depth_pass(
        self, context: FrameContext, camera: np.ndarray, width: int, height: int
    ) -> PassReport:
        self._depth_frame = context.frame
        actors = context.snapshot.actors
        key = (camera.tobytes(), (width, height), tuple(a.key() for a in actors))
        if key == self._depth_key:
            return PassReport(
                "volume depth pre-pass", "reused", "camera and actors unchanged: depth still right"
            )
        draws = [
            DepthDraw(context.buffers.get(actor), camera @ actor.model_matrix()) for actor in actors
        ]
        self._depth_key = key
        assert self._target is not None
        return self._passes.depth(self._target, draws, context.timer)

    def _volume_draws(
        self,
        plan: LightPlan,
        closed: list[tuple[ActorState, VolumeMesh]],
        plan_batches: list[list[tuple]],
        camera: np.ndarray,
        light: np.ndarray,
        zmode: str,
        extrude: str,
        reach: float,
    ) -> tuple[list[list[VolumeDraw]], list[PassReport]]:
        """Each batch's draws, and a report of the CPU rebuild (``extrude="cpu"``).

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
            model = caster.model_matrix()
            light_model = np.linalg.solve(model, light)
            if light_model[3] != 0.0:
                light_model = np.append(light_model[:3] / light_model[3], 1.0)
            mirrored = bool(np.linalg.det(model[:3, :3]) < 0.0)
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
                    draws.append(
                        VolumeDraw(
                            buffers,
                            "gpu",
                            camera @ model,
                            light_model,
                            mirrored,
                            [span],
                            extrude_to,
                        )
                    )
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
                    draws.append(
                        VolumeDraw(
                            volume.buffers, "cpu", camera @ model, light_model, mirrored, pieces
                        )
                    )
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
        plan: LightPlan,
        caster: ActorState,
        mesh: VolumeMesh,
        light_model: np.ndarray,
        extrude_to: float,
    ) -> _CpuVolume:
        cache_key = (vtk_id(plan.light), vtk_id(caster.actor))
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

    def shading(self, plan: LightPlan) -> LightShading:
        """Return how receivers read this light's mask (and fallback map).

        Parameters
        ----------
        plan : LightPlan
            The light's plan.

        Returns
        -------
        LightShading
            The mask lookup, times the fallback's lookup when open casters
            cast from a shadow map.
        """
        i = plan.vtk_index
        own = LightShading(
            i,
            f"pvsVolumeShadow(pvsMask{i}, pvsMaskViewport{i}, pvsLightVC{i}, vertexVC.xyz, "
            "pvsNormalVC)",
            {f"pvsMask{i}": "sampler2D"},
            sources=("shadow_volume.glsl",),
        )
        state = self._lights.get(vtk_id(plan.light))
        if state is None:
            return LightShading(i, "1.0")  # nothing counted this frame (no pixels)
        if state.fallback is None:
            return own
        name, subplan = state.fallback
        return combine_shadings(own, self._fallback(name).shading(subplan))

    def activate(self, plan: LightPlan, context: FrameContext) -> dict[str, object]:
        """Bind the light's mask and return the receivers' uniforms.

        Parameters
        ----------
        plan : LightPlan
            The light's plan.
        context : FrameContext
            This frame's renderer and camera.

        Returns
        -------
        dict
            Uniform names and values for every receiver.
        """
        state = self._lights.get(vtk_id(plan.light))
        if state is None:
            return {}
        state.mask.texture.Activate()
        i = plan.vtk_index
        target = context.target()
        (x0, y0), (width, height) = target.origin, target.size
        light_vc = context.view.light_in_view(_homogeneous_light(plan))
        uniforms: dict[str, object] = {
            f"pvsMask{i}": state.mask.texture.GetTextureUnit(),
            f"pvsMaskViewport{i}": (float(x0), float(y0), float(width), float(height)),
            f"pvsLightVC{i}": light_vc,
        }
        if state.fallback is not None:
            name, subplan = state.fallback
            uniforms.update(self._fallback(name).activate(subplan, context))
        return uniforms

    def deactivate(self) -> None:
        """Free the texture units bound by :meth:`activate`."""
        for state in self._lights.values():
            state.mask.texture.Deactivate()
        for technique in self._fallbacks.values():
            technique.deactivate()

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
            if state.draws:
                self._passes.overlay(state.draws, (x0, y0, width, height), OVERLAY_COLOUR)

    def mask_of(self, light: vtk.vtkLight) -> MaskTexture | None:
        """Return the mask kept for a light, if any (for tests and debugging)."""
        state = self._lights.get(vtk_id(light))
        return state.mask if state else None

    def zmode_of(self, light: vtk.vtkLight) -> str | None:
        """Return the counting used for a light in its last update: ``"zpass"`` or ``"zfail"``."""
        state = self._lights.get(vtk_id(light))
        return state.zmode if state else None

    def keep_only(self, plans: list[LightPlan]) -> None:
        """Release the masks of lights that no longer use volumes, and unused volume data.

        Parameters
        ----------
        plans : list of LightPlan
            This frame's plans.
        """
        using = [p for p in plans if p.technique == self.name]
        alive = {vtk_id(p.light) for p in using}
        for key in set(self._lights) - alive:
            self._lights.pop(key).mask.release()
        casters = {vtk_id(c.actor) for p in using for c in p.casters}
        for mesh_key in set(self._meshes) - casters:
            self._meshes.pop(mesh_key)[1].release()
        for cpu_key in [k for k in self._cpu if k[0] not in alive or k[1] not in casters]:
            self._cpu.pop(cpu_key).buffers.release()
        fallback_plans = [s.fallback[1] for s in self._lights.values() if s.fallback]
        for technique in self._fallbacks.values():
            technique.keep_only(fallback_plans)
        if not self._lights and self._target is not None:
            self._target.release()
            self._target = None

    def release(self) -> None:
        """Release every framebuffer, mask, buffer and program."""
        self.keep_only([])
        for technique in self._fallbacks.values():
            technique.release()
        self._fallbacks.clear()
        self._passes.release()


def _open_reason(caster: ActorState) -> str:
    try:
        prepared_mesh(caster.triangles, caster.name)
    except OpenMeshError as error:
        return str(error)
    return f"{caster.name} is open"  # pragma: no cover


def _finite_reach(context: FrameContext, light: np.ndarray) -> float:
    """Return 0 (extrude to infinity), or how far to extrude for a parallel projection.

    Far enough that every volume reaches past every actor: four times the
    diagonal of the box around the actors and a positional light.
    """
    if not context.camera.GetParallelProjection():
        return 0.0
    boxes = [actor.bounds for actor in context.snapshot.actors]
    if light[3] != 0.0:
        boxes.append(np.stack([light[:3], light[:3]]))
    corners = np.concatenate(boxes)
    return 4.0 * max(float(np.linalg.norm(np.ptp(corners, axis=0))), 1e-300)


def _projection(renderer: vtk.vtkRenderer) -> np.ndarray:
    camera = renderer.GetActiveCamera()
    matrix = camera.GetCompositeProjectionTransformMatrix(renderer.GetTiledAspectRatio(), -1, 1)
    return pv.array_from_vtkmatrix(matrix)


def _holds_the_rest(
    enclosing: ActorState, closed: list[tuple[ActorState, VolumeMesh]], snapshot: Snapshot
) -> bool:
    """Whether every receiver but ``enclosing`` lies inside it (a room around the scene)."""
    mesh = next(m for c, m in closed if c is enclosing)
    others = [r for r in snapshot.receivers if r is not enclosing]
    inverse = np.linalg.inv(enclosing.model_matrix())
    for receiver in others:
        centre = inverse @ np.append(receiver.bounds.mean(axis=0), 1.0)
        if winding_number(mesh.points, mesh.triangles, centre[:3] / centre[3]) < 0.5:
            return False
    return bool(others)
