"""What every technique receives each frame, and what it must provide."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Protocol, TypeVar

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.gl.actor_buffers import ActorBuffers
from pvshadows.gl.frame_block import LightEntry
from pvshadows.gl.timing import PassTimer
from pvshadows.model.plan import Cast
from pvshadows.model.report import PassReport
from pvshadows.scene.render_target import RenderTarget, render_target
from pvshadows.scene.snapshot import Snapshot
from pvshadows.scene.view import FrameView
from pvshadows.shaders.shading import LightShading


@dataclass
class FrameContext:
    """What a technique may read in one frame.

    Attributes
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context is current.
    renderer : vtk.vtkRenderer
        The renderer being drawn.
    camera : vtk.vtkCamera
        Its active camera.
    snapshot : Snapshot
        Its actors this frame.
    frame : int
        Frame counter of this renderer.
    buffers : ActorBuffers
        GPU copies of the actors' triangles, shared by all techniques.
    timer : PassTimer
        Measures each pass's GPU time.
    view : FrameView
        The camera's matrices, viewport and frustum for the target being
        drawn, built once for the frame.
    """

    window: vtk.vtkOpenGLRenderWindow
    renderer: vtk.vtkRenderer
    camera: vtk.vtkCamera
    snapshot: Snapshot
    frame: int
    buffers: ActorBuffers
    timer: PassTimer
    view: FrameView

    def viewport_size(self) -> tuple[int, int]:
        """Return the size in pixels of what the renderer is drawn into this frame.

        The tile being drawn of a scaled screenshot, or the larger framebuffer
        of an SSAA pass (:func:`pvshadows.scene.render_target.render_target`).
        """
        return self._target.size

    def target(self) -> RenderTarget:
        """Return the rectangle the renderer's actors are drawn into this frame."""
        return self._target

    @cached
    def _target(self) -> RenderTarget:
        """The render target, read once: a context is made for each one VTK draws into."""
        return render_target(self.renderer)


@dataclass(slots=True)
class LightFrame:
    """What a technique gave one light in one frame, kept for the next.

    Attributes
    ----------
    passes : list of PassReport
        The passes run, reused or skipped.
    shading : LightShading
        How receivers read the light's shadow data.
    entry : LightEntry
        The light's entry of the frame's uniform block; not changed once
        handed to the block.
    samplers : dict
        The receivers' textures by uniform name.
    again : bool
        Whether it is an earlier frame's handed back (:meth:`Technique.again`):
        its passes then are reported reused.
    """

    passes: list[PassReport]
    shading: LightShading
    entry: LightEntry
    samplers: dict[str, object]
    again: bool = False


class Releasable(Protocol):
    """Something holding GPU resources: a pass's programs, a map's texture."""

    def release(self) -> None:
        """Release them."""


#: The kind of cast a technique draws (a volume technique needs a :class:`VolumeCast`).
CastT = TypeVar("CastT", bound=Cast, contravariant=True)


class Technique(Protocol[CastT]):
    """A shadow technique: the maps it keeps, the passes it runs, the shading it asks for.

    One object serves every light of a renderer that uses the technique.
    """

    name: ClassVar[str]

    def update(self, plan: CastT, context: FrameContext) -> list[PassReport]:
        """Bring the light's shadow data up to date; report each pass run, reused or skipped."""

    def shading(self, plan: CastT) -> LightShading:
        """Return how receivers read the light's shadow data."""

    def activate(self, plan: CastT, context: FrameContext, entry: LightEntry) -> dict[str, object]:
        """Fill the light's entry of the frame's block; return the receivers' textures by name."""

    def again(
        self, plan: CastT, context: FrameContext, last: LightFrame, same_view: bool
    ) -> LightFrame | None:
        """Return last frame's :class:`LightFrame` of a light for this frame, if it still holds.

        It holds when the light's cast is last frame's (``plan`` is the
        cast ``last`` was made for) and its shadow data, shading and
        textures are as they were then: the entry is then last frame's, its
        view-to-light matrix made for this frame's camera unless
        ``same_view``. ``None`` asks the frame to run :meth:`update`,
        :meth:`shading` and :meth:`activate`.
        """

    def end_frame(self) -> None:
        """Let go of what only this frame needed, once its receivers drew."""

    def keep_only(self, plans: list[Cast]) -> None:
        """Release what lights that no longer use the technique held."""

    def release(self) -> None:
        """Release every GPU resource."""
