"""The filters of the map-based techniques: the lookup each light asks for, and what it binds.

Cube maps and 2D maps share the filters (``glsl/shadow_filters.glsl``); this
module names one light's lookup for its kind of map and filter, and
binds the textures that call reads: the map for comparisons, a plain view of
it for PCSS's blocker search, and the jittered disk offsets.
"""

from __future__ import annotations

from pvshadows import _vtk as vtk
from pvshadows.gl.cube_array import CubeSlot
from pvshadows.gl.frame_block import LightEntry
from pvshadows.gl.sampler_units import TextureBinding
from pvshadows.gl.sampling import DiskOffsets, RawDepthView
from pvshadows.gl.textures import DepthTexture
from pvshadows.gl.transmittance_textures import TransmittanceTexture
from pvshadows.model.settings import ShadowSettings
from pvshadows.shaders.library import MapLookup
from pvshadows.shaders.shading import LightShading

#: Side of the tap grid for each ``pcf_taps`` value.
PCF_GRID = {4: 2, 16: 4, 36: 6, 64: 8}
#: Side of the box of bilinear compares the hard filter cuts at one half (its 3 x 3 texels).
HARD_BOX = 2
#: Offsets PCSS needs at least (its blocker search takes 16).
PCSS_SEARCH = 16


def lookup_shading(
    kind: str,
    vtk_index: int,
    settings: ShadowSettings,
    *,
    has_map: bool = True,
    translucent: bool = False,
    texture: str = "",
) -> LightShading:
    """Return how receivers read one light's map of a kind with its filter.

    Parameters
    ----------
    kind : {"cube", "spot", "sun"}
        The kind of map.
    vtk_index : int
        The light's index among VTK's switched-on lights.
    settings : ShadowSettings
        Its filter settings.
    has_map : bool, default: True
        ``False`` when the map had nothing to draw: the lookup is then only
        the facing and cone test.
    translucent : bool, default: False
        ``True`` when the light's translucent casters were drawn into a
        transmittance companion (``pvsTransmit{i}``): the lookup multiplies
        the filter's result by what they let through.
    texture : str, default: ""
        For maps that are layers of one texture (``kind="cubes"``), which
        texture; the random and PCSS filters add their offsets' size, so the
        lights of one group share every texture they read.

    Returns
    -------
    LightShading
        The light's :class:`~pvshadows.shaders.library.MapLookup` (it reads the
        sampler ``pvsDepth{i}`` and the light's entry of the frame's uniform
        block) and the visibility it sets.

    Examples
    --------
    >>> from pvshadows.model.settings import ShadowSettings
    >>> from pvshadows.techniques.filtering import lookup_shading
    >>> shading = lookup_shading("sun", 2, ShadowSettings(filter="pcf", pcf_taps=4))
    >>> shading.visibility, shading.needs[0].group, shading.needs[0].taps
    ('pvsMapVisibility2', 'SunPcf', 2)
    """
    if not has_map:
        lookup = MapLookup(kind, "lit", vtk_index, translucent=translucent, texture=texture)
    elif settings.filter == "pcf":
        lookup = MapLookup(
            kind, "pcf", vtk_index, PCF_GRID[settings.pcf_taps], translucent, texture
        )
    elif settings.filter in ("random", "pcss"):
        offsets = f"x{max(settings.samples, PCSS_SEARCH)}"
        lookup = MapLookup(
            kind, settings.filter, vtk_index, settings.samples, translucent, texture + offsets
        )
    else:
        lookup = MapLookup(kind, "hard", vtk_index, HARD_BOX, translucent, texture)
    return LightShading(vtk_index, lookup.visibility_name, needs=(lookup,))


class FilterBindings:
    """Names what the filters of a technique's lights read, for the receivers' units.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the textures.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._raw: RawDepthView | None = None
        self._offsets: dict[int, DiskOffsets] = {}
        #: Each light's last textures by its VTK index, with what they were named from.
        self._named: dict[int, tuple] = {}

    def _offsets_for(self, samples: int) -> DiskOffsets:
        count = max(samples, PCSS_SEARCH)
        if count not in self._offsets:
            self._offsets[count] = DiskOffsets(self._window, count)
        return self._offsets[count]

    def activate(
        self,
        vtk_index: int,
        settings: ShadowSettings,
        depth: DepthTexture | CubeSlot | None,
        entry: LightEntry,
    ) -> dict:
        """Set one light's biases and filter radius in its entry; return its map's textures.

        Parameters
        ----------
        vtk_index, settings, depth
            As for :meth:`samplers` (``settings`` gives the biases too).
        entry : LightEntry
            The light's entry of the frame's uniform block.

        Returns
        -------
        dict
            :meth:`samplers`.
        """
        entry.bias = (settings.normal_offset, settings.bias, settings.slope_bias, 0.0)
        if depth is not None and settings.filter in ("random", "pcss"):
            entry.filter_radius = float(settings.filter_radius)
        return self.samplers(vtk_index, settings, depth)

    def samplers(
        self, vtk_index: int, settings: ShadowSettings, depth: DepthTexture | CubeSlot | None
    ) -> dict:
        """Return the textures one light's map and filter read.

        Parameters
        ----------
        vtk_index : int
            The light's index among VTK's switched-on lights.
        settings : ShadowSettings
            Its filter settings.
        depth : DepthTexture, CubeSlot or None
            Its shadow map, ``None`` when it had nothing to draw.

        Returns
        -------
        dict
            The textures (:class:`~pvshadows.gl.sampler_units.TextureBinding`)
            by uniform name: ``pvsDepth{i}``, and the random and PCSS
            filters' ``pvsOffsets{i}`` and ``pvsRaw{i}``; none without a map.
            A light asking again with the same settings for the same map, whose
            texture has the same GL name, gets the same bindings (in a new dict).
        """
        if depth is None:
            return {}
        texture = depth.texture
        handle = texture.GetHandle()
        kept = self._named.get(vtk_index)
        if (
            kept is not None
            and kept[0] is depth
            and kept[1] is texture
            and kept[2] == handle
            and kept[3] == settings
        ):
            return dict(kept[4])
        uniforms = self._name(vtk_index, settings, depth)
        self._named[vtk_index] = (depth, texture, handle, settings, uniforms)
        return dict(uniforms)

    def _name(
        self, vtk_index: int, settings: ShadowSettings, depth: DepthTexture | CubeSlot
    ) -> dict[str, object]:
        i = vtk_index
        depth_name = f"pvsDepth{i}"
        uniforms: dict[str, object] = {depth_name: TextureBinding.of(depth_name, depth.texture)}
        if settings.filter in ("random", "pcss"):
            offsets = self._offsets_for(settings.samples)
            uniforms[f"pvsOffsets{i}"] = TextureBinding.of(f"pvsOffsets{i}", offsets.texture)
        if settings.filter == "pcss":
            if self._raw is None:
                self._raw = RawDepthView(self._window)
            uniforms[f"pvsRaw{i}"] = self._raw.binding(f"pvsRaw{i}", depth)
        return uniforms

    def activate_transmittance(self, vtk_index: int, companion: TransmittanceTexture) -> dict:
        """Return the uniform of one light's transmittance companion.

        Parameters
        ----------
        vtk_index : int
            The light's index among VTK's switched-on lights.
        companion : TransmittanceTexture
            The companion of its map.

        Returns
        -------
        dict
            ``{"pvsTransmit{i}": binding}``.
        """
        name = f"pvsTransmit{vtk_index}"
        return {name: TextureBinding.of(name, companion.texture)}

    def release(self) -> None:
        """Delete the offset textures and the raw sampler."""
        for offsets in self._offsets.values():
            offsets.release()
        self._offsets.clear()
        if self._raw is not None:
            self._raw.release()
            self._raw = None
        self._named.clear()
