"""Figures and reports of the "How it works" page, made from one real frame.

Run by the docs build (``python docs/_ext/how_it_works.py OUT``): renders the
demo scene lit by a bulb and a low sun, then writes into ``OUT``

- ``frame_passes.png``: the passes of one frame in order, with what each one
  reported in this frame, above the plain frame, the bulb's depth cube and
  the shadowed frame;
- ``cube_faces.png``: the bulb's depth cube read back from the GPU, its six
  faces unrolled around the floor;
- ``probe.png``: the bulb's visibility as rendered, the ray-traced reference
  and the pixels where they disagree;
- ``last_frame_first.txt`` (the first frame), ``last_frame.txt`` (a later
  one, the bulb moved a hair: the frame of the figures),
  ``last_frame_orbit.txt`` (the camera moved) and ``measure.txt``: what
  ``pl.shadows.last_frame`` and ``pl.shadows.measure`` printed.

Nothing in the figures is typed by hand: every number comes from the frame.
"""

from __future__ import annotations

import os
import re
import sys
import textwrap
from pathlib import Path

if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pyvista as pv
from matplotlib.patches import FancyArrowPatch, FancyBboxPatch, Rectangle

import pvshadows  # noqa: F401  (registers pl.shadows)

FACES = ("+X", "-X", "+Y", "-Y", "+Z", "-Z")
#: The unrolled cube around the floor: grid cell -> (face seen, image right, image up).
CROSS = {
    (1, 0): ("-X", (0, 0, -1), (0, 1, 0)),
    (1, 1): ("-Z", (1, 0, 0), (0, 1, 0)),
    (1, 2): ("+X", (0, 0, 1), (0, 1, 0)),
    (1, 3): ("+Z", (-1, 0, 0), (0, 1, 0)),
    (0, 1): ("+Y", (1, 0, 0), (0, 0, 1)),
    (2, 1): ("-Y", (1, 0, 0), (0, 0, -1)),
}
AXES = {"+X": (1, 0, 0), "-X": (-1, 0, 0), "+Y": (0, 1, 0), "-Y": (0, -1, 0)}
AXES |= {"+Z": (0, 0, 1), "-Z": (0, 0, -1)}


def demo_scene(window_size=(800, 600)):
    """Return the plotter, the bulb and the sun of the demo scene."""
    pl = pv.Plotter(off_screen=True, window_size=list(window_size), lighting="none")
    pl.set_background("#f4f1ea", top="#bcc8d6")
    style = {"ambient": 0.15, "diffuse": 0.85, "specular": 0.2, "smooth_shading": True}
    pl.add_mesh(pv.Plane(i_size=10, j_size=10), color="#d9d4c7", **style)
    pl.add_mesh(pv.Box(bounds=(-2.6, -1.4, -0.9, 0.3, 1.3, 2.1)), color="#c0504d", **style)
    pl.add_mesh(pv.Sphere(radius=0.7, center=(1.6, 1.4, 0.7)), color="#4f81bd", **style)
    pl.add_mesh(
        pv.Cylinder(center=(0.9, -2.1, 0.9), direction=(0, 0, 1), radius=0.45, height=1.8),
        color="#9bbb59",
        **style,
    )
    bulb = pv.Light(position=(0.3, -0.2, 3.5), positional=True, cone_angle=180, intensity=0.8)
    sun = pv.Light(position=(-6, -3, 3), focal_point=(0, 0, 0), intensity=0.35)
    pl.add_light(bulb)
    pl.add_light(sun)
    pl.camera_position = [(11.0, -12.5, 9.5), (0.0, 0.0, 0.3), (0, 0, 1)]
    return pl, bulb, sun


def cube_direction_to_texel(directions: np.ndarray, resolution: int):
    """Return the face and texel OpenGL samples for each direction (the cube-map rule)."""
    x, y, z = directions[..., 0], directions[..., 1], directions[..., 2]
    ax, ay, az = np.abs(x), np.abs(y), np.abs(z)
    face = np.where(
        (ax >= ay) & (ax >= az),
        np.where(x > 0, 0, 1),
        np.where(ay >= az, np.where(y > 0, 2, 3), np.where(z > 0, 4, 5)),
    )
    # (sc, tc, major) per face, as in the OpenGL specification's table.
    sc = np.choose(face, [-z, z, x, x, x, -x])
    tc = np.choose(face, [-y, -y, z, -z, -y, -y])
    major = np.choose(face, [ax, ax, ay, ay, az, az])
    s = np.clip(((sc / major + 1) / 2 * resolution).astype(int), 0, resolution - 1)
    t = np.clip(((tc / major + 1) / 2 * resolution).astype(int), 0, resolution - 1)
    return face, t, s


def unrolled_cube(faces: np.ndarray, cell: int = 256) -> np.ndarray:
    """Return the cube's depths unrolled into a cross around its floor (NaN outside)."""
    resolution = faces.shape[-1]
    picture = np.full((3 * cell, 4 * cell), np.nan, np.float32)
    u = (np.arange(cell) + 0.5) / cell * 2 - 1
    across, up = np.meshgrid(u, -u)
    for (row, col), (name, right, above) in CROSS.items():
        directions = (
            np.array(AXES[name], float)
            + across[..., None] * np.array(right, float)
            + up[..., None] * np.array(above, float)
        )
        face, t, s = cube_direction_to_texel(directions, resolution)
        picture[row * cell : (row + 1) * cell, col * cell : (col + 1) * cell] = faces[face, t, s]
    return picture


def draw_cross(axes, faces: np.ndarray, skipped: set[str], fontsize: float = 8):
    """Draw the unrolled cube with its face names; texels holding no caster in grey."""
    picture = unrolled_cube(faces)
    colours = matplotlib.colormaps["magma"].with_extremes(over="#d4d4d4", bad="white")
    shown = axes.imshow(picture, cmap=colours, vmin=0.0, vmax=0.9999)
    cell = picture.shape[0] // 3
    for (row, col), (name, _, _) in CROSS.items():
        axes.add_patch(
            Rectangle((col * cell - 0.5, row * cell - 0.5), cell, cell, fill=False, lw=0.6)
        )
        words = name + (" (skipped: no caster)" if name in skipped else "")
        axes.text(col * cell + 6, row * cell + 6, words, fontsize=fontsize, va="top", ha="left")
    axes.set_axis_off()
    return shown


def box(axes, x, y, width, height, title, body, colour):
    """Draw one step of the frame: a rounded box with a title and wrapped text."""
    axes.add_patch(
        FancyBboxPatch(
            (x, y),
            width,
            height,
            boxstyle="round,pad=0.008,rounding_size=0.015",
            facecolor=colour,
            edgecolor="0.35",
            linewidth=0.8,
        )
    )
    axes.text(x + 0.008, y + height - 0.014, title, fontsize=10.5, weight="bold", va="top")
    axes.text(x + 0.008, y + height - 0.062, body, fontsize=7.6, va="top")


def wrap(lines: list[str], width: int = 29) -> str:
    """Wrap each line to ``width`` characters."""
    return "\n".join(textwrap.fill(line, width, subsequent_indent="  ") for line in lines)


def frame_figure(pl, plain, shadowed, faces, skipped, path: Path) -> None:
    """Draw the passes of one frame, with what each reported, above three pictures."""
    renderer = pl.shadows._renderers[0]
    snapshot = renderer.snapshot
    frame = pl.shadows.last_frame
    planned = [
        f"light {light.index} ({light.kind}): {light.technique or 'no shadow'}"
        for light in frame.lights
    ]
    passes = [
        f"light {light.index}, {p.name}: {p.status.upper()}"
        + (f" in {p.ms:.2f} ms" if p.ms is not None else "")
        + (f" - {p.detail}" if p.detail else "")
        for light in frame.lights
        for p in light.passes
    ]
    steps = [
        ("1 StartEvent", ["renderer observer, runs before VTK draws anything"], "#e8eef7"),
        (
            "2 Snapshot",
            [
                f"{len(snapshot.actors)} actors with triangles",
                f"{len(snapshot.casters)} casters, {len(snapshot.receivers)} receivers",
                "triangles re-read only when an actor's data changed",
            ],
            "#e8eef7",
        ),
        ("3 Planner", [*planned, "which lights cast, casters in reach, what is reused"], "#f7efe0"),
        ("4 Shadow passes", passes, "#f7e3e0"),
        (
            "5 Receivers",
            [
                "shader edits: each light's diffuse and specular times its visibility",
                "maps bound to texture units, uniforms set",
            ],
            "#e6f2e6",
        ),
        ("6 VTK draws", ["the frame, as without shadows, with the edited shaders"], "#e6f2e6"),
        (
            "7 EndEvent",
            [
                "texture units freed",
                f"GPU timers read: {frame.gpu_ms:.2f} ms of passes",
                "-> pl.shadows.last_frame",
            ],
            "#e8eef7",
        ),
    ]
    figure = plt.figure(figsize=(15, 8.2), dpi=110)
    axes = figure.add_axes((0, 0, 1, 1))
    axes.set_xlim(0, 1)
    axes.set_ylim(0, 1)
    axes.set_axis_off()
    width, gap, top, height = 0.128, 0.0125, 0.975, 0.33
    for index, (title, lines, colour) in enumerate(steps):
        x = 0.01 + index * (width + gap)
        box(axes, x, top - height, width, height, title, wrap(lines), colour)
        if index:
            axes.add_patch(
                FancyArrowPatch(
                    (x - gap + 0.001, top - height / 2),
                    (x - 0.001, top - height / 2),
                    arrowstyle="-|>",
                    mutation_scale=10,
                    color="0.3",
                )
            )
    pictures = [
        (plain, (0.01, 0.02, 0.32, 0.54), "the scene VTK draws (shadows off)"),
        (None, (0.34, 0.02, 0.32, 0.54), "4: the bulb's depth cube (distance / far), unrolled"),
        (shadowed, (0.67, 0.02, 0.32, 0.54), "6: the same frame with shadows"),
    ]
    for image, rect, caption in pictures:
        inset = figure.add_axes(rect)
        if image is None:
            draw_cross(inset, faces, skipped, fontsize=6.5)
        else:
            inset.imshow(image)
            inset.set_axis_off()
        inset.set_title(caption, fontsize=10)
    figure.savefig(path)
    plt.close(figure)


def cube_figure(faces, skipped, far, path: Path) -> None:
    """Draw the bulb's depth cube unrolled, large, with a colour bar."""
    figure, axes = plt.subplots(figsize=(10, 6.2), dpi=110)
    shown = draw_cross(axes, faces, skipped)
    bar = figure.colorbar(shown, ax=axes, fraction=0.03)
    bar.set_label(f"distance to the bulb / far (far = {far:.3g})")
    axes.set_title("The bulb's depth cube, read back from the GPU: floor (-Z) in the middle")
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)


def grown(mask: np.ndarray, pixels: int = 1) -> np.ndarray:
    """Return ``mask`` grown by ``pixels`` in every direction, so single pixels show."""
    out = mask.copy()
    for dy in range(-pixels, pixels + 1):
        for dx in range(-pixels, pixels + 1):
            out |= np.roll(np.roll(mask, dy, axis=0), dx, axis=1)
    return out


def probe_figure(shown, traced, error, path: Path) -> None:
    """Draw the visibility as rendered, the reference and where they disagree."""
    exact, lit = traced.visibility, traced.lit_side & np.isfinite(shown)
    disagree = np.where(lit, 0.5, np.nan)
    disagree[grown(lit & (shown >= 0.5) & (exact < 0.5))] = 0.0  # drawn lit, dark in truth
    disagree[grown(lit & (shown < 0.5) & (exact >= 0.5))] = 1.0  # drawn dark, lit in truth
    grey = matplotlib.colormaps["gray"].with_extremes(bad="#9fb3c8")
    figure, panels = plt.subplots(1, 3, figsize=(15, 4.4), dpi=110)
    panels[0].imshow(shown, cmap=grey, vmin=0, vmax=1)
    panels[0].set_title("pl.shadows.visibility(bulb): as rendered")
    panels[1].imshow(exact, cmap=grey, vmin=0, vmax=1)
    panels[1].set_title("pl.shadows.reference(bulb): ray traced")
    panels[2].imshow(disagree, cmap="coolwarm", vmin=0, vmax=1)
    panels[2].set_title(
        f"{100 * error.misclassified:.3f} % of {error.lit_pixels} lit-side pixels disagree\n"
        "red: drawn dark, lit in truth; blue: drawn lit, dark in truth (grown 1 px)",
        fontsize=10,
    )
    for panel in panels:
        panel.set_axis_off()
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)


def main(out: Path) -> None:
    """Render the frame and write the figures and reports into ``out``."""
    out.mkdir(parents=True, exist_ok=True)
    pl, bulb, sun = demo_scene()
    plain = pl.screenshot(return_img=True)
    pl.shadows.enable(resolution=1024, filter="pcf")
    pl.screenshot(return_img=True)
    (out / "last_frame_first.txt").write_text(f"{pl.shadows.last_frame}\n", encoding="utf-8")
    pl.render()  # the clipping range settles; the same frame again reuses both maps
    # The bulb moved a hair: its cube is drawn again, the sun's map is reused.
    bulb.position = tuple(np.array(bulb.position) + 1e-4)
    pl.render()
    shadowed = pl.screenshot(return_img=True)
    frame = pl.shadows.last_frame
    (out / "last_frame.txt").write_text(f"{frame}\n", encoding="utf-8")

    renderer = pl.shadows._renderers[0]
    pl.ren_win.MakeCurrent()
    cube = renderer.technique("cubemap")
    faces = cube.cube_of(bulb).read_faces()
    far = cube._states[next(iter(cube._states))].far
    words = " ".join(p.detail for light in frame.lights for p in light.passes)
    found = re.search(r"skipped \(no caster in frustum\): ([-+XYZ ]+)", words)
    skipped = set(found.group(1).split()) if found else set()

    frame_figure(pl, plain, shadowed, faces, skipped, out / "frame_passes.png")
    cube_figure(faces, skipped, far, out / "cube_faces.png")

    error = pl.shadows.measure(bulb)
    shown = pl.shadows.visibility(bulb)
    probe_figure(shown, pl.shadows._trace(bulb), error, out / "probe.png")
    (out / "measure.txt").write_text(
        f"bulb: {error}\nsun:  {pl.shadows.measure(sun)}\n", encoding="utf-8"
    )

    pl.camera.azimuth = 25.0
    pl.screenshot(return_img=True)
    (out / "last_frame_orbit.txt").write_text(f"{pl.shadows.last_frame}\n", encoding="utf-8")
    pl.close()


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "how_it_works"))
