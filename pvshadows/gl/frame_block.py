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
import struct
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.raw_calls import raw_calls

#: The uniform buffer binding point of the block: every program's default.
BINDING = 0
#: ``GL_UNIFORM_BUFFER`` and ``GL_DYNAMIC_DRAW``, as plain ints.
_UNIFORM_BUFFER, _DYNAMIC_DRAW = 0x8A11, 0x88E8
_NO_VECTOR = (0.0, 0.0, 0.0, 0.0)


@dataclass(slots=True)
class LightEntry:
    """One light's ``PvsLight`` entry of the frame's uniform block (``glsl/frame_block.glsl``).

    The frame makes one per shadowed light and the light's technique fills
    in what it reads (:meth:`pvshadows.techniques.base.Technique.activate`);
    what it leaves is the default.

    Attributes
    ----------
    strength : float
        The light's shadow strength.
    view_to_light : numpy.ndarray or None
        ``(4, 4)``: view coordinates to the light's space; ``None`` for the
        identity (a light that reads no map).
    params, cone, bias : tuple of float
        The pack's first three columns: the map's far distance, texel and
        light size or fit; a spot's axis and cosine; the biases.
    filter_radius : float
        The filter's radius in texels.
    taps : int
        PCF's grid side, or the samples of the random and PCSS filters.
    layer : float
        The light's layer in a cube array.
    light_to_clip : numpy.ndarray or None
        ``(4, 4)``: light space to a spot map's clip space; ``None`` for
        the identity.
    light_vc : tuple of float
        The light in view coordinates for a screen mask's facing test:
        ``(position, 1)`` or ``(direction towards the light, 0)``.
    """

    strength: float
    view_to_light: np.ndarray | None = None
    params: tuple = _NO_VECTOR
    cone: tuple = _NO_VECTOR
    bias: tuple = _NO_VECTOR
    filter_radius: float = 0.0
    taps: int = 0
    layer: float = 0.0
    light_to_clip: np.ndarray | None = None
    light_vc: tuple = _NO_VECTOR

    def seen_from(self, view_to_light: np.ndarray) -> LightEntry:
        """Return a copy of the entry with another view-to-light matrix (the camera moved).

        Parameters
        ----------
        view_to_light : numpy.ndarray
            ``(4, 4)``: this frame's view coordinates to the light's space.

        Returns
        -------
        LightEntry
            The copy; this entry is left as it was.

        Examples
        --------
        >>> import numpy as np
        >>> from pvshadows.gl.frame_block import LightEntry
        >>> entry = LightEntry(0.5, params=(2.0, 0.1, 0.0, 0.0))
        >>> moved = entry.seen_from(2.0 * np.eye(4))
        >>> moved.view_to_light[0, 0], moved.params, entry.view_to_light
        (np.float64(2.0), (2.0, 0.1, 0.0, 0.0), None)
        """
        return LightEntry(
            self.strength,
            view_to_light,
            self.params,
            self.cone,
            self.bias,
            self.filter_radius,
            self.taps,
            self.layer,
            self.light_to_clip,
            self.light_vc,
        )

    def floats(self) -> list[float]:
        """Return the entry's floats as GLSL reads them (matrices by columns: transposed).

        Returns
        -------
        list of float
            :data:`ENTRY_FLOATS` values.

        Examples
        --------
        >>> from pvshadows.gl.frame_block import LightEntry
        >>> floats = LightEntry(0.5, params=(2.0, 0.1, 0.0, 0.0), taps=4).floats()
        >>> floats[16:18], floats[29], floats[52]
        ([2.0, 0.1], 4, 0.5)
        """
        view, clip = self.view_to_light, self.light_to_clip
        return [
            *(_EYE_FLOATS if view is None else view.T.flat),
            *self.params,
            *self.cone,
            *self.bias,
            self.filter_radius,
            self.taps,
            self.layer,
            0.0,
            *(_EYE_FLOATS if clip is None else clip.T.flat),
            *self.light_vc,
            self.strength,
            0.0,
            0.0,
            0.0,
        ]


#: Floats before the lights' entries: the probe's light and a zero (ints, padded to
#: 16 bytes) and the viewport (a vec4).
HEADER_FLOATS = 8
#: Floats of one entry: three matrices and two vectors.
ENTRY_FLOATS = 3 * 16 + 2 * 4
#: The identity's 16 floats: a matrix a light leaves out.
_EYE_FLOATS = tuple(np.eye(4).ravel().tolist())
#: The header's bytes (the probe's index, a zero, padding, the viewport) and an entry's.
_HEADER = struct.Struct("=2i8x4f")
_ENTRY = struct.Struct(f"={ENTRY_FLOATS}f")
_EMPTY_ENTRY = bytes(_ENTRY.size)


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
        self._gl = gl
        # Plain ctypes bindings: PyOpenGL's wrappers check and convert each argument.
        calls = raw_calls()
        self._send, self._bind_base = calls.buffer_data, calls.bind_buffer_base
        self._buffer = int(gl.glGenBuffers(1))
        self._data = bytearray()
        self._view = (ctypes.c_char * 0).from_buffer(self._data)
        self._pointer = ctypes.c_void_p(0)
        #: The entries packed last frame by light index (a light gone since is zeroed).
        self._packed: dict[int, LightEntry] = {}
        #: The probe and viewport packed last frame.
        self._header: tuple = ()
        self._sent = b""
        self.uploads = 0

    @property
    def floats(self) -> np.ndarray:
        """The block as it was last filled, as float32 (the probe's index is an int's bits)."""
        return np.frombuffer(bytes(self._data), dtype=np.float32)

    def update(
        self,
        entries: Mapping[int, LightEntry],
        probe: int = -1,
        viewport: tuple[float, float, float, float] = (0.0, 0.0, 1.0, 1.0),
    ) -> None:
        """Send this frame's block and bind it.

        The buffer holds at least 8 entries, and twice the entries asked for
        whenever more are: never fewer than any receiver's block declares.
        Only a block that differs from the last one sent is uploaded, and an
        entry handed again (the same object as last time, for the same light)
        is not packed again: an entry is not changed once handed over. A
        frame that hands every entry again, with the last probe and
        viewport, only binds the buffer.

        Parameters
        ----------
        entries : dict
            Each shadowed light's entry by its VTK light index; the entries
            of other lights are zero.
        probe : int, default: -1
            The VTK index of the light a probe frame shows, or -1.
        viewport : tuple of float, default: (0.0, 0.0, 1.0, 1.0)
            The renderer's origin and size in the window, in pixels.

        Examples
        --------
        >>> import pyvista as pv
        >>> from pvshadows.gl.frame_block import FrameBlock, LightEntry
        >>> pl = pv.Plotter(off_screen=True)
        >>> pl.ren_win.Render()
        >>> block = FrameBlock(pl.ren_win)
        >>> entry = LightEntry(0.8, light_vc=(0.0, 0.0, 1.0, 1.0))
        >>> block.update({0: entry}, probe=-1, viewport=(0, 0, 300, 200))
        >>> block.update({0: entry}, probe=-1, viewport=(0, 0, 300, 200))
        >>> block.uploads
        1
        """
        packed = self._packed
        offset, step = HEADER_FLOATS * 4, _ENTRY.size
        header = (probe, viewport)
        if header == self._header and entries.keys() == packed.keys():
            # The same lights, in a block as large as they need: only new entries are packed.
            # A loop, not all() over a generator: this runs every frame.
            data, changed = self._data, False
            for index, entry in entries.items():
                if packed[index] is not entry:
                    _ENTRY.pack_into(data, offset + index * step, *entry.floats())
                    changed = True
            if not changed:  # last frame's block, as sent: bound again only
                self._bind_base(_UNIFORM_BUFFER, BINDING, self._buffer)
                return
        else:
            data = self._fill(entries, probe, viewport)
            self._header = header
        self._packed = dict(entries)
        # Binding to the indexed point binds the buffer to GL_UNIFORM_BUFFER too, where
        # glBufferData reads it.
        self._bind_base(_UNIFORM_BUFFER, BINDING, self._buffer)
        sent = bytes(data)  # compared as bytes: a NaN parameter equals itself
        if sent != self._sent:
            self._send(_UNIFORM_BUFFER, len(data), self._pointer, _DYNAMIC_DRAW)
            self._sent = sent
            self.uploads += 1

    def _fill(
        self,
        entries: Mapping[int, LightEntry],
        probe: int,
        viewport: tuple[float, float, float, float],
    ) -> bytearray:
        """Pack the header and every entry not packed last time; zero the lights gone."""
        capacity = max(8, 2 * (max(entries, default=-1) + 1))
        size = (HEADER_FLOATS + capacity * ENTRY_FLOATS) * 4
        data, packed = self._data, self._packed
        if len(data) < size:
            data = self._data = bytearray(size)
            # Held: the bytes stay where the pointer says (a bytearray exported to ctypes
            # cannot be resized), and the pointer is read once, not a ctypes view per read.
            self._view = (ctypes.c_char * size).from_buffer(data)
            self._pointer = ctypes.c_void_p(ctypes.addressof(self._view))
            packed = {}
        _HEADER.pack_into(data, 0, probe, 0, *viewport)
        offset, step = HEADER_FLOATS * 4, _ENTRY.size
        for index in packed.keys() - entries.keys():
            data[offset + index * step : offset + (index + 1) * step] = _EMPTY_ENTRY
        for index, entry in entries.items():
            if packed.get(index) is not entry:
                _ENTRY.pack_into(data, offset + index * step, *entry.floats())
        return data

    def release(self) -> None:
        """Delete the buffer."""
        if self._buffer:
            self._gl.glDeleteBuffers(1, [self._buffer])
            self._buffer = 0
        self._header, self._sent = (), b""
