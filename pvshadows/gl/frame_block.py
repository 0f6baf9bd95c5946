"""The receivers' uniform block: each light's matrices and parameters, set once per frame.

Each light's view-to-light matrix changes whenever the camera moves, its
parameters (far distance, texel size, cone, a sun's fit) whenever it or its
casters move, its strength when the user sets it, and every receiver reads
them, as it reads the probe's light and the viewport. Held as per-receiver
uniforms, such values would cost one call per receiver and light, and VTK
would set each again at every draw; held in one uniform buffer
(``glsl/frame_block.glsl``: a header, then one ``PvsLight`` per VTK light
index), they cost one upload per frame whatever the number of receivers,
and a receiver keeps only its samplers' texture units as its own uniforms.

The block sits at binding point 0, where GL puts every program's blocks
until told otherwise: so the very first frame of a receiver, drawn with a
program VTK has just compiled, reads it, with no call per program. VTK's
own OpenGL code uses no uniform blocks; the buffer is bound there at the
start of each of the renderer's frames, after pvshadows' own passes.
"""

from __future__ import annotations

import ctypes
from collections.abc import Mapping
from typing import NamedTuple

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for

_EYE = np.eye(4)
#: The uniform buffer binding point of the block: every program's default.
BINDING = 0
#: ``GL_UNIFORM_BUFFER`` and ``GL_DYNAMIC_DRAW``, as plain ints.
_UNIFORM_BUFFER, _DYNAMIC_DRAW = 0x8A11, 0x88E8


class LightEntry(NamedTuple):
    """One light's ``PvsLight`` entry of the frame's uniform block (``glsl/frame_block.glsl``).

    Attributes
    ----------
    view_to_light : numpy.ndarray
        ``(4, 4)``: view coordinates to the light's space (the identity for
        a light that reads no map).
    pack : tuple
        The four columns of the pack: params, cone, bias and filter
        (radius in texels, taps, layer in a cube array, 0).
    light_to_clip : numpy.ndarray or None
        ``(4, 4)``: light space to a spot map's clip space; ``None`` for
        the identity.
    light_vc : tuple
        The light in view coordinates for a screen mask's facing test:
        ``(position, 1)`` or ``(direction towards the light, 0)``.
    strength : float
        The light's shadow strength.
    """

    view_to_light: np.ndarray
    pack: tuple
    light_to_clip: np.ndarray | None
    light_vc: tuple
    strength: float


#: Floats before the lights' entries: the probe's light and a zero (ints, padded to
#: 16 bytes) and the viewport (a vec4).
HEADER_FLOATS = 8
#: Floats of one entry: three matrices and two vectors.
ENTRY_FLOATS = 3 * 16 + 2 * 4


class FrameBlock:
    """One uniform buffer holding the frame's probe, viewport and every shadowed light's entry.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the buffer.

    Attributes
    ----------
    uploads : int
        Times the block changed and was sent to the GPU.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        gl = opengl_for(window)
        # The raw entry points skip PyOpenGL's argument wrappers; imported here, once
        # PyOpenGL is loaded for the window's platform.
        from OpenGL.raw.GL.VERSION.GL_1_5 import glBufferData
        from OpenGL.raw.GL.VERSION.GL_3_0 import glBindBufferBase

        self._gl = gl
        self._send, self._bind_base = glBufferData, glBindBufferBase
        self._buffer = int(gl.glGenBuffers(1))
        self._data = np.zeros(0, dtype=np.float32)
        self._probe = self._data.view(np.int32)
        self._pointer = ctypes.c_void_p(0)
        self._sent = b""
        self.uploads = 0

    def update(
        self,
        entries: Mapping[int, LightEntry],
        probe: int = -1,
        viewport: tuple[float, float, float, float] = (0.0, 0.0, 1.0, 1.0),
    ) -> None:
        """Send this frame's block and bind it.

        The buffer holds at least 8 entries, and twice the entries asked for
        whenever more are: never fewer than any receiver's block declares.
        Only a block that differs from the last one sent is uploaded.

        Parameters
        ----------
        entries : dict
            Each light's entry by its VTK light index
            (:func:`pvshadows.shaders.library.take_light_entries`); the
            entries of other lights are zero.
        probe : int, default: -1
            The VTK index of the light a probe frame shows, or -1.
        viewport : tuple of float, default: (0.0, 0.0, 1.0, 1.0)
            The renderer's origin and size in the window, in pixels.

        Examples
        --------
        >>> import numpy as np
        >>> import pyvista as pv
        >>> from pvshadows.gl.frame_block import FrameBlock, LightEntry
        >>> pl = pv.Plotter(off_screen=True)
        >>> pl.ren_win.Render()
        >>> block = FrameBlock(pl.ren_win)
        >>> entry = LightEntry(np.eye(4), ((0.0,) * 4,) * 4, None, (0, 0, 1, 1), 0.8)
        >>> block.update({0: entry}, probe=-1, viewport=(0, 0, 300, 200))
        >>> block.update({0: entry}, probe=-1, viewport=(0, 0, 300, 200))
        >>> block.uploads
        1
        """
        capacity = max(8, 2 * (max(entries, default=-1) + 1))
        size = HEADER_FLOATS + capacity * ENTRY_FLOATS
        data = self._data
        if data.size < size:
            data = self._data = np.zeros(size, dtype=np.float32)
            self._probe = data[:1].view(np.int32)
            self._pointer = ctypes.c_void_p(data.ctypes.data)  # read once: a ctypes view per read
        else:
            data.fill(0.0)
        self._probe[0] = probe
        data[4:HEADER_FLOATS] = viewport
        block = data[HEADER_FLOATS:].reshape(-1, ENTRY_FLOATS)
        # GLSL reads matrices by columns: each stored matrix is the transpose
        for index, entry in entries.items():
            row = block[index]
            row[0:16].reshape(4, 4)[:] = entry.view_to_light.T
            row[16:32].reshape(4, 4)[:] = entry.pack
            light_to_clip = _EYE if entry.light_to_clip is None else entry.light_to_clip
            row[32:48].reshape(4, 4)[:] = light_to_clip.T
            row[48:52] = entry.light_vc
            row[52] = entry.strength
        # Binding to the indexed point binds the buffer to GL_UNIFORM_BUFFER too, where
        # glBufferData reads it.
        self._bind_base(_UNIFORM_BUFFER, BINDING, self._buffer)
        sent = data.tobytes()  # compared as bytes: a NaN parameter equals itself
        if sent != self._sent:
            self._send(_UNIFORM_BUFFER, data.nbytes, self._pointer, _DYNAMIC_DRAW)
            self._sent = sent
            self.uploads += 1

    def release(self) -> None:
        """Delete the buffer."""
        if self._buffer:
            self._gl.glDeleteBuffers(1, [self._buffer])
            self._buffer = 0
