"""The ``pvshadows`` command: ``demo``, ``info`` and ``bench``."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from pathlib import Path

from pvshadows import __version__


def _prefer_egl_without_display() -> None:
    """Open EGL windows directly when there is no X display, instead of trying X first.

    VTK has no Wayland window: without ``DISPLAY`` (XWayland) it falls back to EGL anyway.
    """
    if not os.environ.get("DISPLAY") and sys.platform.startswith("linux"):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def _size(text: str) -> tuple[int, int]:
    try:
        width, height = (int(part) for part in text.lower().split("x"))
    except ValueError:
        msg = f"size must look like 800x600, got {text!r}"
        raise argparse.ArgumentTypeError(msg) from None
    if width < 1 or height < 1:
        msg = f"size must be positive, got {text!r}"
        raise argparse.ArgumentTypeError(msg)
    return width, height


def _demo(args: argparse.Namespace) -> int:
    from pvshadows.tools.demo import render_demo

    path = render_demo(args.out, window_size=args.size)
    print(f"wrote {path}")
    return 0


def _info(args: argparse.Namespace) -> int:
    from pvshadows.tools.info import capabilities

    try:
        print(capabilities(onscreen=args.onscreen))
    except RuntimeError as error:
        print(f"pvshadows info: {error}", file=sys.stderr)
        return 1
    return 0


def _bench(args: argparse.Namespace) -> int:
    from pvshadows.tools import bench
    from pvshadows.tools.bench_presets import choose_presets, presets_lines, write_presets
    from pvshadows.tools.bench_progress import ProgressBar

    out = Path(args.out)
    cases = bench.quick_cases() if args.quick else bench.all_cases()
    sizes = (20_000,) if args.quick else (100_000, 1_000_000)
    bar = ProgressBar(len(cases) + 3)
    bar.show("setting up; each light's first case also traces its references")

    def measured(rows: list) -> None:
        bench.write_table(rows, out)
        bar.step(f"{rows[-1].technique} ({rows[-1].light}) {rows[-1].setting}")

    # The table is rewritten after every case, so an interrupted run keeps what it measured.
    rows = bench.run_bench(
        cases,
        frames=args.frames,
        window_size=args.size,
        area=not args.quick,
        progress=bar.line,
        on_row=measured,
    )
    bench.plot_frontier(rows, out / "frontier.png")
    picks = choose_presets(rows)
    presets = write_presets(picks, out)
    bar.line(bench.append_lines(presets_lines(picks, rows), out))
    timings = bench.silhouette_timings(sizes, repeats=1 if args.quick else 3, progress=bar.line)
    bar.step("silhouettes")
    bar.line(bench.append_silhouette_table(timings, out))
    bar.line(bench.append_planner_table(bench.planner_counts(), out))
    bar.step("planner")
    bar.line(bench.append_overhead_table(out, quick=args.quick, huge=args.huge))
    bar.step("overhead")
    bar.close()
    print(f"wrote {out / 'bench.csv'}, {out / 'bench.md'}, {out / 'frontier.png'} and {presets}")
    print(
        f'apply a preset measured here: pl.shadows.enable(**json.load(open("{presets}"))["draft"])'
    )
    return 0


def parser() -> argparse.ArgumentParser:
    """Return the command-line parser.

    Returns
    -------
    argparse.ArgumentParser
        Parser with the ``demo``, ``info`` and ``bench`` commands and ``--version``.

    Examples
    --------
    >>> from pvshadows.tools.cli import parser
    >>> parser().parse_args(["demo", "--out", "x.png"]).out
    'x.png'
    """
    main_parser = argparse.ArgumentParser(
        prog="pvshadows", description="Real-time shadows for PyVista, measured against ray tracing."
    )
    main_parser.add_argument("--version", action="version", version=f"pvshadows {__version__}")
    commands = main_parser.add_subparsers(dest="command", required=True)
    demo = commands.add_parser("demo", help="render the demo scene with shadows to a PNG")
    demo.add_argument("--out", default="shadows.png", help="PNG to write (default shadows.png)")
    demo.add_argument("--size", type=_size, default=(1024, 768), help="window size, e.g. 800x600")
    demo.set_defaults(run=_demo)
    info = commands.add_parser(
        "info", help="what an OpenGL window offers pvshadows, and which techniques run in it"
    )
    info.add_argument(
        "--onscreen",
        action="store_true",
        help="ask an on-screen window (needs a display) instead of an off-screen one",
    )
    info.set_defaults(run=_info)
    bench = commands.add_parser("bench", help="error and time ratio of every technique and setting")
    bench.add_argument("--out", required=True, help="folder for bench.csv, bench.md, frontier.png")
    bench.add_argument(
        "--frames",
        type=int,
        default=10,
        help="most frames per median (default 10); fewer (at least 3) once the ratio is steady",
    )
    bench.add_argument("--size", type=_size, default=(800, 600), help="window size (800x600)")
    bench.add_argument(
        "--quick",
        action="store_true",
        help="5 cases (hard and PCF cube maps, volumes, a spot map, planar), no area-light "
        "reference, small silhouette sizes: checks the bench runs, in about a minute",
    )
    bench.add_argument(
        "--huge",
        action="store_true",
        help="add a 10-million-triangle caster to the overhead table (about 3 GB of memory, "
        "a few minutes more)",
    )
    bench.set_defaults(run=_bench)
    return main_parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``pvshadows`` command.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status.
    """
    args = parser().parse_args(argv)
    _prefer_egl_without_display()
    return args.run(args)
