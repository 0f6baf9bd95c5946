"""
Accuracy against time
=====================

What does a sharper or softer shadow cost? ``pvshadows bench`` renders the
same scene with every technique and setting, measures each frame against ray
tracing, and times it against the same scene drawn without shadows. Here a
handful of its cases run through :mod:`pvshadows.bench` in a small window,
with few frames per median and an area light of 32 rays per pixel, so this
takes well under a minute; the :doc:`accuracy and cost </accuracy>` page
shows the whole bench.

Read the plot from the bottom left: cheap and right. A point no other point
beats on both error and time lies on the grey frontier.
"""

# %%
import tempfile
from pathlib import Path

from pvshadows.bench import BenchCase, plot_frontier, run_bench, write_table

cases = [
    BenchCase("cubemap", {"resolution": 256, "filter": "hard"}),
    BenchCase("cubemap", {"resolution": 1024, "filter": "hard"}),
    BenchCase("cubemap", {"resolution": 1024, "filter": "pcf", "pcf_taps": 16}),
    BenchCase("cubemap", {"resolution": 1024, "filter": "pcss", "samples": 32, "light_size": 0.25}),
    BenchCase("volume", {"extrude": "gpu", "zmode": "auto"}),
    BenchCase("map", {"resolution": 512, "filter": "hard"}, light="spot"),
    BenchCase("map", {"resolution": 2048, "filter": "pcf", "pcf_taps": 16}, light="spot"),
    BenchCase("vtk", {}, light="spot"),
]

# %%
# Each case: the error against the ray-traced reference of the same frame, and
# the median frame time over the median time of the plain frame, with the light
# nudged every frame (every pass runs) and with a static scene (maps reused).
rows = run_bench(cases, frames=4, window_size=(400, 300), reference_samples=32)

with tempfile.TemporaryDirectory() as folder:
    write_table(rows, Path(folder))
    print((Path(folder) / "bench.md").read_text())

# %%
# The plot the bench draws: error against time ratio, the frontier in grey.
plot_frontier(rows, Path("accuracy_vs_time.png"))
