"""The pvshadows command: info, demo and bench, run as a user runs them."""

import csv
import subprocess
import sys

import numpy as np
import pyvista as pv


def pvshadows(*args, cwd=None):
    result = subprocess.run(
        [sys.executable, "-m", "pvshadows", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_info_reports_the_context_and_the_techniques():
    out = pvshadows("info")
    for words in (
        "renderer",
        "OpenGL",
        "geometry shaders  yes",
        "max cube map face",
        "stencil bits",
        "cubemap (passes='single') available",
        "cubemap (passes='six')    available",
        "volume (extrude='gpu')    available",
        "volume (extrude='cpu')    available",
        "map (spot, directional)   available",
    ):
        assert words in out


def test_demo_writes_a_picture_with_shadows(tmp_path):
    out = pvshadows("demo", "--out", str(tmp_path / "shadows.png"), "--size", "400x300")
    assert "wrote" in out
    image = pv.read(tmp_path / "shadows.png")
    assert image.dimensions[:2] == (400, 300)
    rgb = np.asarray(image.point_data.active_scalars)[:, :3].astype(int)
    # The ground is light; its shadows are dark grey, well below the lit ground.
    assert np.mean(rgb.max(axis=1) < 60) > 0.02


def test_bench_writes_table_and_frontier(tmp_path):
    command = ["bench", "--out", str(tmp_path), "--quick", "--frames", "3", "--size", "320x240"]
    result = subprocess.run(
        [sys.executable, "-m", "pvshadows", *command],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr
    out = result.stdout
    assert "[5/5]" in out
    # The progress bar, on stderr: cases, then the silhouette, planner and overhead sections.
    assert "bench [" in result.stderr and "8/8" in result.stderr
    rows = list(csv.DictReader(open(tmp_path / "bench.csv")))
    assert [r["setting"] for r in rows] == [
        "resolution=256 filter=hard",
        "resolution=256 filter=pcf pcf_taps=16",
        "extrude=gpu zmode=auto",
        "resolution=256 filter=hard",
        "receivers=ground",
    ]
    for row in rows:
        assert 0 <= float(row["misclassified"]) < 0.05
        assert float(row["ratio_moving"]) > 0.5
    assert float(rows[2]["misclassified"]) < 0.003
    table = (tmp_path / "bench.md").read_text()
    assert table.count("| cubemap |") == 2
    assert table.count("| volume |") == 1
    assert table.count("| map | spot |") == 1
    # Five cases do not cover every light: the presets are not chosen, and it says so.
    assert "Quality presets: not chosen" in table
    assert (tmp_path / "presets.json").read_text().strip() == "{}"
    planner = table[table.index("Only what the scene calls for") :]
    assert "| 8 spot lights, 6 of them reach no visible receiver (1 frame) | 2 | 8 |" in planner
    assert "static scene seen from 3 new cameras (3 frames) | 0 | 9 |" in planner
    assert table.count("| planar | spot |") == 1
    assert "silhouette + volume, point light" in table
    assert "Shadow volumes built on the CPU" in out
    assert (tmp_path / "frontier.png").stat().st_size > 10_000
    overhead = table[table.index("Overhead per frame") :]
    assert "| standard scene, point |" in overhead
    assert "| standard scene, point |" in (tmp_path / "overhead.md").read_text()
    assert "standard scene, point" in (tmp_path / "overhead.csv").read_text()


def test_bad_command_line_is_refused():
    result = subprocess.run(
        [sys.executable, "-m", "pvshadows", "demo", "--size", "big"], capture_output=True, text=True
    )
    assert result.returncode == 2
    assert "size must look like 800x600" in result.stderr


def test_frontier_plot_takes_every_technique_and_light(tmp_path):
    from pvshadows.tools.bench import BenchRow, plot_frontier

    rows = [
        BenchRow(technique, light, "filter=hard", 0.001 * (i + 1), 0.01, "hard", 1.0 + i, 1.0, 10)
        for i, (technique, light) in enumerate(
            (t, lt)
            for t in ("cubemap", "map", "volume", "planar", "auto", "vtk", "x")
            for lt in ("point", "spot")
        )
    ]
    plot_frontier(rows, tmp_path / "frontier.png")
    assert (tmp_path / "frontier.png").stat().st_size > 10_000
