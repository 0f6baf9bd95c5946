"""How far what the renderer shows is from the exact visibility."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


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
    """

    misclassified: float
    false_shadow: float
    missed_shadow: float
    rmse: float
    lit_pixels: int

    def __str__(self) -> str:
        return (
            f"misclassified {100 * self.misclassified:.3f} % of {self.lit_pixels} lit-side pixels "
            f"(false shadow {100 * self.false_shadow:.3f} %, "
            f"missed {100 * self.missed_shadow:.3f} %), "
            f"RMSE {self.rmse:.4f}"
        )


def _share(mask: np.ndarray, among: np.ndarray) -> float:
    count = int(among.sum())
    return float((mask & among).sum()) / count if count else 0.0


def compare(shown: np.ndarray, reference) -> Measurement:
    """Compare a rendered visibility image with the reference.

    Parameters
    ----------
    shown : numpy.ndarray
        ``(H, W)`` visibility from the renderer (NaN where no receiver).
    reference : pvshadows.reference.ReferenceResult
        The ray-traced result for the same frame.

    Returns
    -------
    Measurement
        The error figures.

    Examples
    --------
    >>> import numpy as np
    >>> from types import SimpleNamespace
    >>> from pvshadows.measure import compare
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
    )
