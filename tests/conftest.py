"""Shared fixtures: the standard scene, point lights, fresh frames."""

import pytest
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows)
from pvshadows.tools.scenes import standard_scene

pv.OFF_SCREEN = True


@pytest.fixture(autouse=True)
def _close_plotters():
    yield
    pv.close_all()


@pytest.fixture
def scene():
    """The standard scene (800x600), shadows not yet enabled."""
    return standard_scene()


def point_light(position, **kwargs):
    """A point light (positional, cone angle 180) at ``position``."""
    position = tuple(float(v) for v in position)
    focal = (position[0], position[1], position[2] - 1.0)
    return pv.Light(position=position, focal_point=focal, positional=True, cone_angle=180, **kwargs)


def draw(plotter):
    """Render a fresh frame and return it (``screenshot`` alone renders only the first time)."""
    plotter.render()
    return plotter.screenshot(return_img=True)


def spot_box_scene(**plotter_options):
    """A 400x300 plotter lit only by a spot light above a box on a white ground.

    Returns the plotter and the light; names the actors ``"ground"`` and ``"box"``.
    """
    pl = pv.Plotter(off_screen=True, lighting="none", window_size=(400, 300), **plotter_options)
    pl.add_mesh(pv.Plane(i_size=8, j_size=8), color="white", name="ground")
    pl.add_mesh(pv.Cube(center=(0, 0, 1), x_length=1.5, y_length=1.5, z_length=1.5), name="box")
    spot = pv.Light(position=(0.5, 0.3, 5), focal_point=(0, 0, 0), positional=True, cone_angle=60)
    pl.add_light(spot)
    pl.camera_position = [(7, -7, 7), (0, 0, 0.5), (0, 0, 1)]
    return pl, spot
