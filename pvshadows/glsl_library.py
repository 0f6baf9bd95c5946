"""Assemble the shadow-lookup functions a receiver's fragment shader needs.

Like three.js's shader chunks: each kind of map (cube, spot, sun) has a file
of primitives, and ``shadow_filters.glsl`` is instantiated once per kind with
``#define`` lines naming that kind's types and functions and selecting only
the filters its lights use.
"""

from __future__ import annotations

from collections.abc import Iterable

from pvshadows.gl.programs import glsl_source

#: Kinds of depth map and the GLSL names the filter file uses for each.
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
    },
}
#: The filters of ``shadow_filters.glsl``; "lit" (no map: only the facing and cone
#: test) serves lights whose map had nothing to draw.
FILTERS = ("lit", "hard", "pcf", "random", "pcss")


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
    >>> from pvshadows.glsl_library import filter_function
    >>> filter_function("sun", "pcf")
    'pvsSunPcf'
    """
    return f"pvs{kind.capitalize()}{filter_name.capitalize()}"


def _instance(kind: str, filters: set[str]) -> str:
    names = {k: v for k, v in KINDS[kind].items() if k != "file"}
    names.update({f"PVS_{f.upper()}": filter_function(kind, f) for f in FILTERS})
    names.update({f"PVS_WITH_{f.upper()}": "" for f in filters})
    names["PVS_BOX"] = filter_function(kind, "box")
    defines = "".join(
        f"#define {name} {value}\n".replace(" \n", "\n") for name, value in names.items()
    )
    undefines = "".join(f"#undef {name}\n" for name in names)
    return defines + glsl_source("shadow_filters.glsl") + undefines


def shadow_functions(needs: Iterable[tuple[str, str]]) -> str:
    """Return the GLSL of every lookup a set of (kind, filter) pairs needs.

    Parameters
    ----------
    needs : iterable of tuple
        ``(kind, filter)`` pairs of the lights a receiver shows.

    Returns
    -------
    str
        The common code, each kind's primitives once, and one instance of
        the filters per kind holding only the filters asked for.

    Examples
    --------
    >>> from pvshadows.glsl_library import shadow_functions
    >>> code = shadow_functions([("cube", "pcf")])
    >>> "#define PVS_WITH_PCF" in code, "#define PVS_WITH_PCSS" in code
    (True, False)
    """
    by_kind: dict[str, set[str]] = {}
    for kind, filter_name in needs:
        by_kind.setdefault(kind, set()).add(filter_name)
    if not by_kind:
        return ""
    code = [glsl_source("shadow_common.glsl")]
    for kind, filters in by_kind.items():
        code.append(glsl_source(KINDS[kind]["file"]))
        code.append(_instance(kind, filters))
    return "\n".join(code)
