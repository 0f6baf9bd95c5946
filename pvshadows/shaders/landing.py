"""Check that pvshadows' shader edits landed in the program VTK compiled for a receiver.

A ``vtkShaderProperty`` replacement whose original text is not in the code
VTK generated does nothing, silently: a VTK version that words its lighting
code differently would leave receivers unshadowed without a sign. So the
program VTK draws a receiver with after each change of its edits (its
mapper's ``UpdateShaderEvent`` hands it over) is read once, and each edit is
looked for in its fragment source; then the receiver costs no call per
frame.
An edit counts as required unless the variant legitimately lacks its place:
a light's hooks only where VTK's code shades with that light, the facet normal
only where the variant computes a view position.

A variant whose patched code does not compile ("Could not set shader
program", the mapper's ``ErrorEvent``) is noticed too, so that the receiver
can be left exactly as VTK built it.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence

from vtkmodules.util.misc import calldata_type

from pvshadows import _vtk as vtk

#: VTK's replacement tags: the shader cache substitutes or keeps them, so they
#: are not looked for.
_TAG = re.compile(r"//VTK::\w+::\w+")
#: The hooks of one light (Phong diffuse and specular, PBR radiance).
_HOOK = re.compile(r"^(?:diffuse \+= \(df|specular \+= \(sf|radiance =) \*? ?lightColor(\d+)")
#: Edits a variant may lack a place for without harm (the facet normal: the
#: shading normal stands in).
OPTIONAL = ("vec4 vertexVC = vertexVCVSOutput;",)
#: What VTK's mapper reports when a program does not compile.
COMPILE_FAILED = "Could not set shader program"


def _uses_light(source: str, index: int) -> bool:
    """Tell whether VTK's code shades with light ``index`` (not only declares it)."""
    name = f"lightColor{index}"
    return source.count(name) > source.count(f"uniform vec3 {name};")


def missing_edits(edits: Sequence[tuple[str, str]], source: str) -> list[str]:
    """Return the originals of the required edits that did not land in ``source``.

    Parameters
    ----------
    edits : sequence of tuple
        ``(original, replacement)`` pairs pvshadows gave the shader property.
    source : str
        The fragment shader source VTK compiled.

    Returns
    -------
    list of str
        The original text of each required edit whose replacement is not in
        the source.

    Examples
    --------
    >>> from pvshadows.shaders.landing import missing_edits
    >>> source = "uniform vec3 lightColor0; diffuse += (df * lightColor0);"
    >>> missing_edits([("diffuse += (df * lightColor0);", "shadowed")], source)
    ['diffuse += (df * lightColor0);']
    >>> missing_edits([("diffuse += (df * lightColor1);", "shadowed")], source)
    []
    """
    # With a geometry shader (wide lines, edges) VTK renames the fragment
    # shader's inputs from ...VSOutput to ...GSOutput after the edits.
    source = source.replace("GSOutput", "VSOutput")
    missing = []
    for original, replacement in edits:
        if original in OPTIONAL:
            continue
        hook = _HOOK.match(original)
        if hook is not None and not _uses_light(source, int(hook.group(1))):
            continue
        pieces = [piece for piece in _TAG.split(replacement) if piece.strip()]
        if not all(piece in source for piece in pieces):
            missing.append(original)
    return missing


def opengl_mapper(actor: vtk.vtkActor) -> vtk.vtkMapper | None:
    """Return the mapper that compiles ``actor``'s shaders, once it exists.

    Parameters
    ----------
    actor : vtk.vtkActor
        A receiver.

    Returns
    -------
    vtk.vtkMapper or None
        The inner ``vtkOpenGLPolyDataMapper`` of a ``vtkDataSetMapper``
        (present after the first render), else the actor's own mapper.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.shaders.landing import opengl_mapper
    >>> pl = pv.Plotter(off_screen=True)
    >>> actor = pl.add_mesh(pv.Sphere())
    >>> opengl_mapper(actor) is None
    True
    """
    # VTK's own methods, called on the class: PyVista's wrappers check every attribute
    # (asked each frame of the receivers VTK has not drawn yet)
    mapper = vtk.vtkActor.GetMapper(actor)
    inner = getattr(type(mapper), "GetPolyDataMapper", None)
    return mapper if inner is None else inner(mapper)


class LandingCheck:
    """Reads each program VTK compiles for one receiver and checks the edits in it.

    Parameters
    ----------
    actor : vtk.vtkActor
        The receiver.

    Attributes
    ----------
    missing : list of str
        Originals of the required edits absent from the last program checked.
    failed : bool
        Whether a program with the edits failed to compile since :meth:`expect`.
    checked : int
        Programs read so far.
    notify : callable or None
        Called with no argument whenever :attr:`missing` or :attr:`failed`
        changes, so that an owner keeps no per-frame watch over every receiver.
    """

    def __init__(self, actor: vtk.vtkActor) -> None:
        self.actor = actor
        self.missing: list[str] = []
        self.failed = False
        self.checked = 0
        self.notify: Callable[[], None] | None = None
        self._edits: list[tuple[str, str]] = []
        self._seen: set[str] = set()
        self._mapper: vtk.vtkMapper | None = None
        self._error_tag: int | None = None
        self._program_tag: int | None = None

    def expect(self, edits: list[tuple[str, str]]) -> None:
        """Check the next program VTK draws the actor with for ``edits``.

        Parameters
        ----------
        edits : list of tuple
            The ``(original, replacement)`` pairs now on the shader property.
        """
        if edits != self._edits:
            self._edits = list(edits)
            self._seen.clear()
            self.missing = []
            self.failed = False
        self.attach()

    def attach(self) -> bool:
        """Watch the actor's OpenGL mapper; return whether it exists yet.

        Its compile errors are watched for as long as the check lives; its
        program only until the next draw has handed it over and it was
        checked (VTK hands it over at every draw, so a Python call per
        receiver per frame would be the price of watching longer). A
        ``vtkDataSetMapper`` makes its inner mapper during its first render,
        so an actor edited before then is watched from the next frame on.

        Returns
        -------
        bool
            ``True`` once the mapper is watched.
        """
        mapper = opengl_mapper(self.actor)
        if mapper is None:
            return False
        if id(mapper) != id(self._mapper):  # (``is`` would narrow ``mapper`` to Optional)
            self.release()
            self._error_tag = mapper.AddObserver(vtk.vtkCommand.ErrorEvent, self._on_error)
            self._mapper = mapper
        if self._program_tag is None:
            self._program_tag = mapper.AddObserver(
                vtk.vtkCommand.UpdateShaderEvent, self._on_program
            )
        return True

    @calldata_type(vtk.VTK_OBJECT)
    def _on_program(self, mapper: vtk.vtkMapper, event: str, program: vtk.vtkShaderProgram) -> None:
        if program is None or not self._edits or self.failed:
            return  # after a failed compile VTK draws with its previous program
        if self._program_tag is not None:
            mapper.RemoveObserver(self._program_tag)
            self._program_tag = None
        key = program.GetHash()
        if key in self._seen:
            return
        self._seen.add(key)
        self.checked += 1
        missing = missing_edits(self._edits, program.GetFragmentShader().GetSource())
        if missing != self.missing:
            self.missing = missing
            self._changed()

    @calldata_type(vtk.VTK_STRING)
    def _on_error(self, mapper: vtk.vtkMapper, event: str, message: str) -> None:
        if self._edits and COMPILE_FAILED in (message or ""):
            if not self.failed:
                self.failed = True
                self._changed()
        elif message:
            vtk.vtkOutputWindow.GetInstance().DisplayErrorText(message)

    def _changed(self) -> None:
        if self.notify is not None:
            self.notify()

    def release(self) -> None:
        """Remove the observers from the mapper."""
        if self._mapper is not None:
            for tag in (self._error_tag, self._program_tag):
                if tag is not None:
                    self._mapper.RemoveObserver(tag)
        self._mapper = None
        self._error_tag = self._program_tag = None
