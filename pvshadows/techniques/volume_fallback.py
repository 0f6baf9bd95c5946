"""Open casters of a volume light cast from a shadow map instead (``on_open="fallback"``).

The planner chooses the map (:data:`pvshadows.model.plan.FALLBACK_TECHNIQUES`);
here live the techniques that draw it, one per name and window. The light's
visibility is then its volume mask times the fallback map's lookup over the
open casters only.
"""

from __future__ import annotations

from dataclasses import fields

from pvshadows import _vtk as vtk
from pvshadows.model.plan import Cast
from pvshadows.model.report import PassReport
from pvshadows.shaders.shading import LightShading
from pvshadows.techniques.base import FrameContext, Technique


def combine_shadings(first: LightShading, second: LightShading) -> LightShading:
    """Return one light's shading whose visibility is the product of two.

    Parameters
    ----------
    first, second : LightShading
        Two lookups of the same light (e.g. a volume mask and a cube map).

    Returns
    -------
    LightShading
        Visibility ``(first) * (second)``; samplers merged, every other
        field (sources, defines, ...) concatenated without repeats.

    Examples
    --------
    >>> from pvshadows.shaders.shading import LightShading
    >>> from pvshadows.techniques.volume_fallback import combine_shadings
    >>> both = combine_shadings(LightShading(0, "a", sources=("x",)), LightShading(0, "b"))
    >>> both.visibility, both.sources
    ('(a) * (b)', ('x',))
    """
    merged = {}
    for item in fields(LightShading):
        a, b = getattr(first, item.name), getattr(second, item.name)
        if item.name == "vtk_index":
            merged[item.name] = a
        elif item.name == "visibility":
            merged[item.name] = f"({a}) * ({b})"
        elif isinstance(a, tuple):
            merged[item.name] = tuple(dict.fromkeys((*a, *b)))
        elif isinstance(a, dict) or hasattr(a, "items"):
            merged[item.name] = {**a, **b}
        else:
            merged[item.name] = a
    return LightShading(**merged)


#: A fallback: the technique's name and its plan over the open casters.
Fallback = tuple[str, Cast]


class OpenCasterFallbacks:
    """The shadow-map techniques that cast the open casters of a window's volume lights.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns the fallback maps.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        self._fallbacks: dict[str, Technique] = {}

    def update(self, fallback: Fallback | None, context: FrameContext) -> list[PassReport]:
        """Bring a fallback's map up to date; its passes are reported as ``fallback ...``."""
        if fallback is None:
            return []
        name, subplan = fallback
        technique = self.technique(name)
        reports = technique.update(subplan, context)
        for report in reports:
            report.name = f"fallback {report.name}"
        return reports

    def technique(self, name: str) -> Technique:
        """Return the fallback technique of that name, made on first use."""
        if name not in self._fallbacks:
            from pvshadows.techniques import TECHNIQUE_CLASSES

            self._fallbacks[name] = TECHNIQUE_CLASSES[name](self._window)
        return self._fallbacks[name]

    def end_frame(self) -> None:
        """End the frame of every fallback technique."""
        for technique in self._fallbacks.values():
            technique.end_frame()

    def keep_only(self, plans: list[Cast]) -> None:
        """Release the fallback maps of lights whose plans are not in ``plans``."""
        for technique in self._fallbacks.values():
            technique.keep_only(plans)

    def release(self) -> None:
        """Release every fallback map."""
        for technique in self._fallbacks.values():
            technique.release()
        self._fallbacks.clear()
