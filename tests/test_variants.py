"""Every shader variant VTK builds for a receiver compiles with pvshadows' edits.

VTK's mapper writes a different fragment shader for surfaces, lines and
vertices, with and without normals, scalars, textures, lights, PBR, points as
spheres and lines as tubes. Each variant is drawn with shadows on: VTK must
report no error, the receiver must still be drawn where it was drawn without
shadows, and every required edit must have landed in the program VTK compiled
(``last_frame.receivers`` names any receiver for which one did not).
"""

import numpy as np
import pytest
import pyvista as pv
from pyvista.core.utilities.observers import VtkErrorCatcher

import pvshadows.shaders.shading
from conftest import draw, point_light
from pvshadows.scene.triangles import vtk_id

SIZE = (240, 180)


def _surface_without_normals():
    mesh = pv.Sphere(radius=0.6, center=(0, 0, 1.2))
    mesh.point_data.clear()
    return mesh


def _surface_and_line():
    line = pv.Line((-1.5, 0.5, 0.8), (1.5, 0.5, 0.8))
    return pv.Sphere(radius=0.6, center=(0, 0, 1.2)).merge(line, merge_points=False)


def _surface_and_vertices():
    sphere = pv.Sphere(radius=0.6, center=(0, 0, 1.2))
    vertices = pv.PolyData(np.array([[-1.2, 0.0, 0.8], [1.2, 0.0, 0.8], [0.0, 1.2, 0.8]]))
    return sphere.merge(vertices, merge_points=False)


def _polyline():
    return pv.Spline(np.array([[-1.5, -0.5, 0.6], [0.0, 0.5, 1.4], [1.5, -0.5, 0.6]]), 40)


def _cloud():
    rng = np.random.default_rng(0)
    return pv.PolyData(rng.uniform((-1, -1, 0.6), (1, 1, 1.6), (200, 3)))


def _textured():
    mesh = pv.Plane(center=(0, 0, 1.0), i_size=2, j_size=2)
    image = np.zeros((8, 8, 3), dtype=np.uint8)
    image[::2, ::2] = 255
    return mesh, {"texture": pv.Texture(image)}


#: Variant name -> (mesh, add_mesh keywords).
VARIANTS = {
    "surface": lambda: (pv.Sphere(radius=0.6, center=(0, 0, 1.2)), {}),
    "surface smooth": lambda: (pv.Sphere(radius=0.6, center=(0, 0, 1.2)), {"smooth_shading": True}),
    "surface without normals": lambda: (_surface_without_normals(), {}),
    "surface with scalars": lambda: (
        pv.Sphere(radius=0.6, center=(0, 0, 1.2)).elevation(),
        {"scalars": "Elevation"},
    ),
    "surface with cell scalars": lambda: (
        pv.Sphere(radius=0.6, center=(0, 0, 1.2)).compute_cell_sizes(),
        {"scalars": "Area"},
    ),
    "surface textured": _textured,
    "surface pbr": lambda: (
        pv.Sphere(radius=0.6, center=(0, 0, 1.2)),
        {"pbr": True, "metallic": 0.2, "roughness": 0.5},
    ),
    "surface unlit": lambda: (pv.Sphere(radius=0.6, center=(0, 0, 1.2)), {"lighting": False}),
    "surface as points": lambda: (pv.Sphere(radius=0.6, center=(0, 0, 1.2)), {"style": "points"}),
    "surface as wireframe": lambda: (
        pv.Sphere(radius=0.6, center=(0, 0, 1.2)),
        {"style": "wireframe"},
    ),
    "surface with edges": lambda: (pv.Sphere(radius=0.6, center=(0, 0, 1.2)), {"show_edges": True}),
    "surface and line": lambda: (_surface_and_line(), {}),
    "surface and vertices": lambda: (_surface_and_vertices(), {}),
    "lines": lambda: (_polyline(), {"line_width": 3}),
    "lines as tubes": lambda: (_polyline(), {"line_width": 6, "render_lines_as_tubes": True}),
    "points": lambda: (_cloud(), {"point_size": 4}),
    "points as spheres": lambda: (_cloud(), {"point_size": 8, "render_points_as_spheres": True}),
    "points as spheres pbr": lambda: (
        _cloud(),
        {"point_size": 8, "render_points_as_spheres": True, "pbr": True},
    ),
}


def _scene(lights=True):
    lighting = "none" if not lights else "light kit"
    pl = pv.Plotter(off_screen=True, window_size=SIZE, lighting=lighting)
    pl.add_mesh(pv.Plane(i_size=6, j_size=6), color="white")
    if lights:
        pl.add_light(point_light((0.4, -0.3, 3.5)))
    pl.camera_position = [(4.0, -6.0, 5.0), (0.0, 0.0, 0.8), (0.0, 0.0, 1.0)]
    return pl


def _drawn(pl, actor):
    """Pixels that ``actor`` covers in the current frame (where hiding it changes the image)."""
    actor.SetVisibility(False)
    hidden = draw(pl).astype(int)
    actor.SetVisibility(True)
    shown = draw(pl).astype(int)
    return np.abs(shown - hidden).max(axis=-1) > 8


def _check_variant(pl, actor):
    before = _drawn(pl, actor)
    assert before.sum() > 50, "the variant draws nothing even without shadows"
    pl.shadows.enable()
    with VtkErrorCatcher() as catcher:
        after = _drawn(pl, actor)
    assert not catcher.events, catcher.events[0]
    kept = (after & before).sum() / before.sum()
    assert kept > 0.9, f"only {kept:.0%} of the variant's pixels are drawn with shadows on"
    assert pl.shadows.last_frame.receivers == []
    key = vtk_id(actor)
    edits = [r._edits.of(key) for r in pl.shadows._renderers if r._edits.of(key) is not None]
    assert edits and edits[0].check.checked >= 1  # its compiled program was read and checked


@pytest.mark.parametrize("variant", list(VARIANTS))
def test_variant_compiles_and_is_drawn(variant):
    pl = _scene()
    mesh, keywords = VARIANTS[variant]()
    if "scalars" not in keywords and "texture" not in keywords:
        keywords["color"] = "tan"
    actor = pl.add_mesh(mesh, **keywords)
    _check_variant(pl, actor)


def test_plotter_without_lights():
    pl = _scene(lights=False)
    actor = pl.add_mesh(pv.Sphere(radius=0.6, center=(0, 0, 1.2)), color="blue")
    before = _drawn(pl, actor)
    pl.shadows.enable()
    with VtkErrorCatcher() as catcher:
        after = _drawn(pl, actor)
    assert not catcher.events, catcher.events[0]
    assert (after & before).sum() / before.sum() > 0.9
    assert pl.shadows.last_frame.receivers == []


@pytest.mark.parametrize("drawn_first", [True, False], ids=["drawn first", "edited first"])
def test_edit_that_does_not_land_is_reported(monkeypatch, drawn_first):
    # As if VTK's generated code had changed: the light hooks look for text VTK no longer writes.
    # A vtkDataSetMapper makes the mapper that compiles its shaders during its first draw:
    # edits put on before then are watched from the next frame.
    hooks = pvshadows.shaders.shading._light_hooks

    def reworded(*args):
        return [(original.replace("(df * ", "(df*"), new) for original, new in hooks(*args)]

    monkeypatch.setattr(pvshadows.shaders.shading, "_light_hooks", reworded)
    pl = _scene()
    pl.add_mesh(pv.Sphere(radius=0.6, center=(0, 0, 1.2)), color="tan")
    if drawn_first:
        draw(pl)
    with pytest.warns(UserWarning, match="did not land"):
        pl.shadows.enable()
        draw(pl)
        if not drawn_first:
            draw(pl)
    notes = pl.shadows.last_frame.receivers
    assert len(notes) == 2  # the plane and the sphere
    assert all("diffuse += (df*lightColor" in note for note in notes)


def test_variant_that_does_not_compile_is_left_as_vtk_built_it(monkeypatch):
    monkeypatch.setattr(pvshadows.shaders.shading, "_FACET_NORMAL", "\n  pvsFacetVC = ;")
    pl = _scene()
    pl.add_mesh(pv.Sphere(radius=0.6, center=(0, 0, 1.2)), color="tan")
    plain = draw(pl).astype(int)
    pl.shadows.enable()
    with VtkErrorCatcher(), pytest.warns(UserWarning, match="does not compile"):
        draw(pl)  # the failed compile is noticed here
        drawn = [draw(pl).astype(int) for _ in range(2)]
    for image in drawn:
        assert np.abs(image - plain).max() <= 2  # unshadowed, exactly as VTK draws it
    notes = pl.shadows.last_frame.receivers
    assert len(notes) == 2 and all("does not compile" in note for note in notes)
