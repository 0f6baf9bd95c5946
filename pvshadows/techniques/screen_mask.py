"""How receivers read a screen mask: what shadow volumes and planar shadows share.

Both techniques leave, per light, a mask the size of the viewport (1 where
the light reaches the surface seen in the pixel, 0 where it is shadowed);
a receiver reads it at its own pixel, times a facing test
(``glsl/shadow_mask.glsl``). These functions give the shading and the
uniforms of that lookup, so both techniques name them the same way, and
tell alike whether last frame's mask is this frame's (:func:`mask_holds`).
"""

from __future__ import annotations

from pvshadows.gl.frame_block import LightEntry
from pvshadows.gl.mask_target import MaskTexture
from pvshadows.gl.sampler_units import TextureBinding
from pvshadows.model.plan import Cast
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext

#: The GLSL file of the lookup.
MASK_SOURCE = "shadow_mask.glsl"


def facing_shading(vtk_index: int) -> LightShading:
    """Return the facing test alone: 0 where the visible side faces away from the light.

    Parameters
    ----------
    vtk_index : int
        The light's index among VTK's lights.

    Returns
    -------
    LightShading
        The call, reading the light's ``lightVC`` in the frame's uniform block.

    Examples
    --------
    >>> from pvshadows.techniques.screen_mask import facing_shading
    >>> facing_shading(2).visibility
    'pvsFacingLight(pvsLights[2].lightVC, vertexVC.xyz, pvsNormalVC)'
    """
    return LightShading(
        vtk_index,
        f"pvsFacingLight(pvsLights[{vtk_index}].lightVC, vertexVC.xyz, pvsNormalVC)",
        sources=(MASK_SOURCE,),
    )


def mask_shading(
    vtk_index: int,
    only_on: frozenset[str] | None = None,
    elsewhere: LightShading | None = None,
) -> LightShading:
    """Return the mask lookup of a light, times the facing test.

    Parameters
    ----------
    vtk_index : int
        The light's index among VTK's lights.
    only_on, elsewhere : optional
        As :class:`LightShading` takes them, for a mask that covers some
        receivers only.

    Returns
    -------
    LightShading
        The call, reading the sampler ``pvsMask{i}`` and, in the frame's
        uniform block, the viewport and the light's ``lightVC``.

    Examples
    --------
    >>> from pvshadows.techniques.screen_mask import mask_shading
    >>> mask_shading(0).samplers
    {'pvsMask0': 'sampler2D'}
    """
    i = vtk_index
    return LightShading(
        i,
        f"pvsMaskShadow(pvsMask{i}, pvsViewport, pvsLights[{i}].lightVC, vertexVC.xyz, "
        "pvsNormalVC)",
        {f"pvsMask{i}": "sampler2D"},
        sources=(MASK_SOURCE,),
        only_on=only_on,
        elsewhere=elsewhere,
    )


def mask_uniforms(
    plan: Cast, context: FrameContext, mask: MaskTexture | None, entry: LightEntry
) -> dict[str, object]:
    """Set the light in view coordinates in its block entry; return the mask's texture.

    Parameters
    ----------
    plan : Cast
        The light's cast.
    context : FrameContext
        This frame's camera and render target.
    mask : MaskTexture or None
        The mask; ``None`` for the facing test alone.
    entry : LightEntry
        The light's entry of the frame's uniform block: its ``light_vc`` is
        set, for the facing test.

    Returns
    -------
    dict
        With a mask its texture ``pvsMask{i}``
        (:class:`~pvshadows.gl.sampler_units.TextureBinding`), else empty.
    """
    entry.light_vc = tuple(context.view.light_in_view(plan.pose.homogeneous()).tolist())
    if mask is None:
        return {}
    name = f"pvsMask{plan.vtk_index}"
    return {name: TextureBinding.of(name, mask.texture)}


def held_for(plan: Cast, context: FrameContext) -> tuple:
    """Return what a screen mask drawn now is right for: the cast, snapshot, view and target size.

    Parameters
    ----------
    plan : Cast
        The light's cast.
    context : FrameContext
        The frame the mask is drawn in.

    Returns
    -------
    tuple
        For :func:`mask_holds` (a technique may add what else its mask
        depends on after these four).
    """
    return (plan, context.snapshot, context.view, context.viewport_size())


def mask_holds(held: tuple, plan: Cast, context: FrameContext) -> bool:
    """Tell whether a mask drawn for ``held`` (:func:`held_for`) is right in this frame.

    A screen mask holds for the very cast it was drawn for, seen in the
    same snapshot of the actors, from the same view, in a render target of
    the same size.

    Parameters
    ----------
    held : tuple
        What the mask was drawn for; its first four values are compared.
    plan : Cast
        This frame's cast of the light.
    context : FrameContext
        This frame.

    Returns
    -------
    bool
        ``True`` when none of them changed.
    """
    cast, snapshot, view, size = held[:4]
    return (
        cast is plan
        and snapshot is context.snapshot
        and view is context.view
        and size == context.viewport_size()
    )
