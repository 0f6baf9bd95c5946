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

The cases of one kind of light share one pair of scenes and one reference of
each kind (:class:`References`), and each median stops as soon as its ratio
is steady (:func:`steady`), so the full bench (:func:`all_cases`) costs about
eight CPU-minutes. Quality presets are chosen from the rows by
:mod:`pvshadows.tools.bench_presets`.
"""

from __future__ import annotations

import csv
import math
import statistics
import time
from collections.abc import Callable, Iterable, Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from pvshadows.gl.binding import opengl_for
from pvshadows.tools.scenes import (
    StandardScene,
    crowd_scene,
    eight_spots_scene,
    standard_scene,
    three_lights_scene,
)
from pvshadows.verify.builtin import builtin_visibility
from pvshadows.verify.measure import compare


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
    rmse_area : float
        RMSE of visibility against the area-light reference, for every case
        (hard ones too, so soft and hard edges compare on one scale); NaN
        where it was not traced (cases with only some receivers, ``--quick``).
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
    rmse_area: float = math.nan


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
    >>> from pvshadows.tools.bench import cubemap_cases
    >>> len(cubemap_cases())
    16
    """
    return [
        BenchCase("cubemap", {"resolution": r, "filter": f, "passes": p})
        for r in resolutions
        for f in filters
        for p in passes
    ]


#: The technique that draws each kind of light's shadow map (what ``auto`` picks).
MAP_TECHNIQUE = {"point": "cubemap", "spot": "map", "directional": "map"}
#: Map settings measured for every kind of light alike, so a preset can be chosen among them.
MAP_GRID: tuple[Mapping[str, object], ...] = (
    *(
        {"resolution": r, **f}
        for r in (256, 512, 1024, 2048)
        for f in ({"filter": "hard"}, {"filter": "pcf", "pcf_taps": 16})
    ),
    *({"resolution": r, "filter": "pcf", "pcf_taps": 4} for r in (512, 1024)),
    {"resolution": 1024, "filter": "random", "samples": 16},
    {"resolution": 1024, "filter": "random", "samples": 64},
)


def map_cases(light: str) -> list[BenchCase]:
    """Return the shadow-map cases of one kind of light: :data:`MAP_GRID` and PCSS.

    Parameters
    ----------
    light : str
        ``"point"`` (cube maps), ``"spot"`` or ``"directional"`` (2D maps).

    Returns
    -------
    list of BenchCase
        One case per setting of :data:`MAP_GRID`, then PCSS at 1024 texels
        with the light's size.

    Examples
    --------
    >>> from pvshadows.tools.bench import map_cases
    >>> [case.label for case in map_cases("spot")][-1]
    'map (spot) resolution=1024 filter=pcss samples=32 light_size=0.25'
    """
    technique = MAP_TECHNIQUE[light]
    pcss = {"resolution": 1024, "filter": "pcss", "samples": 32, "light_size": LIGHT_SIZE[light]}
    return [BenchCase(technique, dict(settings), light) for settings in (*MAP_GRID, pcss)]


def all_cases() -> list[BenchCase]:
    """Return the published bench: every technique and setting, and VTK's own shadows.

    Returns
    -------
    list of BenchCase
        For each kind of light (point, spot, directional, in that order):
        its shadow map over :data:`MAP_GRID` and PCSS, shadow volumes
        (GPU and CPU extrusion; for the point light also forced z-fail),
        and planar shadows on the ground alone; for the point light also the
        cube filled by six draws; for the spot light VTK's
        ``enable_shadows()``.

    Examples
    --------
    >>> from pvshadows.tools.bench import all_cases
    >>> sorted({c.technique for c in all_cases()})
    ['cubemap', 'map', 'planar', 'volume', 'vtk']
    >>> len(all_cases())
    54
    """
    cases = map_cases("point")
    cases += cubemap_cases(resolutions=(512, 1024, 2048), filters=("hard",), passes=("six",))
    cases += volume_cases(zmodes=("auto", "zfail"))
    cases += planar_cases(["point"])
    cases += map_cases("spot")
    cases += volume_cases(zmodes=("auto",), light="spot")
    cases += planar_cases(["spot"])
    cases.append(BenchCase("vtk", {}, "spot"))
    cases += map_cases("directional")
    cases += volume_cases(zmodes=("auto",), light="directional")
    cases += planar_cases(["directional"])
    return cases


def quick_cases() -> list[BenchCase]:
    """Return the cases of ``pvshadows bench --quick``: one of each kind, to check the bench runs.

    Returns
    -------
    list of BenchCase
        Point light: a hard and a PCF cube map of 256 texels and GPU shadow
        volumes; spot light: a hard 2D map of 256 texels and planar shadows.

    Examples
    --------
    >>> from pvshadows.tools.bench import quick_cases
    >>> len(quick_cases())
    5
    """
    cases = [
        BenchCase("cubemap", {"resolution": 256, "filter": "hard"}),
        BenchCase("cubemap", {"resolution": 256, "filter": "pcf", "pcf_taps": 16}),
        *volume_cases(extrudes=("gpu",), zmodes=("auto",)),
        BenchCase("map", {"resolution": 256, "filter": "hard"}, "spot"),
    ]
    return cases + planar_cases(["spot"])


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
    >>> from pvshadows.tools.bench import planar_cases
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
    >>> from pvshadows.tools.bench import volume_cases
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
        :func:`pvshadows.geometry.silhouette.time_silhouette`'s figures per size, plus
        ``prepare_s``: the one-time preparation for volumes (welding,
        checking, adjacency, bodies; :func:`pvshadows.geometry.volume_casters.prepare_volume_mesh`).

    Examples
    --------
    >>> from pvshadows.tools.bench import silhouette_timings
    >>> silhouette_timings([2000], repeats=1, progress=lambda line: None)[0]["n_triangles"] > 1000
    True
    """
    import pyvista as pv

    from pvshadows.geometry.silhouette import time_silhouette
    from pvshadows.geometry.volume_casters import prepare_volume_mesh

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
        assert window is not None
        start = time.perf_counter()
        window.Render()
        window.MakeCurrent()
        self._gl.glFinish()
        return (time.perf_counter() - start) * 1e3

    def medians(
        self, count: int, *, moving: bool, at_least: int | None = None, spread: float = 0.03
    ) -> tuple[float, float]:
        """Return the median frame times (plain, shadowed) in milliseconds.

        Parameters
        ----------
        count : int
            Most timed frames of each scene (two more of each are drawn first).
        moving : bool
            Nudge the light by a hair every frame, so no map can be reused.
        at_least : int, optional
            Stop after this many timed frames once the ratio is steady: the
            spread of the per-frame ratios (interquartile range over the
            median, divided by the square root of the frames) is below
            ``spread``. By default all ``count`` frames are timed.
        spread : float, default: 0.03
            The steadiness asked of the ratio.

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
            if at_least is not None and len(times[0]) >= at_least and steady(*times, spread):
                break
        for scene, home in zip(self._scenes, self._homes, strict=True):
            scene.light.position = tuple(home)
        return statistics.median(times[0]), statistics.median(times[1])


def steady(plain: list[float], shadowed: list[float], spread: float) -> bool:
    """Whether frame-by-frame ratios are steady enough for their median to be kept.

    Parameters
    ----------
    plain, shadowed : list of float
        Frame times of the two scenes, frame for frame.
    spread : float
        Largest interquartile range of the ratios, over their median and
        the square root of their number.

    Returns
    -------
    bool
        True when the ratios vary less than ``spread`` asks.

    Examples
    --------
    >>> from pvshadows.tools.bench import steady
    >>> steady([10.0, 10.0, 10.0], [15.0, 15.1, 14.9], 0.03)
    True
    >>> steady([10.0, 10.0, 10.0], [15.0, 30.0, 10.0], 0.03)
    False
    """
    ratios = np.asarray(shadowed) / np.asarray(plain)
    low, middle, high = np.percentile(ratios, [25, 50, 75])
    return bool((high - low) / middle / math.sqrt(len(ratios)) < spread)


def _receive_only(scene: StandardScene, names: tuple[str, ...]) -> None:
    """Let only the named actors of the standard scene receive shadows (all when none are)."""
    for name in ("ground", "box", "sphere", "cylinder"):
        scene.plotter.shadows.set_receiver(getattr(scene, name), not names or name in names)


class References:
    """The ray-traced references of one light's scene, each traced once and shared by every case.

    Every case of a light renders the same frame (same scene, camera and
    light), so its exact hard visibility and its area-light visibility are
    the same for all of them; only the receivers change it.

    Parameters
    ----------
    scene : StandardScene
        The shadowed scene (its component traces).
    light : str
        Its kind of light, which sizes the area light (:data:`LIGHT_SIZE`).
    samples : int
        Shadow rays per pixel of the area-light reference.
    """

    def __init__(self, scene: StandardScene, light: str, samples: int) -> None:
        self._scene = scene
        self._size = LIGHT_SIZE[light]
        self._samples = samples
        self._traced: dict[tuple, object] = {}

    def hard(self, receivers: tuple[str, ...]):
        """Return the exact hard visibility (a ``ReferenceResult``) with these receivers."""
        return self._trace(receivers, 0.0, 1)

    def area(self, receivers: tuple[str, ...]):
        """Return the area light's visibility with these receivers."""
        return self._trace(receivers, self._size, self._samples)

    def _trace(self, receivers: tuple[str, ...], size: float, samples: int):
        key = (receivers, size, samples)
        if key not in self._traced:
            shadows = self._scene.plotter.shadows
            self._traced[key] = shadows._trace(self._scene.light, light_size=size, samples=samples)
        return self._traced[key]


def _vtk_visibility(scene: StandardScene, clock: PairedClock, frames: int, at_least: int):
    plotter = scene.plotter
    plotter.enable_shadows()  # type: ignore[call-arg]  # pyvista: decorated, self untyped
    base, moving = clock.medians(frames, moving=True, at_least=at_least)
    plotter.disable_shadows()  # type: ignore[call-arg]  # pyvista: decorated, self untyped
    return builtin_visibility(plotter, scene.light), (base, moving), (base, moving)


def _own_visibility(scene: StandardScene, clock: PairedClock, frames: int, at_least: int, case):
    shadows = scene.plotter.shadows
    shadows.enable(technique=case.technique, **case.settings)
    moving = clock.medians(frames, moving=True, at_least=at_least)
    static = clock.medians(frames, moving=False, at_least=at_least)
    return shadows.visibility(scene.light), moving, static


def _bench_light(
    cases: list[BenchCase],
    light: str,
    options: dict,
    on_row: Callable[[BenchCase, BenchRow], None],
) -> None:
    window_size = options["window_size"]
    shadowed = standard_scene(window_size=window_size, light=light)
    plain = standard_scene(window_size=window_size, light=light)
    for scene in (shadowed, plain):
        scene.plotter.screenshot(return_img=True)
    clock = PairedClock(shadowed, plain)
    shadows = shadowed.plotter.shadows
    references = References(shadowed, light, options["reference_samples"])
    area_light = f"area light {LIGHT_SIZE[light]:g}{'deg' if light == 'directional' else ''}"
    trace_area = options["area"] and any(case.soft for case in cases)
    frames, at_least = options["frames"], options["at_least"]
    for case in cases:
        _receive_only(shadowed, case.receivers)
        if case.technique == "vtk":
            shown, moving, static = _vtk_visibility(shadowed, clock, frames, at_least)
            shadows.enable(filter="hard")
        else:
            shown, moving, static = _own_visibility(shadowed, clock, frames, at_least, case)
        hard = compare(shown, references.hard(case.receivers))
        area = None
        if trace_area and (case.soft or not case.receivers):
            area = compare(shown, references.area(case.receivers))
        shadows.disable()
        soft = case.soft and area is not None
        row = BenchRow(
            case.technique if case.technique != "vtk" else "vtk enable_shadows()",
            light,
            case.setting,
            hard.misclassified,
            area.rmse if soft and area is not None else hard.rmse,
            area_light if soft else "hard",
            moving[1] / moving[0],
            static[1] / static[0],
            moving[1],
            area.rmse if area is not None else math.nan,
        )
        on_row(case, row)
    for scene in (shadowed, plain):
        scene.plotter.close()


def run_bench(
    cases: list[BenchCase],
    *,
    frames: int = 10,
    at_least: int = 3,
    window_size: tuple[int, int] = (800, 600),
    reference_samples: int = REFERENCE_SAMPLES,
    area: bool = True,
    progress: Callable[[str], None] = print,
    on_row: Callable[[list[BenchRow]], None] | None = None,
) -> list[BenchRow]:
    """Measure every case on the standard scene lit by the case's kind of light.

    Cases of the same light share one pair of scenes and one ray-traced
    reference of each kind; each case's frames stop as soon as its time
    ratio is steady.

    Parameters
    ----------
    cases : list of BenchCase
        What to measure.
    frames : int, default: 10
        Most timed frames per median.
    at_least : int, default: 3
        Fewest timed frames per median; more are timed until the ratio is
        steady (see :meth:`PairedClock.medians`) or ``frames`` are reached.
    window_size : tuple of int, default: (800, 600)
        Size of the frame.
    reference_samples : int, default: REFERENCE_SAMPLES
        Shadow rays per pixel of the area-light reference.
    area : bool, default: True
        Trace the area-light reference for lights with soft cases, and
        judge every case of those lights against it too (``rmse_area``).
    progress : callable, default: print
        Receives one line per finished case.
    on_row : callable, optional
        Receives the rows measured so far after each case, in the order
        measured (to write them as they come).

    Returns
    -------
    list of BenchRow
        One row per case, in the order of the cases.
    """
    import pvshadows  # noqa: F401 - registers pl.shadows

    measured: dict[int, BenchRow] = {}
    so_far: list[BenchRow] = []
    options = {
        "frames": frames,
        "at_least": min(at_least, frames),
        "window_size": window_size,
        "reference_samples": reference_samples,
        "area": area,
    }

    def finished(case: BenchCase, row: BenchRow) -> None:
        measured[id(case)] = row
        so_far.append(row)
        progress(
            f"[{len(so_far)}/{len(cases)}] {case.label}: misclassified "
            f"{100 * row.misclassified:.3f} %, RMSE {row.rmse:.4f} vs {row.reference}, "
            f"time x{row.ratio_moving:.2f} moving / x{row.ratio_static:.2f} static "
            f"(frame {row.frame_ms:.1f} ms)"
        )
        if on_row is not None:
            on_row(list(so_far))

    for light in dict.fromkeys(case.light for case in cases):
        _bench_light([case for case in cases if case.light == light], light, options, finished)
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


def append_lines(lines: list[str], out: Path) -> str:
    """Append Markdown lines (a section: caption and table) to ``out/bench.md``.

    Parameters
    ----------
    lines : list of str
        The section's lines.
    out : pathlib.Path
        Folder holding ``bench.md`` (created if needed).

    Returns
    -------
    str
        The section written, to print.
    """
    return _append(out, lines)


def append_overhead_table(out: Path, *, quick: bool = False, huge: bool = False) -> str:
    """Measure the CPU time shadows add per frame and append it to ``out/bench.md``.

    Writes ``overhead.csv`` and ``overhead.md`` too (see :mod:`pvshadows.tools.overhead`).

    Parameters
    ----------
    out : pathlib.Path
        Folder holding ``bench.md``.
    quick : bool, default: False
        Only the standard scene with a point light, a few frames.
    huge : bool, default: False
        Add a 10-million-triangle caster (``pvshadows bench --huge``).

    Returns
    -------
    str
        The section written, to print.
    """
    from pvshadows.tools.overhead import overhead_scenes, run_overhead, write_overhead

    frames, budget_s = (5, 5.0) if quick else (100, 20.0)
    scenes = overhead_scenes(quick=quick, huge=huge)
    rows = run_overhead(scenes, frames=frames, budget_s=budget_s)
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
    >>> from pvshadows.tools.bench import BenchRow, pareto_front
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


#: Marker of each filter in the frontier plot; cases without a filter get :data:`NO_FILTER`.
FILTER_MARKERS: dict[str | None, str] = {"hard": "s", "pcf": "o", "random": "^", "pcss": "D"}
#: Marker of cases without a filter (volumes, planar shadows, VTK's own).
NO_FILTER = "X"


def _filter_of(row: BenchRow) -> str | None:
    return next((f for f in FILTER_MARKERS if f"filter={f}" in row.setting), None)


def technique_colours(rows: list[BenchRow]) -> dict[str, tuple]:
    """Return one colour per technique of ``rows``, the same in every panel of the plot.

    Parameters
    ----------
    rows : list of BenchRow
        The measurements.

    Returns
    -------
    dict
        Technique name to an RGB colour of matplotlib's ``tab10`` palette
        (repeated if there are more than ten techniques).

    Examples
    --------
    >>> from pvshadows.tools.bench import BenchRow, technique_colours
    >>> rows = [BenchRow(t, "point", "", 0, 0, "hard", 1, 1, 1) for t in ("map", "volume", "map")]
    >>> list(technique_colours(rows))
    ['map', 'volume']
    """
    import matplotlib.pyplot as plt

    # matplotlib types plt.cm.tab10 as a Colormap; it is a ListedColormap, with colours.
    palette: list[tuple] = plt.cm.tab10.colors  # type: ignore[attr-defined]
    names = dict.fromkeys(row.technique for row in rows)
    return {name: palette[i % len(palette)] for i, name in enumerate(names)}


#: Where a point's label may go, in points from the marker, tried in order.
_LABEL_OFFSETS = ((5, 3), (5, -10), (-5, 3), (-5, -10), (5, 12), (-5, 12), (5, -19), (-5, -19))


def _place_labels(axes, points: list[tuple[float, float, str]]) -> None:
    """Label points where the label overlaps no other label or marker; leave out what cannot fit."""
    renderer = axes.figure.canvas.get_renderer()
    taken = []
    for x, y, _ in points:
        centre = axes.transData.transform((x, y))
        taken.append((centre[0] - 4, centre[1] - 4, centre[0] + 4, centre[1] + 4))
    box = axes.get_window_extent(renderer)
    for x, y, text in points:
        for dx, dy in _LABEL_OFFSETS:
            label = axes.annotate(
                text,
                (x, y),
                xytext=(dx, dy),
                textcoords="offset points",
                fontsize=7,
                ha="left" if dx > 0 else "right",
            )
            extent = label.get_window_extent(renderer)
            here = (extent.x0, extent.y0, extent.x1, extent.y1)
            inside = box.x0 <= here[0] and here[2] <= box.x1 and box.y0 <= here[1] <= box.y1
            if inside and not any(_overlap(here, other) for other in taken):
                taken.append(here)
                break
            label.remove()


def _overlap(a: tuple, b: tuple) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _panel(axes, rows: list[BenchRow], error: Callable[[BenchRow], float], colours: dict) -> None:
    for row in rows:
        kind = _filter_of(row)
        axes.scatter(
            row.ratio_moving,
            error(row),
            color=colours[row.technique],
            marker=FILTER_MARKERS.get(kind, NO_FILTER),
            s=36,
            edgecolors="black",
            linewidths=0.4,
            zorder=3,
        )
    # Cases where only some actors receive (planar: the ground) judge another picture.
    front = pareto_front([r for r in rows if "receivers=" not in r.setting] or rows, error)
    # The frontier runs on to the dearest case, so a single exact and cheap case still shows it.
    axes.step(
        [r.ratio_moving for r in front] + [max(r.ratio_moving for r in rows)],
        [error(r) for r in front] + [error(front[-1])],
        where="post",
        color="0.5",
        linewidth=1,
        zorder=2,
    )
    positive = [error(r) for r in rows if error(r) > 0]
    if len(positive) < len(rows):
        # Exact cases (shadow volumes: no pixel wrong) stay on the plot: linear near zero.
        linear_below = 10 ** (np.floor(np.log10(min(positive))) - 1) if positive else 1.0
        axes.set_yscale("symlog", linthresh=linear_below)
        axes.set_ylim(bottom=0.0)
    else:
        axes.set_yscale("log")
    axes.grid(alpha=0.3, which="both")
    axes.figure.canvas.draw()
    _place_labels(axes, [(r.ratio_moving, error(r), _label(r)) for r in front])


def _label(row: BenchRow) -> str:
    """Return a frontier point's label: its values, and its technique when it has no filter."""
    short = _short(row.setting)
    if _filter_of(row) is not None:
        return short
    return f"{row.technique.split()[0]} {short}".strip()


def _legend(figure, rows: list[BenchRow], colours: dict, columns: int) -> None:
    from matplotlib.lines import Line2D

    def marker(shape: str, colour, label: str) -> Line2D:
        return Line2D(
            [], [], marker=shape, color=colour, markeredgecolor="black", linestyle="", label=label
        )

    handles = [marker("o", colour, name) for name, colour in colours.items()]
    kinds = dict.fromkeys(_filter_of(row) for row in rows)
    handles += [
        marker(FILTER_MARKERS[k], "0.7", f"filter {k}") for k in FILTER_MARKERS if k in kinds
    ]
    if None in kinds:
        handles.append(marker(NO_FILTER, "0.7", "no filter (volume, planar, VTK)"))
    handles.append(Line2D([], [], color="0.5", label="frontier (labelled: its settings)"))
    figure.legend(handles=handles, loc="lower center", ncol=columns, fontsize=9)


def plot_frontier(rows: list[BenchRow], path: Path) -> None:
    """Plot error against time ratio, with the frontier, per kind of light.

    One row of panels per kind of light. Left: every case's share of
    lit-side pixels misclassified against exact hard visibility. Right,
    where the area-light reference was traced: every case's RMSE against
    it, so soft and hard edges compare on one scale. Colour: technique, the
    same in every panel; marker: filter; the frontier's points are labelled
    with their settings' values.

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

    lights = list(dict.fromkeys(row.light for row in rows))
    soft = any(not math.isnan(row.rmse_area) for row in rows)
    columns = 2 if soft else 1
    figure, panels = plt.subplots(
        len(lights),
        columns,
        figsize=(6.5 * columns if soft else 8.0, 4.2 * len(lights) + 1.4),
        dpi=100,
        squeeze=False,
    )
    colours = technique_colours(rows)
    for line, light in enumerate(lights):
        mine = [row for row in rows if row.light == light]
        hard = panels[line, 0]
        _panel(hard, mine, lambda r: 100 * r.misclassified, colours)
        hard.set_title(f"{light} light: hard shadow class")
        hard.set_ylabel("lit-side pixels misclassified (%)")
        if soft:
            traced = [row for row in mine if not math.isnan(row.rmse_area)]
            area = panels[line, 1]
            if traced:
                _panel(area, traced, lambda r: r.rmse_area, colours)
                area.set_title(f"{light} light: against an area light")
                area.set_ylabel("RMSE of visibility")
            else:
                area.set_axis_off()
    for axes in panels[-1]:
        axes.set_xlabel("frame time / plain frame time (light moving)")
    figure.suptitle("pvshadows: accuracy against cost")
    _legend(figure, rows, colours, 4 if soft else 3)
    figure.tight_layout(rect=(0, 1.2 / (4.2 * len(lights) + 1.4), 1, 0.98))
    figure.savefig(path)
    plt.close(figure)
