"""Check that pvshadows' shader edits landed in the program VTK compiled for a receiver.

A ``vtkShaderProperty`` replacement whose original text is not in the code
VTK generated does nothing, silently: a VTK version that words its lighting
code differently would leave receivers unshadowed without a sign. So the
program VTK draws a receiver with after each change of its edits (its
mapper's ``UpdateShaderEvent`` hands it over) is read once, and each edit is
looked for in its fragment source (once between the receivers VTK draws
with the same program and edits); then the receiver costs no call per
frame. Receivers whose shaders VTK writes alike
(:func:`~pvshadows.shaders.variant.shader_variant`) and that carry the same
edits are drawn with one program: one of them is watched and the others
take its verdict (:class:`~pvshadows.shaders.landing_views.Watchers`),
because an observer leaves VTK walking the mapper's observer list at every
draw, for good.
An edit counts as required unless the variant legitimately lacks its place:
a light's hooks only where VTK's code shades with that light, the facet normal
only where the variant computes a view position.

A variant whose patched code does not compile ("Could not set shader
program", the mapper's ``ErrorEvent``) is noticed too, so that the receiver
can be left exactly as VTK built it.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Hashable, Sequence

from vtkmodules.util.misc import calldata_type

from pvshadows import _vtk as vtk
from pvshadows.shaders.landing_views import Watchers
from pvshadows.shaders.variant import shader_variant

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
#: The edits missing from each program read, by its hash and the edits: receivers
#: drawn with the same program and edits (VTK shares programs between actors) read
#: its source once between them. Kept up to ``_VERDICTS_KEPT`` entries.
_VERDICTS: dict[tuple[str, tuple[tuple[str, str], ...]], tuple[str, ...]] = {}
_VERDICTS_KEPT = 256


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
    """Reads the program VTK compiles for one receiver and checks the edits in it.

    VTK draws actors whose shaders it writes alike with one program, so
    receivers of one renderer with the same :func:`~pvshadows.shaders.variant.shader_variant`
    and the same edits share one reading: the first of them whose mapper
    exists watches it (the *watcher*), the others follow its verdict and put
    no observer on their own mapper (an observer, even removed, leaves VTK
    walking an observer list at every draw of that mapper).

    Parameters
    ----------
    actor : vtk.vtkActor
        The receiver.
    watchers : Watchers, optional
        The watcher of each shader variant and edits in the receiver's
        renderer, shared by the checks of its receivers; without it the
        check watches its own mapper.

    Attributes
    ----------
    missing : list of str
        Originals of the required edits absent from the last program checked.
    failed : bool
        Whether a program with the edits failed to compile since :meth:`expect`.
    checked : int
        Programs this check read so far (a follower reads none).
    settled : bool
        Whether a program with the current edits was read, by this check or
        by the watcher it follows.
    notify : callable or None
        Called with no argument whenever :attr:`missing` or :attr:`failed`
        changes, or the watcher this check followed left before it read a
        program (then the owner applies the edits again, which finds a new
        one), so that an owner keeps no per-frame watch over every receiver.
    """

    def __init__(self, actor: vtk.vtkActor, watchers: Watchers | None = None) -> None:
        self.actor = actor
        self.missing: list[str] = []
        self.failed = False
        self.checked = 0
        self.settled = False
        self.notify: Callable[[], None] | None = None
        self._edits: list[tuple[str, str]] = []
        self._variant: Hashable = None
        #: What decided the variant last read, and that variant.
        self._stamp: tuple | None = None
        self._read_variant: Hashable = None
        self._watchers = Watchers() if watchers is None else watchers
        self._watcher: LandingCheck | None = None
        self._followers: list[LandingCheck] = []
        self._followers_changed = 0
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
            self._reset(edits, self._variant)
        self.attach()

    def _reset(self, edits: list[tuple[str, str]], variant: Hashable) -> None:
        """Forget the verdict: the edits or the variant changed."""
        self._leave()
        self._edits = list(edits)
        self._variant = variant
        self._seen.clear()
        self.missing = []
        self.failed = False
        self.settled = False

    def _shader_variant(self) -> Hashable:
        """Return the actor's :func:`shader_variant`, read again only where its inputs changed."""
        actor = self.actor
        mapper = vtk.vtkActor.GetMapper(actor)
        if mapper is None:
            return None
        data = mapper.GetInputDataObject(0, 0)
        texture = actor.GetTexture()
        stamp = (
            id(mapper),
            mapper.GetMTime(),
            None if data is None else (id(data), data.GetMTime()),
            actor.GetProperty().GetMTime(),
            actor.GetShaderProperty().GetMTime(),
            actor.GetBackfaceProperty(),
            texture,
            None if texture is None else texture.GetMTime(),
            actor.GetForceOpaque(),
            actor.GetForceTranslucent(),
        )
        if stamp != self._stamp:
            self._stamp = stamp
            self._read_variant = shader_variant(actor)
        return self._read_variant

    def _key(self) -> Hashable:
        if self._variant is None or not self._edits:
            return None
        return (self._variant, tuple(self._edits))

    @property
    def followers(self) -> Sequence[LandingCheck]:
        """The checks that take this one's verdict (empty unless it watches for others)."""
        return self._followers

    @property
    def followers_changed(self) -> int:
        """How many times :attr:`followers` changed: their boxes hold while it does not."""
        return self._followers_changed

    def can_watch(self) -> bool:
        """Return whether VTK made the actor's OpenGL mapper, so that a watch could go to it."""
        return opengl_mapper(self.actor) is not None

    @property
    def attached(self) -> bool:
        """Whether the check watches its mapper or follows a watcher (what :meth:`attach` said)."""
        return self._watcher is not None or self._mapper is not None

    def attach(self) -> bool:
        """Watch the actor's OpenGL mapper, or follow the watcher of its kind; return whether done.

        Its compile errors are watched for as long as the check lives; its
        program only until the next draw has handed it over and it was
        checked (VTK hands it over at every draw, so a Python call per
        receiver per frame would be the price of watching longer). A
        ``vtkDataSetMapper`` makes its inner mapper during its first render,
        so an actor edited before then is watched from the next frame on,
        unless a receiver of the same kind is watched already.

        Returns
        -------
        bool
            ``True`` once the mapper is watched or the check follows a watcher.
        """
        mapper = opengl_mapper(self.actor)
        if mapper is None and self._watcher is None and not self._watchers:
            return False  # nothing to watch nor to follow yet: the variant can wait
        variant = self._shader_variant()
        if variant != self._variant:
            self._reset(self._edits, variant)
        if self._watcher is not None:
            return True
        key = self._key()
        watcher = self._watchers.get(key) if key is not None else None
        if watcher is not None and watcher is not self:
            self._follow(watcher)
            return True
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
        if key is not None and self._watchers.get(key) is not self:
            self._watchers.register(key, self)
        return True

    def _follow(self, watcher: LandingCheck) -> None:
        self._watcher = watcher
        watcher._followers.append(self)
        watcher._followers_changed += 1
        if watcher.settled or watcher.failed:
            self._take(watcher)

    def _take(self, watcher: LandingCheck) -> None:
        """Take the watcher's verdict; tell the owner where it changed."""
        changed = watcher.missing != self.missing or watcher.failed != self.failed
        self.missing, self.failed = list(watcher.missing), watcher.failed
        self.settled = watcher.settled
        if changed:
            self._changed()

    def _leave(self) -> None:
        """Stop following a watcher, or stop watching for others (unsettled followers are told)."""
        if self._watcher is not None:
            self._watcher._followers.remove(self)
            self._watcher._followers_changed += 1
            self._watcher = None
        key = self._key()
        if key is not None and self._watchers.get(key) is self:
            self._watchers.drop(key)
        followers, self._followers = self._followers, []
        self._followers_changed += 1
        for follower in followers:
            follower._watcher = None
            if not (follower.settled or follower.failed):
                follower._changed()

    def hand_over(self, successor: LandingCheck) -> None:
        """Give the watch to ``successor``, one of this check's followers whose mapper exists.

        This check and the other followers follow it from then on.

        Parameters
        ----------
        successor : LandingCheck
            The follower that watches its own mapper from now on.
        """
        key = self._key()
        others = [check for check in self._followers if check is not successor] + [self]
        self._followers = []
        self._followers_changed += 1
        successor._watcher = None
        self._watchers.drop(key)
        if self._mapper is not None and self._program_tag is not None:
            self._mapper.RemoveObserver(self._program_tag)
            self._program_tag = None
        successor.attach()
        for check in others:
            check._watcher = None
            check._follow(successor)

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
        verdict_key = (key, tuple(self._edits))
        verdict = _VERDICTS.get(verdict_key)
        if verdict is None:
            source = program.GetFragmentShader().GetSource()
            verdict = tuple(missing_edits(self._edits, source))
            if len(_VERDICTS) >= _VERDICTS_KEPT:
                _VERDICTS.clear()
            _VERDICTS[verdict_key] = verdict
        # A follower still watching from before (a watch handed over, edits changed)
        # reads its kind's program: the verdict is its watcher's too.
        (self if self._watcher is None else self._watcher)._settle(list(verdict))

    def _settle(self, missing: list[str]) -> None:
        """Take the verdict of a program read with the edits; pass it to the followers."""
        news = missing != self.missing or not self.settled
        self.settled = True
        if missing != self.missing:
            self.missing = missing
            self._changed()
        if news:
            for follower in self._followers:
                follower._take(self)

    @calldata_type(vtk.VTK_STRING)
    def _on_error(self, mapper: vtk.vtkMapper, event: str, message: str) -> None:
        if self._edits and COMPILE_FAILED in (message or ""):
            (self if self._watcher is None else self._watcher)._fail()
        elif message:
            vtk.vtkOutputWindow.GetInstance().DisplayErrorText(message)

    def _fail(self) -> None:
        """Note that the program with the edits did not compile; pass it to the followers."""
        if not self.failed:
            self.failed = True
            self._changed()
            for follower in self._followers:
                follower._take(self)

    def _changed(self) -> None:
        if self.notify is not None:
            self.notify()

    def release(self) -> None:
        """Remove the observers from the mapper, and stop following or watching for others."""
        self._leave()
        if self._mapper is not None:
            for tag in (self._error_tag, self._program_tag):
                if tag is not None:
                    self._mapper.RemoveObserver(tag)
        self._mapper = None
        self._error_tag = self._program_tag = None
