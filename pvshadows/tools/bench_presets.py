"""Quality presets chosen from the bench's measured frontier, by what each promises.

``pvshadows bench`` measures the same shadow-map settings for every kind of
light (:data:`pvshadows.tools.bench.MAP_GRID`) and shadow volumes for every kind
of light. Each quality preset is a promise, and the bench picks, among what
it measured on the machine it ran on, the cheapest settings that keep it for
every kind of light (cost: the mean time ratio with the light moving over
the point, spot and directional scenes):

- ``draft``: the fastest hard-edged shadow map with at most
  :data:`DRAFT_WITHIN` of lit-side pixels misclassified;
- ``balanced``: the fastest soft-edged shadow map (``pcf`` or ``random``)
  with at most :data:`BALANCED_WITHIN` misclassified;
- ``exact``: pixel-exact hard edges: the fastest shadow volumes with at most
  :data:`EXACT_WITHIN` misclassified, and for casters volumes cannot take
  (open ones) the most accurate hard-edged shadow map.

Costs closer than :data:`COST_TIE` are within the bench's noise and count as
equal: among them the more accurate setting wins, so a preset never trades
accuracy for a speed-up the bench cannot tell from chance. PCSS is left out:
its penumbra needs the light's physical size, which only the user knows.
The bench writes its picks to ``presets.json``, each as the keyword
arguments of :meth:`pvshadows.ShadowsComponent.enable`.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from pvshadows.model.settings import QUALITY_PRESETS, preset, validated
from pvshadows.tools.bench import MAP_TECHNIQUE, BenchRow

#: Largest share of lit-side pixels ``draft`` may misclassify, for every kind of light.
DRAFT_WITHIN = 0.005
#: Largest share of lit-side pixels ``balanced`` may misclassify, for every kind of light
#: (between draft's and exact's; at 0.1 % only 2048-texel PCF qualified, at 3.4 times the
#: plain frame, on the bench that set the package's presets).
BALANCED_WITHIN = 0.002
#: Largest share of lit-side pixels ``exact`` may misclassify ("pixel-exact").
EXACT_WITHIN = 0.0001
#: Relative difference of cost below which two settings cost the same: three full
#: benches on the 2-core llvmpipe machine gave the same case time ratios whose
#: spread (largest minus smallest over the mean) had a median of 18 %.
COST_TIE = 0.15
#: The lights a preset must keep its promise for.
LIGHTS = ("point", "spot", "directional")
#: Soft-edged filters a preset may use (PCSS needs the light's size).
SOFT_PRESET_FILTERS = ("pcf", "random")

PROMISES = {
    "draft": f"fastest hard-edged shadow map within {100 * DRAFT_WITHIN:g} % misclassified",
    "balanced": f"soft edges within {100 * BALANCED_WITHIN:g} % misclassified, at the lowest cost",
    "exact": f"pixel-exact hard edges (within {100 * EXACT_WITHIN:g} %), at the lowest cost",
}


def parse_setting(setting: str) -> dict:
    """Return a bench row's ``name=value`` words as settings, numbers as numbers.

    Parameters
    ----------
    setting : str
        A :attr:`pvshadows.tools.bench.BenchRow.setting`.

    Returns
    -------
    dict
        Setting names and values.

    Examples
    --------
    >>> from pvshadows.tools.bench_presets import parse_setting
    >>> parse_setting("resolution=1024 filter=pcf pcf_taps=16")
    {'resolution': 1024, 'filter': 'pcf', 'pcf_taps': 16}
    """
    settings: dict = {}
    for word in setting.split():
        name, _, text = word.partition("=")
        for kind in (int, float):
            try:
                settings[name] = kind(text)
                break
            except ValueError:
                continue
        else:
            settings[name] = text
    return settings


@dataclass(frozen=True)
class Pick:
    """One preset as the bench chose it.

    Attributes
    ----------
    quality : str
        ``"draft"``, ``"balanced"`` or ``"exact"``.
    settings : dict
        What it sets, as ``enable()`` takes it (``quality`` included).
    rows : tuple of BenchRow
        The measurements it stands on, one per kind of light.
    kept : bool
        Whether it keeps its promise for every kind of light; when no
        setting does, the most accurate one is picked and this is False.
    """

    quality: str
    settings: dict
    rows: tuple[BenchRow, ...]
    kept: bool

    @property
    def cost(self) -> float:
        """Mean time ratio with the light moving, over the kinds of light."""
        return sum(r.ratio_moving for r in self.rows) / len(self.rows)

    @property
    def worst(self) -> float:
        """Largest share misclassified over the kinds of light."""
        return max(r.misclassified for r in self.rows)


def _by_setting(rows: list[BenchRow], keep: Callable[[BenchRow], bool]) -> dict[str, tuple]:
    """Rows measured for every kind of light with the same setting, by setting."""
    found: dict[str, dict[str, BenchRow]] = {}
    for row in rows:
        if keep(row) and row.light in LIGHTS:
            found.setdefault(row.setting, {})[row.light] = row
    return {s: tuple(by[lt] for lt in LIGHTS) for s, by in found.items() if len(by) == len(LIGHTS)}


def _cheapest(quality: str, groups: dict[str, tuple], within: float) -> Pick | None:
    picks = [Pick(quality, parse_setting(s), g, True) for s, g in groups.items()]
    if not picks:
        return None
    kept = [p for p in picks if p.worst <= within]
    if kept:
        cheapest = min(p.cost for p in kept)
        tied = [p for p in kept if p.cost <= (1.0 + COST_TIE) * cheapest]
        return min(tied, key=lambda p: (p.worst, p.cost))
    best = min(picks, key=lambda p: (p.worst, p.cost))
    return Pick(quality, best.settings, best.rows, False)


def _is_map(row: BenchRow) -> bool:
    return row.technique == MAP_TECHNIQUE.get(row.light) and "passes=six" not in row.setting


def choose_presets(rows: list[BenchRow]) -> dict[str, Pick]:
    """Choose each quality preset's settings from the measured rows.

    Parameters
    ----------
    rows : list of BenchRow
        The bench's measurements.

    Returns
    -------
    dict of str to Pick
        The presets that could be chosen (a preset whose candidates were not
        measured for every kind of light is left out).

    Examples
    --------
    >>> from pvshadows.tools.bench import BenchRow
    >>> from pvshadows.tools.bench_presets import choose_presets
    >>> def row(light, setting, wrong, ratio, technique=None):
    ...     technique = technique or ("cubemap" if light == "point" else "map")
    ...     return BenchRow(technique, light, setting, wrong, 0.0, "hard", ratio, 1.0, 10.0)
    >>> rows = [row(light, s, w, t) for light in ("point", "spot", "directional")
    ...         for s, w, t in [("resolution=512 filter=hard", 0.004, 1.2),
    ...                         ("resolution=1024 filter=hard", 0.002, 1.5),
    ...                         ("resolution=1024 filter=pcf pcf_taps=4", 0.0008, 1.6)]]
    >>> picks = choose_presets(rows)
    >>> picks["draft"].settings
    {'resolution': 512, 'filter': 'hard', 'quality': 'draft'}
    >>> picks["balanced"].settings["pcf_taps"], picks["balanced"].kept
    (4, True)
    """
    maps = _by_setting(rows, _is_map)
    soft = {s: g for s, g in maps.items() if parse_setting(s).get("filter") in SOFT_PRESET_FILTERS}
    hard = {s: g for s, g in maps.items() if parse_setting(s).get("filter") == "hard"}
    volumes = _by_setting(rows, lambda r: r.technique == "volume" and "zmode=auto" in r.setting)
    picks = {
        "draft": _cheapest("draft", hard, DRAFT_WITHIN),
        "balanced": _cheapest("balanced", soft, BALANCED_WITHIN),
        "exact": _cheapest("exact", volumes, EXACT_WITHIN),
    }
    fallback = _cheapest("exact", hard, 0.0)
    exact = picks["exact"]
    if exact is not None:
        settings = {"extrude": exact.settings["extrude"]}
        if fallback is not None:
            settings |= fallback.settings
        picks["exact"] = Pick("exact", settings, exact.rows, exact.kept)
    return {
        quality: Pick(quality, {**pick.settings, "quality": quality}, pick.rows, pick.kept)
        for quality, pick in picks.items()
        if pick is not None
    }


def dominated_by(pick: Pick, rows: list[BenchRow]) -> list[BenchRow]:
    """Return the rows that beat a preset on every measure at once, for some kind of light.

    The measures: the share misclassified, the RMSE against the area light
    (where both were measured) and the time ratio with the light moving.
    Cases where only some actors receive (planar shadows) judge another
    picture and are left out.

    Parameters
    ----------
    pick : Pick
        A preset as chosen.
    rows : list of BenchRow
        Every measurement.

    Returns
    -------
    list of BenchRow
        The rows that dominate it (empty: it is on the frontier).
    """

    def beats(row: BenchRow, mine: BenchRow) -> bool:
        softer = (
            math.isnan(row.rmse_area)
            or math.isnan(mine.rmse_area)
            or row.rmse_area < mine.rmse_area
        )
        return (
            row.ratio_moving < mine.ratio_moving
            and row.misclassified < mine.misclassified
            and softer
        )

    return [
        row
        for mine in pick.rows
        for row in rows
        if row.light == mine.light and "receivers=" not in row.setting and beats(row, mine)
    ]


def write_presets(picks: dict[str, Pick], out: Path) -> Path:
    """Write the picks to ``out/presets.json``, each as ``enable()``'s keyword arguments.

    Parameters
    ----------
    picks : dict of str to Pick
        From :func:`choose_presets`.
    out : pathlib.Path
        Folder to write into.

    Returns
    -------
    pathlib.Path
        The file written. Apply a preset with
        ``pl.shadows.enable(**json.load(open(path))["balanced"])``.
    """
    out.mkdir(parents=True, exist_ok=True)
    path = out / "presets.json"
    text = json.dumps({q: p.settings for q, p in picks.items()}, indent=2)
    path.write_text(text + "\n", encoding="utf-8")
    return path


def _words(settings: dict) -> str:
    return " ".join(f"{k}={v}" for k, v in settings.items() if k != "quality")


def presets_lines(picks: dict[str, Pick], rows: list[BenchRow]) -> list[str]:
    """Return the presets table of ``bench.md``: each pick and the numbers it stands on.

    Parameters
    ----------
    picks : dict of str to Pick
        From :func:`choose_presets`.
    rows : list of BenchRow
        Every measurement (to say what, if anything, beats a pick on both
        error and cost).

    Returns
    -------
    list of str
        Markdown lines: a caption and a table with one row per preset and
        kind of light.
    """
    if not picks:
        return [
            "",
            "Quality presets: not chosen, as this bench did not measure the same settings for "
            "every kind of light (the full bench does).",
        ]
    lines = [
        "",
        "Quality presets chosen by this bench (`presets.json`), and the numbers each stands on:",
        "",
        "| quality | light | chosen here | misclassified | RMSE, area light | time ratio "
        "| promise kept | beaten on all three by | package preset |",
        "| --- | --- | --- | ---: | ---: | ---: | --- | --- | --- |",
    ]
    for quality, pick in picks.items():
        package = "the same" if _same(pick, quality) else _words(QUALITY_PRESETS[quality])
        for row in pick.rows:
            beaten = dominated_by(Pick(quality, pick.settings, (row,), pick.kept), rows)
            rmse = "—" if math.isnan(row.rmse_area) else f"{row.rmse_area:.4f}"
            lines.append(
                f"| {quality} | {row.light} | {row.technique} {row.setting} "
                f"| {100 * row.misclassified:.3f} % | {rmse} | {row.ratio_moving:.2f} "
                f"| {'yes' if pick.kept else 'no'} "
                f"| {', '.join(f'{r.technique} {r.setting}' for r in beaten) or 'nothing'} "
                f"| {package} |"
            )
    return lines


def _same(pick: Pick, quality: str) -> bool:
    """Whether the package's preset sets what the bench picked."""
    package = preset(quality)
    return validated(package, **pick.settings) == package
