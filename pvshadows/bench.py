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


class FrameClock:
    """Times whole frames of one scene, GPU work included.

    Parameters
    ----------
    scene : StandardScene
        The scene whose window is drawn.
    """

    def __init__(self, scene: StandardScene) -> None:
        self._scene = scene
        self._window = scene.plotter.ren_win
        self._gl = opengl_for(self._window)
        self._home = np.array(scene.light.position, dtype=np.float64)

    def frames(self, count: int, *, moving: bool) -> list[float]:
        """Draw ``count`` frames and return each one's time in milliseconds.

        Parameters
        ----------
        count : int
            Frames to time (two more are drawn first, untimed).
        moving : bool
            Nudge the light by a hair every frame, so no map can be reused.

        Returns
        -------
        list of float
            Frame times.
        """
        step = 1e-4 * self._scene.scale
        times = []
        for frame in range(count + 2):
            if moving:
                self._scene.light.position = tuple(self._home + (frame % 2) * step)
            start = time.perf_counter()
            self._window.Render()
            self._gl.glFinish()
            if frame >= 2:
                times.append((time.perf_counter() - start) * 1e3)
        self._scene.light.position = tuple(self._home)
        return times


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
        Receives one line per finished step.

    Returns
    -------
    list of BenchRow
        One row per case, in order.
    """
    import pvshadows  # noqa: F401 - registers pl.shadows

    scene = standard_scene(window_size=window_size)
    plotter = scene.plotter
    plotter.screenshot(return_img=True)
    clock = FrameClock(scene)
    plain = clock.frames(frames, moving=True)
    progress(f"plain frame: {statistics.median(plain):.1f} ms (median of {frames})")
    rows = []
    for number, case in enumerate(cases, start=1):
        plotter.shadows.enable(technique=case.technique, **case.settings)
        moving = statistics.median(clock.frames(frames, moving=True))
        static = statistics.median(clock.frames(frames, moving=False))
        error = plotter.shadows.measure(scene.light)
        plotter.shadows.disable()
        plain += clock.frames(max(2, frames // 4), moving=True)
        base = statistics.median(plain)
        row = BenchRow(
            case.technique,
            case.label.removeprefix(case.technique).strip(),
            error.misclassified,
            error.rmse,
            moving / base,
            static / base,
            moving,
        )
        rows.append(row)
        progress(
            f"[{number}/{len(cases)}] {case.label}: misclassified {100 * row.misclassified:.3f} %, "
            f"RMSE {row.rmse:.4f}, "
            f"time x{row.ratio_moving:.2f} moving / x{row.ratio_static:.2f} static"
        )
    plotter.close()
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


def plot_frontier(rows: list[BenchRow], path: Path) -> None:
    """Plot error against time ratio, one marker per case, one colour per technique.

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

    figure, axes = plt.subplots(figsize=(8, 5.5), dpi=120)
    for technique in dict.fromkeys(r.technique for r in rows):
        chosen = [r for r in rows if r.technique == technique]
        axes.scatter(
            [r.ratio_moving for r in chosen],
            [100 * r.misclassified for r in chosen],
            label=technique,
        )
        for r in chosen:
            axes.annotate(
                r.setting,
                (r.ratio_moving, 100 * r.misclassified),
                fontsize=6,
                xytext=(3, 3),
                textcoords="offset points",
            )
    axes.set_xlabel("frame time / frame time without shadows (light moving every frame)")
    axes.set_ylabel("lit-side pixels misclassified against ray tracing (%)")
    axes.set_title("pvshadows: accuracy against cost")
    axes.grid(alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)
