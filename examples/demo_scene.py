"""
The demo scene
==============

The scene ``pvshadows demo`` renders: a ground, a floating box, a sphere and
a cylinder around a point light. It also shows how far the shadows are from
exact ray-traced visibility on the same frame.
"""

# %%
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows)

pl = pv.Plotter(off_screen=True, window_size=(1024, 768), lighting="none")
pl.set_background("#f4f1ea", top="#bcc8d6")
style = {"ambient": 0.15, "diffuse": 0.85, "specular": 0.2, "smooth_shading": True}
pl.add_mesh(pv.Plane(i_size=10, j_size=10), color="#d9d4c7", **style)
pl.add_mesh(pv.Box(bounds=(-2.6, -1.4, -0.9, 0.3, 1.3, 2.1)), color="#c0504d", **style)
pl.add_mesh(pv.Sphere(radius=0.7, center=(1.6, 1.4, 0.7)), color="#4f81bd", **style)
pl.add_mesh(
    pv.Cylinder(center=(0.9, -2.1, 0.9), direction=(0, 0, 1), radius=0.45, height=1.8),
    color="#9bbb59",
    **style,
)

# %%
# A point light among the objects, and one line for shadows.
bulb = pv.Light(position=(0.3, -0.2, 3.5), positional=True, cone_angle=180)
pl.add_light(bulb)
pl.shadows.enable()
pl.camera_position = [(11.0, -12.5, 9.5), (0.0, 0.0, 0.3), (0, 0, 1)]
pl.screenshot("demo_scene.png")

# %%
# How right is it? Compare with ray tracing (Embree) on the same frame.
print(pl.shadows.measure(bulb))
print(pl.shadows.last_frame)
