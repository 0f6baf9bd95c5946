"""Faults inside pvshadows: every failed frame is plain, said, and refused by the readers."""

import warnings

import numpy as np
import pytest

from conftest import draw
from pvshadows.passes.cube_depth import CubeDepthPass
from pvshadows.techniques.cubemap import CubemapTechnique
from pvshadows.tools.scenes import standard_scene
from pvshadows.verify.probe import FrameFailedError


def _broken(*args, **kwargs):
    raise RuntimeError("injected fault")


def _shader_edits(scene):
    actors = (scene.ground, scene.box, scene.sphere, scene.cylinder)
    props = [actor.GetShaderProperty() for actor in actors]
    return [
        (p.GetNumberOfShaderReplacements(), p.GetFragmentCustomUniforms().GetNumberOfUniforms())
        for p in props
    ]


@pytest.fixture
def small():
    return standard_scene(window_size=(400, 300))


def test_a_fault_in_a_pass_draws_plain_says_where_and_readers_refuse(small, monkeypatch):
    pl = small.plotter
    plain = pl.screenshot(return_img=True)
    pl.shadows.enable(filter="hard")
    good = draw(pl)
    monkeypatch.setattr(CubeDepthPass, "render", _broken)
    where = r"light 0 \(point, cubemap\) in CubemapTechnique.update raised RuntimeError"
    with pytest.warns(UserWarning, match=where):
        pl.shadows.configure(small.light, resolution=512)  # the map must be drawn again
    frame = draw(pl)
    assert np.array_equal(frame, plain)
    assert not np.array_equal(good, plain)
    assert _shader_edits(small) == [(0, 0)] * 4
    report = pl.shadows.last_frame
    assert report.failure.error == "RuntimeError: injected fault"
    assert report.lights[0].technique is None
    assert "frame" in str(report) and "injected fault" in str(report)
    with pytest.raises(FrameFailedError, match="injected fault"):
        pl.shadows.visibility(small.light)
    with pytest.raises(FrameFailedError, match=r"CubemapTechnique\.update"):
        pl.shadows.measure(small.light)


def test_a_persistent_fault_warns_once_and_counts_every_frame(small, monkeypatch):
    pl = small.plotter
    pl.shadows.enable(filter="hard")
    monkeypatch.setattr(CubeDepthPass, "render", _broken)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        for _ in range(5):
            draw(pl)
    assert len([w for w in caught if "injected fault" in str(w.message)]) == 1
    assert pl.shadows.last_frame.failure.repeats >= 5
    monkeypatch.undo()
    draw(pl)
    assert pl.shadows.last_frame.failure is None
    assert pl.shadows.measure(small.light).misclassified <= 0.01


def test_a_fault_whose_clean_up_fails_stays_inside_the_observer(small, monkeypatch, capfd):
    pl = small.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    monkeypatch.setattr(CubemapTechnique, "activate", _broken)
    monkeypatch.setattr(CubemapTechnique, "end_frame", _broken)
    monkeypatch.setattr(CubemapTechnique, "release", _broken)
    with pytest.warns(
        UserWarning, match=r"clean-up also failed: ending the frame of CubemapTechnique"
    ):
        draw(pl)
    assert _shader_edits(small) == [(0, 0)] * 4
    assert "Traceback" not in capfd.readouterr().err
    assert "releasing CubemapTechnique" in str(pl.shadows.last_frame.failure)


def test_a_fault_at_the_end_of_the_frame_is_caught(small, monkeypatch, capfd):
    pl = small.plotter
    pl.shadows.enable(filter="hard")
    monkeypatch.setattr(CubemapTechnique, "end_frame", _broken)
    with pytest.warns(UserWarning, match=r"the end of the frame in RendererShadows\._finish_frame"):
        draw(pl)
    assert "Traceback" not in capfd.readouterr().err
    assert _shader_edits(small) == [(0, 0)] * 4
    with pytest.raises(FrameFailedError):
        pl.shadows.visibility()


def test_a_fault_in_the_receiver_edits_leaves_vtk_shaders(small, monkeypatch):
    from pvshadows.shaders import edits as receivers

    pl = small.plotter
    pl.shadows.enable(filter="hard")
    draw(pl)
    monkeypatch.setattr(receivers, "receiver_replacements", _broken)
    with pytest.warns(UserWarning, match="receiver shader edits"):
        pl.shadows.configure(small.light, filter="pcf")  # new lookups: edits are rebuilt
        draw(pl)
    assert _shader_edits(small) == [(0, 0)] * 4
