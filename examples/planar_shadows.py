"""
Planar shadows under an airplane
================================

``technique="planar"`` flattens every caster onto one receiving plane along
the lines to the light, with the projection matrix ``(plane . light) I -
light plane^T``, and draws the flattened triangles once per pixel into a
screen-space mask that only the plane reads. It is the cheapest technique
and exact on its plane, from point, spot and directional lights alike; but
shadows fall on that plane only: objects do not shadow each other. Here an
airplane flies over the ground; a cube map of the same frame is compared.
"""

# %%
import pyvista as pv
from pyvista import examples

import pvshadows  # noqa: F401  (registers pl.shadows; installing pvshadows also does)

pl = pv.Plotter(off_screen=True, window_size=(800, 600), lighting="none")
pl.set_background("#f4f1ea", top="#bcc8d6")
ground = pl.add_mesh(
    pv.Plane(center=(900, 700, -300), i_size=5000, j_size=5000),
    color="#d9d4c7",
    ambient=0.2,
    diffuse=0.8,
    specular=0.0,
    name="ground",
)
airplane = pl.add_mesh(
    examples.load_airplane(),
    color="#c8ccd4",
    ambient=0.2,
    specular=0.4,
    smooth_shading=True,
    name="airplane",
)
bulb = pv.Light(position=(1050, 800, 1800), positional=True, cone_angle=180)
pl.add_light(bulb)
pl.camera_position = [(2700, -1500, 2000), (900, 700, -150), (0, 0, 1)]

# %%
# The ground is found on its own (its points are coplanar); naming it says so
# explicitly, and a mesh that is not flat would be refused with a ValueError.
pl.shadows.set_receiver(ground, plane=True)
pl.shadows.enable(technique="planar")
_ = pl.screenshot("planar_shadows.png")
print(pl.shadows.last_frame)

# %%
# How exact? On the ground, against ray tracing on the same frame; the
# airplane shows no shadow of its own with planar shadows, so it is left out
# of the comparison.
pl.shadows.set_receiver(airplane, False)
print("planar:      ", pl.shadows.measure(bulb))
pl.shadows.configure(bulb, technique="cubemap", filter="hard")
print("cubemap hard:", pl.shadows.measure(bulb))
