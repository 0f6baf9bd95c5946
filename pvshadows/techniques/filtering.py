"""The filters of the map-based techniques: the lookup each light asks for, and what it binds.

Cube maps and 2D maps share the filters (``glsl/shadow_filters.glsl``); this
module writes one light's lookup call for its kind of map and filter, and
binds the textures that call reads: the map for comparisons, a plain view of
it for PCSS's blocker search, and the jittered disk offsets.
"""

from __future__ import annotations

from pvshadows import _vtk as vtk
from pvshadows.gl.sampling import DiskOffsets, RawDepthView
from pvshadows.gl.textures import DepthTexture
from pvshadows.glsl_library import KINDS, filter_function
from pvshadows.settings import ShadowSettings
from pvshadows.shading import LightShading

#: Side of the tap grid for each ``pcf_taps`` value.
PCF_GRID = {4: 2, 16: 4, 36: 6, 64: 8}
#: Offsets PCSS needs at least (its blocker search takes 16).
PCSS_SEARCH = 16

_MAP_STRUCTS = {
    "cube": "PvsCubeMap(pvsParams{i}, pvsCone{i})",
    "spot": "PvsSpotMap(pvsLightToClip{i}, pvsParams{i}, pvsCone{i})",
    "sun": "PvsSunMap(pvsParams{i})",
}


def lookup_shading(
    kind: str, vtk_index: int, settings: ShadowSettings, *, has_map: bool = True
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

    Returns
    -------
    LightShading
        The lookup call (reading the uniforms ``pvsDepth{i}``, ``pvsParams{i}``,
        ``pvsViewToLight{i}``, ``pvsBias{i}``, ...), its samplers and its needs.

    Examples
    --------
    >>> from pvshadows.settings import ShadowSettings
    >>> from pvshadows.techniques.filtering import lookup_shading
    >>> shading = lookup_shading("sun", 2, ShadowSettings(filter="pcf", pcf_taps=4))
    >>> shading.visibility.startswith("pvsSunPcf(pvsDepth2, PvsSunMap(pvsParams2)")
    True
    """
    i = vtk_index
    names = KINDS[kind]
    map_struct = _MAP_STRUCTS[kind].format(i=i)
    receiver = (
        f"pvs{kind.capitalize()}Receiver({map_struct}, pvsViewToLight{i}, pvsBias{i}.xyz, "
        "vertexVC.xyz, pvsNormalVC)"
    )
    if not has_map:
        call = f"{filter_function(kind, 'lit')}({map_struct}, {receiver})"
        return LightShading(i, call, needs=((kind, "lit"),))
    function = filter_function(kind, settings.filter)
    samplers = {f"pvsDepth{i}": names["PVS_COMPARE_MAP"]}
    if settings.filter == "hard":
        call = f"{function}(pvsDepth{i}, {map_struct}, {receiver})"
    elif settings.filter == "pcf":
        call = f"{function}(pvsDepth{i}, {map_struct}, {receiver}, {PCF_GRID[settings.pcf_taps]})"
    elif settings.filter == "random":
        samplers[f"pvsOffsets{i}"] = "sampler3D"
        call = (
            f"{function}(pvsDepth{i}, {map_struct}, {receiver}, pvsOffsets{i}, "
            f"{settings.samples}, pvsFilterRadius{i})"
        )
    else:
        samplers[f"pvsOffsets{i}"] = "sampler3D"
        samplers[f"pvsRaw{i}"] = names["PVS_RAW_MAP"]
        call = (
            f"{function}(pvsDepth{i}, pvsRaw{i}, {map_struct}, {receiver}, pvsOffsets{i}, "
            f"{settings.samples})"
        )
    return LightShading(i, call, samplers, needs=((kind, settings.filter),))


class FilterBindings:
    """Binds what the filters of a technique's lights read, and unbinds it after the frame.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the textures.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._raw: RawDepthView | None = None
        self._offsets: dict[int, DiskOffsets] = {}
        self._active: list[vtk.vtkTextureObject] = []

    def _offsets_for(self, samples: int) -> DiskOffsets:
        count = max(samples, PCSS_SEARCH)
        if count not in self._offsets:
            self._offsets[count] = DiskOffsets(self._window, count)
        return self._offsets[count]

    def _activate(self, texture: vtk.vtkTextureObject) -> int:
        if texture not in self._active:
            texture.Activate()
            self._active.append(texture)
        return int(texture.GetTextureUnit())

    def activate(
        self, vtk_index: int, settings: ShadowSettings, depth: DepthTexture | None
    ) -> dict:
        """Bind one light's map and filter textures; return their uniforms.

        Parameters
        ----------
        vtk_index : int
            The light's index among VTK's switched-on lights.
        settings : ShadowSettings
            Its filter and bias settings.
        depth : DepthTexture or None
            Its shadow map, ``None`` when it had nothing to draw.

        Returns
        -------
        dict
            Sampler units, biases and filter radius, by uniform name.
        """
        i = vtk_index
        bias = (settings.normal_offset, settings.bias, settings.slope_bias, 0.0)
        if depth is None:
            return {f"pvsBias{i}": bias}
        uniforms: dict[str, object] = {
            f"pvsDepth{i}": self._activate(depth.texture),
            f"pvsBias{i}": bias,
        }
        if settings.filter in ("random", "pcss"):
            offsets = self._offsets_for(settings.samples)
            uniforms[f"pvsOffsets{i}"] = self._activate(offsets.texture)
            uniforms[f"pvsFilterRadius{i}"] = float(settings.filter_radius)
        if settings.filter == "pcss":
            if self._raw is None:
                self._raw = RawDepthView(self._window)
            uniforms[f"pvsRaw{i}"] = self._raw.bind(depth)
        return uniforms

    def deactivate(self) -> None:
        """Free every unit bound this frame."""
        for texture in self._active:
            texture.Deactivate()
        self._active.clear()
        if self._raw is not None:
            self._raw.unbind_all()

    def release(self) -> None:
        """Delete the offset textures and the raw sampler."""
        self.deactivate()
        for offsets in self._offsets.values():
            offsets.release()
        self._offsets.clear()
        if self._raw is not None:
            self._raw.release()
            self._raw = None
