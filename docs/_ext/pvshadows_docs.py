"""Sphinx extension: measures and draws what the pages show, during the build.

When the builder starts it

- renders ``pvshadows demo`` into ``docs/_generated/demo.png`` for the front page;
- runs ``pvshadows bench`` into ``docs/_generated/bench`` (``bench.csv``,
  ``bench.md``, ``frontier.png``) and turns its tables into reST for the
  "Accuracy and cost" page;
- runs ``how_it_works.py`` into ``docs/_generated/how_it_works``: the figures
  and reports of one real frame for the "How it works" page.

Both run in their own process, as a user would run them. The environment
variable ``PVSHADOWS_DOCS_BENCH`` chooses the bench:

- ``full`` (the default, and what CI publishes): every case, as
  ``pvshadows bench`` runs it;
- ``quick``: ``pvshadows bench --quick``, a few cases, for working on the docs;
- ``reuse``: keep the bench and figures of the last build when they are
  there (a quick bench otherwise).
"""

from __future__ import annotations

import csv
import os
import re
import subprocess
import sys
import time
from datetime import UTC, datetime
from pathlib import Path

MODES = ("full", "quick", "reuse")
HERE = Path(__file__).parent


def _run(command: list[str], what: str) -> float:
    print(f"pvshadows docs: {what}: {' '.join(command)}", flush=True)
    start = time.perf_counter()
    subprocess.run(command, check=True)
    return time.perf_counter() - start


def _mode() -> str:
    mode = os.environ.get("PVSHADOWS_DOCS_BENCH", "full").strip().lower() or "full"
    if mode not in MODES:
        msg = f"PVSHADOWS_DOCS_BENCH={mode!r} is not allowed; choose one of {', '.join(MODES)}"
        raise ValueError(msg)
    return mode


def _context() -> str:
    """Return what ``pvshadows info`` says about the OpenGL context, as reST field lines."""
    result = subprocess.run(
        [sys.executable, "-m", "pvshadows", "info"], capture_output=True, text=True, check=True
    )
    keep = ("renderer", "OpenGL", "window")
    lines = []
    for line in result.stdout.splitlines():
        name, _, value = line.partition(" ")
        if name in keep and value.strip():
            lines.append(f":{name}: {value.strip()}")
    return "\n".join(lines)


def run_bench(out: Path, mode: str) -> str:
    """Run the bench into ``out`` (or keep the last one) and return a sentence saying how."""
    record = out / "measured.txt"
    if mode == "reuse" and (out / "bench.csv").exists() and (out / "bench.md").exists():
        earlier = record.read_text(encoding="utf-8").strip() if record.exists() else "measured"
        return f"{earlier} (kept for this build: ``PVSHADOWS_DOCS_BENCH=reuse``)"
    quick = mode != "full"
    command = [sys.executable, "-m", "pvshadows", "bench", "--out", str(out)]
    seconds = _run(command + (["--quick"] if quick else []), "bench")
    which = "``pvshadows bench --quick``" if quick else "``pvshadows bench``"
    when = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    how = f"measured by {which} during a build of these docs, {when}, in {seconds / 60:.1f} min"
    record.write_text(how + "\n", encoding="utf-8")
    return how


# -- bench.csv and bench.md as reST ------------------------------------------------------------


def formatted_csv(source: Path, target: Path) -> None:
    """Write ``bench.csv`` with readable numbers and few columns for the ``csv-table`` directive."""
    with open(source, newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    header = [
        "technique (light)",
        "setting",
        "misclassified (%)",
        "RMSE",
        "RMSE against",
        "RMSE, area light",
        "time ratio, light moving",
        "time ratio, static",
        "frame (ms)",
    ]
    with open(target, "w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        for row in rows:
            area = float(row.get("rmse_area") or "nan")
            writer.writerow(
                [
                    f"{row['technique']} ({row['light']})",
                    row["setting"].replace(" ", ", "),
                    f"{100 * float(row['misclassified']):.3f}",
                    f"{float(row['rmse']):.4f}",
                    row["reference"],
                    "—" if area != area else f"{area:.4f}",
                    f"{float(row['ratio_moving']):.2f}",
                    f"{float(row['ratio_static']):.2f}",
                    f"{float(row['frame_ms']):.1f}",
                ]
            )


def _inline(text: str) -> str:
    """Markdown inline code to reST inline literals."""
    return re.sub(r"`([^`]+)`", r"``\1``", text.strip())


def _cells(line: str) -> list[str]:
    return [_inline(cell) for cell in line.strip().strip("|").split("|")]


def markdown_tables(markdown: str) -> list[tuple[str, list[list[str]]]]:
    """Return each table of ``bench.md`` as (the sentence before it, rows), header row first.

    Examples
    --------
    >>> text = "Presets:\\n\\n| a | b |\\n| --- | ---: |\\n| `x` | 1 |\\n"
    >>> markdown_tables(text)
    [('Presets', [['a', 'b'], ['``x``', '1']])]
    """
    tables: list[tuple[str, list[list[str]]]] = []
    caption, rows = "", []
    for line in [*markdown.splitlines(), ""]:
        if line.lstrip().startswith("|"):
            if not set(line.replace("|", "").strip()) <= set("-: "):
                rows.append(_cells(line))
            continue
        if rows:
            tables.append((caption, rows))
            caption, rows = "", []
        if line.strip():
            caption = _inline(line).rstrip(":")
    return tables


def list_table(caption: str, rows: list[list[str]]) -> str:
    """Return one table as a reST ``list-table``."""
    lines = [f".. list-table:: {caption}".rstrip(), "   :header-rows: 1", ""]
    for row in rows:
        lines.append(f"   * - {row[0] or ' '}")
        lines.extend(f"     - {cell or ' '}" for cell in row[1:])
    return "\n".join(lines) + "\n"


#: Which generated file each table of ``bench.md`` goes to, by its first header cell.
SECTIONS = {
    "quality": "presets",
    "triangles": "silhouettes",
    "scene": "planner",
    "overhead scene": "overhead",
    "series": "overhead",
}


def write_bench_rst(bench: Path, out: Path, how: str) -> None:
    """Write the reST pieces the accuracy page includes."""
    formatted_csv(bench / "bench.csv", out / "bench_table.csv")
    tables = markdown_tables((bench / "bench.md").read_text(encoding="utf-8"))[1:]
    pieces: dict[str, list[str]] = {name: [] for name in [*SECTIONS.values(), "more"]}
    for caption, rows in tables:
        pieces[SECTIONS.get(rows[0][0], "more")].append(list_table(caption, rows))
    for name, texts in pieces.items():
        body = "\n".join(texts) if texts else "*(This bench did not write this table.)*\n"
        if name == "more" and not texts:
            body = ""
        (out / f"bench_{name}.rst").write_text(body, encoding="utf-8")
    (out / "bench_how.rst").write_text(
        f"These results were {how}, on this machine:\n\n{_context()}\n", encoding="utf-8"
    )


# -- tables read from the package -------------------------------------------------------------

#: What each technique is, in a few words (a technique missing here still gets its row).
TECHNIQUE_WORDS = {
    "cubemap": "depth cube map: distance to the light in six faces, one draw or six",
    "map": "2D depth map: perspective for a spot, orthographic and fitted for a sun",
    "volume": "stencil shadow volumes: pixel-exact hard shadows; casters must be closed",
    "planar": "casters flattened onto one receiving plane; objects do not shadow each other",
}


def write_package_tables(out: Path) -> None:
    """Write the techniques x lights and the quality presets tables, read from the package."""
    from pvshadows.model.plan import AUTO_TECHNIQUE, SERVES
    from pvshadows.model.settings import QUALITY_PRESETS
    from pvshadows.scene.lights import LightKind
    from pvshadows.tools.bench_presets import PROMISES

    kinds = list(LightKind)
    rows = [["technique", *[f"{kind.value} light" for kind in kinds], "what"]]
    for name, served in SERVES.items():
        marks = ["yes" if kind in served else "—" for kind in kinds]
        rows.append([f"``{name}``", *marks, TECHNIQUE_WORDS.get(name, "")])
    auto = [f"``{AUTO_TECHNIQUE[kind]}``" for kind in kinds]
    rows.append(["``auto`` picks", *auto, "``volume`` for every light with ``quality='exact'``"])
    text = list_table("Techniques and the lights they serve", rows)
    (out / "techniques.rst").write_text(text, encoding="utf-8")
    names = sorted({key for preset in QUALITY_PRESETS.values() for key in preset})
    rows = [["quality", *names]]
    for quality, preset in QUALITY_PRESETS.items():
        rows.append(
            [f"``{quality}``", *[f"``{preset[n]!r}``" if n in preset else "—" for n in names]]
        )
    text = list_table("What each quality sets (pvshadows.model.settings.QUALITY_PRESETS)", rows)
    (out / "presets.rst").write_text(text, encoding="utf-8")
    promises = [["quality", "promise (for every kind of light)"]]
    promises += [[f"``{quality}``", words] for quality, words in PROMISES.items()]
    text = list_table(
        "What each quality promises (pvshadows.tools.bench_presets.PROMISES)", promises
    )
    (out / "promises.rst").write_text(text, encoding="utf-8")
    write_bench_constants(out)


def write_bench_constants(out: Path) -> None:
    """Write reST substitutions for the bench's constants, so the pages quote the code."""
    from pvshadows.tools import bench

    values = {
        "bench_size_point": f"{bench.LIGHT_SIZE['point']:g}",
        "bench_size_spot": f"{bench.LIGHT_SIZE['spot']:g}",
        "bench_size_sun": f"{bench.LIGHT_SIZE['directional']:g}",
        "bench_samples": f"{bench.REFERENCE_SAMPLES}",
        "bench_soft": ", ".join(f"``{name}``" for name in bench.SOFT_FILTERS),
    }
    text = "".join(f".. |{name}| replace:: {value}\n" for name, value in values.items())
    (out / "bench_constants.rst").write_text(text, encoding="utf-8")


# -- Sphinx --------------------------------------------------------------------------------------


def generate(app) -> None:
    """Run the bench and draw the figures (Sphinx ``builder-inited``)."""
    mode = _mode()
    out = Path(app.srcdir) / "_generated"
    out.mkdir(parents=True, exist_ok=True)
    write_package_tables(out)
    bench = out / "bench"
    bench.mkdir(parents=True, exist_ok=True)
    how = run_bench(bench, mode)
    write_bench_rst(bench, out, how)
    demo = out / "demo.png"
    if not (mode == "reuse" and demo.exists()):
        command = [sys.executable, "-m", "pvshadows", "demo", "--out", str(demo)]
        _run([*command, "--size", "960x600"], "the demo picture")
    figures = out / "how_it_works"
    if not (mode == "reuse" and (figures / "frame_passes.png").exists()):
        _run([sys.executable, str(HERE / "how_it_works.py"), str(figures)], "How it works")


def setup(app) -> dict:
    """Register the generator with Sphinx."""
    app.connect("builder-inited", generate)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
