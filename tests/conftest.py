"""Shared fixtures: the standard scene, point lights, fresh frames."""

import pytest
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows)
from pvshadows.scenes import standard_scene

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
