"""What a Jupyter user sees: rich tables, and the pictures notebook backends show."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from IPython.lib.pretty import pretty

from conftest import draw, spot_box_scene
from pvshadows.verify.measure import Measurement

TRAME_SESSION = Path(__file__).with_name("trame_session.py")


def test_last_frame_and_measure_display_as_tables():
    pl, spot = spot_box_scene()
    pl.shadows.enable(technique="map", filter="hard")
    draw(pl)
    frame = pl.shadows.last_frame
    html = frame._repr_html_()
    assert html.startswith("<table><caption>pvshadows frame: 1 light(s), ")
    assert "<th>technique</th>" in html and "<td>map</td>" in html
    assert html.count("<tr>") == 1 + len(frame.lights[0].passes) + len(frame.lights[0].notes)
    assert pretty(frame) == str(frame)
    assert "light 0 (spot): map" in pretty(frame)

    error = pl.shadows.measure(spot)
    html = error._repr_html_()
    assert f"<td>{error.lit_pixels}</td>" in html
    assert f"<td>{100 * error.misclassified:.3f} %</td>" in html
    assert f"{error.shadow_pixels} of the compared pixels are in shadow" in html
    assert error.shadow_pixels > 1000
    assert pretty(error) == str(error)


def test_measure_of_a_light_that_casts_nothing_says_so():
    pl, spot = spot_box_scene()
    pl.shadows.enable(technique="map", filter="hard")
    pl.shadows.set_caster(pl.actors["box"], False)
    draw(pl)
    error = pl.shadows.measure(spot)
    assert error.shadow_pixels == 0 and error.lit_pixels > 10_000
    assert str(error).startswith("the light casts no shadow in view: only false shadows")
    assert "casts no shadow in view" in error._repr_html_()
    nothing = Measurement(0.0, 0.0, 0.0, 0.0, 0, 0)
    assert str(nothing).startswith("the light reaches no receiver in view")


def _shadowed_twin():
    """The same scene with shadows drawn by screenshot, and its shadow and lit pixels."""
    pl, spot = spot_box_scene()
    plain = pl.screenshot(return_img=True).astype(int)
    pl.shadows.enable(technique="map", filter="hard")
    shot = draw(pl).astype(int)
    vis = pl.shadows.visibility(spot)
    dark = np.isfinite(vis) & (vis == 0.0) & (plain.min(axis=2) > 40)
    # The probe reads one sample per pixel and the picture is multisampled: keep the pixels
    # whose four neighbours are in shadow too, so no pixel on an outline is judged.
    for axis in (0, 1):
        for shift in (1, -1):
            dark &= np.roll(dark, shift, axis=axis)
    assert dark.sum() > 1000
    return plain, shot, dark


def test_static_notebook_backend_shows_the_shadows():
    plain, shot, dark = _shadowed_twin()
    pl, _ = spot_box_scene(notebook=True)
    pl.shadows.enable(technique="map", filter="hard")
    shown = np.asarray(pl.show(jupyter_backend="static", return_viewer=True).convert("RGB"))
    assert shown.shape == shot.shape
    assert np.abs(shown.astype(int) - shot).max() <= 1
    assert shown[dark].max() <= 1 and plain[dark].min() > 40


def test_trame_server_side_backend_shows_the_shadows(tmp_path):
    """``jupyter_backend="server"``: trame renders the plotter's own window and streams it."""
    pytest.importorskip("trame_pyvista", reason="needs trame: pip install '.[jupyter]'")
    plain, shot, dark = _shadowed_twin()
    out = tmp_path / "streamed.npz"
    result = subprocess.run(
        [sys.executable, str(TRAME_SESSION), str(out)],
        cwd=TRAME_SESSION.parent,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    saved = np.load(out)
    assert bool(saved["own_window"])
    streamed = saved["streamed"].astype(int)
    assert streamed.shape == shot.shape
    assert streamed[dark].mean() < 8 and plain[dark].mean() > 100
    assert np.abs(streamed - shot).mean() < 2  # JPEG at quality 100
