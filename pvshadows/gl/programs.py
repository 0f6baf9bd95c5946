"""GLSL sources from the ``glsl/`` folder, compiled through VTK's shader cache.

Shaders live in files, one per stage and purpose. A program is assembled
from them with ``#define`` lines, so each program holds only the code its
light and filter need, and compiled by VTK (``vtkOpenGLShaderCache``), which
keeps VTK's idea of the bound program true.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from functools import cache
from importlib import resources
from pathlib import Path

from pvshadows import _vtk as vtk


class ShaderCompileError(RuntimeError):
    """A shader did not compile or link; the message holds the driver's log."""


def glsl_dir() -> Path:
    """Return the folder that holds the shader sources.

    Returns
    -------
    pathlib.Path
        ``pvshadows/glsl`` inside an installed wheel, or the repository's
        top-level ``glsl/`` in a source checkout.

    Examples
    --------
    >>> from pvshadows.gl.programs import glsl_dir
    >>> (glsl_dir() / "distance_depth.frag").is_file()
    True
    """
    packaged = Path(str(resources.files("pvshadows"))) / "glsl"
    if packaged.is_dir():
        return packaged
    return Path(__file__).resolve().parents[2] / "glsl"


@cache
def glsl_source(name: str) -> str:
    """Return the text of one file in ``glsl/``.

    Parameters
    ----------
    name : str
        File name, for example ``"cube_depth.geom"``.

    Returns
    -------
    str
        The file's text.

    Examples
    --------
    >>> from pvshadows.gl.programs import glsl_source
    >>> "gl_FragDepth" in glsl_source("distance_depth.frag")
    True
    """
    return (glsl_dir() / name).read_text(encoding="utf-8")


def with_defines(source: str, defines: Mapping[str, object] | None = None) -> str:
    r"""Put ``#define`` lines right after a stage's ``#version`` line.

    Parameters
    ----------
    source : str
        Stage source whose first line is its ``#version`` directive.
    defines : dict, optional
        Macro names and values; ``None`` or ``True`` values define the name
        alone.

    Returns
    -------
    str
        Complete stage source.

    Examples
    --------
    >>> from pvshadows.gl.programs import glsl_source, with_defines
    >>> source = glsl_source("distance_depth.frag")
    >>> stage = with_defines(source, {"TAPS": 4, "SIX_PASSES": True})
    >>> stage.splitlines()[0] == source.splitlines()[0]  # the version line stays first
    True
    >>> [line.split()[1] for line in stage.splitlines()[1:3]]
    ['TAPS', 'SIX_PASSES']
    """
    version, _, body = source.partition("\n")
    lines = [version]
    for name, value in (defines or {}).items():
        lines.append(
            f"#define {name}" if value is None or value is True else f"#define {name} {value}"
        )
    lines.append(body)
    return "\n".join(lines)


def compile_files(
    window: vtk.vtkOpenGLRenderWindow,
    vertex: str,
    fragment: str,
    geometry: str = "",
    defines: Mapping[str, object] | None = None,
) -> vtk.vtkShaderProgram:
    """Compile, link and bind a program from stage files of ``glsl/``.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose shader cache compiles and binds the program.
    vertex, fragment, geometry : str
        File names of the stages; ``geometry`` may be empty.
    defines : dict, optional
        Macros given to every stage (see :func:`with_defines`).

    Returns
    -------
    vtk.vtkShaderProgram
        The compiled program, bound.

    Raises
    ------
    ShaderCompileError
        With each failing stage's log.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.programs import compile_files
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> program = compile_files(pl.ren_win, "map_depth.vert", "distance_depth.frag")
    >>> bool(program.GetCompiled())
    True
    """
    sources = [
        with_defines(glsl_source(name), defines) if name else ""
        for name in (vertex, fragment, geometry)
    ]
    return compile_program(window, *sources)


def compile_program(
    window: vtk.vtkOpenGLRenderWindow,
    vertex: str,
    fragment: str,
    geometry: str = "",
) -> vtk.vtkShaderProgram:
    """Compile, link and bind a program in the window's context.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose shader cache compiles and binds the program.
    vertex, fragment, geometry : str
        Complete stage sources, each starting with its ``#version`` line;
        ``geometry`` may be empty.

    Returns
    -------
    vtk.vtkShaderProgram
        The compiled program, bound. The caller releases it with
        ``ReleaseGraphicsResources(window)``.

    Raises
    ------
    ShaderCompileError
        With each failing stage's log, when compiling or linking fails.
        Nothing is printed on the console.
    """
    program = vtk.vtkShaderProgram()
    program.GetVertexShader().SetSource(vertex)
    program.GetFragmentShader().SetSource(fragment)
    program.GetGeometryShader().SetSource(geometry)
    shown = vtk.vtkObject.GetGlobalWarningDisplay()
    vtk.vtkObject.GlobalWarningDisplayOff()
    try:
        ready = window.GetShaderCache().ReadyShaderProgram(program)
    finally:
        vtk.vtkObject.SetGlobalWarningDisplay(shown)
    if ready is None or not program.GetCompiled():
        stages = {
            "vertex": program.GetVertexShader(),
            "geometry": program.GetGeometryShader(),
            "fragment": program.GetFragmentShader(),
        }
        logs = [
            f"{stage} shader:\n{shader.GetError()}"
            for stage, shader in stages.items()
            if shader.GetError()
        ]
        if program.GetError():
            logs.append(f"link:\n{program.GetError()}")
        raise ShaderCompileError("pvshadows could not build a shader program.\n" + "\n".join(logs))
    return program


def bind_program(window: vtk.vtkOpenGLRenderWindow, program: vtk.vtkShaderProgram) -> None:
    """Bind a compiled program through VTK's shader cache.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose cache binds it.
    program : vtk.vtkShaderProgram
        A program from :func:`compile_program`.
    """
    window.GetShaderCache().ReadyShaderProgram(program)


class ProgramCache:
    """Programs of one window, compiled once per key and released together.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the programs.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._programs: dict[object, vtk.vtkShaderProgram] = {}

    def get(self, key: object, build: Callable[[], vtk.vtkShaderProgram]) -> vtk.vtkShaderProgram:
        """Return the program for ``key``, calling ``build`` to compile it the first time.

        Parameters
        ----------
        key : hashable
            What distinguishes the program (stage files, defines).
        build : callable
            Compiles it (for example with :func:`compile_program`).

        Returns
        -------
        vtk.vtkShaderProgram
            The compiled program.
        """
        if key not in self._programs:
            self._programs[key] = build()
        return self._programs[key]

    def release(self) -> None:
        """Release every program."""
        for program in self._programs.values():
            program.ReleaseGraphicsResources(self._window)
        self._programs.clear()
