"""What the first ``pl.shadows`` imports: not all of VTK, no ray tracer until a reference."""

import subprocess
import sys

SCRIPT = """
import sys
import pyvista as pv
pl = pv.Plotter(off_screen=True, window_size=(160, 120))
pl.add_mesh(pv.Plane())
pl.add_mesh(pv.Sphere(center=(0, 0, 1)))
pl.add_light(pv.Light(position=(0, 0, 3), positional=True, cone_angle=180))
pl.shadows.enable()
pl.screenshot(return_img=True)
print(sorted({"trimesh", "embreex", "vtk"} & set(sys.modules)))
pl.shadows.reference()
print(sorted({"trimesh", "embreex"} & set(sys.modules)))
"""


def test_shadows_import_the_ray_tracer_only_for_a_reference():
    result = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, timeout=300
    )
    assert result.returncode == 0, result.stderr
    before, after, _ = result.stdout.split("\n")
    assert before == "[]"
    assert after == "['embreex', 'trimesh']"
