"""CPU time pvshadows adds to a frame, measured on Mesa's no-op driver.

With ``GALLIUM_NOOP=1`` Mesa validates every GL call and draws nothing, so a
frame costs only its CPU work: what remains for a user whose GPU is fast.
Each scene is built twice, once with shadows and once without (the twin);
frames of the two alternate, each moved the same way (nothing, the camera,
the first light, or one caster; the light always the same way, so that no
cache keyed by its pose answers a frame for free), and the CPU time of the
thread drawing them
(``time.thread_time()``) is kept. The overhead is the median of the
differences between the two frames of each turn, every motion measured in
rounds spread over the run. The first frame after ``enable()`` is timed
separately on the real driver (llvmpipe), wall clock, against the twin's
first frame, with Mesa's shader cache off (every shader compiled, as on a
user's first run).

Every scene runs in its own subprocess, so no scene's caches, memory or
driver warm-up reach another's.
"""

from __future__ import annotations

import csv
import json
import math
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

#: What changes between two frames of a measurement.
MOTIONS = ("static", "camera", "light", "actor")
#: Stretches of a run each motion is measured in, in turn with the others.
ROUNDS = 4
#: How far a moving light goes along x each frame (a run moves it about 0.1).
LIGHT_STEP = 1e-4
#: Window of every overhead scene (the no-op driver draws no pixel, so size barely matters).
WINDOW = (400, 300)


@dataclass(frozen=True)
class OverheadScene:
    """One scene of the overhead table.

    Attributes
    ----------
    series : str
        What the series varies: ``"standard"`` (the standard scene, one
        light of kind ``light``), ``"actors"``, ``"lights"`` or
        ``"triangles"``.
    light : str
        ``"point"``, ``"spot"`` or ``"directional"``.
    actors : int
        Casters besides the ground.
    lights : int
        Shadowed lights.
    triangles : int
        Triangles of the one big caster of the ``"triangles"`` series
        (0 elsewhere).
    cold_after : int
        Casters of a plain scene (no shadows) drawn, untimed, before each
        timed frame of both twins, or 0. Drawing that many actors evicts
        from the CPU's caches what the next frame reads, as a big scene's
        own frame does: the ``"cold"`` series (one caster after a
        1000-caster frame) tells how much of the growth along the
        ``"actors"`` series is colder caches rather than more work.
    technique : str
        The ``technique`` given to :meth:`~pvshadows.ShadowsComponent.enable`:
        ``"auto"`` (a map or a cube, as a user gets), or ``"volume"`` or
        ``"planar"``, the techniques that draw a mask in screen space and so
        work again whenever the camera moves.
    """

    series: str
    light: str = "spot"
    actors: int = 4
    lights: int = 1
    triangles: int = 0
    cold_after: int = 0
    technique: str = "auto"

    @property
    def label(self) -> str:
        """Name of the scene in the table."""
        drawn_by = "" if self.technique == "auto" else f", technique={self.technique}"
        if self.series == "standard":
            return f"standard scene, {self.light}{drawn_by}"
        casters = f"{self.actors} caster{'s' * (self.actors != 1)}"
        if self.series == "actors":
            return f"{casters}, {self.light}{drawn_by}"
        if self.series == "lights":
            return f"{self.lights} {self.light} lights"
        if self.series == "cold":
            return f"{casters} after a {self.cold_after}-caster frame, {self.light}"
        count = f"{self.triangles:_}".replace("_", " ")
        return f"{count} triangles, {self.light}"

    @property
    def size(self) -> int:
        """The quantity the series varies."""
        return {"actors": self.actors, "lights": self.lights, "triangles": self.triangles}.get(
            self.series, 1
        )


@dataclass
class OverheadRow:
    """The overhead of one scene.

    Attributes
    ----------
    scene : OverheadScene
        The scene.
    plain_ms : dict
        Median CPU ms of a frame of the twin without shadows, per motion.
    added_ms : dict
        Median CPU ms pvshadows adds to a frame, per motion.
    own_ms : dict
        Median CPU ms of pvshadows' own code in the shadowed frame
        (:attr:`pvshadows.model.report.FrameReport.cpu_ms`), per motion:
        steadier than the added time, which also holds what the receivers'
        shaders cost VTK and how each twin's work evicts the other's from
        the CPU's caches.
    passes_ms : dict
        Median CPU ms of those spent issuing the frame's passes
        (:attr:`pvshadows.model.report.FrameReport.pass_cpu_ms`), per motion.
    frames : int
        Frames per median.
    first_plain_s, first_shadowed_s : float
        Wall seconds of the first frame on llvmpipe: of the twin, and from
        ``enable()`` to the end of the first shadowed frame (NaN when not
        measured).
    """

    scene: OverheadScene
    plain_ms: dict[str, float] = field(default_factory=dict)
    added_ms: dict[str, float] = field(default_factory=dict)
    own_ms: dict[str, float] = field(default_factory=dict)
    passes_ms: dict[str, float] = field(default_factory=dict)
    frames: int = 0
    first_plain_s: float = float("nan")
    first_shadowed_s: float = float("nan")


def overhead_scenes(*, quick: bool = False, huge: bool = False) -> list[OverheadScene]:
    """Return the scenes of the overhead table.

    Parameters
    ----------
    quick : bool, default: False
        Only the standard scene with a point light, to check that it runs.
    huge : bool, default: False
        Add a 10-million-triangle caster (needs about 3 GB of memory).

    Returns
    -------
    list of OverheadScene
        The standard scene with each kind of light, the standard scene with
        a spot light drawn by the volume and the planar technique, then the
        series over casters (1, 50, 500, 1000), 500 casters drawn by the
        volume technique (one draw call per caster and pass), one caster with caches left cold by a
        1000-caster frame (:attr:`OverheadScene.cold_after`), spot lights
        (1, 4, 16) and triangles of one caster under a point light (10 k,
        1 M, and 10 M with ``huge``).

    Examples
    --------
    >>> from pvshadows.tools.overhead import overhead_scenes
    >>> [scene.label for scene in overhead_scenes()][:2]
    ['standard scene, point', 'standard scene, spot']
    >>> overhead_scenes()[3].label
    'standard scene, spot, technique=volume'
    >>> overhead_scenes(huge=True)[-1].label
    '10 000 000 triangles, point'
    """
    if quick:
        return [OverheadScene("standard", "point")]
    scenes = [OverheadScene("standard", kind) for kind in ("point", "spot", "directional")]
    scenes += [OverheadScene("standard", technique=name) for name in ("volume", "planar")]
    scenes += [OverheadScene("actors", actors=n) for n in (1, 50, 500, 1000)]
    scenes += [OverheadScene("actors", actors=500, technique=name) for name in ("volume", "planar")]
    scenes.append(OverheadScene("cold", actors=1, cold_after=1000))
    scenes += [OverheadScene("lights", lights=n) for n in (1, 4, 16)]
    counts = (10_000, 1_000_000, 10_000_000) if huge else (10_000, 1_000_000)
    scenes += [OverheadScene("triangles", "point", actors=1, triangles=n) for n in counts]
    return scenes


def _sphere_of(triangles: int):
    import pyvista as pv

    # A UV sphere of resolution n has 2 n (n - 2) triangles.
    n = max(8, round(1.0 + np.sqrt(1.0 + triangles / 2.0)))
    return pv.Sphere(radius=1.2, center=(0.0, 0.0, 1.4), theta_resolution=n, phi_resolution=n)


def build_scene(scene: OverheadScene, window_size: tuple[int, int] = WINDOW):
    """Build one scene of the table, shadows not enabled.

    Parameters
    ----------
    scene : OverheadScene
        Which scene.
    window_size : tuple of int, default: WINDOW
        Window size.

    Returns
    -------
    tuple
        The plotter, its shadowed lights and the caster that ``"actor"``
        motion moves.

    Examples
    --------
    >>> from pvshadows.tools.overhead import OverheadScene, build_scene
    >>> plotter, lights, moved = build_scene(OverheadScene("actors", actors=3), (160, 120))
    >>> plotter.renderer.GetActors().GetNumberOfItems(), len(lights)
    (4, 1)
    """
    import pyvista as pv

    from pvshadows.tools.scenes import spot_light, standard_scene

    if scene.series in ("standard", "lights"):
        standard = standard_scene(window_size=window_size, light=scene.light)
        plotter, lights = standard.plotter, [standard.light]
        if scene.series == "lights":
            standard.light.SetSwitch(False)
            angles = np.linspace(0.0, 2.0 * np.pi, scene.lights, endpoint=False)
            lights = [
                spot_light((4 * np.cos(a), 4 * np.sin(a), 5), (0, 0, 0), 40, 1.0 / scene.lights)
                for a in angles
            ]
            for light in lights:
                plotter.add_light(light)
        return plotter, lights, standard.sphere
    plotter = pv.Plotter(off_screen=True, window_size=list(window_size), lighting="none")
    plotter.add_mesh(pv.Plane(i_size=12, j_size=12), color="white")
    if scene.series == "triangles":
        moved = plotter.add_mesh(_sphere_of(scene.triangles), color="tan")
    else:
        side = int(np.ceil(np.sqrt(scene.actors)))
        step = 10.0 / side
        spots = [(i % side, i // side) for i in range(scene.actors)]
        moved = None
        for i, j in spots:
            centre = (-5 + step * (i + 0.5), -5 + step * (j + 0.5), 0.5 * step)
            sphere = pv.Sphere(
                radius=0.3 * step, center=centre, theta_resolution=8, phi_resolution=8
            )
            actor = plotter.add_mesh(sphere, color="tan")
            moved = actor if moved is None else moved
    if scene.light == "point":
        light = pv.Light(
            position=(0.5, -0.3, 6), focal_point=(0.5, -0.3, 0), positional=True, cone_angle=180
        )
    elif scene.light == "spot":
        light = spot_light((0, 0, 12), (0, 0, 0), cone_angle=35, intensity=1.0)
    else:
        light = pv.Light(position=(5, 3, 8), focal_point=(0, 0, 0))
    plotter.add_light(light)
    plotter.camera_position = [(9, -12, 10), (0, 0, 0.5), (0, 0, 1)]
    return plotter, [light], moved


def _move(plotter, lights: list, moved, motion: str, frame: int) -> None:
    if motion == "camera":
        plotter.camera.Azimuth(0.5)
    elif motion == "light":
        # Always the same way: no pose comes back, so no cache keyed by the light's
        # pose answers for free (a light swaying between two poses would hit them).
        x, y, z = lights[0].GetPosition()
        lights[0].SetPosition(x + LIGHT_STEP, y, z)
    elif motion == "actor":
        moved.AddPosition(1e-3 if frame % 2 else -1e-3, 0.0, 0.0)


def _timed_frame(plotter, chill=None) -> float:
    """Return the CPU ms of one frame of ``plotter``, after an untimed frame of ``chill``."""
    if chill is not None:
        chill.camera.Azimuth(0.5)
        chill.ren_win.Render()
    start = time.thread_time()
    plotter.ren_win.Render()
    return (time.thread_time() - start) * 1e3


def measure_frames(
    scene: OverheadScene, frames: int = 100, budget_s: float = 20.0
) -> tuple[dict[str, float], dict[str, float], dict[str, float], dict[str, float], int]:
    """Measure, in this process, the CPU ms of frames with and without shadows.

    Run it with ``GALLIUM_NOOP=1`` set before the first window is made (as
    :func:`run_overhead` does), or the times include drawing. The two
    plotters draw in turn, and each motion is measured in
    ``ROUNDS`` rounds spread over the run, so that a stretch of a slow
    machine weighs on every motion alike; the added time is the median of
    the differences between the twins' frames drawn one after the other.

    Parameters
    ----------
    scene : OverheadScene
        Which scene.
    frames : int, default: 100
        Frames per median (fewer when a frame is so slow that the scene
        would take longer than ``budget_s``; never fewer than 3). A small
        scene's frame costs a fraction of a millisecond, so only many
        frames hold its median still against the machine's noise.
    budget_s : float, default: 20.0
        Rough CPU seconds one scene may take.

    Returns
    -------
    tuple
        Median plain ms per motion, median added ms per motion, median ms
        of pvshadows' own code per motion, median ms of issuing the passes
        per motion (part of its own), frames used.
    """
    import pvshadows  # noqa: F401 - registers pl.shadows

    twins = [build_scene(scene), build_scene(scene)]
    shadowed, lights, _ = twins[1]
    shadowed.shadows.enable(lights=lights, technique=scene.technique)
    chill = None
    if scene.cold_after:
        chill = build_scene(OverheadScene("actors", scene.light, actors=scene.cold_after))[0]
    for plotter in [plotter for plotter, _, _ in twins] + ([chill] if chill else []):
        plotter.screenshot(return_img=True)
    slowest = max(_timed_frame(plotter, chill) for plotter, _, _ in twins)
    frames = int(max(3, min(frames, budget_s * 1e3 / (2 * len(MOTIONS) * max(slowest, 1e-3)))))
    plain: dict[str, list[float]] = {motion: [] for motion in MOTIONS}
    added: dict[str, list[float]] = {motion: [] for motion in MOTIONS}
    own: dict[str, list[float]] = {motion: [] for motion in MOTIONS}
    submitted: dict[str, list[float]] = {motion: [] for motion in MOTIONS}
    per_round = math.ceil(frames / ROUNDS)
    for _ in range(ROUNDS):
        for motion in MOTIONS:
            for frame in range(per_round + 2):
                pair = []
                for plotter, moved_lights, moved in twins:
                    _move(plotter, moved_lights, moved, motion, frame)
                    pair.append(_timed_frame(plotter, chill))
                if frame >= 2:  # the first two settle what the last motion left
                    plain[motion].append(pair[0])
                    added[motion].append(pair[1] - pair[0])
                    report = shadowed.shadows.last_frame
                    own[motion].append(report.cpu_ms)
                    submitted[motion].append(report.pass_cpu_ms)
    for plotter in [plotter for plotter, _, _ in twins] + ([chill] if chill else []):
        plotter.close()
    plain_ms, added_ms, own_ms, passes_ms = (
        {motion: statistics.median(values[motion]) for motion in MOTIONS}
        for values in (plain, added, own, submitted)
    )
    return plain_ms, added_ms, own_ms, passes_ms, per_round * ROUNDS


def measure_first_frame(scene: OverheadScene) -> tuple[float, float]:
    """Return wall seconds of the twin's first frame and of ``enable()`` to the first shadowed one.

    Every plotter is fresh; a small plotter is drawn first so that none pays
    the driver's start-up, and the twin is drawn before and after the
    shadowed plotter (the faster of its two first frames counts).

    Parameters
    ----------
    scene : OverheadScene
        Which scene.

    Returns
    -------
    tuple of float
        Plain and shadowed first-frame seconds.
    """
    import pyvista as pv

    import pvshadows  # noqa: F401 - registers pl.shadows
    from pvshadows.gl.binding import opengl_for

    warm = pv.Plotter(off_screen=True, window_size=[64, 64])
    warm.add_mesh(pv.Cube())
    warm.screenshot(return_img=True)
    warm.close()
    seconds = []
    for shadows in (False, True, False):
        plotter, lights, _ = build_scene(scene)
        start = time.perf_counter()
        if shadows:
            plotter.shadows.enable(lights=lights, technique=scene.technique)
        plotter.screenshot(return_img=True)
        opengl_for(plotter.ren_win).glFinish()
        seconds.append(time.perf_counter() - start)
        plotter.close()
    return min(seconds[0], seconds[2]), seconds[1]


def _worker(spec: dict) -> dict:
    scene = OverheadScene(**spec["scene"])
    if spec["mode"] == "first":
        plain, shadowed = measure_first_frame(scene)
        return {"first_plain_s": plain, "first_shadowed_s": shadowed}
    plain_ms, added_ms, own_ms, passes_ms, frames = measure_frames(
        scene, spec["frames"], spec["budget_s"]
    )
    return {
        "plain_ms": plain_ms,
        "added_ms": added_ms,
        "own_ms": own_ms,
        "passes_ms": passes_ms,
        "frames": frames,
    }


def _in_subprocess(spec: dict, noop: bool) -> dict:
    env = dict(os.environ)
    env.pop("GALLIUM_NOOP", None)
    if noop:
        env["GALLIUM_NOOP"] = "1"
    else:
        # A first frame compiles every receiver's shader: from Mesa's disk cache, a
        # second run would time a fraction of that (16 spot lights: 0.28 s against 2.4 s).
        env["MESA_SHADER_CACHE_DISABLE"] = "true"
    if sys.platform.startswith("linux") and not env.get("DISPLAY"):
        env.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
        env.setdefault("PYOPENGL_PLATFORM", "egl")
    done = subprocess.run(
        [sys.executable, "-m", "pvshadows.tools.overhead", json.dumps(spec)],
        env=env,
        capture_output=True,
        text=True,
        check=False,
    )
    if done.returncode != 0:
        msg = f"overhead worker failed for {spec['scene']}:\n{done.stderr[-2000:]}"
        raise RuntimeError(msg)
    return json.loads(done.stdout.strip().splitlines()[-1])


def run_overhead(
    scenes: Iterable[OverheadScene],
    *,
    frames: int = 100,
    budget_s: float = 20.0,
    first_frame: bool = True,
    progress: Callable[[str], None] = print,
) -> list[OverheadRow]:
    """Measure every scene, each in its own subprocess.

    Parameters
    ----------
    scenes : iterable of OverheadScene
        What to measure (see :func:`overhead_scenes`).
    frames : int, default: 100
        Frames per median.
    budget_s : float, default: 20.0
        Rough CPU seconds per scene for the per-frame medians.
    first_frame : bool, default: True
        Also time ``enable()`` to the first shadowed frame on llvmpipe.
    progress : callable, default: print
        Receives one line per scene.

    Returns
    -------
    list of OverheadRow
        One row per scene.
    """
    rows = []
    for scene in scenes:
        spec = {"scene": asdict(scene), "frames": frames, "budget_s": budget_s, "mode": "frames"}
        row = OverheadRow(scene, **_in_subprocess(spec, noop=True))
        if first_frame and not scene.cold_after:  # a control of per-frame time only
            first = _in_subprocess({**spec, "mode": "first"}, noop=False)
            row.first_plain_s, row.first_shadowed_s = (
                first["first_plain_s"],
                first["first_shadowed_s"],
            )
        rows.append(row)
        added = ", ".join(f"{m} {row.added_ms[m]:+.2f}" for m in MOTIONS)
        progress(
            f"overhead {scene.label}: {added} ms over a plain {row.plain_ms['static']:.2f} ms; "
            f"first frame s (plain) {_first(row)}"
        )
    return rows


def growth_fits(rows: list[OverheadRow]) -> list[str]:
    """Describe how the added time grows along each series, as ``c * x**k`` per motion.

    The exponent comes from a least-squares line through ``log(added)``
    against ``log(x)``; added times below 0.01 ms count as 0.01 ms (noise).
    Only rows drawn by the ``"auto"`` techniques make up a series: a row
    drawn by another technique (:attr:`OverheadScene.technique`) stands
    apart.

    Parameters
    ----------
    rows : list of OverheadRow
        Measured rows.

    Returns
    -------
    list of str
        One line per series and motion with at least two sizes.

    Examples
    --------
    >>> from pvshadows.tools.overhead import OverheadRow, OverheadScene, growth_fits
    >>> rows = [
    ...     OverheadRow(OverheadScene("actors", actors=n), added_ms={"camera": 0.01 * n**2})
    ...     for n in (10, 100)
    ... ]
    >>> growth_fits(rows)
    ['actors, camera: 0.01 ms * actors^2.00']
    """
    lines = []
    for series in ("actors", "lights", "triangles"):
        # The series of the auto techniques; a row drawn by another is no size of them.
        chosen = [
            row for row in rows if row.scene.series == series and row.scene.technique == "auto"
        ]
        if len({row.scene.size for row in chosen}) < 2:
            continue
        x = np.log([row.scene.size for row in chosen])
        for motion in MOTIONS:
            if not all(motion in row.added_ms for row in chosen):
                continue
            y = np.log([max(row.added_ms[motion], 0.01) for row in chosen])
            k, c = np.polyfit(x, y, 1)
            lines.append(f"{series}, {motion}: {np.exp(c):.3g} ms * {series}^{k:.2f}")
    return lines


def write_overhead(rows: list[OverheadRow], out: Path) -> str:
    """Write ``overhead.csv`` and ``overhead.md`` into ``out``.

    Parameters
    ----------
    rows : list of OverheadRow
        The measurements.
    out : pathlib.Path
        Folder to write into (created if needed).

    Returns
    -------
    str
        The markdown written, to print.
    """
    out.mkdir(parents=True, exist_ok=True)
    fields = ["scene", "series", "light", "actors", "lights", "triangles", "cold_after"]
    fields += ["technique", "frames"]
    fields += [f"plain_{m}_ms" for m in MOTIONS] + [f"added_{m}_ms" for m in MOTIONS]
    fields += [f"own_{m}_ms" for m in MOTIONS] + [f"passes_{m}_ms" for m in MOTIONS]
    fields += ["first_plain_s", "first_shadowed_s"]
    with open(out / "overhead.csv", "w", newline="", encoding="utf-8") as handle:
        writer = csv.DictWriter(handle, fieldnames=fields)
        writer.writeheader()
        for row in rows:
            record = {"scene": row.scene.label, "frames": row.frames, **asdict(row.scene)}
            record.update({f"plain_{m}_ms": row.plain_ms.get(m) for m in MOTIONS})
            record.update({f"added_{m}_ms": row.added_ms.get(m) for m in MOTIONS})
            record.update({f"own_{m}_ms": row.own_ms.get(m) for m in MOTIONS})
            record.update({f"passes_{m}_ms": row.passes_ms.get(m) for m in MOTIONS})
            record.update(first_plain_s=row.first_plain_s, first_shadowed_s=row.first_shadowed_s)
            writer.writerow(record)
    lines = [
        "CPU ms pvshadows adds to a frame (Mesa `GALLIUM_NOOP=1`, median difference of "
        "interleaved frames against the same scene without shadows; in brackets, the median "
        "ms of pvshadows' own code in the frame, steadier from run to run, and of that the "
        "ms spent issuing the passes that ran), and the first frame after `enable()` "
        "(llvmpipe, wall seconds):",
        "",
        "| overhead scene | plain frame ms | static | camera moving | light moving | actor moving "
        "| first frame s (plain) | frames |",
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
    ]
    lines += [
        f"| {row.scene.label} | {row.plain_ms['static']:.2f} "
        + "".join(f"| {_added(row, m)} " for m in MOTIONS)
        + f"| {_first(row)} | {row.frames} |"
        for row in rows
    ]
    fits = growth_fits(rows)
    if fits:
        lines += ["", "Growth of the added time with the scene, fitted as c * x^k:", ""]
        lines += ["| series | motion | added ms |", "| --- | --- | --- |"]
        lines += [
            "| {} | {} | {} |".format(*fit.replace(": ", ", ", 1).split(", ", 2)) for fit in fits
        ]
    text = "\n".join(lines) + "\n"
    (out / "overhead.md").write_text(text, encoding="utf-8")
    return text


def _first(row: OverheadRow) -> str:
    """Return a table cell: the first frame's seconds, the twin's in brackets, or "not timed"."""
    if math.isnan(row.first_shadowed_s):
        return "not timed"
    return f"{row.first_shadowed_s:.2f} ({row.first_plain_s:.2f})"


def _added(row: OverheadRow, motion: str) -> str:
    """Return a table cell: the added ms, pvshadows' own, and the passes' part when some ran."""
    added = f"{row.added_ms[motion]:+.2f}"
    own, passes = row.own_ms.get(motion), row.passes_ms.get(motion, 0.0)
    if own is None:
        return added
    return f"{added} ({own:.2f}, {passes:.2f})" if passes >= 0.005 else f"{added} ({own:.2f})"


if __name__ == "__main__":
    print(json.dumps(_worker(json.loads(sys.argv[1]))))
