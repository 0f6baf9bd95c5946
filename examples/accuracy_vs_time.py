"""
Accuracy against time
=====================

What does a sharper or softer shadow cost? ``pvshadows bench`` renders the
same scene with every technique and setting, measures each frame against ray
tracing, and times it against the same scene drawn without shadows. Here a
handful of its point-light cases run through :mod:`pvshadows.tools.bench` in a
small window, with three frames per median and an area light of 16 rays per
pixel, so this takes well under a minute; the
:doc:`accuracy and cost </accuracy>` page shows the whole bench, with spot
and directional lights and VTK's own shadows.

Read the plot from the bottom left: cheap and right. A point no other point
beats on both error and time lies on the grey frontier.
"""

# %%
import tempfile
from pathlib import Path

from pvshadows.tools.bench import BenchCase, plot_frontier, run_bench, write_table

cases = [
    BenchCase("cubemap", {"resolution": 256, "filter": "hard"}),
    BenchCase("cubemap", {"resolution": 1024, "filter": "hard"}),
    BenchCase("cubemap", {"resolution": 1024, "filter": "pcf", "pcf_taps": 4}),
    BenchCase("cubemap", {"resolution": 1024, "filter": "pcss", "samples": 32, "light_size": 0.25}),
    BenchCase("volume", {"extrude": "gpu", "zmode": "auto"}),
]

# %%
# Each case: the error against the ray-traced reference of the same frame, and
# the median frame time over the median time of the plain frame, with the light
# nudged every frame (every pass runs) and with a static scene (maps reused).
rows = run_bench(cases, frames=3, window_size=(400, 300), reference_samples=16)

with tempfile.TemporaryDirectory() as folder:
    write_table(rows, Path(folder))
    print((Path(folder) / "bench.md").read_text())

# %%
# The plot the bench draws: error against time ratio, the frontier in grey.
plot_frontier(rows, Path("accuracy_vs_time.png"))
