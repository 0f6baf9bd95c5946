"""How PyOpenGL reaches VTK's context: chosen from the window, bridged, or refused clearly."""

import ctypes.util
import os
import subprocess
import sys
import textwrap

import pytest
import pyvista as pv

from pvshadows.gl.binding import current_api, platform_for
from pvshadows.tools.info import TRIALS


def run_offscreen(code, **env):
    """Run ``code`` in a fresh process with no display (an EGL window) and ``env``."""
    environment = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    environment.pop("PYOPENGL_PLATFORM", None)
    environment.pop("XDG_SESSION_TYPE", None)
    environment.update({"VTK_DEFAULT_OPENGL_WINDOW": "vtkEGLRenderWindow", **env})
    return subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        env=environment,
        capture_output=True,
        text=True,
        timeout=300,
    )


def test_the_api_of_the_current_context_is_the_windows():
    pl = pv.Plotter(off_screen=True, window_size=[32, 32])
    pl.screenshot(return_img=True)
    pl.ren_win.MakeCurrent()
    assert current_api() == platform_for(pl.ren_win)


def test_pyopengl_is_imported_for_the_window_and_leaves_no_setting_behind():
    result = run_offscreen(
        """
        import os
        import pyvista as pv
        from pvshadows.gl.binding import loaded_platform, opengl_for
        opengl_for(pv.Plotter(off_screen=True).ren_win)
        print(loaded_platform(), os.environ.get("PYOPENGL_PLATFORM"))
        """
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["egl", "None"]


def test_pyopengl_imported_for_glx_first_is_bridged_to_the_egl_window():
    """A user imported OpenGL before pvshadows, with no display: PyOpenGL chose GLX."""
    result = run_offscreen(
        """
        import OpenGL.GL
        from pvshadows.gl.binding import describe_binding
        from pvshadows.tools.scenes import standard_scene
        scene = standard_scene(window_size=(400, 300))
        scene.plotter.shadows.enable(technique="cubemap", filter="hard")
        print(scene.plotter.shadows.measure(scene.light).misclassified)
        print(describe_binding(scene.plotter.ren_win))
        """
    )
    assert result.returncode == 0, result.stderr
    error, binding = result.stdout.splitlines()
    assert float(error) <= 0.01
    assert binding.startswith("glx, bridged to this EGL context through libglvnd")
    assert "Warning" not in result.stderr


def test_a_platform_that_cannot_reach_the_window_is_refused_clearly():
    result = run_offscreen(
        """
        import OpenGL.GL
        import pvshadows.gl.binding as binding
        binding._glvnd_loaded = lambda: False  # as on a system without libglvnd
        from pvshadows.tools.info import capabilities
        from pvshadows.tools.scenes import standard_scene
        scene = standard_scene(window_size=(64, 48))
        try:
            scene.plotter.shadows.enable()
        except binding.OpenGLPlatformError as error:
            print(error)
        print(capabilities())
        """
    )
    assert result.returncode == 0, result.stderr
    refusal, report = result.stdout.split("\n", 1)
    assert "PyOpenGL was already imported for 'glx'" in refusal
    assert "vtkEGLRenderWindow needs the 'egl' platform" in refusal
    assert "libglvnd" in refusal
    assert "PYOPENGL_PLATFORM=egl" in refusal
    assert "PyOpenGL platform unavailable: PyOpenGL was already imported" in report
    techniques = report.split("techniques:\n")[1].splitlines()
    assert len(techniques) == len(TRIALS)
    assert all("unavailable: PyOpenGL was already imported" in line for line in techniques)


def test_info_onscreen_without_a_display_says_why():
    result = run_offscreen(
        "from pvshadows.tools.cli import main; raise SystemExit(main(['info', '--onscreen']))",
        WAYLAND_DISPLAY="wayland-0",
    )
    assert result.returncode == 1
    assert "cannot open an on-screen window: DISPLAY is not set" in result.stderr
    assert "XWayland" in result.stderr


@pytest.mark.skipif(
    ctypes.util.find_library("OSMesa") is None,
    reason="libOSMesa is not installed (Debian/Ubuntu package libosmesa6; .ci/run installs it)",
)
def test_an_osmesa_window_runs_every_technique():
    result = run_offscreen(
        """
        from pvshadows.tools.info import capabilities
        from pvshadows.tools.scenes import standard_scene
        print(capabilities())
        scene = standard_scene(light="spot", window_size=(400, 300))
        scene.plotter.shadows.enable(technique="map", filter="hard")
        print("misclassified", scene.plotter.shadows.measure(scene.light).misclassified)
        """,
        VTK_DEFAULT_OPENGL_WINDOW="vtkOSOpenGLRenderWindow",
    )
    assert result.returncode == 0, result.stderr
    assert "window            vtkOSOpenGLRenderWindow" in result.stdout
    assert "PyOpenGL platform osmesa\n" in result.stdout
    techniques = result.stdout.split("techniques:\n")[1].splitlines()[:5]
    assert all(line.endswith(" available") for line in techniques), techniques
    assert float(result.stdout.split("misclassified")[1]) <= 0.01
