"""
Pixel-exact shadows with shadow volumes
=======================================

``technique="volume"`` extrudes each caster's silhouette away from the light
to infinity and counts, per pixel, how many of these volumes hold the
surface seen there (in the stencil buffer). Shadow edges are then as sharp as
the pixels themselves, from point, spot and directional lights alike; a cube
map of the same scene is compared on the same frame.
"""

# %%
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows; installing pvshadows also does)

# sphinx_gallery_thumbnail_number = 2

pl = pv.Plotter(off_screen=True, window_size=(800, 600), lighting="none")
pl.set_background("#f4f1ea", top="#bcc8d6")
flat = {"ambient": 0.15, "diffuse": 0.85, "specular": 0.2}
style = {**flat, "smooth_shading": True}  # round things only: a box's normals would blur
_ = pl.add_mesh(pv.Plane(i_size=10, j_size=10), color="#d9d4c7", **flat)
_ = pl.add_mesh(pv.Box(bounds=(-2.6, -1.4, -0.9, 0.3, 1.3, 2.1)), color="#c0504d", **flat)
_ = pl.add_mesh(pv.Sphere(radius=0.7, center=(1.6, 1.4, 0.7)), color="#4f81bd", **style)
_ = pl.add_mesh(
    pv.Cylinder(center=(0.9, -2.1, 0.9), direction=(0, 0, 1), radius=0.45, height=1.8),
    color="#9bbb59",
    **style,
)

# %%
# A bulb among the objects and a low sun: each light gets its own count.
bulb = pv.Light(position=(0.3, -0.2, 3.5), positional=True, cone_angle=180, intensity=0.7)
sun = pv.Light(position=(-4, -6, 5), focal_point=(0, 0, 0), intensity=0.5)
pl.add_light(bulb)
pl.add_light(sun)
pl.camera_position = [(11.0, -12.5, 9.5), (0.0, 0.0, 0.3), (0, 0, 1)]
pl.shadows.enable(technique="volume")
_ = pl.screenshot("shadow_volumes.png")
print(pl.shadows.last_frame)

# %%
# How exact? Against ray tracing on the same frame, next to a hard cube map.
print("volume, bulb:      ", pl.shadows.measure(bulb))
print("volume, sun:       ", pl.shadows.measure(sun))
pl.shadows.configure(bulb, technique="cubemap", filter="hard")
print("cubemap hard, bulb:", pl.shadows.measure(bulb))
pl.shadows.configure(bulb, technique="volume")

# %%
# The volumes themselves, drawn translucent over the scene.
pl.shadows.show_volumes(True)
_ = pl.screenshot("shadow_volumes_debug.png")
