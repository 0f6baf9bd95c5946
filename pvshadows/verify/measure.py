"""How far what the renderer shows is from the exact visibility."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pvshadows.model.tables import html_table


@dataclass(frozen=True)
class Measurement:
    """Error of one light's shadows against the ray-traced reference on one frame.

    Attributes
    ----------
    misclassified : float
        Share of lit-side pixels whose shadow/lit class (visibility below or
        above 0.5) disagrees with the reference.
    false_shadow : float
        Share of the pixels the reference sees fully lit that are shown in
        shadow (acne, over-large shadows).
    missed_shadow : float
        Share of the pixels the reference sees in shadow that are shown lit
        (light leaks, detached shadows).
    rmse : float
        Root mean square difference of visibility over lit-side pixels.
    lit_pixels : int
        Number of lit-side pixels compared.
    shadow_pixels : int
        How many of them the reference sees wholly or partly in shadow; 0 when the light
        casts no shadow in view, so the figures only say that none was
        drawn where there is none.
    """

    misclassified: float
    false_shadow: float
    missed_shadow: float
    rmse: float
    lit_pixels: int
    shadow_pixels: int = 0

    @property
    def verdict(self) -> str:
        """What the figures stand on, in words: a shadow in view, none, or no lit pixel."""
        if not self.lit_pixels:
            return "the light reaches no receiver in view: nothing was compared"
        if not self.shadow_pixels:
            return "the light casts no shadow in view: only false shadows can be judged"
        return f"{self.shadow_pixels} of the compared pixels are in shadow"

    def __str__(self) -> str:
        if not self.shadow_pixels:
            return f"{self.verdict} ({self._figures()})"
        return self._figures()

    def _figures(self) -> str:
        return (
            f"misclassified {100 * self.misclassified:.3f} % of {self.lit_pixels} lit-side pixels "
            f"(false shadow {100 * self.false_shadow:.3f} %, "
            f"missed {100 * self.missed_shadow:.3f} %), "
            f"RMSE {self.rmse:.4f}"
        )

    def _repr_pretty_(self, printer, cycle: bool) -> None:
        printer.text(str(self))

    def _repr_html_(self) -> str:
        rows = [
            ["misclassified", f"{100 * self.misclassified:.3f} %", "lit-side pixels"],
            ["false shadow", f"{100 * self.false_shadow:.3f} %", "of the pixels lit in truth"],
            ["missed shadow", f"{100 * self.missed_shadow:.3f} %", "of the pixels dark in truth"],
            ["RMSE", f"{self.rmse:.4f}", "visibility over lit-side pixels"],
            ["lit-side pixels", str(self.lit_pixels), "compared"],
            ["in shadow", str(self.shadow_pixels), "by the reference"],
        ]
        caption = f"pvshadows against ray tracing: {self.verdict}"
        return html_table(caption, ["", "value", "of"], rows)


def _share(mask: np.ndarray, among: np.ndarray) -> float:
    count = int(among.sum())
    return float((mask & among).sum()) / count if count else 0.0


def compare(shown: np.ndarray, reference) -> Measurement:
    """Compare a rendered visibility image with the reference.

    Parameters
    ----------
    shown : numpy.ndarray
        ``(H, W)`` visibility from the renderer (NaN where no receiver).
    reference : pvshadows.verify.reference.ReferenceResult
        The ray-traced result for the same frame.

    Returns
    -------
    Measurement
        The error figures.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from pvshadows.verify.measure import compare
    >>> exact = SimpleNamespace(
    ...     visibility=np.array([[1.0, 0.0]]), lit_side=np.array([[True, True]])
    ... )
    >>> compare(np.array([[1.0, 1.0]]), exact).misclassified
    0.5
    """
    lit = reference.lit_side & np.isfinite(shown)
    exact = reference.visibility
    shown_dark = shown < 0.5
    exact_dark = exact < 0.5
    difference = np.where(lit, shown - exact, 0.0)
    count = int(lit.sum())
    return Measurement(
        misclassified=_share(shown_dark != exact_dark, lit),
        false_shadow=_share(shown_dark, lit & ~exact_dark),
        missed_shadow=_share(~shown_dark, lit & exact_dark),
        rmse=float(np.sqrt((difference**2).sum() / count)) if count else 0.0,
        lit_pixels=count,
        shadow_pixels=int((lit & (exact < 1.0)).sum()),
    )
