"""A real on-screen window: Xvfb, an X window through GLX, mouse events, the same shadows.

The test starts a virtual X display and runs ``onscreen_session.py`` in a
process of its own (PyOpenGL's platform is fixed per process): it opens the
standard scene in ``pv.Plotter()`` for each technique, orbits the camera with
interactor events, zooms, moves the light and records every frame. This
process rebuilds each frame off screen (EGL) from the recorded camera and
light, and the two must agree.
"""

import os
import select
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
from onscreen_session import CASES, STEPS, apply_camera, build

from pvshadows.tools.info import TRIALS

pytestmark = [
    pytest.mark.skipif(
        shutil.which("Xvfb") is None,
        reason="Xvfb is not installed (Debian/Ubuntu package xvfb; .ci/run installs it)",
    ),
]

SESSION = Path(__file__).with_name("onscreen_session.py")


@pytest.fixture(scope="module")
def x_display(tmp_path_factory):
    """Start Xvfb on a free display number; yield the environment of a process using it.

    ``-noreset``: by default Xvfb resets when its last client disconnects, and a
    connection opened during the reset is refused (2 % of back-to-back opens
    here); the session closes and opens windows and display connections in turn.
    """
    log = open(tmp_path_factory.mktemp("xvfb") / "xvfb.log", "w")
    read_end, write_end = os.pipe()
    server = subprocess.Popen(
        [
            "Xvfb",
            "-displayfd",
            str(write_end),
            "-screen",
            "0",
            "1024x768x24",
            "-nolisten",
            "tcp",
            "-noreset",
        ],
        pass_fds=(write_end,),
        stdout=log,
        stderr=log,
    )
    os.close(write_end)
    try:
        ready, _, _ = select.select([read_end], [], [], 30)
        number = os.read(read_end, 64).decode().strip() if ready else ""
        if not number.isdigit():
            pytest.fail(f"Xvfb did not start: {Path(log.name).read_text()}")
        env = dict(os.environ, DISPLAY=f":{number}")
        for name in ("VTK_DEFAULT_OPENGL_WINDOW", "PYOPENGL_PLATFORM", "WAYLAND_DISPLAY"):
            env.pop(name, None)
        env["XDG_SESSION_TYPE"] = "x11"
        yield env
    finally:
        os.close(read_end)
        server.terminate()
        try:
            server.wait(timeout=10)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()
        log.close()


def run_on_display(env, args, **extra_env):
    result = subprocess.run(
        [sys.executable, *args],
        env={**env, **extra_env},
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    assert "pvshadows" not in result.stderr, result.stderr  # no frame drawn without shadows
    return result.stdout


@pytest.fixture(scope="module")
def recorded(x_display, tmp_path_factory):
    """Every frame of every on-screen session, by case and step."""
    out = tmp_path_factory.mktemp("onscreen")
    run_on_display(x_display, [str(SESSION), str(out)])
    return {(case, step): np.load(out / f"{case}-{step}.npz") for case in CASES for step in STEPS}


def class_differences(a, b):
    """Share of pixels whose class (no receiver / shadow / lit) differs."""
    seen_a, seen_b = np.isfinite(a), np.isfinite(b)
    differ = (seen_a != seen_b) | (seen_a & seen_b & ((a < 0.5) != (b < 0.5)))
    return float(differ.mean())


def test_the_window_is_an_x_window_drawn_through_glx(recorded):
    for frame in recorded.values():
        assert str(frame["window"]) == "vtkXOpenGLRenderWindow"
        assert str(frame["binding"]) == "glx"
        assert str(frame["interactor_style"]) == "vtkInteractorStyleTrackballCamera"
    for case in CASES:
        assert {str(recorded[case, step]["technique"]) for step in STEPS} == {case}


def test_onscreen_shadows_match_ray_traced_visibility(recorded):
    for frame in recorded.values():
        assert float(frame["misclassified"]) <= 0.01


def test_mouse_events_orbited_and_zoomed_and_the_light_moved(recorded):
    for case in CASES:
        frames = [recorded[case, step] for step in STEPS]
        opened, left, up, moved = frames
        to_camera = [f["position"] - f["focal_point"] for f in frames]
        turn = np.degrees(
            np.arccos(np.dot(*to_camera[:2]) / np.prod(np.linalg.norm(to_camera[:2], axis=1)))
        )
        assert turn > 20  # the drag orbited the camera about the focal point ...
        assert np.isclose(*np.linalg.norm(to_camera[:2], axis=1))  # ... at the same distance
        assert np.linalg.norm(to_camera[2]) < 0.95 * np.linalg.norm(to_camera[1])  # wheel zoom
        assert np.allclose(up["position"], moved["position"])
        assert not np.allclose(up["light_position"], moved["light_position"])
        changed = np.isfinite(up["visibility"]) & (
            (up["visibility"] < 0.5) != (moved["visibility"] < 0.5)
        )
        assert changed.mean() > 0.01  # the shadows followed the light
        assert not np.array_equal(opened["screenshot"], left["screenshot"])


@pytest.mark.parametrize("case", list(CASES))
def test_onscreen_frames_match_offscreen_frames(recorded, case):
    for step in STEPS:
        frame = recorded[case, step]
        scene = build(case, off_screen=True)
        plotter = scene.plotter
        apply_camera(plotter.camera, frame)
        scene.light.position = tuple(frame["light_position"])
        scene.light.focal_point = tuple(frame["light_focal_point"])
        image = plotter.screenshot(return_img=True)
        assert np.allclose(plotter.camera.GetClippingRange(), frame["clipping_range"])
        visibility = plotter.shadows.visibility(scene.light)
        shown = frame["visibility"]
        assert np.mean(shown < 0.5) > 0.02  # there are shadows to compare
        assert class_differences(shown, visibility) <= 0.005, step
        colour = np.abs(frame["screenshot"].astype(int) - image).max(axis=2)
        assert np.mean(colour > 32) <= 0.01, step
        plotter.close()


def test_the_window_shows_the_normal_frame_around_visibility(recorded):
    """What the X server shows equals VTK's screenshot, before and after the probe frame."""
    for frame in recorded.values():
        assert np.array_equal(frame["shown"], frame["screenshot"])
        assert np.array_equal(frame["shown_after_visibility"], frame["shown"])
        assert np.array_equal(frame["image_after_visibility"], frame["shown"])


def test_info_reports_the_onscreen_window(x_display):
    out = run_on_display(x_display, ["-m", "pvshadows", "info", "--onscreen"])
    assert "window            vtkXOpenGLRenderWindow" in out
    assert f"display           X {x_display['DISPLAY']}\n" in out
    assert "PyOpenGL platform glx\n" in out
    for technique in (
        "cubemap (passes='single')",
        "map (spot, directional)",
        "volume (extrude='gpu')",
    ):
        assert f"{technique:26s}available" in out


def test_info_in_a_wayland_session_uses_glx_through_xwayland(x_display):
    """PyOpenGL alone would pick EGL here (the session, and the user's setting); VTK's is X."""
    out = run_on_display(
        x_display,
        ["-m", "pvshadows", "info", "--onscreen"],
        XDG_SESSION_TYPE="wayland",
        WAYLAND_DISPLAY="wayland-0",
        PYOPENGL_PLATFORM="egl",
    )
    assert "(XWayland in a Wayland session)" in out
    assert "PyOpenGL platform glx\n" in out
    states = [line.split(")", 1)[1].strip() for line in out.split("techniques:\n")[1].splitlines()]
    assert states == ["available"] * len(TRIALS)


def test_pyopengl_imported_for_egl_first_still_reaches_the_x_window(x_display):
    code = textwrap.dedent(
        f"""
        import sys
        import OpenGL.GL  # the user's import, before pvshadows, for EGL
        sys.path.insert(0, {str(SESSION.parent)!r})
        from onscreen_session import build
        from pvshadows.gl.binding import describe_binding
        scene = build("cubemap", off_screen=False)
        scene.plotter.show(interactive_update=True, auto_close=False)
        print(describe_binding(scene.plotter.ren_win))
        print(scene.plotter.shadows.measure(scene.light).misclassified)
        """
    )
    out = run_on_display(x_display, ["-c", code], PYOPENGL_PLATFORM="egl").splitlines()
    assert out[0].startswith("egl, bridged to this GLX context through libglvnd")
    assert float(out[1]) <= 0.01
