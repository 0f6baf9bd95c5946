"""``pvshadows bench``: error against the reference and time ratio of every setting, in one run.

Each case renders the standard scene with one technique and setting. Its
error is measured against the ray-traced reference of the same frame; its
cost is the median frame time over the median frame time of the same scene
without shadows, measured in the same run (ratios, because shared machines
are noisy). Two ratios are kept: with the light moving every frame, so every
shadow pass runs, and with a static scene, where maps are reused.
"""

from __future__ import annotations

import csv
import statistics
import time
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from pvshadows.gl.binding import opengl_for
from pvshadows.scenes import StandardScene, standard_scene


@dataclass(frozen=True)
class BenchCase:
    """One technique and setting to measure.

    Attributes
    ----------
    technique : str
        Technique name, as ``configure`` takes it.
    settings : dict
        Settings passed to ``configure``.
    """

    technique: str
    settings: dict = field(default_factory=dict)

    @property
    def label(self) -> str:
        """Short description, e.g. ``"cubemap resolution=512 filter=hard passes=single"``."""
        return " ".join([self.technique] + [f"{k}={v}" for k, v in self.settings.items()])


@dataclass(frozen=True)
class BenchRow:
    """What one case measured.

    Attributes
    ----------
    technique, setting : str
        The case.
    misclassified : float
        Share of lit-side pixels whose shadow class disagrees with the reference.
    rmse : float
        RMSE of visibility against the reference.
    ratio_moving : float
        Median frame time with the light moving every frame, over the plain frame.
    ratio_static : float
        Median frame time of the static scene (maps reused), over the plain frame.
    frame_ms : float
        Median frame time with the light moving, in milliseconds.
    """

    technique: str
    setting: str
    misclassified: float
    rmse: float
    ratio_moving: float
    ratio_static: float
    frame_ms: float


def cubemap_cases(
    resolutions: Iterable[int] = (256, 512, 1024, 2048),
    filters: Iterable[str] = ("hard", "pcf"),
    passes: Iterable[str] = ("single", "six"),
) -> list[BenchCase]:
    """Return the cube-map cases: every resolution x filter x way of filling the cube.

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


def volume_cases(
    extrudes: Iterable[str] = ("gpu", "cpu"), zmodes: Iterable[str] = ("zpass", "zfail")
) -> list[BenchCase]:
    """Return the shadow-volume cases: GPU and CPU extrusion, each counted z-pass and z-fail.

    Parameters
    ----------
    extrudes, zmodes : iterable
        The values to combine.

    Returns
    -------
    list of BenchCase
        One case per combination.

    Examples
    --------
    >>> from pvshadows.bench import volume_cases
    >>> [case.label for case in volume_cases(extrudes=("gpu",))]
    ['volume extrude=gpu zmode=zpass', 'volume extrude=gpu zmode=zfail']
    """
    return [BenchCase("volume", {"extrude": e, "zmode": z}) for e in extrudes for z in zmodes]


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
    section = "\n".join(lines) + "\n"
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "bench.md", "a", encoding="utf-8") as handle:
        handle.write(section)
    return section


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


def run_bench(
    cases: list[BenchCase],
    *,
    frames: int = 10,
    window_size: tuple[int, int] = (800, 600),
    progress: Callable[[str], None] = print,
) -> list[BenchRow]:
    """Measure every case on the standard scene.

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
        One row per case, in order.
    """
    import pvshadows  # noqa: F401 - registers pl.shadows

    shadowed = standard_scene(window_size=window_size)
    plain = standard_scene(window_size=window_size)
    for scene in (shadowed, plain):
        scene.plotter.screenshot(return_img=True)
    clock = PairedClock(shadowed, plain)
    shadows = shadowed.plotter.shadows
    rows = []
    for number, case in enumerate(cases, start=1):
        shadows.enable(technique=case.technique, **case.settings)
        base_moving, moving = clock.medians(frames, moving=True)
        base_static, static = clock.medians(frames, moving=False)
        error = shadows.measure(shadowed.light)
        shadows.disable()
        row = BenchRow(
            case.technique,
            case.label.removeprefix(case.technique).strip(),
            error.misclassified,
            error.rmse,
            moving / base_moving,
            static / base_static,
            moving,
        )
        rows.append(row)
        progress(
            f"[{number}/{len(cases)}] {case.label}: misclassified {100 * row.misclassified:.3f} %, "
            f"RMSE {row.rmse:.4f}, "
            f"time x{row.ratio_moving:.2f} moving / x{row.ratio_static:.2f} static "
            f"(plain frame {base_moving:.1f} ms)"
        )
    for scene in (shadowed, plain):
        scene.plotter.close()
    return rows


def write_table(rows: list[BenchRow], out: Path) -> None:
    """Write ``bench.csv`` and ``bench.md`` into ``out``.

    Parameters
    ----------
    rows : list of BenchRow
        The measurements.
    out : pathlib.Path
        Folder to write into (created if needed).
    """
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "bench.csv", "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(asdict(rows[0])))
        writer.writeheader()
        writer.writerows(asdict(row) for row in rows)
    lines = [
        "| technique | setting | misclassified | RMSE | time ratio (light moving) "
        "| time ratio (static) | frame ms |",
        "| --- | --- | ---: | ---: | ---: | ---: | ---: |",
    ]
    lines += [
        f"| {r.technique} | {r.setting} | {100 * r.misclassified:.3f} % | {r.rmse:.4f} "
        f"| {r.ratio_moving:.2f} | {r.ratio_static:.2f} | {r.frame_ms:.1f} |"
        for r in rows
    ]
    (out / "bench.md").write_text("\n".join(lines) + "\n", encoding="utf-8")


def _short(setting: str) -> str:
    values = [part.split("=", 1)[1] for part in setting.split() if "=" in part]
    return "/".join(values)


def pareto_front(rows: list[BenchRow]) -> list[BenchRow]:
    """Return the rows no other row beats on both error and time, cheapest first.

    Parameters
    ----------
    rows : list of BenchRow
        The measurements.

    Returns
    -------
    list of BenchRow
        The accuracy-cost frontier.

    Examples
    --------
    >>> from pvshadows.bench import BenchRow, pareto_front
    >>> rows = [BenchRow("a", "x", 0.1, 0, 1.0, 1.0, 1), BenchRow("a", "y", 0.2, 0, 2.0, 1.0, 1),
    ...         BenchRow("a", "z", 0.05, 0, 3.0, 1.0, 1)]
    >>> [r.setting for r in pareto_front(rows)]
    ['x', 'z']
    """
    front = []
    for row in sorted(rows, key=lambda r: (r.ratio_moving, r.misclassified)):
        if not front or row.misclassified < front[-1].misclassified:
            front.append(row)
    return front


def plot_frontier(rows: list[BenchRow], path: Path) -> None:
    """Plot error against time ratio: colour per technique, marker per filter, and the frontier.

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

    markers = {"hard": "s", "pcf": "o", "random": "^", "pcss": "D"}
    figure, axes = plt.subplots(figsize=(8, 5.5), dpi=120)
    colours = dict(zip(dict.fromkeys(r.technique for r in rows), plt.cm.tab10.colors, strict=False))
    for row in rows:
        kind = next((f for f in markers if f"filter={f}" in row.setting), None)
        axes.scatter(
            row.ratio_moving,
            100 * row.misclassified,
            color=colours[row.technique],
            marker=markers.get(kind, "o"),
            s=36,
            zorder=3,
        )
        axes.annotate(
            _short(row.setting),
            (row.ratio_moving, 100 * row.misclassified),
            fontsize=6,
            xytext=(4, 2),
            textcoords="offset points",
        )
    front = pareto_front(rows)
    axes.step(
        [r.ratio_moving for r in front],
        [100 * r.misclassified for r in front],
        where="post",
        color="0.5",
        linewidth=1,
        zorder=2,
        label="frontier",
    )
    for technique, colour in colours.items():
        axes.scatter([], [], color=colour, label=technique)
    for kind, marker in markers.items():
        if any(f"filter={kind}" in r.setting for r in rows):
            axes.scatter([], [], color="0.3", marker=marker, label=f"filter {kind}")
    axes.set_yscale("log")
    axes.set_xlabel("frame time / frame time without shadows (light moving every frame)")
    axes.set_ylabel("lit-side pixels misclassified against ray tracing (%)")
    axes.set_title("pvshadows: accuracy against cost (labels: setting values)")
    axes.grid(alpha=0.3, which="both")
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)
