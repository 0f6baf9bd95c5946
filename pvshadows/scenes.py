"""Scenes whose shadows can be reasoned about, shared by the demo, the bench and the tests."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

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
    >>> from pvshadows.scenes import standard_scene
    >>> scene = standard_scene(window_size=(320, 240))
    >>> scene.plotter.window_size
    [320, 240]
    """
    offset = np.asarray(offset, dtype=np.float64)

    def place(mesh: pv.PolyData) -> pv.PolyData:
        mesh = mesh.copy()
        mesh.points = np.asarray(mesh.points, dtype=np.float64) * scale + offset
        return mesh

    plotter = pv.Plotter(off_screen=off_screen, window_size=list(window_size), lighting="none")
    plotter.set_background("white")
    style = {"ambient": ambient, "diffuse": 0.85, "specular": 0.2, "smooth_shading": True}
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
    light_at = np.asarray(light_position, dtype=np.float64) * scale + offset
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
            focal_point=tuple(offset),
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
            position=tuple(offset + 10.0 * scale * towards_sun),
            focal_point=tuple(offset),
            light_type="scene light",
        )
    plotter.add_light(light_object)
    position, focal, up = camera
    plotter.camera_position = [
        tuple(np.asarray(position) * scale + offset),
        tuple(np.asarray(focal) * scale + offset),
        tuple(up),
    ]
    return StandardScene(plotter, light_object, ground, box, sphere, cylinder, scale, offset)
