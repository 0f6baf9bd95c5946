"""Closing a plotter releases everything pvshadows kept for it (counted, in a fresh process)."""

import subprocess
import sys
import textwrap

CYCLES = """
import gc
import sys

import pyvista as pv
from OpenGL import contextdata

import pvshadows
import pvshadows._cached
from pvshadows.tools.scenes import standard_scene

for technique in sys.argv[1:]:
    scene = standard_scene(window_size=(200, 150), light="spot" if technique == "map" else "point")
    scene.plotter.actors["sphere"].prop.opacity = 0.5  # the maps keep a transmittance companion
    scene.plotter.shadows.enable(technique=technique, filter="hard")
    scene.plotter.screenshot(return_img=True)
    scene.plotter.close()
    del scene
gc.collect()
descriptors = (pvshadows._cached.cached,)  # live on classes, as long as the classes
kept = sorted(
    type(o).__qualname__
    for o in gc.get_objects()
    if str(type(o).__module__).startswith("pvshadows")
    and not type(o).__module__.endswith("lights")
    and not isinstance(o, descriptors)
)
print(len(kept), len(contextdata.storedPointers), ",".join(sorted(set(kept))))
"""


def test_closed_plotters_leave_no_pvshadows_object_and_no_pyopengl_pointer():
    result = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(CYCLES), "cubemap", "map", "volume", "planar"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stderr
    objects, pointer_contexts, names = result.stdout.split(" ", 2)
    assert int(objects) == 0, names
    assert int(pointer_contexts) == 0
