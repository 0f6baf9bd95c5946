"""
Terrain under a low sun
=======================

A sun a few degrees above the horizon over the random hills that ship with
PyVista (``pyvista.examples.load_random_hills``): every ridge throws a shadow
many times its own height across the valleys behind it.

A directional light casts from a 2D depth map seen along the light with an
orthographic projection. pvshadows fits that map each frame to the casters
that can shadow what the camera sees, and snaps it to whole texels, so the
shadows do not swim while the camera moves. ``pl.shadows.last_frame`` says
how wide the fitted map is and how large one of its texels is.
"""

# %%
import numpy as np
import pyvista as pv

import pvshadows  # noqa: F401  (registers pl.shadows; installing pvshadows also does)

hills = pv.examples.load_random_hills()
print(f"{hills.n_cells} triangles, {hills.bounds.x_max - hills.bounds.x_min:g} units wide")

pl = pv.Plotter(off_screen=True, window_size=(1024, 640), lighting="none")
pl.set_background("#2b3a55", top="#e8b48a")  # dusk
_ = pl.add_mesh(
    hills,
    scalars="Elevation",
    cmap="terrain",
    clim=(-1.0, 9.0),
    ambient=0.25,
    diffuse=0.9,
    specular=0.0,
    smooth_shading=True,
    show_scalar_bar=False,
)

# %%
# The sun: a directional light (``positional=False``) shining from its
# position towards its focal point, 8 degrees above the horizon, from the
# left of the camera, so the shadows run across the picture.
elevation, azimuth = np.radians(8.0), np.radians(170.0)
towards_sun = np.array(
    [np.cos(elevation) * np.cos(azimuth), np.cos(elevation) * np.sin(azimuth), np.sin(elevation)]
)
centre = np.array(hills.center)
sun = pv.Light(
    position=tuple(centre + 100.0 * towards_sun), focal_point=tuple(centre), color="#fff1dc"
)
pl.add_light(sun)

# %%
# One line for shadows: ``"auto"`` gives a directional light a fitted 2D map.
pl.shadows.enable(resolution=2048)
pl.camera_position = [(-14.0, -16.0, 15.0), (0.5, 9.0, 1.0), (0, 0, 1)]
_ = pl.screenshot("terrain_low_sun.png")

# %%
# What ran: the map's pass, with the width it was fitted to and the size of a
# texel on the ground.
print(pl.shadows.last_frame)
print(pl.shadows.measure(sun))
