"""
A room lit by a bare bulb
=========================

A point light hangs in the middle of a room. One depth cube map holds the
distance to the nearest object in every direction, so furniture shadows fall
on the floor and on every wall at once: ``pl.shadows.enable()`` is the only
line that differs from a plain PyVista scene.
"""

# %%
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows; installing pvshadows also does)

pl = pv.Plotter(off_screen=True, window_size=(1024, 768), lighting="none")
walls = {"ambient": 0.12, "diffuse": 0.9, "specular": 0.0}

# %%
# Floor and four walls, 8 x 8 x 4, open at the top so the camera can look in.
_ = pl.add_mesh(
    pv.Plane(center=(0, 0, 0), direction=(0, 0, 1), i_size=8, j_size=8), color="#d8cdb8", **walls
)
for center, normal in [
    ((-4, 0, 2), (1, 0, 0)),
    ((4, 0, 2), (-1, 0, 0)),
    ((0, 4, 2), (0, -1, 0)),
    ((0, -4, 2), (0, 1, 0)),
]:
    _ = pl.add_mesh(
        pv.Plane(center=center, direction=normal, i_size=4, j_size=8), color="#ece6da", **walls
    )

# %%
# Furniture: a table with a vase, a tall column and a shelf near the back wall,
# a ring hanging near the right wall, a ball on the floor. Round things are
# smooth-shaded; boxes are not (their normals would be averaged over the corners).
flat = {"ambient": 0.12, "diffuse": 0.85, "specular": 0.25}
things = {**flat, "smooth_shading": True}
_ = pl.add_mesh(pv.Box(bounds=(-1.4, 0.2, -1.2, 0.0, 0.95, 1.05)), color="#8c5a3c", **flat)
for x in (-1.3, 0.1):
    for y in (-1.1, -0.1):
        _ = pl.add_mesh(
            pv.Cylinder(center=(x, y, 0.475), direction=(0, 0, 1), radius=0.05, height=0.95),
            color="#6b4329",
            **things,
        )
_ = pl.add_mesh(
    pv.Cylinder(center=(-0.8, -0.6, 1.35), direction=(0, 0, 1), radius=0.15, height=0.6),
    color="#3f7f8f",
    **things,
)
_ = pl.add_mesh(
    pv.Cylinder(center=(-1.0, 2.6, 1.1), direction=(0, 0, 1), radius=0.25, height=2.2),
    color="#a3a3a3",
    **things,
)
_ = pl.add_mesh(pv.Box(bounds=(0.8, 2.4, 2.9, 3.3, 1.6, 1.7)), color="#8c5a3c", **flat)
_ = pl.add_mesh(pv.Sphere(radius=0.45, center=(1.6, -1.2, 0.45)), color="#c0504d", **things)
ring = (
    pv.ParametricTorus(ringradius=0.45, crosssectionradius=0.07)
    .rotate_y(90)
    .translate((2.6, 0.6, 2.4))
)
_ = pl.add_mesh(ring, color="#d4a017", **things)

# %%
# The bulb: a point light (positional, cone angle of 90 degrees or more) and a
# small glowing sphere that shows where it is but casts nothing.
bulb = pv.Light(position=(0.3, 0.2, 3.1), positional=True, cone_angle=180)
pl.add_light(bulb)
marker = pl.add_mesh(pv.Sphere(radius=0.08, center=bulb.position), color="#fff3b0", lighting=False)

pl.shadows.enable(filter="pcf")
pl.shadows.set_caster(marker, False)

pl.camera_position = [(-3.5, -3.6, 3.4), (1.2, 1.2, 1.3), (0, 0, 1)]
pl.camera.view_angle = 75
_ = pl.screenshot("bulb_room.png")
print(pl.shadows.last_frame)
