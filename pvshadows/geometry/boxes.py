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
    diagonals : numpy.ndarray
        ``(n,)`` the length of each box's diagonal.
    """

    names: tuple[str, ...]
    low: np.ndarray
    high: np.ndarray
    size: float
    diagonals: np.ndarray

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
            np.linalg.norm(boxes[:, 1] - boxes[:, 0], axis=1),
        )

    def around(self, point: np.ndarray, slack: np.ndarray | float = 0.0) -> list[int]:
        """Return the boxes that hold a point, each widened by its ``slack``.

        Parameters
        ----------
        point : numpy.ndarray
            ``(3,)`` world point.
        slack : numpy.ndarray or float, default: 0.0
            ``(n,)`` per box, or one for all, added on every side.

        Returns
        -------
        list of int
            Their numbers, in order.

        Examples
        --------
        >>> import numpy as np
        >>> from pvshadows.geometry.boxes import CasterBoxes
        >>> unit = np.array([[0.0, 0, 0], [1, 1, 1]])
        >>> boxes = CasterBoxes.of([("a", unit), ("b", unit + 2.0)])
        >>> boxes.around(np.array([2.5, 2.5, 2.5])), boxes.around(np.array([1.1, 1, 1]), 0.2)
        ([1], [0])
        """
        margin = np.reshape(slack, (-1, 1))
        inside = (self.low - margin <= point) & (point <= self.high + margin)
        return np.flatnonzero(inside.all(axis=1)).tolist()

    def box(self, number: int) -> np.ndarray:
        """Return caster ``number``'s ``(2, 3)`` bounds."""
        return np.array([self.low[number], self.high[number]])
