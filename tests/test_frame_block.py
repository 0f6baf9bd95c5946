"""The frame's uniform block holds each light's entry where GLSL reads it (frame_block.glsl)."""

import numpy as np
import pyvista as pv

from pvshadows.gl.binding import opengl_for
from pvshadows.gl.frame_block import BINDING, ENTRY_FLOATS, HEADER_FLOATS, FrameBlock, LightEntry


def _entry(matrix, clip, light_vc, strength):
    return LightEntry(
        strength,
        view_to_light=matrix,
        params=(1.0, 2.0, 3.0, 4.0),
        cone=(5.0, 6.0, 7.0, 8.0),
        bias=(9.0, 10.0, 11.0, 12.0),
        filter_radius=13.0,
        taps=3,
        layer=2.0,
        light_to_clip=clip,
        light_vc=light_vc,
    )


def test_each_lights_entry_lies_at_its_index_with_matrices_by_columns():
    pl = pv.Plotter(off_screen=True, window_size=(64, 48))
    pl.ren_win.Render()
    block = FrameBlock(pl.ren_win)
    matrix = np.arange(16.0).reshape(4, 4)
    pack = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0, 11.0, 12.0, 13.0, 3, 2.0, 0.0]
    entries = {
        3: _entry(matrix, 2.0 * matrix, (0.5, 0.25, -1.0, 1.0), 0.75),
        0: _entry(-matrix, None, (0.0, 0.0, 1.0, 0.0), 1.0),
    }
    block.update(entries, probe=3, viewport=(10.0, 20.0, 300.0, 200.0))
    data = block.floats
    assert data[:1].view(np.int32)[0] == 3
    assert data[1:4].view(np.int32).tolist() == [0, 0, 0]  # the loop's zero, then padding
    assert data[4:HEADER_FLOATS].tolist() == [10.0, 20.0, 300.0, 200.0]
    rows = data[HEADER_FLOATS:].reshape(-1, ENTRY_FLOATS)
    assert len(rows) == 8  # room for twice the highest index and more, never fewer than 8
    third = rows[3]
    assert third[0:16].tolist() == matrix.T.ravel().tolist()  # column after column
    assert third[16:32].tolist() == pack  # params, cone, bias and the filter's column in turn
    assert third[32:48].tolist() == (2.0 * matrix).T.ravel().tolist()
    assert third[48:53].tolist() == [0.5, 0.25, -1.0, 1.0, 0.75]
    first = rows[0]
    assert first[0:16].tolist() == (-matrix).T.ravel().tolist()
    assert first[32:48].tolist() == np.eye(4).ravel().tolist()  # no map projection: identity
    assert first[48:53].tolist() == [0.0, 0.0, 1.0, 0.0, 1.0]
    assert not rows[[1, 2, 4, 5, 6, 7]].any()  # lights without an entry read zeros
    assert not third[53:].any() and not first[53:].any()
    pl.close()


def test_a_light_gone_reads_zeros_and_an_unchanged_block_is_sent_once():
    pl = pv.Plotter(off_screen=True, window_size=(64, 48))
    pl.ren_win.Render()
    block = FrameBlock(pl.ren_win)
    matrix = np.arange(16.0).reshape(4, 4)
    both = {1: _entry(matrix, None, (0.0, 0.0, 1.0, 1.0), 0.5), 2: LightEntry(0.25)}
    block.update(both)
    block.update(both)
    assert block.uploads == 1
    rows = block.floats[HEADER_FLOATS:].reshape(-1, ENTRY_FLOATS)
    assert rows[2, 0:16].tolist() == np.eye(4).ravel().tolist()  # no view matrix: identity
    assert rows[2, 16:48].tolist() == [0.0] * 16 + np.eye(4).ravel().tolist()
    block.update({2: LightEntry(0.25)})
    rows = block.floats[HEADER_FLOATS:].reshape(-1, ENTRY_FLOATS)
    assert block.uploads == 2
    assert not rows[1].any() and rows[2, 52] == 0.25
    assert block.floats[:1].view(np.int32)[0] == -1  # no probe
    pl.close()


def test_the_same_entries_again_pack_nothing_and_the_block_is_bound_again(monkeypatch):
    pl = pv.Plotter(off_screen=True, window_size=(64, 48))
    pl.ren_win.Render()
    gl = opengl_for(pl.ren_win)
    block = FrameBlock(pl.ren_win)
    entries = {0: _entry(np.eye(4), None, (0.0, 0.0, 1.0, 1.0), 0.5)}
    block.update(entries, viewport=(0.0, 0.0, 64.0, 48.0))
    packed = []
    monkeypatch.setattr(LightEntry, "floats", lambda entry: packed.append(entry) or [0.0] * 56)
    gl.glBindBufferBase(gl.GL_UNIFORM_BUFFER, BINDING, 0)  # another user of the binding point
    block.update(dict(entries), viewport=(0.0, 0.0, 64.0, 48.0))
    assert packed == [] and block.uploads == 1
    assert gl.glGetIntegeri_v(gl.GL_UNIFORM_BUFFER_BINDING, BINDING) == block._buffer
    block.update(entries, viewport=(0.0, 0.0, 32.0, 48.0))  # the viewport changed: packed again
    assert block.uploads == 2 and packed == []  # the entry itself still is not
    assert block.floats[4:HEADER_FLOATS].tolist() == [0.0, 0.0, 32.0, 48.0]
    pl.close()
