"""Exact per-pixel light visibility for a camera view, by ray casting with Embree.

Every shadow technique in pvshadows is measured against this module. For each
pixel it casts one primary ray through the pixel centre, takes the first
surface the ray meets and casts shadow rays from that point towards the light.

All geometry is handled in float64 in a *local frame*: world coordinates minus
the centre of the meshes' bounds, divided by the length of the bounds'
diagonal, so that the scene spans about ``[-0.5, 0.5]`` whatever its size or
position. Embree (through :class:`trimesh.ray.ray_pyembree.RayMeshIntersector`)
works in float32 and is only asked *which* triangle a ray meets first; *where*
it meets it is recomputed in float64 from that triangle's plane. Primary rays
start where they enter the scene's bounds, so that their float32 origins stay
close to the geometry even for distant cameras.

Shadow rays run from the light to the surface point, and the point is lit
when the first thing they meet is its own surface (within
:data:`RAY_TOLERANCE`): no offset proportional to the scene is needed, so a
small object in a huge scene still casts its shadow. Blockers closer to the
surface than the float32 resolution of the whole scene (about ``1e-7`` of its
diagonal) count as touching it.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from pvshadows.scene.lights import LightKind, LightPose

RAY_TOLERANCE = 1e-7
"""How close to a surface point (fraction of the scene diagonal) a shadow ray's hit is that point.

Shadow rays run from the light to the point, and a point is lit when the
first thing the ray meets is the point's own surface. Embree works in float32,
so it only picks *which* triangle a ray meets first; the distance is
recomputed in float64 from that triangle's plane, where the point's own
surface lands within about ``1e-12`` of the point. Anything met more than
``RAY_TOLERANCE`` before the point blocks it: so no detail is lost however
small it is next to the scene (a box 1 unit tall on a ground 1e5 wide), and a
blocker closer to the surface than ``1e-7`` of the diagonal, the float32
resolution of the scene, counts as touching it.
"""

LIGHT_CLEARANCE = 1e-7
"""Shadow rays start this far from the light (fraction of the scene diagonal), so
that a light lying on a surface is not blocked by that surface."""

MAX_SAMPLES = 4096
"""Largest number of shadow rays per pixel."""

MIN_INCIDENCE = 1e-4
"""Smallest cosine of the angle between a surface's normal and the light for it to be lit.

A surface that the light grazes at less than about 0.006 degrees receives less
than 1e-4 of full irradiance; it counts as facing away, here and in the
shaders (``glsl/``), so that a light lying in a surface's own plane does not
light it by the sign of a rounding error.
"""

LIGHT_SKIP = 1e-5
"""A shadow ray that meets a surface closer than this to the light (fraction of the scene
diagonal) looks again from there: the light lies on that surface."""

_BOX_MARGIN = 1e-3
"""Margin around the scene's bounds, as a fraction of its diagonal, where primary rays start."""

_CHUNK_RAYS = 1 << 18
#: Most translucent surfaces a shadow ray goes through; a ray meeting more is dark.
_MAX_CROSSINGS = 32
#: How far past a translucent surface a shadow ray starts again (local frame, float32-safe).
_CROSSING_STEP = 1e-5
"""Most rays handed to Embree, and held in memory, at once."""

_BLOCK_PIXELS = 1 << 16
"""Pixels traced together (a constant, so that seeded results do not depend on it)."""

_GOLDEN_ANGLE = math.pi * (3.0 - math.sqrt(5.0))

_INSTALL_HINT = (
    'pvshadows.verify.reference needs Embree: install it with pip install "pvshadows[reference]" '
    "(or pip install embreex)"
)


@dataclass(frozen=True)
class SceneMesh:
    """One actor's surface in world coordinates.

    Attributes
    ----------
    points : numpy.ndarray
        World coordinates, float64 ``(n, 3)``; they must be finite.
    triangles : numpy.ndarray
        Point indices, integer ``(m, 3)``. A mesh without triangles is skipped.
    caster : bool, default: True
        Whether the surface blocks light (shadow rays test it).
    receiver : bool, default: True
        Whether the surface shows shadows; pixels whose visible surface is
        not a receiver are NaN in :attr:`ReferenceResult.visibility`.
    opacity : float, default: 1.0
        Share of the light a caster's surface stops, 0 to 1: each of its
        surfaces a shadow ray crosses lets ``1 - opacity`` through (a closed
        body twice, as VTK's blending draws both its sides).
    faces_seen : bool, default: True
        Whether the camera sees its faces. ``False`` for an actor drawn as
        a wireframe or as points: primary rays pass through its faces (what
        lies behind shows between its lines), while shadow rays still stop
        on them when it is a caster, as shadow maps draw its triangles.

    Raises
    ------
    ValueError
        If the arrays have the wrong shape, points are not finite, an
        index is out of range or the opacity is not in [0, 1].

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.verify.reference import SceneMesh
    >>> quad = SceneMesh(
    ...     points=np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]]),
    ...     triangles=np.array([[0, 1, 2], [0, 2, 3]]),
    ... )
    >>> quad.points.dtype, quad.triangles.shape
    (dtype('float64'), (2, 3))
    """

    points: np.ndarray
    triangles: np.ndarray
    caster: bool = True
    receiver: bool = True
    opacity: float = 1.0
    faces_seen: bool = True

    def __post_init__(self) -> None:
        if not 0.0 <= self.opacity <= 1.0:
            msg = f"SceneMesh opacity must be from 0 to 1, got {self.opacity!r}"
            raise ValueError(msg)
        points = np.asarray(self.points, dtype=np.float64)
        triangles = np.asarray(self.triangles)
        if triangles.size == 0:
            triangles = triangles.reshape(0, 3)
        if points.ndim != 2 or points.shape[1] != 3:
            msg = f"SceneMesh points must have shape (n, 3), got {points.shape}"
            raise ValueError(msg)
        if triangles.ndim != 2 or triangles.shape[1] != 3:
            msg = f"SceneMesh triangles must have shape (m, 3), got {triangles.shape}"
            raise ValueError(msg)
        if not np.isfinite(points).all():
            msg = "SceneMesh points must be finite, got NaN or infinite coordinates"
            raise ValueError(msg)
        triangles = triangles.astype(np.int64)
        if triangles.size and (triangles.min() < 0 or triangles.max() >= points.shape[0]):
            msg = (
                f"SceneMesh triangles must index the {points.shape[0]} points, got indices "
                f"from {triangles.min()} to {triangles.max()}"
            )
            raise ValueError(msg)
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "triangles", triangles)


@dataclass(frozen=True)
class ViewSpec:
    """What the camera sees: the world to NDC matrix and the image size.

    Attributes
    ----------
    world_to_ndc : numpy.ndarray
        Float64 ``(4, 4)`` matrix acting on column vectors ``[x, y, z, 1]``,
        as ``camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1)``
        gives it: the near plane maps to NDC ``z = -1``, the far plane to
        ``z = 1``. Perspective and parallel projections both work.
    width : int
        Image width in pixels.
    height : int
        Image height in pixels.

    Raises
    ------
    ValueError
        If the matrix is not a finite ``(4, 4)`` array or the size is not
        positive.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.verify.reference import ViewSpec
    >>> camera = pv.Camera()
    >>> matrix = pv.array_from_vtkmatrix(
    ...     camera.GetCompositeProjectionTransformMatrix(320 / 240, -1, 1)
    ... )
    >>> ViewSpec(matrix, 320, 240).world_to_ndc.shape
    (4, 4)
    """

    world_to_ndc: np.ndarray
    width: int
    height: int

    def __post_init__(self) -> None:
        matrix = np.asarray(self.world_to_ndc, dtype=np.float64)
        if matrix.shape != (4, 4) or not np.isfinite(matrix).all():
            msg = f"ViewSpec world_to_ndc must be a finite (4, 4) matrix, got {matrix!r}"
            raise ValueError(msg)
        for name in ("width", "height"):
            value = getattr(self, name)
            if not _is_int(value) or value < 1:
                msg = f"ViewSpec {name} must be a positive integer, got {value!r}"
                raise ValueError(msg)
            object.__setattr__(self, name, int(value))
        object.__setattr__(self, "world_to_ndc", matrix)


@dataclass(frozen=True)
class ReferenceResult:
    """Per-pixel light visibility; row 0 is the top of the image, as in a screenshot.

    Attributes
    ----------
    visibility : numpy.ndarray
        Float32 ``(H, W)`` fraction of the light that reaches the surface
        seen in each pixel, in ``[0, 1]``; 0 on surfaces that face away from
        the light or lie outside a spot light's cone; NaN where no receiver
        surface is seen.
    lit_side : numpy.ndarray
        Bool ``(H, W)``: a receiver is seen, the side of it that faces the
        camera faces the light centre and, for a spot light, the point is
        inside the cone.
    surface : numpy.ndarray
        Bool ``(H, W)``: a receiver surface is seen.
    mesh_index : numpy.ndarray
        Int32 ``(H, W)``: index of the :class:`SceneMesh` seen, -1 for none.
    depth : numpy.ndarray
        Float64 ``(H, W)``: NDC ``z`` in ``[-1, 1]`` of the point seen, NaN
        where nothing is hit, to compare with a z-buffer.

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.verify.reference import SceneMesh, ViewSpec, trace_reference
    >>> quad = SceneMesh(
    ...     np.array([[-2, -2, 0], [2, -2, 0], [2, 2, 0], [-2, 2, 0]]),
    ...     np.array([[0, 1, 2], [0, 2, 3]]),
    ... )
    >>> view = ViewSpec(np.diag([1.0, 1.0, -1.0, 1.0]), 4, 3)
    >>> sun = LightPose(LightKind.DIRECTIONAL, np.zeros(3), np.array([0.0, 0.0, -1.0]), 90.0)
    >>> result = trace_reference([quad], view, sun)
    >>> result.visibility.shape, float(result.depth[0, 0])
    ((3, 4), 0.0)
    """

    visibility: np.ndarray
    lit_side: np.ndarray
    surface: np.ndarray
    mesh_index: np.ndarray
    depth: np.ndarray


#: Smallest size of a mesh, as a fraction of the whole scene's, that float32 ray casting resolves.
SMALLEST_TRACEABLE = 1e-6


def require_traceable(sizes: dict[str, float]) -> None:
    """Refuse a scene whose meshes span more sizes than float32 ray casting resolves.

    Embree intersects in float32 in a frame scaled to the whole scene, so a
    mesh below :data:`SMALLEST_TRACEABLE` of the scene's size (say a 2-unit
    box next to a sphere of radius 1e30) is traced as a speck or not at all:
    its shadows would be wrong, silently.

    Parameters
    ----------
    sizes : dict
        Each mesh's name and the diagonal of its world bounds.

    Raises
    ------
    ValueError
        Naming the smallest mesh, its size and the scene's.

    Examples
    --------
    >>> from pvshadows.verify.reference import require_traceable
    >>> require_traceable({"box": 1.7, "ground": 14.1})
    >>> require_traceable({"box": 1.7, "sky": 2e30})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: reference(): box is 1.7 across in a scene 2e+30 across (sky); float32 ...
    """
    if not sizes:
        return
    largest = max(sizes, key=sizes.__getitem__)
    smallest = min(sizes, key=sizes.__getitem__)
    if sizes[smallest] < SMALLEST_TRACEABLE * sizes[largest]:
        msg = (
            f"reference(): {smallest} is {sizes[smallest]:.3g} across in a scene "
            f"{sizes[largest]:.3g} across ({largest}); float32 ray casting resolves meshes "
            f"down to {SMALLEST_TRACEABLE:g} of the scene, so it cannot trace this one"
        )
        raise ValueError(msg)


def trace_reference(
    meshes: Sequence[SceneMesh],
    view: ViewSpec,
    light: LightPose,
    *,
    light_size: float = 0.0,
    samples: int = 1,
    seed: int = 0,
) -> ReferenceResult:
    """Ray trace the exact light visibility of every pixel of a view.

    One primary ray per pixel, through the pixel centre, from the near plane
    to the far plane, meets the first triangle of any mesh. Where that mesh
    is a receiver, its geometric normal is turned towards the camera and
    shadow rays go from the point to the light; only meshes that are casters
    block them.

    Parameters
    ----------
    meshes : sequence of SceneMesh
        The surfaces; :attr:`ReferenceResult.mesh_index` indexes this sequence.
    view : ViewSpec
        The camera's world to NDC matrix and the image size.
    light : LightPose
        The light. Points outside a spot light's cone are not lit.
    light_size : float, default: 0.0
        0 for hard shadows from a point-like light. For point and spot
        lights, the radius (world units) of a spherical emitter centred on
        the light position; for directional lights, the angular radius in
        degrees of the emitter (the sun is about 0.27).
    samples : int, default: 1
        Shadow rays per pixel, 1 to 4096; more than 1 needs ``light_size > 0``.
        Point and spot lights are sampled over the disk of radius
        ``light_size`` that faces the point, directional lights over the cone
        of directions; both with a stratified spiral pattern that a seeded
        random rotation and radial jitter change from pixel to pixel.
    seed : int, default: 0
        Seed of those per-pixel variations: the same seed gives the same
        result.

    Returns
    -------
    ReferenceResult
        Visibility (the fraction of unblocked shadow rays; rays that would
        leave below the surface's tangent plane count as blocked), where the
        light side is, where receivers are, which mesh each pixel sees and
        its NDC depth.

    Raises
    ------
    ValueError
        If ``samples`` or ``light_size`` is out of range or they disagree
        (soft shadows need both ``samples > 1`` and ``light_size > 0``), or
        the light or view cannot be used.
    TypeError
        If an item of ``meshes`` is not a :class:`SceneMesh`.
    ImportError
        If Embree (the ``embreex`` package) is not installed.

    Examples
    --------
    A square one unit above the ground, lit at 45 degrees, seen from straight
    above by a parallel camera: its shadow falls one unit further along +x.

    >>> import numpy as np
    >>> from pvshadows.scene.lights import LightKind, LightPose
    >>> from pvshadows.verify.reference import SceneMesh, ViewSpec, trace_reference
    >>> def square(half, z):
    ...     corners = [[-half, -half, z], [half, -half, z], [half, half, z], [-half, half, z]]
    ...     return SceneMesh(np.array(corners), np.array([[0, 1, 2], [0, 2, 3]]))
    >>> view = ViewSpec(np.diag([0.5, 0.5, -0.2, 1.0]), 4, 4)
    >>> sun = LightPose(
    ...     LightKind.DIRECTIONAL, np.zeros(3), np.array([1.0, 0.0, -1.0]) / np.sqrt(2), 90.0
    ... )
    >>> result = trace_reference([square(2.0, 0.0), square(0.6, 1.0)], view, sun)
    >>> result.mesh_index
    array([[0, 0, 0, 0],
           [0, 1, 1, 0],
           [0, 1, 1, 0],
           [0, 0, 0, 0]], dtype=int32)
    >>> result.visibility
    array([[1., 1., 1., 1.],
           [1., 1., 1., 0.],
           [1., 1., 1., 0.],
           [1., 1., 1., 1.]], dtype=float32)
    """
    light_size, samples = _check_options(light, light_size, samples)
    intersector_type = _require_embree()
    meshes = list(meshes)
    for i, mesh in enumerate(meshes):
        if not isinstance(mesh, SceneMesh):
            msg = f"meshes[{i}] must be a SceneMesh, got {type(mesh).__name__}"
            raise TypeError(msg)
    n_pixels = view.width * view.height
    flat = _FlatResult.empty(n_pixels)
    frame = _Frame.around(meshes)
    primary = (
        None
        if frame is None
        else _Triangles.build(meshes, frame, intersector_type, lambda mesh: mesh.faces_seen)
    )
    if frame is not None and primary is not None:
        tracer = _Tracer(
            primary=primary,
            shadow=_Triangles.build(meshes, frame, intersector_type, lambda mesh: mesh.caster),
            camera=_Camera.of(view, frame),
            emitter=_Emitter.from_pose(light, frame, light_size, samples),
            receivers=np.array([mesh.receiver for mesh in meshes], dtype=bool),
            transmittance=np.array([1.0 - mesh.opacity for mesh in meshes]),
        )
        rng = np.random.default_rng(seed)
        for pixels in _blocks(n_pixels):
            tracer.trace(pixels, rng.random((pixels.size, 2)), flat)
    return flat.reshape(view.height, view.width)


def _is_int(value: object) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _check_options(light: LightPose, light_size: float, samples: int) -> tuple[float, int]:
    if not _is_int(samples) or not 1 <= samples <= MAX_SAMPLES:
        msg = f"samples must be an integer from 1 to {MAX_SAMPLES}, got {samples!r}"
        raise ValueError(msg)
    try:
        size = float(light_size)
    except (TypeError, ValueError):
        size = math.nan
    if not (math.isfinite(size) and size >= 0.0):
        msg = f"light_size must be a finite number >= 0, got {light_size!r}"
        raise ValueError(msg)
    if light.kind is LightKind.DIRECTIONAL and size >= 90.0:
        msg = (
            f"light_size of a directional light is an angular radius in degrees and must be "
            f"below 90, got {light_size!r}"
        )
        raise ValueError(msg)
    if (samples > 1) != (size > 0.0):
        msg = (
            f"soft shadows need both samples > 1 and light_size > 0, hard shadows samples=1 "
            f"and light_size=0; got samples={samples!r} and light_size={light_size!r}"
        )
        raise ValueError(msg)
    return size, int(samples)


def _require_embree() -> type:
    import trimesh  # only a reference pays for trimesh and Embree (0.3 s of imports)

    if not trimesh.ray.has_embree:
        raise ImportError(_INSTALL_HINT)
    from trimesh.ray.ray_pyembree import RayMeshIntersector

    return RayMeshIntersector


def _blocks(n_pixels: int) -> Iterator[np.ndarray]:
    for start in range(0, n_pixels, _BLOCK_PIXELS):
        yield np.arange(start, min(start + _BLOCK_PIXELS, n_pixels))


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.einsum("...i,...i->...", a, b)


def _unit(vectors: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    length = np.sqrt(_dot(vectors, vectors))
    with np.errstate(divide="ignore", invalid="ignore"):
        return vectors / length[..., None], length


def _slab(
    origins: np.ndarray, directions: np.ndarray, lo: np.ndarray, hi: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Distances along the rays where they enter and leave axis-aligned boxes."""
    with np.errstate(divide="ignore", invalid="ignore"):
        near = (lo - origins) / directions
        far = (hi - origins) / directions
    enter = np.fmax.reduce(np.fmin(near, far), axis=-1)
    leave = np.fmin.reduce(np.fmax(near, far), axis=-1)
    return enter, leave


def _perpendicular_basis(axis: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit vectors that make a right-handed orthonormal basis with each unit axis.

    Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
    """
    x, y, z = axis[..., 0], axis[..., 1], axis[..., 2]
    sign = np.where(z >= 0.0, 1.0, -1.0)
    a = -1.0 / (sign + z)
    b = x * y * a
    first = np.stack([1.0 + sign * x * x * a, sign * b, -sign * x], axis=-1)
    second = np.stack([b, sign + y * y * a, -y], axis=-1)
    return first, second


@dataclass(frozen=True)
class _Frame:
    """The local frame: ``local = (world - center) / scale``."""

    center: np.ndarray
    scale: float

    @classmethod
    def around(cls, meshes: Sequence[SceneMesh]) -> _Frame | None:
        used = [mesh.points[mesh.triangles.ravel()] for mesh in meshes if mesh.triangles.shape[0]]
        if not used:
            return None
        lo = np.min([points.min(axis=0) for points in used], axis=0)
        hi = np.max([points.max(axis=0) for points in used], axis=0)
        scale = float(np.linalg.norm(hi - lo))
        if not scale > 0.0:
            return None
        return cls(0.5 * (lo + hi), scale)

    def to_local(self, world: np.ndarray) -> np.ndarray:
        return (world - self.center) / self.scale

    def local_to_world(self) -> np.ndarray:
        matrix = np.diag([self.scale, self.scale, self.scale, 1.0])
        matrix[:3, 3] = self.center
        return matrix


@dataclass(frozen=True)
class _Triangles:
    """Triangles of some meshes in the local frame, with an Embree scene of them."""

    corners: np.ndarray
    normals: np.ndarray
    owner: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    intersector: Any  # trimesh's ray intersector (embree or numpy), untyped

    @classmethod
    def build(
        cls,
        meshes: Sequence[SceneMesh],
        frame: _Frame,
        intersector_type: type,
        keep: Callable[[SceneMesh], bool],
    ) -> _Triangles | None:
        chosen = [(i, m) for i, m in enumerate(meshes) if keep(m) and m.triangles.shape[0]]
        if not chosen:
            return None
        points = [frame.to_local(mesh.points) for _, mesh in chosen]
        offsets = np.cumsum([0] + [p.shape[0] for p in points[:-1]])
        faces = np.concatenate([m.triangles + o for (_, m), o in zip(chosen, offsets, strict=True)])
        vertices = np.concatenate(points)
        corners = vertices[faces]
        normals, _ = _unit(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]))
        owner = np.concatenate([np.full(m.triangles.shape[0], i, np.int32) for i, m in chosen])
        import trimesh

        mesh = trimesh.Trimesh(vertices=vertices, faces=faces, process=False, validate=False)
        intersector = intersector_type(mesh, scale_to_box=False)
        return cls(
            corners,
            np.nan_to_num(normals),
            owner,
            vertices.min(axis=0),
            vertices.max(axis=0),
            intersector,
        )

    def first_hit(
        self, origins: np.ndarray, directions: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Return the first triangle each ray meets (-1 for none) and its distance (inf)."""
        triangle = np.full(origins.shape[0], -1, dtype=np.int64)
        for start in range(0, origins.shape[0], _CHUNK_RAYS):
            part = slice(start, start + _CHUNK_RAYS)
            triangle[part] = self.intersector.intersects_first(origins[part], directions[part])
        distance = np.full(origins.shape[0], np.inf)
        hit = triangle >= 0
        distance[hit] = self._distance(triangle[hit], origins[hit], directions[hit])
        return triangle, distance

    def _distance(
        self, triangle: np.ndarray, origins: np.ndarray, directions: np.ndarray
    ) -> np.ndarray:
        """Float64 distance to the plane of the triangle, clamped to the triangle's box.

        The clamp only matters for rays nearly parallel to the triangle, whose
        plane distance is ill-conditioned.
        """
        corners = self.corners[triangle]
        normals = self.normals[triangle]
        with np.errstate(divide="ignore", invalid="ignore"):
            distance = _dot(normals, corners[:, 0] - origins) / _dot(normals, directions)
        enter, leave = _slab(origins, directions, corners.min(axis=1), corners.max(axis=1))
        box = enter <= leave
        with np.errstate(invalid="ignore"):
            inside = np.where(np.isfinite(distance), distance, 0.5 * (enter + leave))
        clamped = np.clip(inside, enter, np.maximum(enter, leave))
        return np.where(box, clamped, distance)


@dataclass(frozen=True)
class _Camera:
    """Primary rays of a view, in the local frame."""

    ndc_to_local: np.ndarray
    width: int
    height: int

    @classmethod
    def of(cls, view: ViewSpec, frame: _Frame) -> _Camera:
        local_to_ndc = view.world_to_ndc @ frame.local_to_world()
        try:
            inverse = np.linalg.inv(local_to_ndc)
        except np.linalg.LinAlgError:
            inverse = np.full((4, 4), np.nan)
        if not np.isfinite(inverse).all():
            msg = f"ViewSpec world_to_ndc must be invertible, got {view.world_to_ndc!r}"
            raise ValueError(msg)
        return cls(inverse, view.width, view.height)

    def rays(self, pixels: np.ndarray) -> tuple[np.ndarray, ...]:
        """Near points, unit directions, near to far lengths and the two homogeneous w."""
        row, column = np.divmod(pixels, self.width)
        x = 2.0 * (column + 0.5) / self.width - 1.0
        y = 1.0 - 2.0 * (row + 0.5) / self.height
        ones = np.ones_like(x)
        near = np.stack([x, y, -ones, ones], axis=-1) @ self.ndc_to_local.T
        far = np.stack([x, y, ones, ones], axis=-1) @ self.ndc_to_local.T
        with np.errstate(divide="ignore", invalid="ignore"):
            start = near[:, :3] / near[:, 3:]
            end = far[:, :3] / far[:, 3:]
        direction, length = _unit(end - start)
        return start, direction, length, near[:, 3], far[:, 3]


@dataclass(frozen=True)
class _Emitter:
    """The light in the local frame, and how to sample it."""

    kind: LightKind
    position: np.ndarray
    direction: np.ndarray
    cos_cone: float
    radius: float
    cap_height: float
    samples: int

    @classmethod
    def from_pose(
        cls, light: LightPose, frame: _Frame, light_size: float, samples: int
    ) -> _Emitter:
        position = np.asarray(light.position, dtype=np.float64)
        direction, length = _unit(np.asarray(light.direction, dtype=np.float64))
        if not (np.isfinite(position).all() and np.isfinite(direction).all() and length > 0):
            msg = (
                f"light position must be finite and direction finite and non-zero, got "
                f"position {light.position!r} and direction {light.direction!r}"
            )
            raise ValueError(msg)
        spot = light.kind is LightKind.SPOT
        return cls(
            kind=light.kind,
            position=frame.to_local(position),
            direction=direction,
            cos_cone=math.cos(math.radians(light.cone_angle)) if spot else -math.inf,
            radius=light_size / frame.scale,
            cap_height=2.0 * math.sin(math.radians(light_size) / 2.0) ** 2,
            samples=samples,
        )

    def lit_side(self, points: np.ndarray, normals: np.ndarray) -> np.ndarray:
        """Whether each surface faces the light centre and lies inside the cone."""
        if self.kind is LightKind.DIRECTIONAL:
            return _dot(normals, -self.direction) > MIN_INCIDENCE
        to_light, _ = _unit(self.position - points)
        facing = _dot(normals, to_light) > MIN_INCIDENCE
        return facing & (_dot(-to_light, self.direction) >= self.cos_cone)

    def sample_rays(
        self, points: np.ndarray, normals: np.ndarray, variation: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Shadow ray directions ``(c, N, 3)``, distances to the light and if above the surface.

        ``variation`` holds each point's radial jitter and rotation, in [0, 1).
        """
        k = np.arange(self.samples)
        area = (k + variation[:, :1]) / self.samples
        angle = _GOLDEN_ANGLE * k + 2.0 * math.pi * variation[:, 1:]
        around = np.stack([np.cos(angle), np.sin(angle)], axis=-1)
        if self.kind is LightKind.DIRECTIONAL:
            return self._directional_rays(normals, area, around)
        return self._positional_rays(points, normals, area, around)

    def _directional_rays(
        self, normals: np.ndarray, area: np.ndarray, around: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        axis = -self.direction
        first, second = _perpendicular_basis(axis)
        height = area * self.cap_height
        sine = np.sqrt(height * (2.0 - height))
        directions = (
            (1.0 - height)[..., None] * axis
            + (sine * around[..., 0])[..., None] * first
            + (sine * around[..., 1])[..., None] * second
        )
        above = _dot(directions, normals[:, None]) > 0.0
        return directions, np.full(area.shape, np.inf), above

    def _positional_rays(
        self, points: np.ndarray, normals: np.ndarray, area: np.ndarray, around: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        axis, _ = _unit(self.position - points)
        first, second = _perpendicular_basis(axis)
        radius = self.radius * np.sqrt(area)
        targets = (
            self.position
            + (radius * around[..., 0])[..., None] * first[:, None]
            + (radius * around[..., 1])[..., None] * second[:, None]
        )
        directions, distance = _unit(targets - points[:, None])
        above = _dot(targets - points[:, None], normals[:, None]) > 0.0
        return directions, distance, above


@dataclass
class _FlatResult:
    """Result arrays over flat pixel indices."""

    visibility: np.ndarray
    lit_side: np.ndarray
    surface: np.ndarray
    mesh_index: np.ndarray
    depth: np.ndarray

    @classmethod
    def empty(cls, n_pixels: int) -> _FlatResult:
        return cls(
            np.full(n_pixels, np.nan, dtype=np.float32),
            np.zeros(n_pixels, dtype=bool),
            np.zeros(n_pixels, dtype=bool),
            np.full(n_pixels, -1, dtype=np.int32),
            np.full(n_pixels, np.nan),
        )

    def reshape(self, height: int, width: int) -> ReferenceResult:
        return ReferenceResult(
            *(getattr(self, field.name).reshape(height, width) for field in fields(self))
        )


@dataclass(frozen=True)
class _Hits:
    """What some primary rays see: ray and triangle indices, local points, normals, NDC z."""

    rays: np.ndarray
    triangles: np.ndarray
    points: np.ndarray
    normals: np.ndarray
    depth: np.ndarray


@dataclass(frozen=True)
class _Tracer:
    """Everything one call traces with; fills a :class:`_FlatResult` block by block."""

    primary: _Triangles
    shadow: _Triangles | None
    camera: _Camera
    emitter: _Emitter
    receivers: np.ndarray
    transmittance: np.ndarray

    def trace(self, pixels: np.ndarray, variation: np.ndarray, out: _FlatResult) -> None:
        """Fill ``out`` at ``pixels``; ``variation`` holds their sample pattern jitters."""
        hits = self._primary(pixels)
        owner = self.primary.owner[hits.triangles]
        out.mesh_index[pixels[hits.rays]] = owner
        out.depth[pixels[hits.rays]] = hits.depth
        receiver = self.receivers[owner]
        rays = hits.rays[receiver]
        pixels, variation = pixels[rays], variation[rays]
        points, normals = hits.points[receiver], hits.normals[receiver]
        lit = self.emitter.lit_side(points, normals)
        out.surface[pixels] = True
        out.lit_side[pixels] = lit
        out.visibility[pixels] = 0.0
        out.visibility[pixels[lit]] = self._visibility(points[lit], normals[lit], variation[lit])

    def _primary(self, pixels: np.ndarray) -> _Hits:
        """Trace the primary rays of ``pixels`` from where they enter the scene's bounds."""
        start, direction, length, w_near, w_far = self.camera.rays(pixels)
        lo, hi = self.primary.lo - _BOX_MARGIN, self.primary.hi + _BOX_MARGIN
        enter, leave = _slab(start, direction, lo, hi)
        enter = np.maximum(enter, 0.0)
        active = np.flatnonzero(enter <= np.minimum(leave, length))
        origins = start[active] + enter[active, None] * direction[active]
        triangle, distance = self.primary.first_hit(origins, direction[active])
        travel = (enter[active] + distance) / length[active]
        seen = (triangle >= 0) & (travel <= 1.0)
        index = active[seen]
        points = origins[seen] + distance[seen, None] * direction[index]
        normals = self.primary.normals[triangle[seen]]
        normals = normals * np.where(_dot(normals, direction[index]) > 0.0, -1.0, 1.0)[:, None]
        travel = travel[seen]
        w_start, w_end = w_near[index], w_far[index]
        depth = 2.0 * travel * w_start / (travel * w_start + (1.0 - travel) * w_end) - 1.0
        return _Hits(index, triangle[seen], points, normals, depth)

    def _visibility(
        self, points: np.ndarray, normals: np.ndarray, variation: np.ndarray
    ) -> np.ndarray:
        """Fraction of unblocked shadow rays of each lit-side point."""
        per_chunk = max(1, _CHUNK_RAYS // self.emitter.samples)
        fraction = np.empty(points.shape[0], dtype=np.float64)
        for start in range(0, points.shape[0], per_chunk):
            part = slice(start, start + per_chunk)
            fraction[part] = self._chunk_visibility(points[part], normals[part], variation[part])
        return fraction

    def _chunk_visibility(
        self, points: np.ndarray, normals: np.ndarray, variation: np.ndarray
    ) -> np.ndarray:
        directions, distance, open_ray = self.emitter.sample_rays(points, normals, variation)
        if self.shadow is not None:
            pixel, sample = np.nonzero(open_ray)
            toward = directions[pixel, sample]
            # Rays start at the light or where they enter the casters' bounds, whichever is
            # nearer the point: float32 origins then stay close to the geometry at any distance.
            _, leave = _slab(points[pixel], toward, self.shadow.lo, self.shadow.hi)
            span = distance[pixel, sample] - LIGHT_CLEARANCE
            reach = np.minimum(span, np.maximum(leave, 0.0) + _BOX_MARGIN)
            origins = points[pixel] + toward * reach[:, None]
            passed = open_ray.astype(np.float64)
            passed[pixel, sample] = self._through(origins, -toward, reach)
            return passed.sum(axis=1) / self.emitter.samples
        return open_ray.sum(axis=1) / self.emitter.samples

    def _through(
        self, origins: np.ndarray, directions: np.ndarray, reach: np.ndarray
    ) -> np.ndarray:
        """Share of light each shadow ray brings over ``reach``: 0 or 1, less through translucency.

        A ray that meets a translucent surface before its end goes on past it
        with ``1 - opacity`` of its light, up to :data:`_MAX_CROSSINGS` times.
        """
        assert self.shadow is not None
        passed = np.ones(origins.shape[0])
        going = np.arange(origins.shape[0])
        for crossing in range(_MAX_CROSSINGS):
            triangle, blocker = self.shadow.first_hit(origins[going], directions[going])
            if crossing == 0:
                self._look_past_the_light(origins, directions, reach, triangle, blocker)
            blocked = (triangle >= 0) & (blocker < reach[going] - RAY_TOLERANCE)
            through = np.where(blocked, self.transmittance[self.shadow.owner[triangle]], 1.0)
            passed[going] *= through
            onward = blocked & (through > 0.0)
            going, step = going[onward], blocker[onward] + _CROSSING_STEP
            if not going.size:
                break
            origins[going] += directions[going] * step[:, None]
            reach[going] -= step
        else:
            passed[going] = 0.0
        return passed

    def _look_past_the_light(
        self,
        origins: np.ndarray,
        directions: np.ndarray,
        reach: np.ndarray,
        triangle: np.ndarray,
        blocker: np.ndarray,
    ) -> None:
        """Cast again, from just past it, each ray that meets a surface right at the light.

        A light on a surface: float32 meets that surface at the ray's start
        even when the ray leaves it. Looking again from just past it keeps a
        ray into the caster meeting the caster's far side. ``triangle`` and
        ``blocker`` are updated in place.
        """
        assert self.shadow is not None
        grazed = (triangle >= 0) & (blocker < LIGHT_SKIP) & (blocker < reach - RAY_TOLERANCE)
        if grazed.any():
            start = origins[grazed] + directions[grazed] * LIGHT_SKIP
            again, further = self.shadow.first_hit(start, directions[grazed])
            triangle[grazed], blocker[grazed] = again, further + LIGHT_SKIP
