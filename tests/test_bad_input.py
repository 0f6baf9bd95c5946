"""Bad input: a clear error naming the argument, or a correct picture; never a crash."""

import logging

import numpy as np
import pytest
import pyvista as pv

from conftest import draw, point_light
from pvshadows.gl.binding import opengl_for
from pvshadows.tools.scenes import standard_scene


@pytest.mark.parametrize(
    ("settings", "error", "words"),
    [
        ({"resolution": 0}, ValueError, "resolution=0 is out of range; it must be from 64 to 4096"),
        ({"resolution": 5000}, ValueError, "resolution=5000"),
        ({"resolution": "high"}, TypeError, "resolution must be an int"),
        (
            {"technique": "raytrace"},
            ValueError,
            "technique='raytrace' is not allowed; choose one of",
        ),
        (
            {"filter": "blur"},
            ValueError,
            "filter='blur' is not allowed; choose one of 'hard', 'pcf'",
        ),
        ({"pcf_taps": 9}, ValueError, "pcf_taps=9 is not allowed; choose one of 4, 16"),
        ({"passes": "twelve"}, ValueError, "passes='twelve'"),
        ({"bias": -1.0}, ValueError, "bias=-1.0 is out of range"),
        ({"normal_offset": float("nan")}, ValueError, "normal_offset=nan"),
        ({"shininess": 3}, TypeError, "unknown shadow setting(s) shininess"),
        ({"cull_front": "yes"}, TypeError, "cull_front must be True or False, got 'yes'"),
    ],
)
def test_bad_settings_name_the_argument(scene, settings, error, words):
    with pytest.raises(error, match=words.replace("(", r"\(").replace(")", r"\)")):
        scene.plotter.shadows.enable(**settings)
    with pytest.raises(error, match=words.replace("(", r"\(").replace(")", r"\)")):
        scene.plotter.shadows.configure(scene.light, **settings)
    assert not scene.plotter.shadows.enabled


def test_configure_checks_the_light(scene):
    shadows = scene.plotter.shadows
    with pytest.raises(TypeError, match=r"light must be a pyvista\.Light of this plotter, got str"):
        shadows.configure("bulb", filter="hard")
    with pytest.raises(ValueError, match="this light is not in the plotter"):
        shadows.configure(point_light((0, 0, 1)), filter="hard")
    sun = pv.Light(position=(1, 1, 1), focal_point=(0, 0, 0))
    scene.plotter.add_light(sun)
    with pytest.raises(ValueError, match="technique='cubemap' cannot serve this directional light"):
        shadows.configure(sun, technique="cubemap")


def test_set_caster_and_receiver_check_their_arguments(scene):
    with pytest.raises(TypeError, match=r"actor must be a pyvista\.Actor"):
        scene.plotter.shadows.set_caster(pv.Sphere(), False)
    with pytest.raises(TypeError, match="receive must be True or False, got 'no'"):
        scene.plotter.shadows.set_receiver(scene.box, "no")


def test_light_with_nan_position(scene):
    scene.light.position = (np.nan, 0.0, 3.0)
    with pytest.raises(ValueError, match=r"light position .* must be finite numbers"):
        scene.plotter.shadows.enable()
    scene.light.position = (0.3, -0.2, 3.5)
    scene.plotter.shadows.enable(filter="hard")
    scene.light.position = (np.nan, 0.0, 3.0)
    draw(scene.plotter)
    report = scene.plotter.shadows.last_frame.lights[0]
    assert report.technique is None
    assert "must be finite" in " ".join(report.notes)


def test_mesh_with_nan_points(scene):
    bad = pv.Sphere(center=(-3, 3, 1))
    bad.points[5] = np.nan
    scene.plotter.add_mesh(bad, name="broken")
    with pytest.raises(ValueError, match="actor 'broken' has 1 points that are NaN or infinite"):
        scene.plotter.shadows.enable()


def test_mesh_with_nan_points_added_later_is_left_out_with_a_warning(scene):
    scene.plotter.shadows.enable(filter="hard")
    draw(scene.plotter)
    bad = pv.Sphere(center=(-3, 3, 1))
    bad.points[5] = np.inf
    with pytest.warns(UserWarning, match="actor 'broken' has 1 points that are NaN or infinite"):
        scene.plotter.add_mesh(bad, name="broken")
        draw(scene.plotter)
    assert scene.plotter.shadows.last_frame.lights[0].technique == "cubemap"


def test_actors_without_triangles_render_correctly(scene):
    pl = scene.plotter
    pl.add_mesh(pv.Line((-4, -4, 0.5), (4, 4, 0.5)), color="black", line_width=3)
    pl.add_mesh(pv.PolyData(np.random.default_rng(1).uniform(-4, 4, (50, 3))), point_size=6)
    pl.shadows.enable(filter="hard")
    draw(pl)
    assert pl.shadows.measure(scene.light).misclassified <= 0.01


def test_light_inside_a_closed_caster_darkens_everything_outside():
    scene = standard_scene(window_size=(400, 300))
    scene.plotter.add_mesh(
        pv.Cube(center=scene.light.position, x_length=0.3, y_length=0.3, z_length=0.3)
    )
    scene.plotter.shadows.enable(filter="hard")
    shown = scene.plotter.shadows.visibility(scene.light)
    assert np.nanmax(shown) == 0.0
    assert scene.plotter.shadows.measure(scene.light).misclassified <= 0.01


def test_light_on_a_surface():
    """A bulb on the ground: the ground is edge-on and unlit; the objects' lower sides are lit."""
    scene = standard_scene(window_size=(400, 300), light_position=(0.3, -0.2, 0.0))
    scene.plotter.shadows.enable(filter="hard")
    shown = scene.plotter.shadows.visibility(scene.light)
    error = scene.plotter.shadows.measure(scene.light)
    # About 1 000 lit pixels on the objects' lower sides (998 with one sample per pixel).
    assert np.nansum(shown > 0.5) > 900
    # What disagrees is the faceted sphere's terminator, where the light grazes the facets.
    assert error.misclassified * error.lit_pixels < 100
    assert error.misclassified <= 0.03


def test_frames_leave_no_gl_error_and_print_nothing(scene, capfd, caplog):
    pl = scene.plotter
    with caplog.at_level(logging.WARNING):
        pl.shadows.enable(filter="pcf")
        draw(pl)
        pl.shadows.configure(scene.light, passes="six", resolution=256)
        draw(pl)
        pl.shadows.visibility(scene.light)
        gl = opengl_for(pl.ren_win)
        pl.ren_win.MakeCurrent()
        assert gl.glGetError() == gl.GL_NO_ERROR
        pl.shadows.disable()
        draw(pl)
    out, err = capfd.readouterr()
    assert "ERR" not in err and "rror" not in out + err
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]


def test_shader_compile_errors_carry_the_log(scene):
    from pvshadows.gl.programs import ShaderCompileError, compile_program

    draw(scene.plotter)
    with pytest.raises(ShaderCompileError, match=r"vertex shader:\n.*error"):
        compile_program(
            scene.plotter.ren_win,
            "#version 150\nvoid main() { gl_Position = vec4(1.0) }",
            "#version 150\nout vec4 c;\nvoid main() { c = vec4(1.0); }",
        )
