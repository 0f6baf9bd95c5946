"""
The demo scene
==============

The scene ``pvshadows demo`` renders, built the same way: a ground, a
floating box, a sphere and a cylinder around a bare bulb. It also shows how
far the shadows are from exact ray-traced visibility on the same frame.
"""

# %%
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows)

pl = pv.Plotter(off_screen=True, window_size=(1024, 768), lighting="none")
pl.set_background("#f4f1ea", top="#bcc8d6")
# Round things are smooth-shaded; the box is not (its normals would be averaged over its corners).
flat = {"ambient": 0.15, "diffuse": 0.85, "specular": 0.2}
smooth = {**flat, "smooth_shading": True}
_ = pl.add_mesh(
    pv.Plane(i_size=10, j_size=10, i_resolution=20, j_resolution=20), color="#d9d4c7", **smooth
)
_ = pl.add_mesh(pv.Box(bounds=(-2.6, -1.4, -0.9, 0.3, 1.3, 2.1)), color="#c0504d", **flat)
_ = pl.add_mesh(
    pv.Sphere(radius=0.7, center=(1.6, 1.4, 0.7), theta_resolution=48, phi_resolution=48),
    color="#4f81bd",
    **smooth,
)
_ = pl.add_mesh(
    pv.Cylinder(
        center=(0.9, -2.1, 0.9), direction=(0, 0, 1), radius=0.45, height=1.8, resolution=48
    ),
    color="#9bbb59",
    **smooth,
)

# %%
# A bulb among the objects, a small glowing sphere that shows where it is (and
# casts nothing), and one line for shadows.
bulb = pv.Light(position=(0.3, -0.2, 3.5), positional=True, cone_angle=180)
pl.add_light(bulb)
marker = pl.add_mesh(pv.Sphere(radius=0.12, center=bulb.position), color="#fff6c8", lighting=False)
pl.shadows.enable()
pl.shadows.set_caster(marker, False)
pl.camera_position = [(11.0, -12.5, 9.5), (0.0, 0.0, 0.3), (0, 0, 1)]
_ = pl.screenshot("demo_scene.png")

# %%
# How right is it? Compare with ray tracing (Embree) on the same frame.
print(pl.shadows.measure(bulb))
print(pl.shadows.last_frame)
