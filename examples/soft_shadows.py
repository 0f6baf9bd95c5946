"""
Soft shadows side by side
=========================

The same scene four times, each panel lit by its own bulb and drawn with
another filter of the cube map:

- ``hard``: one depth compare per pixel, a sharp edge with the map's texels
  in it;
- ``pcf``: percentage-closer filtering, a grid of hardware-filtered compares
  (``pcf_taps``), a penumbra of fixed width;
- ``random``: compares at jittered points of a disk (``samples``,
  ``filter_radius``), stopping after 8 when they all agree;
- ``pcss``: percentage-closer soft shadows, a blocker search first, then a
  penumbra as wide as the light's physical size (``light_size``) makes it:
  sharp where an object touches the ground, wide far from it.

Each panel is measured against the same bulb ray traced as a sphere of that
radius (many shadow rays per pixel), and its RMSE of visibility is written
into the picture.
"""

# %%
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows; installing pvshadows also does)

RADIUS = 0.3  # the bulb's physical radius, in world units
FILTERS = {
    "hard": {"filter": "hard"},
    "pcf": {"filter": "pcf", "pcf_taps": 16},
    "random": {"filter": "random", "samples": 64, "filter_radius": 3.0},
    "pcss": {"filter": "pcss", "samples": 32, "light_size": RADIUS},
}

pl = pv.Plotter(off_screen=True, shape=(2, 2), window_size=(1200, 900), lighting="none")
style = {"ambient": 0.2, "diffuse": 0.8, "specular": 0.1, "smooth_shading": True}
bulbs = {}
for panel, name in enumerate(FILTERS):
    # Each subplot is its own renderer with its own actors, camera and bulb.
    pl.subplot(panel // 2, panel % 2)
    pl.set_background("#f4f1ea", top="#bcc8d6")
    pl.add_mesh(pv.Plane(i_size=9, j_size=9), color="#d9d4c7", **style)
    pl.add_mesh(pv.Box(bounds=(-0.2, 0.2, 0.6, 1.0, 0.0, 2.6)), color="#9bbb59", **style)
    pl.add_mesh(pv.Sphere(radius=0.55, center=(-1.2, 0.3, 1.5)), color="#4f81bd", **style)
    pl.add_mesh(
        pv.ParametricTorus(ringradius=0.5, crosssectionradius=0.12).translate((1.3, 0.0, 0.9)),
        color="#c0504d",
        **style,
    )
    bulb = pv.Light(position=(2.2, -1.2, 4.0), positional=True, cone_angle=180)
    pl.add_light(bulb, only_active=True)
    bulbs[name] = bulb
    pl.camera_position = [(0.0, -8.0, 8.0), (-0.6, 1.0, 0.3), (0, 0, 1)]

# %%
# Shadows on, then one filter per bulb.
pl.shadows.enable()
for name, bulb in bulbs.items():
    pl.shadows.configure(bulb, **FILTERS[name])

# %%
# Measure each panel against the area light and write the result into it.
for panel, (name, bulb) in enumerate(bulbs.items()):
    error = pl.shadows.measure(bulb, light_size=RADIUS, samples=64)
    print(f"{name:7s}{error}")
    pl.subplot(panel // 2, panel % 2)
    pl.add_text(
        f"{name}: RMSE {error.rmse:.4f}\nagainst a ray-traced bulb of radius {RADIUS}",
        position="upper_left",
        font_size=11,
        color="black",
    )
pl.screenshot("soft_shadows.png")
print(pl.shadows.last_frame)
