"""The demo scene: what ``pvshadows demo`` renders."""

from __future__ import annotations

from pathlib import Path

import pyvista as pv

from pvshadows.tools.scenes import standard_scene


def render_demo(
    out: str | Path = "shadows.png", *, window_size: tuple[int, int] = (1024, 768)
) -> Path:
    """Render the standard scene lit by a bare bulb, with the default shadows, to a PNG.

    The shadows are ``pl.shadows.enable()``'s: ``quality="balanced"``, soft edges.

    Parameters
    ----------
    out : str or pathlib.Path, default: "shadows.png"
        Where to write the picture.
    window_size : tuple of int, default: (1024, 768)
        Picture size in pixels.

    Returns
    -------
    pathlib.Path
        The file written.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from pvshadows.tools.demo import render_demo
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = render_demo(pathlib.Path(folder) / "demo.png", window_size=(320, 240))
    ...     path.stat().st_size > 0
    True
    """
    import pvshadows  # noqa: F401 - registers pl.shadows

    scene = standard_scene(window_size=window_size)
    plotter = scene.plotter
    plotter.set_background("#f4f1ea", top="#bcc8d6")  # type: ignore[arg-type]  # pyvista: decorated, self untyped
    bulb = plotter.add_mesh(
        pv.Sphere(radius=0.12, center=scene.light.position),
        color="#fff6c8",
        lighting=False,
        name="bulb",
    )
    plotter.shadows.enable()
    plotter.shadows.set_caster(bulb, False)
    path = Path(out)
    path.parent.mkdir(parents=True, exist_ok=True)
    plotter.screenshot(str(path))
    plotter.close()
    return path
