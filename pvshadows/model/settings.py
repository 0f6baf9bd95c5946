"""Per-light shadow settings and their validation.

Every public call that takes settings goes through :func:`validated`, which
raises ``ValueError`` or ``TypeError`` naming the argument, the value given
and what is allowed.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, fields, replace
from numbers import Integral, Real
from typing import Any

#: Techniques a light can be given; "auto" lets the planner choose.
TECHNIQUES = ("auto", "cubemap", "map", "volume", "planar")
#: Filters of the map-based techniques.
FILTERS = ("hard", "pcf", "random", "pcss")
#: Ways to fill a depth cube; "auto" lets the planner choose.
CUBE_PASSES = ("auto", "single", "six")
#: Allowed ``pcf_taps``: a square grid of hardware-filtered taps.
PCF_TAPS = (4, 16, 36, 64)
#: Smallest and largest ``samples`` of the random and PCSS filters (a multiple of 8).
SAMPLES_RANGE = (8, 256)
#: How shadow volumes are counted: decided per frame, or forced.
ZMODES = ("auto", "zpass", "zfail")
#: Where shadow volumes are extruded: a geometry shader, or numpy.
EXTRUDE = ("gpu", "cpu")
#: What an open caster of a shadow-volume light does.
ON_OPEN = ("fallback", "raise")
#: Points on the accuracy-cost frontier that ``enable(quality=...)`` picks.
QUALITIES = ("draft", "balanced", "exact")
#: What each quality sets, before the user's own settings: the settings ``pvshadows bench``
#: chose for each preset's promise (:mod:`pvshadows.tools.bench_presets`) on the machine
#: that set them.
QUALITY_PRESETS: dict[str, dict[str, Any]] = {
    "draft": {"resolution": 512, "filter": "hard"},
    "balanced": {"resolution": 1024, "filter": "pcf", "pcf_taps": 4},
    "exact": {"resolution": 2048, "filter": "hard"},
}
#: The settings that move a shadow-map lookup off the surface it shades.
BIASES = ("bias", "slope_bias", "normal_offset")
#: Settings only some filters read, and those filters.
FILTER_SETTINGS = {
    "pcf_taps": ("pcf",),
    "samples": ("random", "pcss"),
    "filter_radius": ("random",),
}
#: Smallest and largest shadow-map resolution (texels per side of a face).
RESOLUTION_RANGE = (64, 4096)


@dataclass(frozen=True)
class ShadowSettings:
    """How one light casts its shadows.

    Attributes
    ----------
    technique : str
        ``"auto"`` (the planner chooses), ``"cubemap"`` (point and spot
        lights), ``"map"`` (spot and directional lights), ``"volume"``
        (stencil shadow volumes, every kind of light) or ``"planar"``
        (casters flattened onto one receiving plane, every kind of light;
        objects do not shadow each other).
    quality : str
        What ``technique="auto"`` aims for: ``"draft"`` (cheapest maps,
        hard edges), ``"balanced"`` (maps with filtered edges) or
        ``"exact"`` (pixel-exact shadow volumes). See :data:`QUALITY_PRESETS`.
    resolution : int
        Texels per side of each shadow-map face, 64 to 4096.
    filter : str
        ``"hard"`` (a sharp edge between texel centres), ``"pcf"`` (percentage-closer filtering on
        a grid), ``"random"`` (jittered disk, early exit) or ``"pcss"``
        (penumbra sized by the light, contact hardening).
    pcf_taps : int
        4, 16, 36 or 64 hardware-filtered taps for ``"pcf"``.
    samples : int
        Taps of ``"random"`` and ``"pcss"``, a multiple of 8 from 8 to 256.
    filter_radius : float
        Radius of the ``"random"`` filter's disk, in texels.
    light_size : float
        Physical size of the light for ``"pcss"``: the radius of a point or
        spot light's sphere in world units, or a directional light's angular
        radius in degrees (the sun: about 0.27).
    passes : str
        ``"single"`` (one draw, geometry shader writes all six faces),
        ``"six"`` (one draw per face) or ``"auto"`` (six once the casters
        hold many triangles, see :data:`pvshadows.pipeline.cube_passes.SIX_PASSES_FROM`)
        for ``"cubemap"``.
    bias : float
        Constant depth bias, in texels (scale-free).
    slope_bias : float
        Depth bias per unit of the tangent of the angle of incidence, in
        texels.
    normal_offset : float
        Lookup point moved along the surface normal by this many texels,
        times the sine of the angle of incidence.
    cull_front : bool
        Draw closed casters into the map with their front faces culled, so
        the map holds their far sides and self-shadowing error falls on
        surfaces facing away from the light. Open casters (a ground, a sheet)
        are still drawn two-sided.
    zmode : str
        ``"volume"``: ``"auto"`` (z-pass when the camera is outside every
        shadow volume, z-fail otherwise, decided each frame), ``"zpass"`` or
        ``"zfail"`` to force one.
    extrude : str
        ``"volume"``: ``"gpu"`` (a geometry shader extrudes the silhouette)
        or ``"cpu"`` (numpy builds the volumes when the light or a caster
        moves).
    on_open : str
        ``"volume"``: what a caster that is not closed does, ``"fallback"``
        (it casts from a shadow map instead, with a warning) or ``"raise"``
        (a ``ValueError`` naming it).

    Notes
    -----
    The three biases are in texels of the shadow map at the receiver's
    distance, so the same values work at every scene scale and resolution.
    Every compare reads one texel at its centre against the receiver's
    tangent plane along the ray through that centre, so a flat receiver
    meets the very depth it wrote and needs no offset at any incidence: the
    small default depth bias only covers rounding. A normal offset moves
    every shadow edge towards the light by up to that many texels (shadows
    shrink), so it is 0 by default. With all three at 0 the compare has no
    margin for rounding and lit surfaces may shadow themselves in speckles
    (acne); :func:`validated` warns.
    """

    technique: str = "auto"
    quality: str = "balanced"
    resolution: int = 1024
    filter: str = "pcf"
    pcf_taps: int = 4
    samples: int = 32
    filter_radius: float = 2.0
    light_size: float = 0.0
    passes: str = "auto"
    bias: float = 0.2
    slope_bias: float = 0.1
    normal_offset: float = 0.0
    cull_front: bool = False
    zmode: str = "auto"
    extrude: str = "gpu"
    on_open: str = "fallback"
    strength: float = 1.0


def _choice(name: str, value: object, allowed: tuple) -> object:
    kind = str if isinstance(allowed[0], str) else Integral
    if not isinstance(value, kind) or isinstance(value, bool) or value not in allowed:
        msg = f"{name}={value!r} is not allowed; choose one of {', '.join(map(repr, allowed))}"
        right_type = isinstance(value, kind) and not isinstance(value, bool)
        raise (ValueError if right_type else TypeError)(msg)
    return value


def _resolution(value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, Integral):
        low, high = RESOLUTION_RANGE
        msg = f"resolution must be an int from {low} to {high}, got {value!r}"
        raise TypeError(msg)
    low, high = RESOLUTION_RANGE
    if not low <= int(value) <= high:
        msg = f"resolution={value} is out of range; it must be from {low} to {high} texels"
        raise ValueError(msg)
    return int(value)


def _samples(value: object) -> int:
    low, high = SAMPLES_RANGE
    if isinstance(value, bool) or not isinstance(value, Integral):
        msg = f"samples must be an int, a multiple of 8 from {low} to {high}, got {value!r}"
        raise TypeError(msg)
    if not low <= int(value) <= high or int(value) % 8:
        msg = f"samples={value} is not allowed; it must be a multiple of 8 from {low} to {high}"
        raise ValueError(msg)
    return int(value)


def _light_size(value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        msg = f"light_size must be a number (0 for a point-like light), got {value!r}"
        raise TypeError(msg)
    number = float(value)
    if not (math.isfinite(number) and number >= 0.0):
        msg = f"light_size={value} is not allowed; it must be a finite number >= 0"
        raise ValueError(msg)
    return float(value)


def _strength(value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        msg = f"strength must be a number from 0 (no shadow) to 1 (full shadow), got {value!r}"
        raise TypeError(msg)
    number = float(value)
    if not (math.isfinite(number) and 0.0 <= number <= 1.0):
        msg = f"strength={value} is out of range; it must be from 0 (no shadow) to 1 (full shadow)"
        raise ValueError(msg)
    return float(value)


def _flag(name: str, value: object) -> bool:
    if not isinstance(value, bool):
        msg = f"{name} must be True or False, got {value!r}"
        raise TypeError(msg)
    return value


def _texels(name: str, value: object) -> float:
    if isinstance(value, bool) or not isinstance(value, Real):
        msg = f"{name} must be a number of texels (a float from 0 to 100), got {value!r}"
        raise TypeError(msg)
    number = float(value)
    if not (math.isfinite(number) and 0.0 <= number <= 100.0):
        msg = f"{name}={value} is out of range; it must be from 0 to 100 texels"
        raise ValueError(msg)
    return float(value)


_CHECKS = {
    "technique": lambda v: _choice("technique", v, TECHNIQUES),
    "quality": lambda v: _choice("quality", v, QUALITIES),
    "resolution": _resolution,
    "filter": lambda v: _choice("filter", v, FILTERS),
    "pcf_taps": lambda v: _choice("pcf_taps", v, PCF_TAPS),
    "samples": _samples,
    "filter_radius": lambda v: _texels("filter_radius", v),
    "light_size": _light_size,
    "passes": lambda v: _choice("passes", v, CUBE_PASSES),
    "bias": lambda v: _texels("bias", v),
    "slope_bias": lambda v: _texels("slope_bias", v),
    "normal_offset": lambda v: _texels("normal_offset", v),
    "cull_front": lambda v: _flag("cull_front", v),
    "zmode": lambda v: _choice("zmode", v, ZMODES),
    "extrude": lambda v: _choice("extrude", v, EXTRUDE),
    "on_open": lambda v: _choice("on_open", v, ON_OPEN),
    "strength": _strength,
}


def _warn_unused(changes: dict[str, object], filter_name: str) -> None:
    for name, users in FILTER_SETTINGS.items():
        if name in changes and filter_name not in users:
            wanted = " or ".join(f"filter={user!r}" for user in users)
            msg = (
                f"{name}={changes[name]!r} has no effect with filter={filter_name!r}; "
                f"only {wanted} uses it"
            )
            warnings.warn(msg, UserWarning, stacklevel=4)


def preset(quality: str) -> ShadowSettings:
    """Return the settings a quality preset stands for.

    Parameters
    ----------
    quality : {"draft", "balanced", "exact"}
        The preset.

    Returns
    -------
    ShadowSettings
        Default settings with the preset's values.

    Raises
    ------
    ValueError
        For an unknown quality.

    Examples
    --------
    >>> from pvshadows.model.settings import preset
    >>> preset("draft").resolution, preset("draft").filter
    (512, 'hard')
    """
    _choice("quality", quality, QUALITIES)
    return replace(ShadowSettings(), quality=quality, **QUALITY_PRESETS[quality])


def validated(base: ShadowSettings, **changes: object) -> ShadowSettings:
    """Return ``base`` with ``changes`` applied, after checking every value.

    Parameters
    ----------
    base : ShadowSettings
        Settings to start from.
    **changes
        Setting names and new values.

    Returns
    -------
    ShadowSettings
        The new settings.

    Raises
    ------
    TypeError
        For an unknown setting name or a value of the wrong type.
    ValueError
        For a value out of range or not among the allowed choices.

    Warns
    -----
    UserWarning
        For ``pcf_taps``, ``samples`` or ``filter_radius`` given with a
        filter that does not read it (see :data:`FILTER_SETTINGS`).

    Examples
    --------
    >>> from pvshadows.model.settings import ShadowSettings, validated
    >>> validated(ShadowSettings(), filter="hard").filter
    'hard'
    >>> validated(ShadowSettings(), resolution=5000)
    Traceback (most recent call last):
    ...
    ValueError: resolution=5000 is out of range; it must be from 64 to 4096 texels
    """
    known = {f.name for f in fields(ShadowSettings)}
    unknown = sorted(set(changes) - known)
    if unknown:
        msg = (
            f"unknown shadow setting(s) {', '.join(unknown)}; "
            f"the settings are {', '.join(sorted(known))}"
        )
        raise TypeError(msg)
    checked: dict[str, Any] = {name: _CHECKS[name](value) for name, value in changes.items()}
    result = replace(base, **checked)
    if set(changes) & set(BIASES) and not any(getattr(result, name) for name in BIASES):
        warnings.warn(
            "bias, slope_bias and normal_offset are all 0: shadow maps compare each lit "
            "surface with its own depth, so much of it shadows itself in speckles (acne); "
            "shadow volumes and planar shadows do not use the biases",
            stacklevel=3,
        )
    _warn_unused(checked, result.filter)
    if result.filter == "pcss" and result.light_size <= 0.0:
        msg = (
            "filter='pcss' sizes penumbrae by the light's physical size: give light_size > 0 "
            "(a point or spot light's radius in world units, a directional light's angular "
            "radius in degrees)"
        )
        raise ValueError(msg)
    return result
