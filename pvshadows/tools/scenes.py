"""Scenes whose shadows can be reasoned about, shared by the demo, the bench and the tests."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pyvista as pv

#: Camera of the standard scene (position, focal point, view up), before scaling.
STANDARD_CAMERA = ((11.0, -12.5, 9.5), (0.0, 0.0, 0.3), (0.0, 0.0, 1.0))


@dataclass
class StandardScene:
    """The plotter of the standard scene and its parts.

    Attributes
    ----------
    plotter : pyvista.Plotter
        The plotter (off screen unless asked otherwise), lit only by ``light``.
    light : pyvista.Light
        The light (point, spot or directional).
    ground, box, sphere, cylinder : pyvista.Actor
        The actors.
    scale : float
        Factor applied to every coordinate.
    offset : numpy.ndarray
        Translation applied after scaling.
    """

    plotter: pv.Plotter
    light: pv.Light
    ground: pv.Actor
    box: pv.Actor
    sphere: pv.Actor
    cylinder: pv.Actor
    scale: float
    offset: np.ndarray

    def place(self, point: Sequence[float]) -> np.ndarray:
        """Map a point of the unit scene into this scene's coordinates.

        Parameters
        ----------
        point : sequence of float
            A point of the unit-scale, untranslated scene.

        Returns
        -------
        numpy.ndarray
            ``point * scale + offset``.
        """
        return np.asarray(point, dtype=np.float64) * self.scale + self.offset


def standard_scene(
    *,
    scale: float = 1.0,
    offset: Sequence[float] = (0.0, 0.0, 0.0),
    light_position: Sequence[float] = (0.3, -0.2, 3.5),
    light: str = "point",
    cone_angle: float = 60.0,
    sun_elevation: float = 40.0,
    window_size: tuple[int, int] = (800, 600),
    camera: tuple = STANDARD_CAMERA,
    ambient: float = 0.15,
    off_screen: bool = True,
) -> StandardScene:
    """Build the standard scene: ground, floating box, sphere, cylinder and a point light.

    The light hangs among the objects at a height of about 3.5, so their
    shadows fall in every direction; the camera looks at it all obliquely.

    Parameters
    ----------
    scale : float, default: 1.0
        Factor applied to every coordinate (also the light's and camera's).
    offset : sequence of float, default: (0, 0, 0)
        Translation applied after scaling.
    light_position : sequence of float, default: (0.3, -0.2, 3.5)
        Where the point or spot light hangs in the unit scene.
    light : {"point", "spot", "directional"}, default: "point"
        The kind of light: a bulb, a spot aimed at the origin with
        ``cone_angle``, or a sun ``sun_elevation`` degrees above the ground
        (azimuth 30 degrees).
    cone_angle : float, default: 60.0
        Half angle of the spot light's cone.
    sun_elevation : float, default: 40.0
        Height of the sun above the ground, in degrees.
    window_size : tuple of int, default: (800, 600)
        Window width and height in pixels.
    camera : tuple, default: STANDARD_CAMERA
        Position, focal point and view up of the unit scene's camera.
    ambient : float, default: 0.15
        Ambient coefficient of every surface, so shadows are not black.
    off_screen : bool, default: True
        ``False`` for an on-screen window (shown with ``plotter.show()``).

    Returns
    -------
    StandardScene
        The plotter and its parts; shadows are not enabled yet.

    Examples
    --------
    >>> from pvshadows.tools.scenes import standard_scene
    >>> scene = standard_scene(window_size=(320, 240))
    >>> scene.plotter.window_size
    [320, 240]
    """
    origin = np.asarray(offset, dtype=np.float64)

    def place(mesh: pv.PolyData) -> pv.PolyData:
        mesh = mesh.copy()
        mesh.points = np.asarray(mesh.points, dtype=np.float64) * scale + origin
        return mesh

    plotter = pv.Plotter(off_screen=off_screen, window_size=list(window_size), lighting="none")
    plotter.set_background("white")  # type: ignore[arg-type]  # pyvista: decorated, self untyped
    style: dict[str, Any] = {
        "ambient": ambient,
        "diffuse": 0.85,
        "specular": 0.2,
        "smooth_shading": True,
    }
    ground = plotter.add_mesh(
        place(pv.Plane(i_size=10, j_size=10, i_resolution=20, j_resolution=20)),
        color="#d9d4c7",
        name="ground",
        **style,
    )
    box = plotter.add_mesh(
        place(pv.Box(bounds=(-2.6, -1.4, -0.9, 0.3, 1.3, 2.1))),
        color="#c0504d",
        name="box",
        ambient=ambient,
        diffuse=0.85,
        specular=0.2,
    )
    sphere = plotter.add_mesh(
        place(
            pv.Sphere(radius=0.7, center=(1.6, 1.4, 0.7), theta_resolution=48, phi_resolution=48)
        ),
        color="#4f81bd",
        name="sphere",
        **style,
    )
    cylinder = plotter.add_mesh(
        place(
            pv.Cylinder(
                center=(0.9, -2.1, 0.9),
                direction=(0, 0, 1),
                radius=0.45,
                height=1.8,
                resolution=48,
                capping=True,
            )
        ),
        color="#9bbb59",
        name="cylinder",
        **style,
    )
    light_at = np.asarray(light_position, dtype=np.float64) * scale + origin
    if light == "point":
        light_object = pv.Light(
            position=tuple(light_at),
            focal_point=tuple(light_at - np.array([0.0, 0.0, scale])),
            positional=True,
            cone_angle=180.0,
            light_type="scene light",
        )
    elif light == "spot":
        light_object = pv.Light(
            position=tuple(light_at),
            focal_point=tuple(origin),
            positional=True,
            cone_angle=cone_angle,
            light_type="scene light",
        )
    else:
        elevation, azimuth = np.radians(sun_elevation), np.radians(30.0)
        towards_sun = np.array(
            [
                np.cos(elevation) * np.cos(azimuth),
                np.cos(elevation) * np.sin(azimuth),
                np.sin(elevation),
            ]
        )
        light_object = pv.Light(
            position=tuple(origin + 10.0 * scale * towards_sun),
            focal_point=tuple(origin),
            light_type="scene light",
        )
    plotter.add_light(light_object)
    position, focal, up = camera
    plotter.camera_position = [
        tuple(np.asarray(position) * scale + origin),
        tuple(np.asarray(focal) * scale + origin),
        tuple(up),
    ]
    return StandardScene(plotter, light_object, ground, box, sphere, cylinder, scale, origin)


def spot_light(position, focal_point, cone_angle=30.0, intensity=0.3) -> pv.Light:
    """Return a scene spot light.

    Parameters
    ----------
    position, focal_point : sequence of float
        Where it is and where it points.
    cone_angle : float, default: 30.0
        Half angle of its cone in degrees.
    intensity : float, default: 0.3
        Its intensity.

    Returns
    -------
    pyvista.Light
        The light.

    Examples
    --------
    >>> from pvshadows.tools.scenes import spot_light
    >>> spot_light((0, 0, 5), (0, 0, 0)).cone_angle
    30.0
    """
    return pv.Light(
        position=tuple(position),
        focal_point=tuple(focal_point),
        positional=True,
        cone_angle=cone_angle,
        intensity=intensity,
        light_type="scene light",
    )


def eight_spots_scene(window_size: tuple[int, int] = (400, 300)) -> tuple[pv.Plotter, list]:
    """Return the standard scene lit by eight spots, of which six reach no visible receiver.

    Two spots aim at the scene; three aim at the sky and three at ground far
    outside the view. The standard scene's point light is off.

    Parameters
    ----------
    window_size : tuple of int, default: (400, 300)
        Window size.

    Returns
    -------
    tuple
        The plotter and the eight spots (the two that reach the scene first).

    Examples
    --------
    >>> from pvshadows.tools.scenes import eight_spots_scene
    >>> len(eight_spots_scene((160, 120))[1])
    8
    """
    scene = standard_scene(window_size=window_size)
    scene.light.SetSwitch(False)
    spots = [spot_light((3, -3, 5), (0, 0, 0)), spot_light((-3, 3, 5), (0, 0, 0))]
    spots += [spot_light((0, 0, 5), (0, 0, 50)) for _ in range(3)]
    spots += [spot_light((60, 60, 5), (60, 60, 0)) for _ in range(3)]
    for light in spots:
        scene.plotter.add_light(light)
    return scene.plotter, spots


def three_lights_scene(window_size: tuple[int, int] = (400, 300)) -> tuple[pv.Plotter, list]:
    """Return the standard scene lit by its point light, a spot and a sun.

    Parameters
    ----------
    window_size : tuple of int, default: (400, 300)
        Window size.

    Returns
    -------
    tuple
        The plotter and its three lights (point, spot, directional).

    Examples
    --------
    >>> from pvshadows.tools.scenes import three_lights_scene
    >>> [light.positional for light in three_lights_scene((160, 120))[1]]
    [True, True, False]
    """
    scene = standard_scene(window_size=window_size)
    scene.light.intensity = 0.4
    spot = spot_light((-3, 3, 5), (0, 0, 0), cone_angle=50, intensity=0.4)
    sun = pv.Light(position=(5, 3, 8), focal_point=(0, 0, 0), intensity=0.4)
    scene.plotter.add_light(spot)
    scene.plotter.add_light(sun)
    return scene.plotter, [scene.light, spot, sun]


def crowd_scene(
    count: int = 200, window_size: tuple[int, int] = (400, 300)
) -> tuple[pv.Plotter, pv.Light, np.ndarray]:
    """Return small spheres spread over a wide ground, under one narrow spot light.

    Parameters
    ----------
    count : int, default: 200
        Number of spheres, spread over 110 x 110 units.
    window_size : tuple of int, default: (400, 300)
        Window size.

    Returns
    -------
    tuple
        The plotter, the spot (20 units up, cone of 20 degrees) and the
        spheres' centres ``(count, 2)``.

    Examples
    --------
    >>> from pvshadows.tools.scenes import crowd_scene
    >>> crowd_scene(5, (160, 120))[2].shape
    (5, 2)
    """
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size), lighting="none")
    plotter.add_mesh(pv.Plane(i_size=120, j_size=120), color="white")
    centres = np.random.default_rng(3).uniform(-55, 55, (count, 2))
    for x, y in centres:
        plotter.add_mesh(
            pv.Sphere(radius=0.6, center=(x, y, 0.6), theta_resolution=12, phi_resolution=12)
        )
    light = spot_light((0, 0, 20), (0, 0, 0), cone_angle=20, intensity=1.0)
    plotter.add_light(light)
    plotter.camera_position = [(0, -40, 45), (0, 0, 0), (0, 0, 1)]
    return plotter, light, centres
