"""What a shadow technique needs to know about a :class:`pyvista.Light`.

PyVista's own light is the light; this module only reads it. A light is a
point light when it is positional with ``cone_angle >= 90``, a spot light when
it is positional with a narrower cone, and a directional light otherwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached


class LightKind(StrEnum):
    """The three kinds of light that cast shadows."""

    POINT = "point"
    SPOT = "spot"
    DIRECTIONAL = "directional"


def light_kind(light: vtk.vtkLight) -> LightKind:
    """Classify a VTK/PyVista light.

    Parameters
    ----------
    light : vtk.vtkLight
        The light, usually a :class:`pyvista.Light`.

    Returns
    -------
    LightKind
        ``POINT`` for positional lights with ``cone_angle >= 90``, ``SPOT``
        for narrower positional lights, ``DIRECTIONAL`` otherwise.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.lights import light_kind
    >>> light_kind(pv.Light(positional=True, cone_angle=180)).value
    'point'
    >>> light_kind(pv.Light(positional=True, cone_angle=30)).value
    'spot'
    """
    # VTK's own methods, called on the class: PyVista's wrappers check every attribute
    if not vtk.vtkLight.GetPositional(light):
        return LightKind.DIRECTIONAL
    return LightKind.POINT if vtk.vtkLight.GetConeAngle(light) >= 90.0 else LightKind.SPOT


@dataclass
class LightPose:
    """A light in world coordinates, as one frame sees it.

    Attributes
    ----------
    kind : LightKind
        Point, spot or directional.
    position : numpy.ndarray
        World position, float64 ``(3,)``. For a directional light, the point
        its direction is measured from (only the direction matters).
    direction : numpy.ndarray
        Unit vector from the light towards its focal point, float64 ``(3,)``.
    cone_angle : float
        Half angle of a spot light's cone in degrees (90 or more otherwise).
    """

    kind: LightKind
    position: np.ndarray
    direction: np.ndarray
    cone_angle: float

    def key(self) -> tuple:
        """Return a hashable value that changes whenever the pose changes (built once)."""
        return self._key

    @cached
    def _key(self) -> tuple:
        return (self.kind, *self.position.tolist(), *self.direction.tolist(), self.cone_angle)

    def degrees_from(self, other: LightPose) -> float:
        """Return the angle between this pose's direction and another's, in degrees.

        Parameters
        ----------
        other : LightPose
            The other pose.

        Returns
        -------
        float
            From 0 (the same direction) to 180.

        Examples
        --------
        >>> import numpy as np
        >>> from pvshadows.scene.lights import LightKind, LightPose
        >>> down = LightPose(LightKind.SPOT, np.zeros(3), np.array([0, 0, -1.0]), 30.0)
        >>> aside = LightPose(LightKind.SPOT, np.zeros(3), np.array([1.0, 0, 0]), 30.0)
        >>> down.degrees_from(aside)
        90.0
        """
        # Unit three-vectors in plain floats, written out: numpy's calls, and a
        # generator's, cost more than the sums.
        (ax, ay, az), (bx, by, bz) = self.direction.tolist(), other.direction.tolist()
        if ax == bx and ay == by and az == bz:
            return 0.0  # not the few ulps of arccos near 1
        cosine = ax * bx + ay * by + az * bz
        return math.degrees(math.acos(max(-1.0, min(1.0, cosine))))

    def homogeneous(self) -> np.ndarray:
        """Return the light as a homogeneous world 4-vector, in the one sign convention used.

        Returns
        -------
        numpy.ndarray
            ``(position, 1)`` for point and spot lights, ``(direction
            towards the light, 0)`` for directional ones.

        Examples
        --------
        >>> import numpy as np
        >>> from pvshadows.scene.lights import LightKind, LightPose
        >>> sun = LightPose(LightKind.DIRECTIONAL, np.zeros(3), np.array([0, 0, -1.0]), 180.0)
        >>> sun.homogeneous().tolist()
        [-0.0, -0.0, 1.0, 0.0]
        """
        if self.kind is LightKind.DIRECTIONAL:
            return np.append(-self.direction, 0.0)
        return np.append(self.position, 1.0)


def pose_time(light: vtk.vtkLight) -> int:
    """Return a modification time that moves whenever the light's pose or state may have changed.

    A camera light or headlight follows the camera through its transform
    matrix, which the renderer edits in place: the light's own time does not
    move then, the matrix's does.

    Parameters
    ----------
    light : vtk.vtkLight
        The light.

    Returns
    -------
    int
        The later of the light's and its transform matrix's modification times.

    Examples
    --------
    >>> import vtk
    >>> from pvshadows.scene.lights import pose_time
    >>> light = vtk.vtkLight()
    >>> light.SetTransformMatrix(vtk.vtkMatrix4x4())
    >>> before = pose_time(light)
    >>> light.GetTransformMatrix().SetElement(0, 3, 1.0)
    >>> pose_time(light) > before
    True
    """
    # VTK's own methods, called on the class: PyVista's wrappers check every
    # attribute they are asked for, a cost paid each frame.
    matrix = vtk.vtkLight.GetTransformMatrix(light)
    own = vtk.vtkLight.GetMTime(light)
    return own if matrix is None else max(own, matrix.GetMTime())


def light_pose(light: vtk.vtkLight) -> LightPose:
    """Read a light's world pose.

    Camera lights and headlights are read through their transform matrix,
    which the renderer updates to follow the camera; call
    ``renderer.UpdateLightsGeometryToFollowCamera()`` first when the camera
    may have moved since the last render.

    Parameters
    ----------
    light : vtk.vtkLight
        The light.

    Returns
    -------
    LightPose
        Its kind, world position, unit direction and cone angle.

    Raises
    ------
    ValueError
        If the position or focal point is not finite, they coincide so that
        the light has no direction, or a spot light's cone angle is not positive.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.lights import light_pose
    >>> pose = light_pose(pv.Light(position=(0, 0, 3), focal_point=(0, 0, 0)))
    >>> pose.direction.tolist()
    [0.0, 0.0, -1.0]
    """
    # plain floats for three-vectors: numpy's per-call cost outweighs its speed here
    position = vtk.vtkLight.GetTransformedPosition(light)
    px, py, pz = position
    fx, fy, fz = vtk.vtkLight.GetTransformedFocalPoint(light)
    if not all(map(math.isfinite, (px, py, pz, fx, fy, fz))):
        msg = (
            f"light position {tuple(light.GetPosition())} and focal_point "
            f"{tuple(light.GetFocalPoint())} must be finite numbers"
        )
        raise ValueError(msg)
    kind = light_kind(light)
    cone_angle = vtk.vtkLight.GetConeAngle(light)
    if kind is LightKind.SPOT and not cone_angle > 0.0:
        msg = (
            f"cone_angle={cone_angle} is not allowed for a spot light: it must be "
            "more than 0 degrees (90 or more makes it a point light)"
        )
        raise ValueError(msg)
    ox, oy, oz = fx - px, fy - py, fz - pz
    length = math.hypot(ox, oy, oz)
    if length == 0.0 or not math.isfinite(length):
        if kind is not LightKind.POINT:
            msg = (
                f"a {kind.value} light needs a direction: its position and focal_point "
                f"are both {tuple(position)}"
            )
            raise ValueError(msg)
        ox, oy, oz, length = 0.0, 0.0, -1.0, 1.0
    direction = np.array((ox / length, oy / length, oz / length))
    return LightPose(kind, np.array(position), direction, cone_angle)


def casts_light(light: vtk.vtkLight) -> bool:
    """Return whether the light is switched on and has a positive intensity.

    Parameters
    ----------
    light : vtk.vtkLight
        The light.

    Returns
    -------
    bool
        ``False`` for a light that is off or has zero intensity: such a
        light casts nothing and costs nothing.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.lights import casts_light
    >>> casts_light(pv.Light(intensity=0.0))
    False
    """
    return bool(vtk.vtkLight.GetSwitch(light)) and vtk.vtkLight.GetIntensity(light) > 0.0


def renderer_lights(renderer: vtk.vtkRenderer) -> tuple[vtk.vtkLight, ...]:
    """Return a renderer's lights, in its order.

    Parameters
    ----------
    renderer : vtk.vtkRenderer
        The renderer.

    Returns
    -------
    tuple of vtk.vtkLight
        Its lights.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.lights import renderer_lights
    >>> len(renderer_lights(pv.Plotter(off_screen=True).renderer))  # the light kit
    5
    """
    collection = vtk.vtkRenderer.GetLights(renderer)  # past PyVista's attribute checks
    collection.InitTraversal()
    return tuple([collection.GetNextItem() for _ in range(collection.GetNumberOfItems())])
