"""Receivers read the shadow maps in the shaders VTK already builds for them.

Only the lighting code of each receiver's fragment shader changes: for every
shadowed light, the light's diffuse and specular terms (Phong) or its
radiance (PBR) are multiplied by ``1 - strength * (1 - visibility)``: the
light's visibility, softened by its shadow ``strength`` (read from the
frame's uniform block, so changing it recompiles nothing). Ambient light and
unshadowed lights are untouched. The edits are ``vtkShaderProperty``
replacements applied after VTK's own substitutions. What they read is the
frame's uniform block (``glsl/frame_block.glsl``: every light's matrices,
parameters and strength, the probe's light, the viewport), uploaded once per
frame, and the samplers, on texture units reserved for them
(:class:`~pvshadows.gl.sampler_units.SamplerUnits`); so a receiver needs no
observer on its mapper and works from its first frame.

Where the context allows, each sampler is declared here with its unit
(``layout(binding = N)``) and the receiver has no custom uniform at all.
Elsewhere VTK declares each sampler as a ``uniform int NAME;`` custom
uniform (its unit), retyped here to the sampler type the lookup needs.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.geometry.transforms import column_major
from pvshadows.gl.programs import glsl_source
from pvshadows.gl.sampler_units import BINDING_EXTENSION
from pvshadows.shaders.landing import LandingCheck
from pvshadows.shaders.landing_views import Watchers
from pvshadows.shaders.library import (
    MapLookup,
    extensions,
    frame_block_source,
    group_samplers,
    group_uniforms,
    shadow_functions,
)

_MAIN = "void main()"
_VIEW_POSITION = "vec4 vertexVC = vertexVCVSOutput;"
_PROBE_ANCHOR = "//VTK::Picking::Impl"
#: Where GLSL extension directives go: before any code (VTK puts ``#version`` there).
_SYSTEM = "//VTK::System::Dec"
_FACET_NORMAL = "\n  pvsFacetVC = pvsFacetNormal(vertexVC.xyz);"


@dataclass(frozen=True)
class LightShading:
    """How one shadowed light edits a receiver's fragment shader.

    Attributes
    ----------
    vtk_index : int
        The light's index among the renderer's switched-on lights: VTK names
        its uniforms ``lightColor{vtk_index}`` and so on.
    visibility : str
        GLSL expression for the light's visibility; it may use
        ``vertexVC.xyz`` and ``pvsNormalVC`` (geometric normal facing the
        camera).
    samplers : Mapping[str, str]
        Uniform name to sampler type, for each texture the expression reads.
    needs : tuple of MapLookup
        The shadow-map lookups whose visibilities the expression reads
        (see :mod:`pvshadows.shaders.library`).
    sources : tuple of str
        Other files of ``glsl/`` that define functions the expression calls.
    defines : tuple of str
        Macros those files need.
    only_on : frozenset of str or None
        Keys (:func:`pvshadows.scene.triangles.vtk_id`) of the only receivers that read
        the light this way; ``None``: every receiver does.
    elsewhere : LightShading or None
        How the other receivers read the light (``None``: fully lit).
    """

    vtk_index: int
    visibility: str
    samplers: Mapping[str, str] = field(default_factory=dict)
    needs: tuple[MapLookup, ...] = ()
    sources: tuple[str, ...] = ()
    defines: tuple[str, ...] = ()
    only_on: frozenset[str] | None = None
    elsewhere: LightShading | None = None

    def for_actor(self, key: str) -> LightShading:
        """Return how the receiver ``key`` reads the light.

        Parameters
        ----------
        key : str
            The receiver's :func:`pvshadows.scene.triangles.vtk_id`.

        Returns
        -------
        LightShading
            This shading, or :attr:`elsewhere` (fully lit when ``None``) for
            a receiver outside :attr:`only_on`.

        Examples
        --------
        >>> from pvshadows.shaders.shading import LightShading
        >>> plane_only = LightShading(0, "mask()", only_on=frozenset({"ground"}))
        >>> plane_only.for_actor("ground").visibility, plane_only.for_actor("box").visibility
        ('mask()', '1.0')
        """
        if self.only_on is None or key in self.only_on:
            return self
        return self.elsewhere or LightShading(self.vtk_index, "1.0")


def _probe_output(colour: str) -> str:
    return f"if (pvsProbeLight >= 0) {{ fragOutput0 = {colour}; }}\n  {_PROBE_ANCHOR}"


def _uses_pbr(actor: vtk.vtkActor) -> bool:
    return actor.GetProperty().GetInterpolation() == vtk.VTK_PBR


def _normal_expression(actor: vtk.vtkActor, triangles: bool) -> str:
    """Return the GLSL normal that a receiver's lookups offset along and test facing with.

    A triangle's own facet normal (screen-space derivatives); for lines and
    points, whose derivatives run along the line or vanish, the normal VTK
    lights them with (the mesh's normals, or VTK's line normal facing the
    camera), so a line is shadowed exactly where VTK lights it.
    """
    if not triangles or actor.GetProperty().GetRepresentation() != vtk.VTK_SURFACE:
        return "normalize(normalVCVSOutput)"
    return "pvsGeometricNormal(pvsFacetVC, normalVCVSOutput)"


def _light_hooks(
    light: LightShading, pbr: bool, normal: str, lookup_maps: bool
) -> list[tuple[str, str]]:
    i = light.vtk_index
    visibility = light.visibility.replace("pvsNormalVC", normal)
    compute = (
        (f"pvsLookupMaps(vertexVC.xyz, {normal});\n  " if lookup_maps else "")
        + f"pvsVisibility{i} = {visibility};\n"
        f"  pvsKept{i} = pvsKeptShare(pvsVisibility{i}, {i}, pvsLights[{i}].shading.x);\n"
    )
    if pbr:
        return [
            (
                f"radiance = lightColor{i};",
                f"{compute}  radiance = lightColor{i} * pvsKept{i};",
            )
        ]
    return [
        (
            f"diffuse += (df * lightColor{i});",
            f"{compute}  diffuse += (df * pvsKept{i} * lightColor{i});",
        ),
        (
            f"specular += (sf * lightColor{i});",
            f"specular += (sf * pvsKept{i} * lightColor{i});",
        ),
    ]


def receiver_replacements(
    actor: vtk.vtkActor,
    lights: Iterable[LightShading],
    *,
    triangles: bool = True,
    units: Mapping[str, int] | None = None,
) -> list[tuple[str, str]]:
    """Return the fragment-shader edits that shadow ``lights`` on ``actor``.

    Parameters
    ----------
    actor : vtk.vtkActor
        A receiver; its property decides between Phong and PBR hooks.
    lights : iterable of LightShading
        The shadowed lights.
    triangles : bool, default: True
        ``False`` for an actor drawn without triangles (points, lines,
        spheres, tubes): its lookups use the normal VTK lights it with, and
        it shows "no surface" in probe frames, since the ray-cast reference
        cannot see it.
    units : Mapping, optional
        Each sampler's texture unit (an array's first), to write into the
        source; by default the samplers are VTK's custom uniforms.

    Returns
    -------
    list of tuple
        ``(original, replacement)`` pairs, applied after VTK's own
        substitutions.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.shaders.shading import LightShading, receiver_replacements
    >>> edits = receiver_replacements(pv.Actor(), [LightShading(0, "1.0")])
    >>> any("pvsVisibility0" in new for _, new in edits)
    True
    """
    lights = sorted(lights, key=lambda light: light.vtk_index)
    pbr = _uses_pbr(actor)
    sources = dict.fromkeys(source for light in lights for source in light.sources)
    defines = dict.fromkeys(define for light in lights for define in light.defines)
    lookups = [lookup for light in lights for lookup in light.needs]
    samplers: dict[str, tuple[str, int | None]] = {
        name: (kind, None) for light in lights for name, kind in light.samplers.items()
    }
    samplers.update(group_samplers(lookups))
    functions = "".join(_sampler_declaration(name, *kind, units) for name, kind in samplers.items())
    functions += "".join(f"#define {name}\n" for name in defines)
    each = " ".join(f"EACH(pvsVisibility{i}, pvsKept{i})" for i in (x.vtk_index for x in lights))
    functions += f"#define PVS_LIGHTS(EACH) {each}\n".replace(" \n", "\n")
    functions += frame_block_source(max((light.vtk_index for light in lights), default=0) + 1)
    functions += glsl_source("receiver_state.glsl") + glsl_source("receiver_normal.glsl")
    functions += shadow_functions(lookups)
    functions += "".join(glsl_source(source) for source in sources)
    edits = [
        (_MAIN, f"{functions}\n{_MAIN}"),
        (_VIEW_POSITION, _VIEW_POSITION + _FACET_NORMAL),
        (
            _PROBE_ANCHOR,
            _probe_output(
                "vec4(pvsProbe, 1.0, 0.0, 1.0)" if triangles else "vec4(0.0, 0.0, 0.0, 1.0)"
            ),
        ),
    ]
    first_lookup = min((lookup.vtk_index for lookup in lookups), default=None)
    needed = extensions(lookups) + ([BINDING_EXTENSION] if units is not None and samplers else [])
    directives = "".join(f"\n#extension {name} : require" for name in needed)
    if directives:
        edits.append((_SYSTEM, _SYSTEM + directives))
    normal = _normal_expression(actor, triangles)
    for light in lights:
        edits.extend(_light_hooks(light, pbr, normal, light.vtk_index == first_lookup))
    if units is None:
        for name, (kind, length) in samplers.items():
            size = "" if length is None else f"[{length}]"
            edits.append((f"uniform int {name}{size};", f"uniform {kind} {name}{size};"))
    return edits


def _sampler_declaration(
    name: str, kind: str, length: int | None, units: Mapping[str, int] | None
) -> str:
    """Declare a sampler on its unit, or nothing where VTK declares it."""
    if units is None:
        return ""
    size = "" if length is None else f"[{length}]"
    return f"layout(binding = {units[name]}) uniform {kind} {name}{size};\n"


def receiver_uniforms(
    lights: Iterable[LightShading], uniforms: Mapping[str, object]
) -> dict[str, object]:
    """Return the uniforms of a receiver that shows ``lights``.

    Parameters
    ----------
    lights : iterable of LightShading
        The shadowed lights, as :func:`receiver_replacements` got them.
    uniforms : Mapping
        Every light's uniforms by name, as the techniques set them.

    Returns
    -------
    dict
        The same, with the map lookups' own uniforms packed into their
        groups' arrays (:func:`pvshadows.shaders.library.group_uniforms`).

    Examples
    --------
    >>> from pvshadows.shaders.shading import LightShading, receiver_uniforms
    >>> receiver_uniforms([LightShading(0, "1.0")], {"pvsMask1": 4})
    {'pvsMask1': 4}
    """
    return group_uniforms([lookup for light in lights for lookup in light.needs], uniforms)


def bystander_replacements() -> list[tuple[str, str]]:
    """Return the edits for an actor that shows no shadow: black when probing.

    Returns
    -------
    list of tuple
        ``(original, replacement)`` pairs: the frame's uniform block, whose
        ``pvsProbeLight`` says when a frame probes, and the probe's output;
        they change nothing in a normal frame.

    Examples
    --------
    >>> from pvshadows.shaders.shading import bystander_replacements
    >>> [original for original, _ in bystander_replacements()]
    ['void main()', '//VTK::Picking::Impl']
    """
    return [
        (_MAIN, f"{frame_block_source(1)}\n{_MAIN}"),
        (_PROBE_ANCHOR, _probe_output("vec4(0.0, 0.0, 0.0, 1.0)")),
    ]


def set_uniform(uniforms: vtk.vtkUniforms, name: str, value: object) -> None:
    """Set one custom uniform from a Python value.

    Parameters
    ----------
    uniforms : vtk.vtkUniforms
        A shader property's fragment custom uniforms.
    name : str
        Uniform name.
    value : int, float, list of int, sequence of 4 floats, (4, 4) or (n, 4, 4) array
        ``int`` sets an ``int`` (also a sampler's texture unit), ``float`` a
        ``float``, a list of ``int`` an ``int[n]`` (also a sampler array's
        units), four numbers a ``vec4``, a 4x4 array a ``mat4`` and an
        ``(n, 4, 4)`` array a ``mat4[n]``.

    Examples
    --------
    >>> import vtk
    >>> from pvshadows.shaders.shading import set_uniform
    >>> uniforms = vtk.vtkShaderProperty().GetFragmentCustomUniforms()
    >>> set_uniform(uniforms, "pvsLevel", 0.5)
    >>> uniforms.GetNumberOfUniforms()
    1
    """
    uniform_setter(name, value)(uniforms)


def uniform_setter(name: str, value: object) -> Callable[[vtk.vtkUniforms], None]:
    """Return a function setting one custom uniform, its value converted once.

    Setting the same value on many receivers converts it only here.

    Parameters
    ----------
    name : str
        Uniform name.
    value : int, float, list of int, sequence of 4 floats, (4, 4) or (n, 4, 4) array
        As :func:`set_uniform` takes it.

    Returns
    -------
    callable
        Takes a ``vtk.vtkUniforms`` and sets the uniform on it.

    Raises
    ------
    TypeError
        For a value of another shape.

    Examples
    --------
    >>> import vtk
    >>> from pvshadows.shaders.shading import uniform_setter
    >>> setter = uniform_setter("pvsUnit", 3)
    >>> uniforms = vtk.vtkShaderProperty().GetFragmentCustomUniforms()
    >>> setter(uniforms)
    >>> uniforms.GetNumberOfUniforms()
    1
    """
    if isinstance(value, bool | int | np.integer):
        whole = int(value)
        return lambda uniforms: uniforms.SetUniformi(name, whole)
    if isinstance(value, list) and all(isinstance(v, int) for v in value):
        units = list(value)
        return lambda uniforms: uniforms.SetUniform1iv(name, len(units), units)
    if isinstance(value, float | np.floating):
        real = float(value)
        return lambda uniforms: uniforms.SetUniformf(name, real)
    array = np.asarray(value, dtype=np.float64)
    if array.shape == (4, 4):
        matrix = column_major(array).tolist()
        return lambda uniforms: uniforms.SetUniformMatrix4x4(name, matrix)
    if array.ndim == 3 and array.shape[1:] == (4, 4):
        matrices = column_major(array).tolist()
        return lambda uniforms: uniforms.SetUniformMatrix4x4v(name, array.shape[0], matrices)
    if array.shape == (4,):
        vector = array.astype(np.float32).tolist()
        return lambda uniforms: uniforms.SetUniform4f(name, vector)
    msg = f"uniform {name}: cannot upload a value of shape {array.shape}"
    raise TypeError(msg)


class ShaderEdits:
    """The edits and custom uniforms pvshadows has put on one actor.

    Keeps track of exactly what it added, so that removing it leaves the
    actor's shader property as the user left it (their own replacements and
    uniforms stay).

    Parameters
    ----------
    actor : vtk.vtkActor
        The actor whose shader property is edited.
    watchers : Watchers, optional
        The landing checks watching a program for the receivers of the
        actor's renderer (see :class:`~pvshadows.shaders.landing.LandingCheck`).
    """

    def __init__(self, actor: vtk.vtkActor, watchers: Watchers | None = None) -> None:
        self.actor = actor
        self._edits: list[tuple[str, str]] = []
        self._uniforms: set[str] = set()
        self._refused: list[tuple[str, str]] | None = None
        #: Checks the program VTK compiles for the actor against the edits.
        self.check = LandingCheck(actor, watchers)

    def apply(self, edits: list[tuple[str, str]]) -> None:
        """Make the actor's pvshadows edits exactly ``edits`` (a no-op when unchanged).

        Edits with which VTK could not compile the actor's shader are not
        applied again: the actor stays as VTK built it (unshadowed) and
        :attr:`problem` says so, until the edits change.

        Parameters
        ----------
        edits : list of tuple
            ``(original, replacement)`` pairs.
        """
        if self.check.failed:
            self._refused = self._edits
        wanted = [] if edits == self._refused else edits
        if wanted != self._edits:
            prop = self.actor.GetShaderProperty()
            for original, _ in self._edits:
                prop.ClearFragmentShaderReplacement(original, False)
            for original, replacement in wanted:
                prop.AddFragmentShaderReplacement(original, False, replacement, False)
            self._edits = list(wanted)
        self.check.expect(self._edits)

    @property
    def replacements(self) -> tuple[tuple[str, str], ...]:
        """The ``(original, replacement)`` pairs now on the actor's shader property."""
        return tuple(self._edits)

    @property
    def problem(self) -> str | None:
        """Why the actor shows fewer shadows than asked, or ``None``.

        Returns
        -------
        str or None
            The actor's shader variant refused the edits (it is drawn
            unshadowed, exactly as VTK built it), or some required edits did
            not land in the program VTK compiled (for example a VTK version
            whose generated lighting code changed).
        """
        if self._refused and not self._edits:
            return (
                "its shader variant does not compile with pvshadows' edits; drawn "
                "unshadowed, exactly as VTK built it"
            )
        if self.check.missing:
            return (
                "pvshadows' shader edits did not land in the program VTK compiled "
                f"(VTK's generated code differs at: {'; '.join(self.check.missing)}); "
                "the lights they shadow are drawn unshadowed on it"
            )
        return None

    def set_uniforms(self, values: Mapping[str, object]) -> None:
        """Set custom uniforms, and remove the ones set before but absent now.

        Parameters
        ----------
        values : Mapping
            Uniform names and values (see :func:`set_uniform`).
        """
        uniforms = self.actor.GetShaderProperty().GetFragmentCustomUniforms()
        for name in self._uniforms - set(values):
            uniforms.RemoveUniform(name)
        for name, value in values.items():
            set_uniform(uniforms, name, value)
        self._uniforms = set(values)

    def remove(self) -> None:
        """Take every pvshadows edit and uniform off the actor, and stop checking it."""
        self.apply([])
        self.set_uniforms({})
        self.check.release()
