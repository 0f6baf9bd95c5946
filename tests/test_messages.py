"""Messages a user reads: actors by their PyVista names, settings a filter ignores."""

import importlib.metadata
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest
import pyvista as pv

from conftest import draw, spot_box_scene
from pvshadows.scene.naming import ActorNames


def test_an_unnamed_actor_is_named_by_its_kind_and_place_not_its_address():
    pl, _ = spot_box_scene()
    pl.shadows.enable(filter="hard")
    draw(pl)
    bad = pv.Sphere(center=(-3, 3, 1))
    bad.points[5] = np.nan
    with pytest.warns(UserWarning) as caught:
        pl.add_mesh(bad)
        draw(pl)
    (message,) = [str(w.message) for w in caught if "NaN" in str(w.message)]
    assert message.startswith(
        "pvshadows leaves it out: the unnamed PolyData actor around (-3, 3, 1) has 1 points"
    )
    assert "Addr" not in message and "0x" not in message
    ball = pl.add_mesh(pv.Sphere(center=(2, -1, 0.5)))
    assert pl.shadows._actor_name(ball) == "the unnamed PolyData actor around (2, -1, 0.5)"
    assert pl.shadows._actor_name(pl.actors["box"]) == "actor 'box'"


def test_names_come_from_a_cached_map_read_once_per_change(monkeypatch):
    pl, _ = spot_box_scene()
    names = ActorNames(pl)
    reads = []
    original = ActorNames._read
    monkeypatch.setattr(ActorNames, "_read", lambda self: reads.append(1) or original(self))
    box, ground = pl.actors["box"], pl.actors["ground"]
    for _ in range(50):
        assert names(box) == "actor 'box'" and names(ground) == "actor 'ground'"
    assert len(reads) == 1
    other = pl.add_mesh(pv.Sphere(), name="box")  # replaces the box under the same name
    assert names(other) == "actor 'box'"
    assert names(box).startswith("the unnamed PolyData actor")
    assert len(reads) == 3


@pytest.mark.parametrize(
    ("settings", "words"),
    [
        ({"samples": 64}, "samples=64 has no effect with filter='pcf'; only filter='random' or"),
        ({"filter": "hard", "pcf_taps": 4}, "pcf_taps=4 has no effect with filter='hard'"),
        ({"filter": "pcss", "light_size": 0.1, "filter_radius": 3.0}, "filter_radius=3.0 has"),
    ],
)
def test_a_setting_the_filter_does_not_read_is_a_warning(settings, words):
    pl, spot = spot_box_scene()
    with pytest.warns(UserWarning, match=words) as caught:
        pl.shadows.enable(**settings)
    assert caught[0].filename == __file__  # points at the user's call
    with pytest.warns(UserWarning, match=words):
        pl.shadows.configure(spot, **settings)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        pl.shadows.configure(spot, filter="random", samples=64, filter_radius=3.0)
        pl.shadows.configure(spot, filter="pcf", pcf_taps=36)


def _command(*args, env=None):
    return subprocess.run(
        [sys.executable, "-m", "pvshadows", *args],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
    )


def test_version():
    result = _command("--version")
    assert result.returncode == 0
    assert result.stdout.strip() == f"pvshadows {importlib.metadata.version('pvshadows')}"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="X and EGL are Linux's")
def test_the_command_without_a_display_opens_egl_without_vtks_x_warning(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "VTK_DEFAULT_OPENGL_WINDOW")}
    result = _command("demo", "--out", str(tmp_path / "s.png"), "--size", "160x120", env=env)
    assert result.returncode == 0, result.stderr
    assert "bad X server connection" not in result.stderr + result.stdout
    assert (tmp_path / "s.png").stat().st_size > 1000
