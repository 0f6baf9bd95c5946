"""Axis-aligned world boxes of many casters, stacked for tests that take them all at once."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class CasterBoxes:
    """The volume casters' names and world bounds, stacked once for every frame's test.

    A kept volume plan is tested again at each camera move; its casters'
    boxes do not change meanwhile, so they are stacked into arrays once.

    Attributes
    ----------
    names : tuple of str
        Each caster's name, in order.
    low, high : numpy.ndarray
        ``(n, 3)`` min and max corners of each box.
    size : float
        The largest absolute coordinate of any box (the tests' slack scales with it).
    """

    names: tuple[str, ...]
    low: np.ndarray
    high: np.ndarray
    size: float

    @classmethod
    def of(cls, casters: Sequence[tuple[str, np.ndarray]]) -> CasterBoxes:
        """Stack ``(name, (2, 3) bounds)`` pairs.

        Parameters
        ----------
        casters : sequence of (str, numpy.ndarray)
            Each volume caster's name and world bounds ``(2, 3)``.

        Returns
        -------
        CasterBoxes
            The same boxes, stacked.

        Examples
        --------
        >>> import numpy as np
        >>> from pvshadows.geometry.boxes import CasterBoxes
        >>> boxes = CasterBoxes.of([("a", np.array([[0.0, 0, 0], [1, 2, 3]]))])
        >>> boxes.names, boxes.high.tolist(), boxes.size
        (('a',), [[1.0, 2.0, 3.0]], 3.0)
        """
        boxes = np.array([box for _, box in casters], dtype=np.float64).reshape(-1, 2, 3)
        return cls(
            tuple(name for name, _ in casters),
            boxes[:, 0],
            boxes[:, 1],
            float(np.abs(boxes).max(initial=0.0)),
        )

    def box(self, number: int) -> np.ndarray:
        """Return caster ``number``'s ``(2, 3)`` bounds."""
        return np.array([self.low[number], self.high[number]])
