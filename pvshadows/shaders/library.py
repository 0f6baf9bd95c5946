"""Assemble the shadow-lookup functions a receiver's fragment shader needs.

Like three.js's shader chunks: each kind of map (cube, spot, sun) has a file
of primitives, and ``shadow_filters.glsl`` is instantiated once per kind with
``#define`` lines naming that kind's types and functions and selecting only
the filters its lights use.

The lights that read one kind of map with one filter form a *group*:
``shadow_group.glsl`` looks them up from the group's uniform arrays, each
filter's taps a loop over a uniform count (not a constant the driver
unrolls), so the shader grows by one small lookup per light, not by lights
times taps: with constant tap counts, 16 lights with 16-tap PCF took minutes
to compile on llvmpipe, and 32 never finished. The cubes of point lights, as
layers of one cube map array (kind ``"cubes"``), are one loop per group over
one sampler: the filter is compiled once however many lights there are.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from dataclasses import dataclass

from pvshadows.gl.programs import glsl_source

#: Kinds of depth map and the GLSL names the filter file uses for each. "cubes"
#: are the cubes of several lights as layers of one cube map array, looked up in
#: one loop (:data:`LOOPED`).
KINDS = {
    "cube": {
        "file": "shadow_cube.glsl",
        "PVS_MAP": "PvsCubeMap",
        "PVS_COMPARE_MAP": "samplerCubeShadow",
        "PVS_RAW_MAP": "samplerCube",
        "PVS_FRAME": "pvsCubeFrame",
        "PVS_TAP": "pvsCubeTap",
        "PVS_TEXEL": "pvsCubeTexel",
        "PVS_TEXEL_DEPTH": "pvsCubeTexelDepth",
        "PVS_SEARCH_RADIUS": "pvsCubeSearchRadius",
        "PVS_PENUMBRA_RADIUS": "pvsCubePenumbraRadius",
        "PVS_TRANSMIT_MAP": "samplerCube",
        "PVS_FRAME_OF_SIZE": "pvsCubeFrameOfSize",
        "PVS_TEXEL_TRANSMITTED": "pvsCubeTransmitted",
    },
    "cubes": {
        "file": "shadow_cube_array.glsl",
        "PVS_MAP": "PvsCubesMap",
        "PVS_COMPARE_MAP": "samplerCubeArrayShadow",
        "PVS_RAW_MAP": "samplerCubeArray",
        "PVS_FRAME": "pvsCubesFrame",
        "PVS_TAP": "pvsCubesTap",
        "PVS_TEXEL": "pvsCubesTexel",
        "PVS_TEXEL_DEPTH": "pvsCubesTexelDepth",
        "PVS_SEARCH_RADIUS": "pvsCubesSearchRadius",
        "PVS_PENUMBRA_RADIUS": "pvsCubesPenumbraRadius",
    },
    "spot": {
        "file": "shadow_spot.glsl",
        "PVS_MAP": "PvsSpotMap",
        "PVS_COMPARE_MAP": "sampler2DShadow",
        "PVS_RAW_MAP": "sampler2D",
        "PVS_FRAME": "pvsSpotFrame",
        "PVS_TAP": "pvsSpotTap",
        "PVS_TEXEL": "pvsSpotTexel",
        "PVS_TEXEL_DEPTH": "pvsSpotTexelDepth",
        "PVS_SEARCH_RADIUS": "pvsSpotSearchRadius",
        "PVS_PENUMBRA_RADIUS": "pvsSpotPenumbraRadius",
        "PVS_TRANSMIT_MAP": "sampler2D",
        "PVS_FRAME_OF_SIZE": "pvsSpotFrameOfSize",
        "PVS_TEXEL_TRANSMITTED": "pvsSpotTransmitted",
    },
    "sun": {
        "file": "shadow_sun.glsl",
        "PVS_MAP": "PvsSunMap",
        "PVS_COMPARE_MAP": "sampler2DShadow",
        "PVS_RAW_MAP": "sampler2D",
        "PVS_FRAME": "pvsSunFrame",
        "PVS_TAP": "pvsSunTap",
        "PVS_TEXEL": "pvsSunTexel",
        "PVS_TEXEL_DEPTH": "pvsSunTexelDepth",
        "PVS_SEARCH_RADIUS": "pvsSunSearchRadius",
        "PVS_PENUMBRA_RADIUS": "pvsSunPenumbraRadius",
        "PVS_TRANSMIT_MAP": "sampler2D",
        "PVS_FRAME_OF_SIZE": "pvsSunFrameOfSize",
        "PVS_TEXEL_TRANSMITTED": "pvsSunTransmitted",
    },
}
#: Kinds whose lights are layers of one texture, looked up in one loop with one
#: sampler per group, and the files each needs before its own.
LOOPED = {"cubes": ("shadow_cube.glsl",)}
#: The GLSL extension a looped kind needs in a GLSL 1.50 shader.
EXTENSIONS = {"cubes": "GL_ARB_texture_cube_map_array"}
#: The filters of ``shadow_filters.glsl``; "lit" (no map: only the facing and cone
#: test) serves lights whose map had nothing to draw.
FILTERS = ("lit", "hard", "pcf", "random", "pcss")
#: The sampler arrays each filter reads, and the per-light uniform that gives
#: each light's texture unit.
GROUP_SAMPLERS = {
    "lit": (),
    "hard": ("Depth",),
    "pcf": ("Depth",),
    "random": ("Depth", "Offsets"),
    "pcss": ("Depth", "Raw", "Offsets"),
}
#: The sampler array a group of lights with translucent casters reads besides its
#: filter's: each light's transmittance companion.
TRANSMIT_SAMPLER = "Transmit"
#: Samplers of one texture for the whole group, not an array: the disk offsets, made
#: per sample count, which is part of the group's name (:attr:`MapLookup.texture`).
GROUP_SHARED = ("Offsets",)


@dataclass(frozen=True)
class MapLookup:
    """One light's read of its shadow map, looked up with the other lights of its group.

    The light's sampler units (``pvsDepth{i}``, ``pvsTransmit{i}``,
    ``pvsOffsets{i}``, ``pvsRaw{i}``) are packed into the group's arrays by
    :func:`group_uniforms`; what its pose, fit, settings and the camera
    decide (its view-to-light matrix, parameters, biases, cone, projection,
    filter radius and layer) goes to its entry of the frame's uniform block
    (:class:`pvshadows.gl.frame_block.LightEntry`, which the light's
    technique fills, and :class:`pvshadows.gl.frame_block.FrameBlock`),
    so that moving a light or the camera sends nothing to receivers; its
    visibility is the GLSL float :attr:`visibility_name`.

    Attributes
    ----------
    kind : {"cube", "spot", "sun"}
        The kind of map.
    filter : {"lit", "hard", "pcf", "random", "pcss"}
        The filter.
    vtk_index : int
        The light's index among VTK's switched-on lights.
    taps : int
        PCF's grid side, or the samples of the random and PCSS filters (0
        for the others).
    translucent : bool
        The light's casters include translucent ones: the filter's result
        is multiplied by what they let through, read from the light's
        transmittance companion (``pvsTransmit{i}``). Not for a looped kind.
    texture : str
        For a looped kind, which texture holds the light's map (the lights of
        a group share it), for example ``"1024"`` for the cube array of
        1024-texel cubes; its layer is the uniform ``pvsLayer{i}``. For the
        random and PCSS filters, then the disk offsets' sample count, for
        example ``"x32"``: a group reads one offset texture.
    """

    kind: str
    filter: str
    vtk_index: int
    taps: int = 0
    translucent: bool = False
    texture: str = ""

    @property
    def group(self) -> str:
        """Name of the light's group, e.g. ``"SpotHardTranslucent"`` or ``"CubesPcf1024"``."""
        return (
            filter_function(self.kind, self.filter)[3:]
            + ("Translucent" if self.translucent else "")
            + self.texture
        )

    @property
    def samplers(self) -> tuple[str, ...]:
        """The parts of the sampler arrays the light's group reads, for example ``("Depth",)``."""
        own = GROUP_SAMPLERS[self.filter]
        return (*own, TRANSMIT_SAMPLER) if self.translucent else own

    @property
    def visibility_name(self) -> str:
        """Name of the global float that holds the light's visibility once looked up."""
        return f"pvsMapVisibility{self.vtk_index}"


def filter_function(kind: str, filter_name: str) -> str:
    """Return the GLSL name of a filter compiled for a kind of map.

    Parameters
    ----------
    kind : {"cube", "spot", "sun"}
        The kind of map.
    filter_name : {"hard", "pcf", "random", "pcss"}
        The filter.

    Returns
    -------
    str
        For example ``"pvsCubePcss"``.

    Examples
    --------
    >>> from pvshadows.shaders.library import filter_function
    >>> filter_function("sun", "pcf")
    'pvsSunPcf'
    """
    return f"pvs{kind.capitalize()}{filter_name.capitalize()}"


def _groups(lookups: Iterable[MapLookup]) -> dict[str, list[MapLookup]]:
    """Group lookups by kind and filter, each group's lights in VTK's order."""
    groups: dict[str, list[MapLookup]] = {}
    for lookup in sorted(set(lookups), key=lambda item: (item.vtk_index, item.group)):
        groups.setdefault(lookup.group, []).append(lookup)
    return groups


def _defines(names: Mapping[str, str]) -> tuple[str, str]:
    defines = "".join(f"#define {name} {value}".rstrip() + "\n" for name, value in names.items())
    return defines, "".join(f"#undef {name.partition('(')[0]}\n" for name in names)


def _group_instance(group: str, lookups: list[MapLookup]) -> str:
    first = lookups[0]
    uniform = f"pvs{group}"
    indices = ", ".join(str(lookup.vtk_index) for lookup in lookups)
    count = len(lookups)
    # Which lights a group holds is part of the receiver's source (each has its own
    # visibility global), so their indices are constants, not uniforms VTK sets at
    # every draw.
    table = f"const int {uniform}Light[{count}] = int[{count}]({indices});\n"
    names = {
        f"PVS_GROUP_{first.kind.upper()}": "",
        f"PVS_GROUP_{first.filter.upper()}": "",
        "PVS_GROUP_SIZE": str(len(lookups)),
        "PVS_GROUP_LOOKUP": f"{uniform}Lookup",
        "PVS_GROUP_RECEIVER": f"pvs{first.kind.capitalize()}Receiver",
        "PVS_GROUP_INDEX": f"{uniform}Light",
        "PVS_GROUP_DEPTH": f"{uniform}Depth",
        "PVS_GROUP_RAW": f"{uniform}Raw",
        "PVS_GROUP_OFFSETS": f"{uniform}Offsets",
    }
    if first.translucent:
        names["PVS_GROUP_TRANSLUCENT"] = ""
        names["PVS_GROUP_TRANSMIT"] = f"{uniform}{TRANSMIT_SAMPLER}"
    if first.kind in LOOPED:
        names["PVS_GROUP_LOOP"] = ""
        # a count the compiler cannot fold keeps the loop a loop (see shadow_group.glsl)
        names["PVS_GROUP_COUNT"] = f"({count} + pvsLoopZero)"
    each = " ".join(f"EACH({j}, {lookup.visibility_name})" for j, lookup in enumerate(lookups))
    names["PVS_GROUP_ALL(EACH)"] = each
    defines, undefines = _defines(names)
    return table + defines + glsl_source("shadow_group.glsl") + undefines


def _kind_instance(kind: str, groups: dict[str, list[MapLookup]]) -> str:
    # hard is PCF's box of 2 x 2 compares cut at one half (shadow_group.glsl)
    filters = {lookups[0].filter.replace("hard", "pcf") for lookups in groups.values()}
    names = {k: v for k, v in KINDS[kind].items() if k != "file"}
    names.update({f"PVS_{f.upper()}": filter_function(kind, f) for f in FILTERS})
    names.update({f"PVS_WITH_{f.upper()}": "" for f in filters})
    names["PVS_BOX"] = filter_function(kind, "box")
    names["PVS_TRANSMIT"] = filter_function(kind, "transmit")
    if any(lookups[0].translucent for lookups in groups.values()):
        names["PVS_WITH_TRANSMIT"] = ""
    defines, undefines = _defines(names)
    code = [defines, glsl_source("shadow_filters.glsl")]
    code.extend(_group_instance(group, lookups) for group, lookups in groups.items())
    code.append(undefines)
    return "".join(code)


def _gather(lookups: Iterable[MapLookup]) -> str:
    """Return ``pvsLookupMaps``: it looks up every group, each setting its lights' visibilities."""
    calls = " ".join(f"EACH(pvs{group}Lookup)" for group in _groups(lookups))
    defines, undefines = _defines({"PVS_LOOKUP_GROUPS(EACH)": calls})
    return defines + glsl_source("lookup_maps.glsl") + undefines


def frame_block_source(lights: int) -> str:
    """Return the declaration of the frame's uniform block (``glsl/frame_block.glsl``).

    Parameters
    ----------
    lights : int
        How many of VTK's lights the shader reads: its highest light index + 1
        (at least 1).

    Returns
    -------
    str
        GLSL declaring ``pvsProbeLight``, ``pvsViewport`` and ``pvsLights``.

    Examples
    --------
    >>> from pvshadows.shaders.library import frame_block_source
    >>> "#define PVS_FRAME_LIGHTS 3" in frame_block_source(3)
    True
    """
    block, unblock = _defines({"PVS_FRAME_LIGHTS": str(max(lights, 1))})
    return block + glsl_source("frame_block.glsl") + unblock


def shadow_functions(lookups: Iterable[MapLookup]) -> str:
    """Return the GLSL of every lookup a receiver's lights need.

    The code reads the frame's uniform block, which the receiver declares
    before it (:func:`frame_block_source`).

    Parameters
    ----------
    lookups : iterable of MapLookup
        The map lookups of the lights a receiver shows.

    Returns
    -------
    str
        The common code, each kind's primitives once, one instance of the
        filters per kind holding only the filters asked for, one lookup
        function per group, and ``pvsLookupMaps(posVC, normalVC)``, which looks every
        light up and sets its :attr:`MapLookup.visibility_name`.

    Examples
    --------
    >>> from pvshadows.shaders.library import MapLookup, shadow_functions
    >>> code = shadow_functions([MapLookup("cube", "pcf", 0, 4), MapLookup("cube", "pcf", 3, 2)])
    >>> "#define PVS_WITH_PCF" in code, "#define PVS_WITH_PCSS" in code
    (True, False)
    >>> code.count("#define PVS_GROUP_LOOKUP pvsCubePcfLookup")  # one lookup function for both
    1
    """
    groups = _groups(lookups)
    if not groups:
        return ""
    by_kind: dict[str, dict[str, list[MapLookup]]] = {}
    for group, members in groups.items():
        by_kind.setdefault(members[0].kind, {})[group] = members
    files = [glsl_source("shadow_common.glsl")]
    for kind in by_kind:
        files.extend(glsl_source(name) for name in (*LOOPED.get(kind, ()), KINDS[kind]["file"]))
    code = list(dict.fromkeys(files))
    code.extend(_kind_instance(kind, kind_groups) for kind, kind_groups in by_kind.items())
    code.append(_gather(lookup for members in groups.values() for lookup in members))
    return "\n".join(code)


def group_samplers(lookups: Iterable[MapLookup]) -> dict[str, tuple[str, int | None]]:
    """Return the sampler arrays of the groups: name to (GLSL sampler type, length).

    Parameters
    ----------
    lookups : iterable of MapLookup
        The map lookups of a receiver's lights.

    Returns
    -------
    dict
        For example ``{"pvsCubePcfDepth": ("samplerCubeShadow", 2)}``; the
        length is ``None`` for a looped kind's one sampler.

    Examples
    --------
    >>> from pvshadows.shaders.library import MapLookup, group_samplers
    >>> group_samplers([MapLookup("sun", "pcss", 1, 16)])["pvsSunPcssRaw"]
    ('sampler2D', 1)
    >>> group_samplers([MapLookup("cube", "hard", 0, 2, translucent=True)])
    {'pvsCubeHardTranslucentDepth': ('samplerCubeShadow', 1), \
'pvsCubeHardTranslucentTransmit': ('samplerCube', 1)}
    """
    samplers: dict[str, tuple[str, int | None]] = {}
    for group, members in _groups(lookups).items():
        kind = members[0].kind
        types = {
            "Depth": KINDS[kind]["PVS_COMPARE_MAP"],
            "Raw": KINDS[kind]["PVS_RAW_MAP"],
            "Offsets": "sampler3D",
            TRANSMIT_SAMPLER: KINDS[kind].get("PVS_TRANSMIT_MAP", ""),
        }
        length = None if kind in LOOPED else len(members)
        for part in members[0].samplers:
            samplers[f"pvs{group}{part}"] = (types[part], None if part in GROUP_SHARED else length)
    return samplers


def extensions(lookups: Iterable[MapLookup]) -> list[str]:
    """Return the GLSL extensions the lookups need in a GLSL 1.50 shader.

    Parameters
    ----------
    lookups : iterable of MapLookup
        The map lookups of a receiver's lights.

    Returns
    -------
    list of str
        For example ``["GL_ARB_texture_cube_map_array"]`` for cube arrays.

    Examples
    --------
    >>> from pvshadows.shaders.library import MapLookup, extensions
    >>> extensions([MapLookup("cubes", "pcf", 0, 2, "1024"), MapLookup("sun", "hard", 1)])
    ['GL_ARB_texture_cube_map_array']
    """
    return list(dict.fromkeys(EXTENSIONS[m.kind] for m in lookups if m.kind in EXTENSIONS))


#: Prefixes of each light's own uniforms, which :func:`group_uniforms` packs.
OWN_UNIFORMS = ("pvsDepth", "pvsTransmit", "pvsRaw", "pvsOffsets")


def group_uniforms(
    lookups: Iterable[MapLookup], uniforms: Mapping[str, object]
) -> dict[str, object]:
    """Pack the lights' own uniforms into their groups' arrays.

    Parameters
    ----------
    lookups : iterable of MapLookup
        The map lookups of a receiver's lights.
    uniforms : Mapping
        Every light's textures by name, as the techniques return them
        (``pvsDepth{i}`` and so on, see :class:`MapLookup`).

    Returns
    -------
    dict
        ``uniforms`` without those lights' own uniforms, with each group's
        arrays: a ``list`` of the members' values for each sampler (a looped
        group's one texture: its first member's value).

    Examples
    --------
    >>> from pvshadows.shaders.library import MapLookup, group_uniforms
    >>> own = {"pvsDepth2": 5, "pvsMask0": 3}
    >>> group_uniforms([MapLookup("sun", "hard", 2)], own)
    {'pvsMask0': 3, 'pvsSunHardDepth': [5]}
    """
    groups = _groups(lookups)
    taken = {f"{name}{m.vtk_index}" for ms in groups.values() for m in ms for name in OWN_UNIFORMS}
    packed: dict[str, object] = {k: v for k, v in uniforms.items() if k not in taken}
    for group, members in groups.items():
        name = f"pvs{group}"
        values = {
            part: [uniforms[f"pvs{part}{m.vtk_index}"] for m in members]
            for part in members[0].samplers
        }
        for part, value in values.items():
            # one texture for the whole group: every member names the same one
            shared = members[0].kind in LOOPED or part in GROUP_SHARED
            packed[f"{name}{part}"] = value[0] if shared else value
    return packed
