"""The texture units receivers read shadow textures from, reserved once and kept.

A sampler uniform tells a program which texture unit to read. Held as a
receiver's custom uniform, VTK sets it again at every draw of every
receiver (about half a microsecond each, so half a millisecond a frame for
a thousand actors). So each sampler keeps the same texture units frame
after frame, and the frame's textures are bound there. Where the context
offers ``GL_ARB_shading_language_420pack`` (GL 4.2 and later drivers), the
units are written into the receivers' source (``layout(binding = N)``), and
receivers carry no custom uniform at all; elsewhere (macOS' GL 4.1) they
stay custom uniforms, whose values never change.

A sampler array needs consecutive units: each array a receiver reads gets a
block of its own, named by the lights' own uniforms it packs (for example
``("pvsDepth0", "pvsDepth2")``), chosen from the top of the unit range
down, away from the low units VTK hands out. The units are taken from VTK's
``vtkTextureUnitManager`` for the frame, as VTK's own textures take theirs,
and given back once the receivers drew.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.capabilities import extension_names
from pvshadows.gl.texture_units import GL_TEXTURE0

#: The extension that lets GLSL 1.50 give a sampler its unit.
BINDING_EXTENSION = "GL_ARB_shading_language_420pack"


@dataclass(frozen=True)
class TextureBinding:
    """One texture a receiver's sampler reads, and what it is read through.

    Attributes
    ----------
    source : str
        The light's own uniform that names it, for example ``"pvsDepth2"``.
    target : int
        The texture's GL target, for example ``GL_TEXTURE_CUBE_MAP``.
    handle : int
        The texture's GL name.
    sampler : int
        A sampler object that overrides the texture's parameters on its unit
        (plain depth reads of a comparison map), or 0.
    texture : vtk.vtkTextureObject or None
        VTK's object for the texture, bound through VTK so that parameters
        set on it are sent; ``None`` for a texture pvshadows binds itself.
    """

    source: str
    target: int
    handle: int
    sampler: int = 0
    texture: vtk.vtkTextureObject | None = field(default=None, compare=False, repr=False)

    @classmethod
    def of(cls, source: str, texture: vtk.vtkTextureObject) -> TextureBinding:
        """Return the binding of one of VTK's texture objects.

        Parameters
        ----------
        source : str
            The light's own uniform that names it.
        texture : vtk.vtkTextureObject
            The texture, already created.

        Returns
        -------
        TextureBinding
            Its target and handle, bound through ``texture.Bind()``.

        Examples
        --------
        >>> import pyvista as pv
        >>> from pvshadows import _vtk as vtk
        >>> from pvshadows.gl.sampler_units import TextureBinding
        >>> pl = pv.Plotter(off_screen=True)
        >>> pl.ren_win.Render()
        >>> texture = vtk.vtkTextureObject()
        >>> texture.SetContext(pl.ren_win)
        >>> texture.Allocate2D(4, 4, 1, vtk.VTK_FLOAT)
        True
        >>> TextureBinding.of("pvsMask0", texture).target == texture.GetTarget()
        True
        """
        return cls(source, int(texture.GetTarget()), int(texture.GetHandle()), 0, texture)


def _bindings(value: object) -> tuple[TextureBinding, ...] | None:
    """Return the textures of a sampler's value (one, or an array's), else ``None``."""
    if isinstance(value, TextureBinding):
        return (value,)
    if isinstance(value, list | tuple) and value and isinstance(value[0], TextureBinding):
        return tuple(value)
    return None


def binding_supported(window: vtk.vtkOpenGLRenderWindow) -> bool:
    """Tell whether the window's context lets GLSL 1.50 give samplers their units.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        A window whose context is current.

    Returns
    -------
    bool
        Whether the context offers :data:`BINDING_EXTENSION`.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.gl.sampler_units import binding_supported
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> isinstance(binding_supported(pl.ren_win), bool)
    True
    """
    return BINDING_EXTENSION in extension_names(opengl_for(window))


class SamplerUnits:
    """Texture units reserved for the samplers of one renderer's receivers.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose texture units are reserved.
    binding : bool, optional
        Write the units into the receivers' source; by default, where the
        context supports it (:func:`binding_supported`).

    Attributes
    ----------
    binding : bool
        Whether receivers declare their samplers' units in their source
        (else they are custom uniforms).
    binds : int
        Textures bound so far (each of a block's at every frame).

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows import _vtk as vtk
    >>> from pvshadows.gl.sampler_units import SamplerUnits, TextureBinding
    >>> pl = pv.Plotter(off_screen=True)
    >>> pl.ren_win.Render()
    >>> texture = vtk.vtkTextureObject()
    >>> texture.SetContext(pl.ren_win)
    >>> texture.Allocate2D(4, 4, 1, vtk.VTK_FLOAT)
    True
    >>> units = SamplerUnits(pl.ren_win)
    >>> mask = TextureBinding.of("pvsMask0", texture)
    >>> first = units.units_of({"pvsMask0": mask})
    >>> first == units.units_of({"pvsMask0": mask}), first["pvsMask0"] > 0
    (True, True)
    >>> units.release()
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow, binding: bool | None = None) -> None:
        self._window = window
        self._gl = opengl_for(window)
        from OpenGL.raw.GL.VERSION.GL_1_1 import glBindTexture
        from OpenGL.raw.GL.VERSION.GL_3_3 import glBindSampler

        self._bind_texture, self._bind_sampler = glBindTexture, glBindSampler
        self.binding = binding_supported(window) if binding is None else binding
        #: First unit of each block, by the sources its array packs.
        self._blocks: dict[tuple[str, ...], int] = {}
        #: Units on which a sampler object was bound (unbound when the block goes).
        self._with_sampler: set[int] = set()
        #: Blocks asked for since the last :meth:`keep_marked`.
        self._marked: set[tuple[str, ...]] = set()
        self.binds = 0
        #: Units taken from VTK's manager for this frame (given back by :meth:`end_frame`).
        self._held: list[int] = []

    def _reserve(self, count: int) -> int:
        """Choose ``count`` consecutive units, free in VTK's manager and in no block.

        The highest such run is chosen (VTK hands out the lowest free unit);
        its first unit is returned.
        """
        manager = self._window.GetTextureUnitManager()
        total = manager.GetNumberOfTextureUnits()
        ours = {
            unit for key, first in self._blocks.items() for unit in range(first, first + len(key))
        }
        for first in range(total - count, -1, -1):
            run = range(first, first + count)
            if not any(unit in ours or manager.IsAllocated(unit) for unit in run):
                return first
        msg = (
            f"pvshadows needs {count} consecutive free texture units for its shadow "
            f"textures, and this window has {total} in all: shadow fewer lights, or "
            "give them one filter and one map kind, so that their maps share samplers"
        )
        raise RuntimeError(msg)

    def _first_unit(self, bindings: tuple[TextureBinding, ...]) -> int:
        """Return the first unit of the block of ``bindings``, reserved when new."""
        key = tuple(binding.source for binding in bindings)
        if key not in self._blocks:
            self._blocks[key] = self._reserve(len(key))
        self._marked.add(key)
        return self._blocks[key]

    def first_units(self, values: Mapping[str, object]) -> dict[str, int]:
        """Return the unit of each sampler of ``values`` (an array's first).

        The block of each array is reserved the first time it is asked for,
        then kept until :meth:`keep_marked` finds it unasked for.

        Parameters
        ----------
        values : Mapping
            A receiver's uniforms: a :class:`TextureBinding`, or a list of
            them for an array, for each sampler.

        Returns
        -------
        dict
            The samplers' names and units; other names are left out.
        """
        units = {}
        for name, value in values.items():
            bindings = _bindings(value)
            if bindings is not None:
                units[name] = self._first_unit(bindings)
        return units

    def units_of(self, values: Mapping[str, object]) -> dict[str, object]:
        """Return ``values`` with each sampler's textures replaced by their units.

        Parameters
        ----------
        values : Mapping
            A receiver's uniforms, as for :meth:`first_units`.

        Returns
        -------
        dict
            The same names, with each sampler's unit (an array's as a list of
            consecutive units); other values as they were.
        """
        units: dict[str, object] = {}
        for name, value in values.items():
            bindings = _bindings(value)
            if bindings is None:
                units[name] = value
            elif isinstance(value, TextureBinding):
                units[name] = self._first_unit(bindings)
            else:
                first = self._first_unit(bindings)
                units[name] = list(range(first, first + len(bindings)))
        return units

    def bind(self, uniforms: Mapping[str, object]) -> None:
        """Take every block's units for this frame and bind this frame's textures there.

        Parameters
        ----------
        uniforms : Mapping
            Every light's own uniforms this frame, by name: each block's
            sources name its textures. A block whose source is absent keeps
            what it held (no receiver reads it this frame).

        Raises
        ------
        RuntimeError
            When another texture holds one of the units (the frame is then
            drawn unshadowed, and the next one chooses other units).
        """
        manager = self._window.GetTextureUnitManager()
        state = self._window.GetState()
        for key, first in self._blocks.items():
            for unit, source in enumerate(key, first):
                if manager.Allocate(unit) != unit:  # -1: held already
                    msg = f"texture unit {unit}, kept for {source}, is held by another texture"
                    raise RuntimeError(msg)
                self._held.append(unit)
                binding = uniforms.get(source)
                if not isinstance(binding, TextureBinding):
                    continue
                state.vtkglActiveTexture(GL_TEXTURE0 + unit)
                if binding.texture is not None:
                    binding.texture.Bind()
                else:
                    self._bind_texture(binding.target, binding.handle)
                if binding.sampler:
                    self._bind_sampler(unit, binding.sampler)
                    self._with_sampler.add(unit)
                self.binds += 1

    def keep_marked(self) -> None:
        """Forget the blocks no :meth:`units_of` asked for since the last call.

        Call it after asking for every receiver's units, before :meth:`bind`:
        the arrays no receiver reads any more give up their units.
        """
        self._blocks = {key: first for key, first in self._blocks.items() if key in self._marked}
        self._marked = set()

    def end_frame(self) -> None:
        """Give this frame's units back to VTK, once the receivers drew.

        A sampler object is unbound from its unit first, so that no VTK
        texture bound there later samples through it.
        """
        manager = self._window.GetTextureUnitManager()
        for unit in self._held:
            if unit in self._with_sampler:
                self._bind_sampler(unit, 0)
            manager.Free(unit)
        self._with_sampler.clear()
        self._held = []

    def release(self) -> None:
        """Give every unit back and forget the blocks (the window's context must be current)."""
        self.end_frame()
        self._blocks.clear()
        self._marked = set()
