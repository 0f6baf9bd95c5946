"""The bench's logic: presets chosen from the frontier, steady timing, progress, partial runs."""

import csv
import io
import json
import math

import pytest

from pvshadows.tools.bench import BenchCase, BenchRow, quick_cases, run_bench, steady, write_table
from pvshadows.tools.bench_presets import (
    BALANCED_WITHIN,
    COST_TIE,
    DRAFT_WITHIN,
    choose_presets,
    dominated_by,
    presets_lines,
    write_presets,
)
from pvshadows.tools.bench_progress import ProgressBar
from pvshadows.tools.cli import parser

LIGHTS = ("point", "spot", "directional")


def _row(light, setting, wrong, ratio, technique=None, area=math.nan):
    technique = technique or ("cubemap" if light == "point" else "map")
    return BenchRow(technique, light, setting, wrong, 0.01, "hard", ratio, 1.0, 10.0, area)


def _frontier():
    rows = []
    for light in LIGHTS:
        rows += [
            _row(light, "resolution=256 filter=hard", 0.008, 1.1, area=0.06),
            _row(light, "resolution=512 filter=hard", 0.004, 1.3, area=0.05),
            _row(light, "resolution=2048 filter=hard", 0.0005, 1.9, area=0.045),
            _row(light, "resolution=512 filter=pcf pcf_taps=16", 0.003, 1.6, area=0.04),
            _row(light, "resolution=1024 filter=pcf pcf_taps=4", 0.0009, 1.7, area=0.035),
            _row(light, "resolution=1024 filter=pcf pcf_taps=16", 0.0007, 2.4, area=0.028),
            _row(light, "extrude=gpu zmode=auto", 0.00001, 1.4, "volume", area=0.05),
            _row(light, "extrude=cpu zmode=auto", 0.00001, 1.5, "volume", area=0.05),
        ]
    return rows


def test_presets_keep_their_promise_at_the_lowest_cost():
    picks = choose_presets(_frontier())
    assert picks["draft"].settings == {"resolution": 512, "filter": "hard", "quality": "draft"}
    assert picks["draft"].worst <= DRAFT_WITHIN
    balanced = picks["balanced"]
    assert balanced.settings == {
        "resolution": 1024,
        "filter": "pcf",
        "pcf_taps": 4,
        "quality": "balanced",
    }
    assert balanced.worst <= BALANCED_WITHIN and balanced.kept
    # exact: the cheaper extrusion; the most accurate hard map for open casters.
    assert picks["exact"].settings == {
        "extrude": "gpu",
        "resolution": 2048,
        "filter": "hard",
        "quality": "exact",
    }
    assert [r.light for r in picks["exact"].rows] == list(LIGHTS)


def test_a_promise_no_setting_keeps_is_said_so():
    rows = [r for r in _frontier() if "pcf_taps=4" not in r.setting]
    rows = [r for r in rows if not (r.light == "spot" and "pcf_taps=16" in r.setting)]
    rows.append(_row("spot", "resolution=1024 filter=pcf pcf_taps=16", 0.0025, 2.4, area=0.03))
    balanced = choose_presets(rows)["balanced"]
    assert not balanced.kept
    assert balanced.settings["resolution"] == 1024  # the most accurate of the soft settings
    lines = "\n".join(presets_lines(choose_presets(rows), rows))
    assert "| balanced | spot |" in lines and "| no |" in lines


def test_costs_within_the_noise_tie_and_the_more_accurate_wins():
    rows = [r for r in _frontier() if "pcf_taps=16" not in r.setting]
    # 512 texels 10 % cheaper than 1024: within COST_TIE, so the more accurate 1024 wins.
    rows += [_row(light, "resolution=1024 filter=hard", 0.002, 1.42) for light in LIGHTS]
    rows += [_row(light, "resolution=512 filter=pcf pcf_taps=4", 0.0015, 1.55) for light in LIGHTS]
    picks = choose_presets(rows)
    assert picks["draft"].settings["resolution"] == 1024
    assert picks["balanced"].settings["resolution"] == 1024
    # Beyond the tie the cheaper one wins, as long as it keeps the promise.
    faster = [r for r in rows if r.setting != "resolution=512 filter=hard"]
    faster += [_row(light, "resolution=512 filter=hard", 0.004, 1.2) for light in LIGHTS]
    assert choose_presets(faster)["draft"].settings["resolution"] == 512
    assert 1.42 > (1.0 + COST_TIE) * 1.2


def test_draft_is_a_hard_edged_map():
    rows = [
        *_frontier(),
        *(_row(lt, "resolution=256 filter=pcf pcf_taps=4", 0.001, 0.9) for lt in LIGHTS),
    ]
    assert choose_presets(rows)["draft"].settings["filter"] == "hard"


def test_a_setting_not_measured_for_every_light_is_no_candidate():
    rows = [*_frontier(), _row("point", "resolution=64 filter=hard", 0.0001, 1.0)]
    assert choose_presets(rows)["draft"].settings["resolution"] == 512


def test_a_preset_is_dominated_only_by_a_case_better_on_every_measure():
    rows = _frontier()
    picks = choose_presets(rows)
    # Volumes are cheaper and misclassify less than balanced, but their hard edges are
    # further from the area light: balanced is on the frontier, and so is draft.
    assert dominated_by(picks["balanced"], rows) == []
    assert dominated_by(picks["draft"], rows) == []
    better = _row("spot", "resolution=512 filter=random samples=16", 0.0005, 1.5, area=0.03)
    assert dominated_by(picks["balanced"], [*rows, better]) == [better]


def test_presets_json_applies_as_enable_arguments(tmp_path):
    import pyvista as pv

    path = write_presets(choose_presets(_frontier()), tmp_path)
    presets = json.loads(path.read_text())
    assert set(presets) == {"draft", "balanced", "exact"}
    pl = pv.Plotter(off_screen=True, window_size=(64, 48), lighting="none")
    _ = pl.add_mesh(pv.Sphere())
    bulb = pv.Light(position=(0, 0, 3), positional=True, cone_angle=180)
    pl.add_light(bulb)
    for quality, settings in presets.items():
        pl.shadows.enable(**settings)
        chosen = pl.shadows.settings(bulb)
        assert (chosen.quality, chosen.resolution, chosen.filter) == (
            quality,
            settings["resolution"],
            settings["filter"],
        )
        pl.shadows.disable()


def test_steady_needs_ratios_that_agree():
    assert steady([10.0] * 4, [20.0, 20.2, 19.9, 20.1], 0.03)
    assert not steady([10.0] * 4, [20.0, 26.0, 15.0, 21.0], 0.03)
    # More frames of the same spread make the median steadier.
    noisy = [20.0, 21.0, 19.0, 20.5]
    assert not steady([10.0] * 4, noisy, 0.01)
    assert steady([10.0] * 64, noisy * 16, 0.01)


def test_progress_bar_says_how_much_is_left():
    out = io.StringIO()
    bar = ProgressBar(4, stream=out)
    assert "0/4" in bar.text() and "~? left" in bar.text()
    bar.step("first")
    bar.step("second")
    last = out.getvalue().splitlines()[-1]
    assert last.startswith("bench [###############---------------] 2/4, 0:00 spent, ~0:00 left")
    assert last.endswith("second")
    bar.step()
    bar.step()
    bar.step()  # never past the total
    assert bar.done == 4


def test_quick_help_says_what_it_runs():
    commands = parser()._subparsers._group_actions[0].choices
    help_text = commands["bench"].format_help()
    assert f"{len(quick_cases())} cases" in " ".join(help_text.split())


def test_an_interrupted_bench_keeps_what_it_measured(tmp_path):
    cases = [
        BenchCase("cubemap", {"resolution": 128, "filter": "hard"}),
        BenchCase("cubemap", {"resolution": 256, "filter": "hard"}),
    ]

    def written(rows):
        write_table(rows, tmp_path)
        if len(rows) == 1:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_bench(
            cases, frames=2, window_size=(160, 120), progress=lambda line: None, on_row=written
        )
    rows = list(csv.DictReader(open(tmp_path / "bench.csv", encoding="utf-8")))
    assert [r["setting"] for r in rows] == ["resolution=128 filter=hard"]
    assert 0.0 <= float(rows[0]["misclassified"]) < 0.05
    assert "| cubemap | point | resolution=128 filter=hard |" in (tmp_path / "bench.md").read_text()


def test_the_cold_cache_control_is_tabled_apart_from_the_actors_series(tmp_path):
    from pvshadows.tools.overhead import (
        MOTIONS,
        OverheadRow,
        OverheadScene,
        overhead_scenes,
        write_overhead,
    )

    cold = [scene for scene in overhead_scenes() if scene.cold_after]
    assert [scene.label for scene in cold] == ["1 caster after a 1000-caster frame, spot"]

    def row(scene, added):
        timed = dict.fromkeys(MOTIONS, added)
        return OverheadRow(scene, plain_ms=timed, added_ms=timed, frames=9, first_plain_s=0.5)

    rows = [
        row(OverheadScene("actors", actors=1), 0.2),
        row(cold[0], 0.6),
        row(OverheadScene("actors", actors=100), 0.2),
        row(OverheadScene("actors", actors=500, technique="volume"), 7.0),
    ]
    text = write_overhead(rows, tmp_path)
    line = next(x for x in text.splitlines() if x.startswith("| 1 caster after"))
    assert "| not timed |" in line  # its first frame is not measured: NaN is not printed
    # Neither the control nor a row drawn by another technique is a size of the actors
    # series: the fit over 1 and 100 casters is flat.
    assert "| actors | camera | 0.2 ms * actors^0.00 |" in text
    assert "| 500 casters, spot, technique=volume | " in text
    with open(tmp_path / "overhead.csv", encoding="utf-8") as handle:
        records = {r["scene"]: r for r in csv.DictReader(handle)}
    assert records["1 caster after a 1000-caster frame, spot"]["cold_after"] == "1000"
