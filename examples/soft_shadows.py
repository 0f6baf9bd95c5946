"""
Soft shadows side by side
=========================

One scene, lit by one bulb, drawn with each filter of the cube map in turn:

- ``hard``: one depth compare per pixel, a sharp edge with the map's texels
  in it;
- ``pcf``: percentage-closer filtering, a grid of hardware-filtered compares
  (``pcf_taps``), a penumbra of fixed width;
- ``random``: compares at jittered points of a disk (``samples``,
  ``filter_radius``), stopping after 8 when they all agree;
- ``pcss``: percentage-closer soft shadows, a blocker search first, then a
  penumbra as wide as the light's physical size (``light_size``) makes it:
  sharp where an object touches the ground, wide far from it.

Each frame is measured against the same bulb ray traced as a sphere of that
radius (32 stratified shadow rays per pixel). The scene, camera and light do
not change between filters, so the reference is traced once and every
filter is judged against it; its RMSE of visibility is written above each
picture.
"""

# %%
import matplotlib.pyplot as plt
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows; installing pvshadows also does)

RADIUS = 0.3  # the bulb's physical radius, in world units
RAYS = 32  # shadow rays per pixel of the reference
FILTERS = {
    "hard": {"filter": "hard"},
    "pcf": {"filter": "pcf", "pcf_taps": 16},
    "random": {"filter": "random", "samples": 64, "filter_radius": 3.0},
    "pcss": {"filter": "pcss", "samples": 32, "light_size": RADIUS},
}

pl = pv.Plotter(off_screen=True, window_size=(480, 360), lighting="none")
pl.set_background("#f4f1ea", top="#bcc8d6")
flat = {"ambient": 0.2, "diffuse": 0.8, "specular": 0.1}
style = {**flat, "smooth_shading": True}  # round things only: a box's normals would blur
_ = pl.add_mesh(pv.Plane(i_size=9, j_size=9), color="#d9d4c7", **flat)
_ = pl.add_mesh(pv.Box(bounds=(-0.2, 0.2, 0.6, 1.0, 0.0, 2.6)), color="#9bbb59", **flat)
_ = pl.add_mesh(pv.Sphere(radius=0.55, center=(-1.2, 0.3, 1.5)), color="#4f81bd", **style)
_ = pl.add_mesh(
    pv.ParametricTorus(ringradius=0.5, crosssectionradius=0.12).translate((1.3, 0.0, 0.9)),
    color="#c0504d",
    **style,
)
bulb = pv.Light(position=(2.2, -1.2, 4.0), positional=True, cone_angle=180)
pl.add_light(bulb)
pl.camera_position = [(0.0, -8.0, 8.0), (-0.6, 1.0, 0.3), (0, 0, 1)]

# %%
# Shadows on, then each filter in turn: its picture and its error against the
# area light (traced on the first call, reused by the others).
pl.shadows.enable()
pictures = {}
for name, settings in FILTERS.items():
    pl.shadows.configure(bulb, **settings)
    pictures[name] = pl.screenshot(return_img=True)
    error = pl.shadows.measure(bulb, light_size=RADIUS, samples=RAYS)
    print(f"{name:7s}{error}")
    pictures[name] = (pictures[name], error)
print(pl.shadows.last_frame)

# %%
# The four pictures side by side.
figure, axes = plt.subplots(2, 2, figsize=(9.6, 7.8), dpi=100)
for panel, (name, (picture, error)) in zip(axes.flat, pictures.items(), strict=True):
    panel.imshow(picture)
    panel.set_title(f"{name}: RMSE {error.rmse:.4f} against a bulb of radius {RADIUS}")
    panel.set_axis_off()
figure.tight_layout()
figure.savefig("soft_shadows.png")
plt.close(figure)
