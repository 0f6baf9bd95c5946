"""What the soft-shadow filters sample with: raw depth views and jittered disk offsets."""

from __future__ import annotations

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.cube_array import CubeSlot
from pvshadows.gl.sampler_units import TextureBinding
from pvshadows.gl.textures import DepthTexture

#: Pixels per side of the tile of per-pixel offset patterns.
OFFSET_TILE = 32


class RawDepthView:
    """Reads a depth map a second time, without comparison, for plain depths.

    PCSS needs both: comparisons for its filter and plain depths for its
    blocker search. A sampler object on a second texture unit overrides the
    texture's compare mode there, and is unbound from it before the unit
    goes back to VTK (:meth:`pvshadows.gl.sampler_units.SamplerUnits.end_frame`),
    so no VTK texture ever samples through it.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the sampler.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._gl = gl = opengl_for(window)
        self._sampler = int(np.asarray(gl.glGenSamplers(1)).ravel()[0])
        for name, value in (
            (gl.GL_TEXTURE_MIN_FILTER, gl.GL_NEAREST),
            (gl.GL_TEXTURE_MAG_FILTER, gl.GL_NEAREST),
            (gl.GL_TEXTURE_COMPARE_MODE, gl.GL_NONE),
            (gl.GL_TEXTURE_WRAP_S, gl.GL_CLAMP_TO_EDGE),
            (gl.GL_TEXTURE_WRAP_T, gl.GL_CLAMP_TO_EDGE),
            (gl.GL_TEXTURE_WRAP_R, gl.GL_CLAMP_TO_EDGE),
        ):
            gl.glSamplerParameteri(self._sampler, name, value)

    def binding(self, source: str, depth: DepthTexture | CubeSlot) -> TextureBinding:
        """Return ``depth`` read through the raw sampler.

        Parameters
        ----------
        source : str
            The light's uniform that names it, for example ``"pvsRaw0"``.
        depth : DepthTexture or CubeSlot
            The shadow map.

        Returns
        -------
        TextureBinding
            The map's target and handle, with this view's sampler object.
        """
        return TextureBinding(source, depth.target, depth.handle, self._sampler)

    def release(self) -> None:
        """Delete the sampler object (GL unbinds it from every unit)."""
        if self._sampler:
            self._gl.glDeleteSamplers(1, [self._sampler])
            self._sampler = 0


def disk_offsets(samples: int, seed: int = 0, tile: int = OFFSET_TILE) -> np.ndarray:
    """Return jittered offsets on the unit disk, a different jitter for each pixel of a tile.

    The disk is cut into ``samples // 8`` rings of 8 sectors, each sample
    jittered inside its cell (equal areas), outer ring first: the first eight
    samples go round the rim, which is what the early exit tests.

    Parameters
    ----------
    samples : int
        Samples per pixel, a multiple of 8.
    seed : int, default: 0
        Seed of the jitter.
    tile : int, default: OFFSET_TILE
        Pixels per side of the tile.

    Returns
    -------
    numpy.ndarray
        float32 ``(samples // 2, tile, tile, 4)``: for each pair of samples,
        each pixel's two offsets as ``(x0, y0, x1, y1)`` (the layout of a 3D
        RGBA texture indexed by pixel and sample pair).

    Examples
    --------
    >>> import numpy as np
    >>> from pvshadows.gl.sampling import disk_offsets
    >>> offsets = disk_offsets(16, tile=4)
    >>> offsets.shape
    (8, 4, 4, 4)
    >>> bool(np.all(np.hypot(offsets[..., 0], offsets[..., 1]) <= 1.0))
    True
    """
    rng = np.random.default_rng(seed)
    rings = samples // 8
    ring = np.repeat(np.arange(rings), 8)
    sector = np.tile(np.arange(8), rings)
    jitter = rng.random((tile, tile, samples, 2))
    radius = np.sqrt((rings - ring - 1 + jitter[..., 0]) / rings)
    angle = 2.0 * np.pi * (sector + jitter[..., 1]) / 8.0
    points = np.stack([radius * np.cos(angle), radius * np.sin(angle)], axis=-1)
    pairs = points.reshape(tile, tile, samples // 2, 4)
    return np.ascontiguousarray(pairs.transpose(2, 0, 1, 3), dtype=np.float32)


class DiskOffsets:
    """3D texture of per-pixel jittered disk offsets (the offset texture of the seed).

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the texture.
    samples : int
        Samples per pixel, a multiple of 8.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, samples: int) -> None:
        self.samples = samples
        data = disk_offsets(samples)
        self.texture = vtk.vtkTextureObject()
        self.texture.SetContext(window)
        self.texture.Create3DFromRaw(OFFSET_TILE, OFFSET_TILE, samples // 2, 4, vtk.VTK_FLOAT, data)
        self.texture.SetMinificationFilter(vtk.vtkTextureObject.Nearest)
        self.texture.SetMagnificationFilter(vtk.vtkTextureObject.Nearest)
        self._window = window

    def release(self) -> None:
        """Delete the texture."""
        self.texture.ReleaseGraphicsResources(self._window)
