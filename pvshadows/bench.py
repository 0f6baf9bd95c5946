"""``pvshadows bench``: error against the reference and time ratio of every setting, in one run.

Each case renders the standard scene, lit by a point, spot or directional
light, with one technique and setting. Its error is measured against the
ray-traced reference of the same frame: the share of lit-side pixels whose
shadow class disagrees with exact hard visibility, and the RMSE of visibility
against the reference that suits the filter (hard visibility for ``hard``,
a many-sample area light for the soft filters). Its cost is the median frame
time over the median frame time of the same scene without shadows, frames
of the two alternating in the same run (ratios, because shared machines are
noisy). Two ratios are kept: with the light moving every frame, so every
shadow pass runs, and with a static scene, where maps are reused. VTK's own
``enable_shadows()`` is measured the same way beside them.
"""

from __future__ import annotations

import csv
import itertools
import statistics
import time
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from pvshadows.builtin import builtin_visibility
from pvshadows.gl.binding import opengl_for
from pvshadows.measure import compare
from pvshadows.scenes import (
    StandardScene,
    crowd_scene,
    eight_spots_scene,
    standard_scene,
    three_lights_scene,
)
from pvshadows.settings import QUALITIES


@dataclass(frozen=True)
class BenchCase:
    """One technique and setting to measure.

    Attributes
    ----------
    technique : str
        Technique name, as ``configure`` takes it, or ``"vtk"`` for VTK's own
        ``enable_shadows()``.
    settings : dict
        Settings passed to ``configure``.
    light : str
        The standard scene's light: ``"point"``, ``"spot"`` or ``"directional"``.
    receivers : tuple of str
        The only actors of the standard scene that receive shadows (``"ground"``,
        ``"box"``, ``"sphere"``, ``"cylinder"``); empty: all of them.
    """

    technique: str
    settings: dict = field(default_factory=dict)
    light: str = "point"
    receivers: tuple[str, ...] = ()

    @property
    def setting(self) -> str:
        """The settings as ``name=value`` words (and the receivers, when not all)."""
        words = [f"{k}={v}" for k, v in self.settings.items()]
        if self.receivers:
            words.append(f"receivers={'+'.join(self.receivers)}")
        return " ".join(words)

    @property
    def label(self) -> str:
        """Short description, e.g. ``"cubemap (point) resolution=512 filter=hard"``."""
        return f"{self.technique} ({self.light}) {self.setting}".strip()

    @property
    def soft(self) -> bool:
        """Whether the case's filter makes soft shadows (judged against an area light)."""
        return self.settings.get("filter") in SOFT_FILTERS


@dataclass(frozen=True)
class BenchRow:
    """What one case measured.

    Attributes
    ----------
    technique, light, setting : str
        The case.
    misclassified : float
        Share of lit-side pixels whose shadow class disagrees with exact hard
        visibility.
    rmse : float
        RMSE of visibility against ``reference``.
    reference : str
        ``"hard"``, or the area light the soft filters are judged against.
    ratio_moving : float
        Median frame time with the light moving every frame, over the plain frame.
    ratio_static : float
        Median frame time of the static scene (maps reused), over the plain frame.
    frame_ms : float
        Median frame time with the light moving, in milliseconds.
    """

    technique: str
    light: str
    setting: str
    misclassified: float
    rmse: float
    reference: str
    ratio_moving: float
    ratio_static: float
    frame_ms: float


#: Filters judged against an area-light reference.
SOFT_FILTERS = ("pcf", "random", "pcss")
#: Size of each light for the soft filters and their reference (world radius, or degrees).
LIGHT_SIZE = {"point": 0.25, "spot": 0.25, "directional": 2.0}
#: Shadow rays per pixel of the area-light reference.
REFERENCE_SAMPLES = 128


def cubemap_cases(
    resolutions: Iterable[int] = (256, 512, 1024, 2048),
    filters: Iterable[str] = ("hard", "pcf"),
    passes: Iterable[str] = ("single", "six"),
) -> list[BenchCase]:
    """Return point-light cube-map cases: every resolution x filter x way of filling the cube.

    Parameters
    ----------
    resolutions, filters, passes : iterable
        The values to combine.

    Returns
    -------
    list of BenchCase
        One case per combination.

    Examples
    --------
    >>> from pvshadows.bench import cubemap_cases
    >>> len(cubemap_cases())
    16
    """
    return [
        BenchCase("cubemap", {"resolution": r, "filter": f, "passes": p})
        for r in resolutions
        for f in filters
        for p in passes
    ]


def filter_cases(technique: str, light: str, resolutions: Iterable[int]) -> list[BenchCase]:
    """Return one technique's cases over every filter setting, for one kind of light.

    Parameters
    ----------
    technique : str
        ``"cubemap"`` or ``"map"``.
    light : str
        The scene's light.
    resolutions : iterable of int
        Map resolutions.

    Returns
    -------
    list of BenchCase
        hard, pcf 4 and 16 taps, random 16 and 64 samples, and pcss, per resolution.

    Examples
    --------
    >>> from pvshadows.bench import filter_cases
    >>> [c.setting for c in filter_cases("map", "spot", [512])][-1]
    'resolution=512 filter=pcss samples=32 light_size=0.25'
    """
    size = LIGHT_SIZE[light]
    filters = [
        {"filter": "hard"},
        {"filter": "pcf", "pcf_taps": 4},
        {"filter": "pcf", "pcf_taps": 16},
        {"filter": "random", "samples": 16},
        {"filter": "random", "samples": 64},
        {"filter": "pcss", "samples": 32, "light_size": size},
    ]
    return [
        BenchCase(technique, {"resolution": r, **f}, light) for r in resolutions for f in filters
    ]


def preset_cases() -> list[BenchCase]:
    """Return the quality presets of ``enable(quality=...)`` for each kind of light.

    Returns
    -------
    list of BenchCase
        ``technique="auto"`` with each quality, for point, spot and directional lights.

    Examples
    --------
    >>> from pvshadows.bench import preset_cases
    >>> preset_cases()[0].label
    'auto (point) quality=draft'
    """
    return [
        BenchCase("auto", {"quality": quality}, light)
        for light in ("point", "spot", "directional")
        for quality in QUALITIES
    ]


def all_cases() -> list[BenchCase]:
    """Return the published bench: every technique and setting, and VTK's own shadows.

    Returns
    -------
    list of BenchCase
        Point light: cube map x resolution x filter x passes, the soft
        filters, and shadow volumes (GPU and CPU extrusion, z-pass and
        z-fail); spot light: 2D map x resolution x filter, volumes, and VTK's
        ``enable_shadows()``; directional light: fitted 2D map x resolution x
        filter, and volumes; every light: planar shadows on the ground alone.

    Examples
    --------
    >>> from pvshadows.bench import all_cases
    >>> sorted({c.technique for c in all_cases()})
    ['auto', 'cubemap', 'map', 'planar', 'volume', 'vtk']
    """
    cases = cubemap_cases()
    cases += [c for c in filter_cases("cubemap", "point", [1024]) if c.soft]
    cases += volume_cases()
    cases += filter_cases("map", "spot", [512, 1024, 2048])
    cases += volume_cases(zmodes=("auto",), light="spot")
    cases.append(BenchCase("vtk", {}, "spot"))
    cases += filter_cases("map", "directional", [1024, 2048])
    cases += volume_cases(zmodes=("auto",), light="directional")
    cases += planar_cases()
    return cases + preset_cases()


def planar_cases(lights: Iterable[str] = ("point", "spot", "directional")) -> list[BenchCase]:
    """Return the planar-shadow cases: the standard scene with only the ground receiving.

    Planar shadows fall on one plane and objects do not shadow each other,
    so the other actors are not receivers in these cases.

    Parameters
    ----------
    lights : iterable of str
        The kinds of light.

    Returns
    -------
    list of BenchCase
        One case per light.

    Examples
    --------
    >>> from pvshadows.bench import planar_cases
    >>> [case.label for case in planar_cases(["spot"])]
    ['planar (spot) receivers=ground']
    """
    return [BenchCase("planar", {}, light, ("ground",)) for light in lights]


def volume_cases(
    extrudes: Iterable[str] = ("gpu", "cpu"),
    zmodes: Iterable[str] = ("zpass", "zfail"),
    light: str = "point",
) -> list[BenchCase]:
    """Return the shadow-volume cases: GPU and CPU extrusion, each counted z-pass and z-fail.

    Parameters
    ----------
    extrudes, zmodes : iterable
        The values to combine.
    light : str, default: "point"
        The scene's light.

    Returns
    -------
    list of BenchCase
        One case per combination.

    Examples
    --------
    >>> from pvshadows.bench import volume_cases
    >>> [case.label for case in volume_cases(extrudes=("gpu",))]
    ['volume (point) extrude=gpu zmode=zpass', 'volume (point) extrude=gpu zmode=zfail']
    """
    return [
        BenchCase("volume", {"extrude": e, "zmode": z}, light) for e in extrudes for z in zmodes
    ]


def silhouette_timings(
    sizes: Iterable[int] = (100_000, 1_000_000),
    *,
    repeats: int = 3,
    progress: Callable[[str], None] = print,
) -> list[dict]:
    """Time building shadow volumes on the CPU alone, for closed spheres of each size.

    Parameters
    ----------
    sizes : iterable of int
        Approximate triangle counts.
    repeats : int, default: 3
        Timed repetitions; medians are reported.
    progress : callable, default: print
        Receives one line per size.

    Returns
    -------
    list of dict
        :func:`pvshadows.silhouette.time_silhouette`'s figures per size, plus
        ``prepare_s``: the one-time preparation for volumes (welding,
        checking, adjacency, bodies; :func:`pvshadows.volume_casters.prepare_volume_mesh`).

    Examples
    --------
    >>> from pvshadows.bench import silhouette_timings
    >>> silhouette_timings([2000], repeats=1, progress=lambda line: None)[0]["n_triangles"] > 1000
    True
    """
    import pyvista as pv

    from pvshadows.silhouette import time_silhouette
    from pvshadows.volume_casters import prepare_volume_mesh

    rows = []
    for size in sizes:
        row = time_silhouette(size, repeats=repeats)
        resolution = max(int(np.sqrt(size / 2.0)), 8)
        sphere = pv.Sphere(theta_resolution=resolution, phi_resolution=resolution + 2)
        times = []
        for _ in range(repeats):
            start = time.perf_counter()
            prepare_volume_mesh(sphere.points, sphere.regular_faces, "sphere")
            times.append(time.perf_counter() - start)
        row["prepare_s"] = float(statistics.median(times))
        rows.append(row)
        progress(
            f"silhouettes, {row['n_triangles']} triangles: per-frame rebuild "
            f"{1e3 * (row['silhouette_point_s'] + row['volume_point_s']):.1f} ms (point light), "
            f"{1e3 * (row['silhouette_directional_s'] + row['volume_directional_s']):.1f} ms "
            f"(directional); once per mesh {1e3 * row['prepare_s']:.0f} ms"
        )
    return rows


def append_silhouette_table(timings: list[dict], out: Path) -> str:
    """Append the silhouette timings to ``out/bench.md`` as a second table.

    Parameters
    ----------
    timings : list of dict
        From :func:`silhouette_timings`.
    out : pathlib.Path
        Folder holding ``bench.md`` (created if needed).

    Returns
    -------
    str
        The section written, to print.
    """
    lines = [
        "",
        'Shadow volumes built on the CPU (extrude="cpu"), closed UV spheres, median ms:',
        "",
        "| triangles | silhouette edges | silhouette + volume, point light "
        "| silhouette + volume, directional | once per mesh: prepare (weld, check, adjacency) |",
        "| ---: | ---: | ---: | ---: | ---: |",
    ]
    lines += [
        f"| {t['n_triangles']} | {t['n_silhouette_edges']} "
        f"| {1e3 * (t['silhouette_point_s'] + t['volume_point_s']):.1f} "
        f"| {1e3 * (t['silhouette_directional_s'] + t['volume_directional_s']):.1f} "
        f"| {1e3 * t['prepare_s']:.0f} |"
        for t in timings
    ]
    return _append(out, lines)


class PairedClock:
    """Times frames of a shadowed scene against the same scene without shadows.

    Frames of the two scenes alternate, so slow drifts of a shared machine
    hit both alike and cancel in the ratio.

    Parameters
    ----------
    shadowed, plain : StandardScene
        Two copies of the same scene; only ``shadowed`` has shadows on.
    """

    def __init__(self, shadowed: StandardScene, plain: StandardScene) -> None:
        self._scenes = (plain, shadowed)
        self._gl = opengl_for(shadowed.plotter.ren_win)
        self._homes = [np.array(scene.light.position, dtype=np.float64) for scene in self._scenes]

    def _frame(self, scene: StandardScene, home: np.ndarray, nudge: float) -> float:
        scene.light.position = tuple(home + nudge * scene.scale)
        window = scene.plotter.ren_win
        start = time.perf_counter()
        window.Render()
        window.MakeCurrent()
        self._gl.glFinish()
        return (time.perf_counter() - start) * 1e3

    def medians(self, count: int, *, moving: bool) -> tuple[float, float]:
        """Return the median frame times (plain, shadowed) in milliseconds.

        Parameters
        ----------
        count : int
            Timed frames of each scene (two more of each are drawn first).
        moving : bool
            Nudge the light by a hair every frame, so no map can be reused.

        Returns
        -------
        tuple of float
            Median plain and shadowed frame times.
        """
        times: tuple[list[float], list[float]] = ([], [])
        for frame in range(count + 2):
            nudge = 1e-4 * (frame % 2) if moving else 0.0
            for scene, home, kept in zip(self._scenes, self._homes, times, strict=True):
                elapsed = self._frame(scene, home, nudge)
                if frame >= 2:
                    kept.append(elapsed)
        for scene, home in zip(self._scenes, self._homes, strict=True):
            scene.light.position = tuple(home)
        return statistics.median(times[0]), statistics.median(times[1])


def _receive_only(scene: StandardScene, names: tuple[str, ...]) -> None:
    """Let only the named actors of the standard scene receive shadows (all when none are)."""
    for name in ("ground", "box", "sphere", "cylinder"):
        scene.plotter.shadows.set_receiver(getattr(scene, name), not names or name in names)


def _bench_light(
    cases: list[BenchCase],
    light: str,
    frames: int,
    window_size: tuple[int, int],
    progress: Callable[[str], None],
    done: int,
    total: int,
) -> list[tuple[BenchCase, BenchRow]]:
    shadowed = standard_scene(window_size=window_size, light=light)
    plain = standard_scene(window_size=window_size, light=light)
    for scene in (shadowed, plain):
        scene.plotter.screenshot(return_img=True)
    clock = PairedClock(shadowed, plain)
    plotter, shadows = shadowed.plotter, shadowed.plotter.shadows
    area_light = f"area light {LIGHT_SIZE[light]:g}{'deg' if light == 'directional' else ''}"
    rows = []
    for case in cases:
        _receive_only(shadowed, case.receivers)
        if case.technique == "vtk":
            plotter.enable_shadows()
            base_moving, moving = clock.medians(frames, moving=True)
            base_static, static = base_moving, moving
            plotter.disable_shadows()
            shown = builtin_visibility(plotter, shadowed.light)
            shadows.enable(filter="hard")
            hard = compare(shown, shadows._trace(shadowed.light))
            shadows.disable()
            error, reference = hard, "hard"
        else:
            shadows.enable(technique=case.technique, **case.settings)
            base_moving, moving = clock.medians(frames, moving=True)
            base_static, static = clock.medians(frames, moving=False)
            shown = shadows.visibility(shadowed.light)
            hard = compare(shown, shadows._trace(shadowed.light))
            error, reference = hard, "hard"
            if case.soft:
                traced = shadows._trace(
                    shadowed.light, light_size=LIGHT_SIZE[light], samples=REFERENCE_SAMPLES
                )
                error, reference = compare(shown, traced), area_light
            shadows.disable()
        row = BenchRow(
            case.technique if case.technique != "vtk" else "vtk enable_shadows()",
            light,
            case.setting,
            hard.misclassified,
            error.rmse,
            reference,
            moving / base_moving,
            static / base_static,
            moving,
        )
        rows.append((case, row))
        done += 1
        progress(
            f"[{done}/{total}] {case.label}: misclassified {100 * row.misclassified:.3f} %, "
            f"RMSE {row.rmse:.4f} vs {reference}, "
            f"time x{row.ratio_moving:.2f} moving / x{row.ratio_static:.2f} static "
            f"(plain frame {base_moving:.1f} ms)"
        )
    for scene in (shadowed, plain):
        scene.plotter.close()
    return rows


def run_bench(
    cases: list[BenchCase],
    *,
    frames: int = 10,
    window_size: tuple[int, int] = (800, 600),
    progress: Callable[[str], None] = print,
) -> list[BenchRow]:
    """Measure every case on the standard scene lit by the case's kind of light.

    Parameters
    ----------
    cases : list of BenchCase
        What to measure.
    frames : int, default: 10
        Frames per median (at least 10 for the published table).
    window_size : tuple of int, default: (800, 600)
        Size of the frame.
    progress : callable, default: print
        Receives one line per finished case.

    Returns
    -------
    list of BenchRow
        One row per case, in the order of the cases.
    """
    import pvshadows  # noqa: F401 - registers pl.shadows

    measured: dict[int, BenchRow] = {}
    for light in dict.fromkeys(case.light for case in cases):
        chosen = [case for case in cases if case.light == light]
        pairs = _bench_light(
            chosen, light, frames, window_size, progress, len(measured), len(cases)
        )
        measured.update((id(case), row) for case, row in pairs)
    return [measured[id(case)] for case in cases]


def write_table(rows: list[BenchRow], out: Path, extra: str = "") -> None:
    """Write ``bench.csv`` and ``bench.md`` into ``out``.

    Parameters
    ----------
    rows : list of BenchRow
        The measurements.
    out : pathlib.Path
        Folder to write into (created if needed).
    extra : str, optional
        Markdown appended to ``bench.md`` (for example the silhouette timings).
    """
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "bench.csv", "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(asdict(rows[0])))
        writer.writeheader()
        writer.writerows(asdict(row) for row in rows)
    lines = [
        "| technique | light | setting | misclassified | RMSE | RMSE against "
        "| time ratio (light moving) | time ratio (static) | frame ms |",
        "| --- | --- | --- | ---: | ---: | --- | ---: | ---: | ---: |",
    ]
    lines += [
        f"| {r.technique} | {r.light} | {r.setting} | {100 * r.misclassified:.3f} % "
        f"| {r.rmse:.4f} | {r.reference} | {r.ratio_moving:.2f} | {r.ratio_static:.2f} "
        f"| {r.frame_ms:.1f} |"
        for r in rows
    ]
    (out / "bench.md").write_text("\n".join(lines) + "\n" + extra, encoding="utf-8")


def append_presets_table(rows: list[BenchRow], out: Path) -> str:
    """Append the quality presets' rows to ``out/bench.md`` as their own table.

    Parameters
    ----------
    rows : list of BenchRow
        The measurements (rows of technique ``"auto"`` are the presets).
    out : pathlib.Path
        Folder holding ``bench.md``.

    Returns
    -------
    str
        The section written, to print.
    """
    lines = [
        "",
        "Quality presets (`pl.shadows.enable(quality=...)`), each a point on the frontier:",
        "",
        "| light | quality | misclassified | time ratio (light moving) | time ratio (static) |",
        "| --- | --- | ---: | ---: | ---: |",
    ]
    lines += [
        f"| {r.light} | {r.setting.removeprefix('quality=')} | {100 * r.misclassified:.3f} % "
        f"| {r.ratio_moving:.2f} | {r.ratio_static:.2f} |"
        for r in rows
        if r.technique == "auto"
    ]
    return _append(out, lines)


def append_overhead_table(out: Path, *, quick: bool = False) -> str:
    """Measure the CPU time shadows add per frame and append it to ``out/bench.md``.

    Writes ``overhead.csv`` and ``overhead.md`` too (see :mod:`pvshadows.overhead`).

    Parameters
    ----------
    out : pathlib.Path
        Folder holding ``bench.md``.
    quick : bool, default: False
        Only the standard scene with a point light, a few frames.

    Returns
    -------
    str
        The section written, to print.
    """
    from pvshadows.overhead import overhead_scenes, run_overhead, write_overhead

    frames, budget_s = (5, 5.0) if quick else (20, 20.0)
    rows = run_overhead(overhead_scenes(quick=quick), frames=frames, budget_s=budget_s)
    table = write_overhead(rows, out)
    return _append(out, ["", "Overhead per frame:", "", table])


def _append(out: Path, lines: list[str]) -> str:
    section = "\n".join(lines) + "\n"
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "bench.md", "a", encoding="utf-8") as handle:
        handle.write(section)
    return section


def planner_counts(window_size: tuple[int, int] = (400, 300)) -> list[dict]:
    """Count the passes the planner runs in three scenes, against drawing every light's map.

    Parameters
    ----------
    window_size : tuple of int, default: (400, 300)
        Window size of the scenes.

    Returns
    -------
    list of dict
        ``scene``, ``passes`` run and ``every_light`` (what drawing every
        light's map every frame would run), and for the crowd the casters drawn.
    """
    import pvshadows  # noqa: F401 - registers pl.shadows

    counts = []
    plotter, _ = eight_spots_scene(window_size)
    plotter.shadows.enable(filter="hard")
    plotter.screenshot(return_img=True)
    counts.append(
        {
            "scene": "8 spot lights, 6 of them reach no visible receiver (1 frame)",
            "passes": plotter.shadows.last_frame.passes_run,
            "every_light": 8,
        }
    )
    plotter.close()
    plotter, lights = three_lights_scene(window_size)
    plotter.shadows.enable(filter="hard")
    plotter.screenshot(return_img=True)
    moved = 0
    for _ in range(3):
        plotter.camera.azimuth = 30
        plotter.render()
        moved += plotter.shadows.last_frame.passes_run
    counts.append(
        {
            "scene": "point, spot and sun, static scene seen from 3 new cameras (3 frames)",
            "passes": moved,
            "every_light": 3 * len(lights),
        }
    )
    plotter.close()
    plotter, _, centres = crowd_scene(200, window_size)
    plotter.shadows.enable(filter="hard")
    plotter.screenshot(return_img=True)
    drawn = int(plotter.shadows.last_frame.lights[0].passes[0].detail.split()[0])
    counts.append(
        {
            "scene": "spot of 20 degrees over 200 spheres spread wide: casters drawn",
            "passes": drawn,
            "every_light": len(centres) + 1,
        }
    )
    plotter.close()
    return counts


def append_planner_table(counts: list[dict], out: Path) -> str:
    """Append the planner's pass counts to ``out/bench.md``.

    Parameters
    ----------
    counts : list of dict
        From :func:`planner_counts`.
    out : pathlib.Path
        Folder holding ``bench.md``.

    Returns
    -------
    str
        The section written, to print.
    """
    lines = [
        "",
        "Only what the scene calls for (passes counted, not timed):",
        "",
        "| scene | run | if every light drew its map |",
        "| --- | ---: | ---: |",
    ]
    lines += [f"| {c['scene']} | {c['passes']} | {c['every_light']} |" for c in counts]
    return _append(out, lines)


def _short(setting: str) -> str:
    values = [part.split("=", 1)[1] for part in setting.split() if "=" in part]
    return "/".join(values)


def pareto_front(rows: list[BenchRow], error: Callable[[BenchRow], float]) -> list[BenchRow]:
    """Return the rows no other row beats on both error and time, cheapest first.

    Parameters
    ----------
    rows : list of BenchRow
        The measurements.
    error : callable
        The error of a row.

    Returns
    -------
    list of BenchRow
        The accuracy-cost frontier.

    Examples
    --------
    >>> from pvshadows.bench import BenchRow, pareto_front
    >>> rows = [BenchRow("a", "point", s, e, 0, "hard", t, 1.0, 1)
    ...         for s, e, t in [("x", 0.1, 1.0), ("y", 0.2, 2.0), ("z", 0.05, 3.0)]]
    >>> [r.setting for r in pareto_front(rows, lambda r: r.misclassified)]
    ['x', 'z']
    """
    front: list[BenchRow] = []
    for row in sorted(rows, key=lambda r: (r.ratio_moving, error(r))):
        if not front or error(row) < error(front[-1]):
            front.append(row)
    return front


def _panel(axes, rows: list[BenchRow], error: Callable[[BenchRow], float], label: str) -> None:
    markers = {"hard": "s", "pcf": "o", "random": "^", "pcss": "D"}
    groups = list(dict.fromkeys(f"{r.technique} ({r.light})" for r in rows))
    colours = dict(zip(groups, itertools.cycle(plt_colours()), strict=False))
    for row in rows:
        kind = next((f for f in markers if f"filter={f}" in row.setting), None)
        axes.scatter(
            row.ratio_moving,
            error(row),
            color=colours[f"{row.technique} ({row.light})"],
            marker=markers.get(kind, "X"),
            s=32,
            zorder=3,
        )
        axes.annotate(
            _short(row.setting),
            (row.ratio_moving, error(row)),
            fontsize=5,
            xytext=(3, 2),
            textcoords="offset points",
        )
    front = pareto_front(rows, error)
    # The frontier runs on to the dearest case, so a single exact and cheap case still shows it.
    axes.step(
        [r.ratio_moving for r in front] + [max(r.ratio_moving for r in rows)],
        [error(r) for r in front] + [error(front[-1])],
        where="post",
        color="0.5",
        linewidth=1,
        zorder=2,
        label="frontier",
    )
    for group, colour in colours.items():
        axes.scatter([], [], color=colour, label=group)
    for kind, marker in markers.items():
        if any(f"filter={kind}" in r.setting for r in rows):
            axes.scatter([], [], color="0.3", marker=marker, label=f"filter {kind}")
    positive = [error(r) for r in rows if error(r) > 0]
    if len(positive) < len(rows):
        # Exact cases (shadow volumes: no pixel wrong) stay on the plot: linear near zero.
        linear_below = 10 ** (np.floor(np.log10(min(positive))) - 1) if positive else 1.0
        axes.set_yscale("symlog", linthresh=linear_below)
        axes.set_ylim(bottom=0.0)
    else:
        axes.set_yscale("log")
    axes.set_xlabel("frame time / plain frame time (light moving)")
    axes.set_ylabel(label)
    axes.grid(alpha=0.3, which="both")
    axes.legend(fontsize=6)


def plt_colours() -> list:
    """Return matplotlib's twenty-colour qualitative palette (repeated if there are more groups)."""
    import matplotlib.pyplot as plt

    return list(plt.cm.tab20.colors)


def plot_frontier(rows: list[BenchRow], path: Path) -> None:
    """Plot error against time ratio, with the frontier, for hard and for soft shadows.

    Left: every row's share of lit-side pixels misclassified against exact
    hard visibility. Right: the soft filters' RMSE against the area-light
    reference. Colour: technique and light; marker: filter; labels: setting values.

    Parameters
    ----------
    rows : list of BenchRow
        The measurements.
    path : pathlib.Path
        PNG file to write.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    soft = [r for r in rows if r.reference != "hard"]
    figure, panels = plt.subplots(
        1, 2 if soft else 1, figsize=(14 if soft else 8, 6), dpi=120, squeeze=False
    )
    _panel(
        panels[0, 0],
        rows,
        lambda r: 100 * r.misclassified,
        "lit-side pixels misclassified against ray tracing (%)",
    )
    panels[0, 0].set_title("hard shadow class, every technique")
    if soft:
        _panel(panels[0, 1], soft, lambda r: r.rmse, "RMSE of visibility against the area light")
        panels[0, 1].set_title("soft shadows against a many-sample area light")
    figure.suptitle("pvshadows: accuracy against cost")
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)
