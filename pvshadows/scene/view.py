"""What the camera shows in one frame: its matrices, viewport and frustum, built once.

VTK can draw one frame in pieces (tiles of a large screenshot, a larger
framebuffer for SSAA); a :class:`FrameView` describes the piece being drawn,
so build one per render target from that target's renderer and camera.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows._cached import cached
from pvshadows.geometry.transforms import from_vtk_matrix
from pvshadows.scene.culling import clip_planes

#: The corners of the near plane in clip coordinates.
_NEAR_CORNERS = np.array([[x, y, -1.0, 1.0] for x in (-1.0, 1.0) for y in (-1.0, 1.0)])
#: A matrix VTK inverts into, then read: VTK's routine is cheaper to call than numpy's.
_INVERSE = vtk.vtkMatrix4x4()


def _inverse(matrix: vtk.vtkMatrix4x4) -> np.ndarray:
    """Return the inverse of a VTK matrix."""
    vtk.vtkMatrix4x4.Invert(matrix, _INVERSE)
    return from_vtk_matrix(_INVERSE)


@dataclass(frozen=True)
class FrameView:
    """The camera of one render target in one frame.

    Attributes
    ----------
    world_to_view : numpy.ndarray
        VTK's view matrix (``vertexVC`` in shaders), float64 ``(4, 4)``.
    view_to_world : numpy.ndarray
        Its inverse.
    world_to_clip : numpy.ndarray
        The camera's projection (depth in [-1, 1]) times :attr:`world_to_view`.
    aspect : float
        The renderer's tiled aspect ratio.
    viewport : tuple of int
        Width and height of the renderer in pixels.
    planes : numpy.ndarray
        ``(6, 4)`` world frustum planes (see :func:`pvshadows.scene.culling.frustum_planes`).
    stamp : tuple
        The camera's modification time, the aspect ratio and the size it
        was built at: a view with the same stamp is the same view.
    """

    world_to_view: np.ndarray
    view_to_world: np.ndarray
    world_to_clip: np.ndarray
    aspect: float
    viewport: tuple[int, int]
    planes: np.ndarray
    stamp: tuple = ()
    #: The camera's VTK matrices this view was read from, and the one its camera lights
    #: follow (every frame's :func:`~pvshadows.scene.lights.pose_time` reads it). Held
    #: only so that their Python wrappers live on: VTK makes a wrapper afresh, looking
    #: its class up by name, for an object that Python no longer holds.
    _matrices: tuple = field(default=(), repr=False, compare=False)

    @classmethod
    def of(cls, renderer: vtk.vtkRenderer, last: FrameView | None = None) -> FrameView:
        """Build the view of a renderer's active camera as it is now.

        Parameters
        ----------
        renderer : vtk.vtkRenderer
            The renderer (or tile) being drawn.
        last : FrameView, optional
            The view of the last frame, returned itself when the camera,
            aspect ratio and size did not change since.

        Returns
        -------
        FrameView
            Its matrices, viewport and frustum planes.

        Examples
        --------
        >>> import pyvista as pv
        >>> from pvshadows.scene.view import FrameView
        >>> pl = pv.Plotter(off_screen=True, window_size=(400, 300))
        >>> view = FrameView.of(pl.renderer)
        >>> view.planes.shape, round(view.aspect, 3)
        ((6, 4), 1.333)
        """
        # VTK's own methods, called on the class: PyVista's wrappers check every
        # attribute they are asked for, a cost paid each frame.
        camera = vtk.vtkRenderer.GetActiveCamera(renderer)
        aspect = float(vtk.vtkRenderer.GetTiledAspectRatio(renderer))
        width, height = vtk.vtkRenderer.GetSize(renderer)
        stamp = (camera, vtk.vtkCamera.GetMTime(camera), aspect, width, height)
        if last is not None and last.stamp == stamp:
            return last
        to_view = vtk.vtkCamera.GetModelViewTransformMatrix(camera)
        # VTK multiplies projection and view itself: one call, no product in Python
        to_clip = vtk.vtkCamera.GetCompositeProjectionTransformMatrix(camera, aspect, -1, 1)
        world_to_clip = from_vtk_matrix(to_clip)
        return cls(
            from_vtk_matrix(to_view),
            _inverse(to_view),
            world_to_clip,
            aspect,
            (int(width), int(height)),
            clip_planes(world_to_clip),
            stamp,
            (to_view, to_clip, vtk.vtkCamera.GetCameraLightTransformMatrix(camera)),
        )

    @cached
    def projection(self) -> np.ndarray:
        """View to clip coordinates, depth in [-1, 1] (read from the camera when first asked)."""
        camera, _, aspect = self.stamp[:3]
        return from_vtk_matrix(vtk.vtkCamera.GetProjectionTransformMatrix(camera, aspect, -1, 1))

    @cached
    def clip_to_world(self) -> np.ndarray:
        """The inverse of :attr:`world_to_clip` (computed when first asked)."""
        camera, _, aspect = self.stamp[:3]
        return _inverse(vtk.vtkCamera.GetCompositeProjectionTransformMatrix(camera, aspect, -1, 1))

    @cached
    def near_region(self) -> np.ndarray | None:
        """The camera's position and its near-plane corners (worked out when first asked).

        ``(5, 3)`` float64 world points, the camera first; ``None`` for a
        parallel projection, whose view rays start at infinity behind the camera.
        """
        camera = self.stamp[0]
        if vtk.vtkCamera.GetParallelProjection(camera):
            return None
        corners = _NEAR_CORNERS @ self.clip_to_world.T
        return np.vstack([vtk.vtkCamera.GetPosition(camera), corners[:, :3] / corners[:, 3:4]])

    def to_frame_at(self, origin: np.ndarray) -> np.ndarray:
        """Return the matrix from view coordinates to world axes moved to ``origin``.

        Parameters
        ----------
        origin : numpy.ndarray
            ``(3,)`` world point, e.g. a point light's position.

        Returns
        -------
        numpy.ndarray
            ``(4, 4)``: ``translation(-origin) @ view_to_world``.

        Examples
        --------
        >>> import numpy as np
        >>> import pyvista as pv
        >>> from pvshadows.scene.view import FrameView
        >>> view = FrameView.of(pv.Plotter(off_screen=True).renderer)
        >>> camera = view.to_frame_at(np.zeros(3)) @ np.array([0.0, 0.0, 0.0, 1.0])
        >>> np.allclose(camera[:3], view.view_to_world[:3, 3])
        True
        """
        # The view-to-world matrix is affine: moving the origin shifts its last column.
        moved = self.view_to_world.copy()
        moved[:3, 3] -= origin
        return moved

    def light_in_view(self, light: np.ndarray) -> np.ndarray:
        """Return a homogeneous world light vector in view coordinates.

        Parameters
        ----------
        light : numpy.ndarray
            ``(x, y, z, 1)`` for a positional light, ``(d, 0)`` with ``d``
            pointing towards a directional light.

        Returns
        -------
        numpy.ndarray
            The same in view coordinates; a direction comes back of unit length.

        Examples
        --------
        >>> import numpy as np
        >>> import pyvista as pv
        >>> from pvshadows.scene.view import FrameView
        >>> view = FrameView.of(pv.Plotter(off_screen=True).renderer)
        >>> float(np.linalg.norm(view.light_in_view(np.array([0, 0, 5.0, 0])[:4])[:3]))
        1.0
        """
        in_view = self.world_to_view @ np.asarray(light, dtype=np.float64)
        if light[3] == 0.0:
            in_view[:3] /= np.linalg.norm(in_view[:3])
        return in_view
