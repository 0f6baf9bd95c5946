"""Drive pvshadows in a real on-screen window and record every frame.

Run with ``DISPLAY`` set (``tests/test_onscreen.py`` starts Xvfb for it)::

    python onscreen_session.py OUT

For each case it opens the standard scene in an on-screen ``pv.Plotter`` (an
X window drawn through GLX), orbits the camera with mouse events sent to the
interactor (trackball camera style), zooms with the wheel and moves the light.
After each step it writes ``OUT/<case>-<step>.npz`` with the camera, the
light, VTK's screenshot, the window as the X server shows it, the visibility
read by ``pl.shadows.visibility``, its error against the ray-traced reference
(``pl.shadows.measure``) and the window as the X server shows it after those
calls. The test rebuilds
each frame off screen and compares.
"""

from __future__ import annotations

import ctypes
import sys
from pathlib import Path

import numpy as np
import vtk

from pvshadows.gl.binding import describe_binding
from pvshadows.tools.scenes import standard_scene

WINDOW_SIZE = (400, 300)

#: Each case: the kind of light and the settings it casts its shadows with.
CASES = {
    "cubemap": ("point", {"technique": "cubemap", "filter": "hard", "resolution": 1024}),
    "map": ("directional", {"technique": "map", "filter": "hard", "resolution": 2048}),
    "volume": ("spot", {"technique": "volume"}),
}

#: The steps of each session, in order.
STEPS = ("opened", "orbited-left", "orbited-up-zoomed", "light-moved")


def build(case: str, *, off_screen: bool):
    """Return the standard scene of ``case`` with its shadows enabled."""
    light, settings = CASES[case]
    scene = standard_scene(light=light, window_size=WINDOW_SIZE, off_screen=off_screen)
    scene.plotter.shadows.enable(**settings)
    return scene


def camera_state(camera: vtk.vtkCamera) -> dict[str, np.ndarray]:
    """Return everything that places a perspective camera."""
    return {
        "position": np.array(camera.GetPosition()),
        "focal_point": np.array(camera.GetFocalPoint()),
        "view_up": np.array(camera.GetViewUp()),
        "view_angle": np.array(camera.GetViewAngle()),
        "clipping_range": np.array(camera.GetClippingRange()),
    }


def apply_camera(camera: vtk.vtkCamera, state) -> None:
    """Place ``camera`` as recorded by :func:`camera_state`."""
    camera.SetPosition(*state["position"])
    camera.SetFocalPoint(*state["focal_point"])
    camera.SetViewUp(*state["view_up"])
    camera.SetViewAngle(float(state["view_angle"]))
    camera.SetClippingRange(*state["clipping_range"])


def moved_light(scene) -> tuple[np.ndarray, np.ndarray]:
    """Return a new position and focal point for the scene's light."""
    if scene.light.positional:
        return scene.place((-0.9, 0.7, 3.1)), np.array(scene.light.focal_point)
    elevation, azimuth = np.radians(55.0), np.radians(-40.0)
    towards = np.array(
        [
            np.cos(elevation) * np.cos(azimuth),
            np.cos(elevation) * np.sin(azimuth),
            np.sin(elevation),
        ]
    )
    return scene.offset + 10.0 * scene.scale * towards, scene.offset.copy()


class XImage(ctypes.Structure):
    """The leading fields of Xlib's ``XImage``."""

    _fields_ = [
        ("width", ctypes.c_int),
        ("height", ctypes.c_int),
        ("xoffset", ctypes.c_int),
        ("format", ctypes.c_int),
        ("data", ctypes.c_void_p),
        ("byte_order", ctypes.c_int),
        ("bitmap_unit", ctypes.c_int),
        ("bitmap_bit_order", ctypes.c_int),
        ("bitmap_pad", ctypes.c_int),
        ("depth", ctypes.c_int),
        ("bytes_per_line", ctypes.c_int),
        ("bits_per_pixel", ctypes.c_int),
    ]


def _xlib() -> ctypes.CDLL:
    x11 = ctypes.CDLL("libX11.so.6")
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
    x11.XGetImage.restype = ctypes.POINTER(XImage)
    x11.XGetImage.argtypes = [
        ctypes.c_void_p,
        ctypes.c_ulong,
        ctypes.c_int,
        ctypes.c_int,
        ctypes.c_uint,
        ctypes.c_uint,
        ctypes.c_ulong,
        ctypes.c_int,
    ]
    x11.XFree.argtypes = [ctypes.c_void_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    return x11


def x_window_pixels(window: vtk.vtkRenderWindow) -> np.ndarray:
    """Return what the X server shows in ``window``: uint8 RGB, row 0 at the top."""
    x11 = _xlib()
    x11.XSync(int(window.GetGenericDisplayId().split("_")[1], 16), 0)
    window_id = int(window.GetGenericWindowId().split("_")[1], 16)
    width, height = window.GetSize()
    display = x11.XOpenDisplay(None)
    try:
        all_planes, z_pixmap = ctypes.c_ulong(-1).value, 2
        image = x11.XGetImage(display, window_id, 0, 0, width, height, all_planes, z_pixmap)
        fields = image.contents
        layout = (fields.bits_per_pixel, fields.byte_order)
        row_bytes = fields.bytes_per_line
        raw = ctypes.string_at(fields.data, row_bytes * height)
        x11.XFree(fields.data)
        x11.XFree(image)
    finally:
        x11.XCloseDisplay(display)
    assert layout == (32, 0), f"expects 32-bit little-endian BGRX pixels, got {layout}"
    pixels = np.frombuffer(raw, np.uint8).reshape(height, row_bytes // 4, 4)
    return pixels[:, :width, 2::-1].copy()


def drag(interactor: vtk.vtkRenderWindowInteractor, start, end, moves: int = 6) -> None:
    """Press the left button at ``start``, move to ``end`` and release it."""
    interactor.SetEventInformation(*start)
    interactor.InvokeEvent("LeftButtonPressEvent")
    for step in range(1, moves + 1):
        x = round(start[0] + (end[0] - start[0]) * step / moves)
        y = round(start[1] + (end[1] - start[1]) * step / moves)
        interactor.SetEventInformation(x, y)
        interactor.InvokeEvent("MouseMoveEvent")
    interactor.InvokeEvent("LeftButtonReleaseEvent")


def record(scene, case: str, step: str, out: Path) -> None:
    """Draw the current frame and save what a user and pvshadows see of it."""
    plotter = scene.plotter
    plotter.render()
    screenshot = plotter.screenshot(return_img=True)
    shown = x_window_pixels(plotter.ren_win)
    visibility = plotter.shadows.visibility(scene.light)
    error = plotter.shadows.measure(scene.light)
    np.savez_compressed(
        out / f"{case}-{step}.npz",
        window=plotter.ren_win.GetClassName(),
        binding=describe_binding(plotter.ren_win),
        technique=str(plotter.shadows.last_frame.lights[0].technique),
        interactor_style=plotter.iren.interactor.GetInteractorStyle().GetClassName(),
        light_position=np.array(scene.light.position),
        light_focal_point=np.array(scene.light.focal_point),
        screenshot=screenshot,
        shown=shown,
        visibility=visibility,
        misclassified=error.misclassified,
        shown_after_visibility=x_window_pixels(plotter.ren_win),
        image_after_visibility=np.asarray(plotter.image),
        **camera_state(plotter.camera),
    )


def session(case: str, out: Path) -> None:
    """Open one case on screen, interact with it and record each step."""
    scene = build(case, off_screen=False)
    plotter = scene.plotter
    plotter.show(interactive_update=True, auto_close=False)
    interactor = plotter.iren.interactor
    width, height = WINDOW_SIZE
    middle = (width // 2, height // 2)
    record(scene, case, "opened", out)
    drag(interactor, middle, (middle[0] + 90, middle[1]))
    record(scene, case, "orbited-left", out)
    drag(interactor, middle, (middle[0] - 20, middle[1] - 45))
    interactor.InvokeEvent("MouseWheelForwardEvent")
    record(scene, case, "orbited-up-zoomed", out)
    position, focal_point = moved_light(scene)
    scene.light.position = tuple(position)
    scene.light.focal_point = tuple(focal_point)
    record(scene, case, "light-moved", out)
    plotter.close()


if __name__ == "__main__":
    folder = Path(sys.argv[1])
    folder.mkdir(parents=True, exist_ok=True)
    for name in sys.argv[2:] or CASES:
        session(name, folder)
