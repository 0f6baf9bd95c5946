"""What decides the program VTK compiles for an actor, read from the actor without drawing it.

VTK's OpenGL mapper writes an actor's shaders from its mapper, its
property, its textures, its shader property and the arrays of its data, and
shares one compiled program between actors whose written source is the
same. :func:`shader_variant` gathers every one of those inputs that can
change the written source into one hashable key, so that actors with equal
keys (in one renderer, with the same pvshadows edits) are drawn with the
same program: checking that the edits landed in one of them checks them
all (:class:`pvshadows.shaders.landing.LandingCheck`). The key may tell
apart actors VTK draws with one program (then each is checked on its own,
as without sharing); it must never join actors VTK draws with different
programs. ``tests/test_landing_variants.py`` holds it to that on a range of
PyVista's styles.
"""

from __future__ import annotations

from collections.abc import Hashable

from pvshadows import _vtk as vtk

#: The names of the textures VTK's PBR code reads by name (any other name is a plain texture).
_PBR_TEXTURES = (
    "albedoTex",
    "materialTex",
    "normalTex",
    "emissiveTex",
    "anisotropyTex",
    "coatNormalTex",
)


def _offsets(mapper: vtk.vtkMapper) -> tuple[float, ...]:
    """Return the mapper's coincident-topology offsets (VTK writes depth code unless all are 0)."""
    factor, units, point = vtk.reference(0.0), vtk.reference(0.0), vtk.reference(0.0)
    found = []
    for read in (
        mapper.GetCoincidentTopologyPolygonOffsetParameters,
        mapper.GetCoincidentTopologyLineOffsetParameters,
    ):
        read(factor, units)
        found += [float(factor), float(units)]
    mapper.GetCoincidentTopologyPointOffsetParameter(point)
    return (*found, float(point), vtk.vtkMapper.GetResolveCoincidentTopology())


def _attributes(arrays: vtk.vtkDataSetAttributes) -> tuple:
    """Return the names and sizes of a point or cell data's arrays, with its active ones."""
    found = []
    for index in range(arrays.GetNumberOfArrays()):
        array = arrays.GetAbstractArray(index)
        size = array.GetNumberOfComponents()
        found.append((array.GetName(), size, arrays.IsArrayAnAttribute(index)))
    return tuple(found)


def _data_arrays(actor: vtk.vtkActor, data: vtk.vtkDataObject | None) -> Hashable:
    """Return which arrays and cells of the mapper's input VTK's shaders may read.

    An input without cells (a pipeline VTK has not run yet) gives a key no
    other actor has: what it will hold is not known.
    """
    if not isinstance(data, vtk.vtkDataSet) or data.GetNumberOfCells() == 0:
        return ("not known", actor.__this__)
    arrays = (_attributes(data.GetPointData()), _attributes(data.GetCellData()))
    if isinstance(data, vtk.vtkPolyData):
        kinds = tuple(
            count > 0
            for count in (
                data.GetNumberOfVerts(),
                data.GetNumberOfLines(),
                data.GetNumberOfPolys(),
                data.GetNumberOfStrips(),
            )
        )
    else:
        kinds = ()
    return (type(data).__name__, arrays, kinds)


def _property(prop: vtk.vtkProperty | None) -> Hashable:
    """Return the property's settings that change VTK's written shader source."""
    if prop is None:
        return None
    return (
        prop.GetInterpolation(),
        prop.GetRepresentation(),
        prop.GetLighting(),
        prop.GetEdgeVisibility(),
        prop.GetVertexVisibility(),
        prop.GetRenderLinesAsTubes(),
        prop.GetRenderPointsAsSpheres(),
        prop.GetLineWidth(),
        prop.GetPointSize(),
        prop.GetOpacity() < 1.0,
        prop.GetAnisotropy() != 0.0,
        prop.GetCoatStrength() != 0.0,
        prop.GetShowTexturesOnBackface(),
        prop.GetNumberOfTextures(),
        tuple(prop.GetTexture(name) is not None for name in _PBR_TEXTURES),
    )


def _shader_property(shader: vtk.vtkShaderProperty) -> Hashable:
    """Return the replacements, custom uniforms and own code a shader property gives VTK."""
    name, first, value, every = (
        vtk.reference(""),
        vtk.reference(False),
        vtk.reference(""),
        vtk.reference(False),
    )
    replacements = []
    for index in range(shader.GetNumberOfShaderReplacements()):
        shader.GetNthShaderReplacement(index, name, first, value, every)
        stage = shader.GetNthShaderReplacementTypeAsString(index)
        replacements.append((stage, str(name), bool(first), str(value), bool(every)))
    uniforms = shader.GetFragmentCustomUniforms()
    names = tuple(uniforms.GetNthUniformName(i) for i in range(uniforms.GetNumberOfUniforms()))
    return (
        tuple(replacements),
        names,
        shader.GetVertexCustomUniforms().GetNumberOfUniforms(),
        shader.GetGeometryCustomUniforms().GetNumberOfUniforms(),
        shader.GetVertexShaderCode(),
        shader.GetFragmentShaderCode(),
        shader.GetGeometryShaderCode(),
    )


def _keys(keys: vtk.vtkInformation | None) -> int:
    """Return how many information keys a prop carries (render passes mark props with them)."""
    return 0 if keys is None else keys.GetNumberOfKeys()


def shader_variant(actor: vtk.vtkActor) -> Hashable:
    """Return a key equal for two actors only if VTK writes the same shaders for both.

    Parameters
    ----------
    actor : vtk.vtkActor
        An actor of a renderer (the renderer's lights and passes, the same
        for all its actors, are not in the key).

    Returns
    -------
    Hashable
        The mapper's class and colouring, clipping and depth-offset settings;
        the property's style, lighting, PBR features and textures (the
        back face's too); the actor's texture, translucency (VTK's own
        answer, which reads the colours' opacity too: a translucent actor
        is drawn in the translucent pass, whose passes edit its shaders)
        and information keys; the shader
        property's replacements, uniforms and own code; and which normals,
        texture coordinates, tangents, scalars and cell kinds the data holds.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.shaders.variant import shader_variant
    >>> pl = pv.Plotter(off_screen=True)
    >>> one = pl.add_mesh(pv.Sphere(center=(0, 0, 0)))
    >>> two = pl.add_mesh(pv.Sphere(center=(2, 0, 0)))
    >>> three = pl.add_mesh(pv.Sphere(center=(4, 0, 0)), style="wireframe")
    >>> shader_variant(one) == shader_variant(two), shader_variant(one) == shader_variant(three)
    (True, False)
    """
    mapper = vtk.vtkActor.GetMapper(actor)
    if mapper is None:
        return None
    data = mapper.GetInputDataObject(0, 0)
    return (
        type(mapper).__name__,
        mapper.GetScalarVisibility(),
        mapper.GetScalarMode(),
        mapper.GetColorMode(),
        mapper.GetInterpolateScalarsBeforeMapping(),
        mapper.GetArrayAccessMode(),
        mapper.GetArrayId(),
        mapper.GetArrayName(),
        mapper.GetNumberOfClippingPlanes(),
        _offsets(mapper),
        _data_arrays(actor, data),
        _property(actor.GetProperty()),
        _property(actor.GetBackfaceProperty()),
        actor.GetTexture() is not None,
        bool(actor.HasTranslucentPolygonalGeometry()),
        actor.GetForceOpaque(),
        actor.GetForceTranslucent(),
        _keys(actor.GetPropertyKeys()),
        _shader_property(actor.GetShaderProperty()),
    )
