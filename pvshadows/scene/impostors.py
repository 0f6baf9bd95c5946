"""Point clouds and lines that VTK lights: they receive shadows from shadow maps, and cast none.

VTK lights a mesh of points or lines only when it can give each fragment a
normal: points drawn as spheres (``render_points_as_spheres=True``), lines
drawn as tubes (``render_lines_as_tubes=True``), or points and lines with
normals of their own. These actors have no triangles, so:

- they **receive** the shadows of lights served by a shadow map
  (``"cubemap"``, ``"map"``): each fragment looks the map up at its own
  position, along the normal VTK lights it with. Shadow volumes and planar
  shadows are screen-space masks of the triangles' surface; they do not
  reach these actors, which stay lit by those lights;
- they **cast no shadow** (the shadow passes and the ray-cast reference draw
  triangles): a user who wants a point cloud to cast gives it a surface,
  e.g. ``pv.PolyData(points).glyph(geom=pv.Sphere(radius=r))``.

``pl.shadows.last_frame`` names them under each light.
"""

from __future__ import annotations

from pvshadows import _vtk as vtk

#: Techniques whose lookups work at any fragment's own position.
LIGHT_SPACE_TECHNIQUES = frozenset({"cubemap", "map"})


def lit_without_triangles(actor: vtk.vtkActor) -> bool:
    """Return whether VTK lights an actor that has no triangles (spheres, tubes, or normals).

    Parameters
    ----------
    actor : vtk.vtkActor
        A visible actor without triangles.

    Returns
    -------
    bool
        ``True`` when its points or lines are lit, so a shadow can remove that light.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> from pvshadows.scene.impostors import lit_without_triangles
    >>> pl = pv.Plotter(off_screen=True)
    >>> cloud = pl.add_points(np.zeros((3, 3)), render_points_as_spheres=True)
    >>> lit_without_triangles(cloud)
    True
    """
    prop = actor.GetProperty()
    if not prop.GetLighting():
        return False
    if prop.GetRenderPointsAsSpheres() or prop.GetRenderLinesAsTubes():
        return True
    mapper = actor.GetMapper()
    data = mapper.GetInputDataObject(0, 0) if mapper is not None else None
    point_data = data.GetPointData() if data is not None and hasattr(data, "GetPointData") else None
    return point_data is not None and point_data.GetNormals() is not None
