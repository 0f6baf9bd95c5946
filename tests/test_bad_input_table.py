"""Every public argument of ``pl.shadows``, given bad values: the right error, naming the argument.

Each row is (call, arguments, exception, argument named). The values cover
a wrong type, NaN, inf, zero, negative, huge, a wrong object and an object
from another plotter, wherever the argument can take them.
"""

import math

import pytest
import pyvista as pv

from conftest import point_light
from pvshadows.tools.scenes import standard_scene

NAN, INF = math.nan, math.inf

#: Settings that are a number of texels from 0 to 100.
TEXELS = ("bias", "slope_bias", "normal_offset", "filter_radius")
#: Settings that are one of a few names.
CHOICES = ("technique", "quality", "filter", "passes", "zmode", "extrude", "on_open")


def _setting_rows():
    rows = []
    for name in TEXELS:
        rows += [
            ({name: "1"}, TypeError, name),
            ({name: None}, TypeError, name),
            ({name: NAN}, ValueError, name),
            ({name: INF}, ValueError, name),
            ({name: -INF}, ValueError, name),
            ({name: -0.5}, ValueError, name),
            ({name: 1e300}, ValueError, name),
        ]
    for name in CHOICES:
        rows += [
            ({name: "nonsense"}, ValueError, name),
            ({name: 3}, TypeError, name),
            ({name: None}, TypeError, name),
        ]
    rows += [
        ({"resolution": 1024.0}, TypeError, "resolution"),
        ({"resolution": NAN}, TypeError, "resolution"),
        ({"resolution": True}, TypeError, "resolution"),
        ({"resolution": 0}, ValueError, "resolution"),
        ({"resolution": -512}, ValueError, "resolution"),
        ({"resolution": 10**12}, ValueError, "resolution"),
        ({"pcf_taps": 0}, ValueError, "pcf_taps"),
        ({"pcf_taps": -16}, ValueError, "pcf_taps"),
        ({"pcf_taps": 16.0}, TypeError, "pcf_taps"),
        ({"pcf_taps": 10**9}, ValueError, "pcf_taps"),
        ({"samples": 0}, ValueError, "samples"),
        ({"samples": -8}, ValueError, "samples"),
        ({"samples": 12}, ValueError, "samples"),
        ({"samples": 2**40}, ValueError, "samples"),
        ({"samples": 32.0}, TypeError, "samples"),
        ({"light_size": "big"}, TypeError, "light_size"),
        ({"light_size": NAN}, ValueError, "light_size"),
        ({"light_size": INF}, ValueError, "light_size"),
        ({"light_size": -1.0}, ValueError, "light_size"),
        ({"filter": "pcss", "light_size": 0.0}, ValueError, "light_size"),
        ({"cull_front": 1}, TypeError, "cull_front"),
        ({"cull_front": "yes"}, TypeError, "cull_front"),
        ({"shininess": 3}, TypeError, "shininess"),
    ]
    return rows


SETTING_ROWS = _setting_rows()


@pytest.fixture(autouse=True)
def _close_plotters():
    """Keep the module's plotters open between rows (``world`` closes them)."""


@pytest.fixture(scope="module")
def world():
    """A small scene, a second plotter and things that belong to neither."""
    scene = standard_scene(window_size=(200, 150))
    other = pv.Plotter(off_screen=True, window_size=[200, 150])
    foreign_light = point_light((0, 0, 3))
    other.add_light(foreign_light)
    removed = scene.plotter.add_mesh(pv.Sphere(center=(3, 3, 1)), name="gone")
    scene.plotter.remove_actor(removed)
    things = {
        "light": scene.light,
        "actor": scene.box,
        "foreign light": foreign_light,
        "loose light": point_light((1, 1, 3)),
        "foreign actor": other.add_mesh(pv.Sphere()),
        "removed actor": removed,
        "loose actor": pv.Actor(mapper=pv.DataSetMapper(pv.Sphere())),
        "mesh": pv.Sphere(),
    }
    yield scene, things
    scene.plotter.close()
    other.close()


def _call_rows():
    """(call, arguments, exception, argument); strings in arguments name things of ``world``."""
    rows = []
    for settings, error, name in SETTING_ROWS:
        rows.append(("enable", settings, error, name))
        rows.append(("configure", {"light": "light", **settings}, error, name))
    rows += [
        ("enable", {"lights": 5}, TypeError, "lights"),
        ("enable", {"lights": NAN}, TypeError, "lights"),
        ("enable", {"lights": "bulb"}, TypeError, "lights"),
        ("enable", {"lights": ["mesh"]}, TypeError, "lights"),
        ("enable", {"lights": "foreign light"}, ValueError, "lights"),
        ("enable", {"lights": ["light", "loose light"]}, ValueError, "lights"),
        ("enable", {"quality": INF}, TypeError, "quality"),
    ]
    for call in ("configure", "settings"):
        rows += [
            (call, {"light": "bulb!"}, TypeError, "light"),
            (call, {"light": 0}, TypeError, "light"),
            (call, {"light": NAN}, TypeError, "light"),
            (call, {"light": "actor"}, TypeError, "light"),
            (call, {"light": "foreign light"}, ValueError, "light"),
            (call, {"light": "loose light"}, ValueError, "light"),
        ]
    for call, flag in (("set_caster", "cast"), ("set_receiver", "receive")):
        rows += [
            (call, {"actor": "mesh"}, TypeError, "actor"),
            (call, {"actor": "light"}, TypeError, "actor"),
            (call, {"actor": 7}, TypeError, "actor"),
            (call, {"actor": "foreign actor"}, ValueError, "actor"),
            (call, {"actor": "removed actor"}, ValueError, "actor"),
            (call, {"actor": "loose actor"}, ValueError, "actor"),
            (call, {"actor": "actor", flag: "no"}, TypeError, flag),
            (call, {"actor": "actor", flag: 0}, TypeError, flag),
            (call, {"actor": "actor", flag: NAN}, TypeError, flag),
            (call, {"actor": "actor", flag: None}, TypeError, flag),
        ]
    for value, error in (
        ("0.5", TypeError),
        (True, TypeError),
        ([0.5], TypeError),
        (NAN, ValueError),
        (INF, ValueError),
        (-0.1, ValueError),
        (1.5, ValueError),
    ):
        given = {"actor": "actor", "transmittance": value}
        rows.append(("set_caster", given, error, "transmittance"))
    rows += [
        ("set_receiver", {"actor": "actor", "plane": "yes"}, TypeError, "plane"),
        ("set_receiver", {"actor": "actor", "plane": 1}, TypeError, "plane"),
        ("set_receiver", {"actor": "foreign actor", "plane": True}, ValueError, "actor"),
        ("set_receiver", {"actor": "actor", "receive": False, "plane": True}, ValueError, "plane"),
        ("show_volumes", {"show": "yes"}, TypeError, "show"),
        ("show_volumes", {"show": 1}, TypeError, "show"),
        ("show_volumes", {"show": None}, TypeError, "show"),
    ]
    for call in ("visibility", "reference", "measure"):
        rows += [
            (call, {"light": "bulb!"}, TypeError, "light"),
            (call, {"light": 5}, TypeError, "light"),
            (call, {"light": INF}, TypeError, "light"),
            (call, {"light": "mesh"}, TypeError, "light"),
            (call, {"light": "foreign light"}, ValueError, "light"),
            (call, {"light": "loose light"}, ValueError, "light"),
        ]
    for call in ("reference", "measure"):
        rows += [
            (call, {"light_size": "big"}, TypeError, "light_size"),
            (call, {"light_size": NAN}, ValueError, "light_size"),
            (call, {"light_size": INF}, ValueError, "light_size"),
            (call, {"light_size": -0.1}, ValueError, "light_size"),
            (call, {"samples": 4.0}, TypeError, "samples"),
            (call, {"samples": 0}, ValueError, "samples"),
            (call, {"samples": -4}, ValueError, "samples"),
            (call, {"samples": 10**9}, ValueError, "samples"),
            (call, {"samples": 16}, ValueError, "samples"),  # several rays need light_size > 0
        ]
    rows.append(("measure", {"colour": 1}, TypeError, "colour"))
    return rows


CALL_ROWS = _call_rows()


def test_the_table_covers_every_public_argument():
    named = {name for _, _, _, name in CALL_ROWS}
    arguments = {
        "technique", "quality", "lights", "light", "actor", "cast", "receive", "plane",
        "show", "light_size", "samples", "resolution", "filter", "pcf_taps", "filter_radius",
        "passes", "bias", "slope_bias", "normal_offset", "cull_front", "zmode", "extrude",
        "on_open", "transmittance",
    }  # fmt: skip
    assert arguments <= named
    assert len(CALL_ROWS) >= 220


@pytest.mark.parametrize(
    ("call", "arguments", "error", "name"),
    CALL_ROWS,
    ids=[f"{row[0]}-{row[3]}-{index}" for index, row in enumerate(CALL_ROWS)],
)
def test_bad_argument(world, call, arguments, error, name):
    scene, things = world
    given = {}
    for key, value in arguments.items():
        if isinstance(value, list):
            value = [things.get(v, v) for v in value]
        elif isinstance(value, str) and value in things:
            value = things[value]
        given[key] = value
    with pytest.raises(error) as raised:
        getattr(scene.plotter.shadows, call)(**given)
    assert name in str(raised.value)
