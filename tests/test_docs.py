"""The docs' own code: gallery scripts fit sphinx-gallery, bench output becomes the docs' tables."""

import ast
import sys
from pathlib import Path

import pytest

from pvshadows.tools.bench import (
    BenchRow,
    append_lines,
    append_planner_table,
    append_silhouette_table,
    write_table,
)
from pvshadows.tools.bench_presets import choose_presets, presets_lines

ROOT = Path(__file__).parents[1]
sys.path.insert(0, str(ROOT / "docs" / "_ext"))

import gallery_support  # noqa: E402
import pvshadows_docs  # noqa: E402

EXAMPLES = sorted((ROOT / "examples").glob("*.py"))


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_has_a_gallery_title_and_saves_into_the_current_folder(script):
    source = script.read_text(encoding="utf-8")
    docstring = ast.get_docstring(ast.parse(source))
    assert docstring, "sphinx-gallery needs a docstring with a title"
    title, underline = docstring.splitlines()[:2]
    assert title and set(underline) == {"="} and len(underline) >= len(title)
    assert "# %%" in source
    assert ".png" in source, "each example saves its picture (the gallery shows that file)"


def _rows():
    def row(technique, light, setting, misclassified, reference="hard"):
        return BenchRow(technique, light, setting, misclassified, 0.05, reference, 1.5, 1.2, 20.0)

    return [
        row("cubemap", "point", "resolution=256 filter=hard", 0.003),
        row("cubemap", "point", "resolution=256 filter=pcf", 0.002, "area light 0.25"),
        row("volume", "point", "extrude=gpu zmode=zpass", 0.0),
        row("map", "spot", "resolution=256 filter=hard", 0.001),
    ]


def _preset_rows():
    return [
        BenchRow(t, light, setting, 0.0005, 0.05, "hard", 1.5, 1.2, 20.0)
        for light in ("point", "spot", "directional")
        for t, setting in [
            ("cubemap" if light == "point" else "map", "resolution=512 filter=pcf pcf_taps=4"),
            ("cubemap" if light == "point" else "map", "resolution=512 filter=hard"),
            ("volume", "extrude=gpu zmode=auto"),
        ]
    ]


def test_bench_output_becomes_the_accuracy_pages_tables(tmp_path):
    bench = tmp_path / "bench"
    write_table(_rows(), bench)
    append_lines(presets_lines(choose_presets(_preset_rows()), _preset_rows()), bench)
    timing = {
        "n_triangles": 2000,
        "n_silhouette_edges": 80,
        "silhouette_point_s": 1e-3,
        "volume_point_s": 1e-3,
        "silhouette_directional_s": 1e-3,
        "volume_directional_s": 1e-3,
        "prepare_s": 0.01,
    }
    append_silhouette_table([timing], bench)
    append_planner_table([{"scene": "8 spots", "passes": 2, "every_light": 8}], bench)
    (bench / "measured.txt").write_text("measured in a test\n", encoding="utf-8")
    out = tmp_path / "generated"
    out.mkdir()
    pvshadows_docs.write_bench_rst(bench, out, "measured in a test")
    table = (out / "bench_table.csv").read_text(encoding="utf-8").splitlines()
    assert len(table) == 1 + len(_rows())
    assert table[3].startswith('volume (point),"extrude=gpu, zmode=zpass",0.000,')
    presets = (out / "bench_presets.rst").read_text(encoding="utf-8")
    assert presets.startswith(".. list-table:: Quality presets chosen by this bench (``presets")
    assert "   * - draft" in presets and "   * - exact" in presets
    assert "2000" in (out / "bench_silhouettes.rst").read_text(encoding="utf-8")
    assert "8 spots" in (out / "bench_planner.rst").read_text(encoding="utf-8")
    assert (out / "bench_more.rst").read_text(encoding="utf-8") == ""


def test_markdown_tables():
    text = "Presets:\n\n| a | b |\n| --- | ---: |\n| `x` | 1 |\n"
    assert pvshadows_docs.markdown_tables(text) == [("Presets", [["a", "b"], ["``x``", "1"]])]


def test_gallery_order_puts_the_named_scripts_first():
    order = gallery_support.GalleryOrder(str(ROOT / "examples"))
    names = ["zzz_new.py", "accuracy_vs_time.py", "bulb_room.py", "aaa_new.py"]
    assert sorted(names, key=order) == ["bulb_room.py", "accuracy_vs_time.py", *sorted(names[::3])]


def test_ci_runs_the_readme_commands():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    commands = readme.split("```bash\n", 1)[1].split("```", 1)[0].splitlines()
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()
    assert "python -m pytest -n auto" in commands[1]  # the suite runs on every core
    assert commands[:2] == ci[-3:-1]
    # CI's docs build is the README's, with warnings failing it.
    assert ci[-1] == commands[2].replace("sphinx-build -b", "sphinx-build -W --keep-going -b")
