"""Which receivers the camera sees, tested only as far as the planner asks.

A light's kept plan needs to know only whether the camera sees some
receiver, and some receiver in the light's reach. The receiver that
answered yes last frame (its *witness*) usually answers yes again: one box
tested instead of every receiver's. Only when the witness is out of view, or
a plan asks exactly which receivers are seen, is every receiver tested, in
one vectorised test; and none is while the box round them all is in view.
"""

from __future__ import annotations

import numpy as np

from pvshadows.scene.culling import box_seen, boxes_in_frustum, boxes_seen


class ViewSight:
    """What a view sees of a snapshot's receivers.

    Parameters
    ----------
    bounds : numpy.ndarray
        ``(n, 2, 3)`` the receivers' world bounds.
    whole : numpy.ndarray
        ``(2, 3)`` the box round them all.
    planes : numpy.ndarray
        ``(6, 4)`` the view's frustum planes.
    witnesses : dict, optional
        Rows that answered :meth:`sees_some` before, by the mask they
        answered for (``id``; 0 for none), updated here; shared from
        frame to frame.

    Attributes
    ----------
    tested : int
        Receivers tested one by one (a box per witness, every receiver for
        :attr:`every`).

    Examples
    --------
    >>> import numpy as np
    >>> import vtk
    >>> from pvshadows.pipeline.sight import ViewSight
    >>> from pvshadows.scene.culling import frustum_planes
    >>> planes = frustum_planes(vtk.vtkCamera(), 1.0)  # at z = 1, looking down -z
    >>> bounds = np.array([[[-0.1, -0.1, -1.0], [0.1, 0.1, -0.5]], [[5, 5, 2], [6, 6, 3]]])
    >>> whole = np.array([bounds[:, 0].min(axis=0), bounds[:, 1].max(axis=0)])
    >>> sight = ViewSight(bounds, whole, planes)
    >>> sight.sees_some(np.array([False, True])), sight.sees_some(), sight.every.tolist()
    (False, True, [True, False])
    """

    def __init__(
        self,
        bounds: np.ndarray,
        whole: np.ndarray,
        planes: np.ndarray,
        witnesses: dict[int, int] | None = None,
    ) -> None:
        self._bounds, self._planes = bounds, planes
        self._plane_rows = [tuple(row) for row in planes.tolist()]
        self._witnesses = {} if witnesses is None else witnesses
        low, high = whole.tolist()
        # The corners swapped, the test meets each plane's nearest corner: all inside.
        inside = box_seen(high, low, self._plane_rows)
        self._every = np.ones(len(bounds), dtype=bool) if inside else None
        self.tested = 0

    def following(self, bounds: np.ndarray, whole: np.ndarray, rows: list[int]) -> ViewSight:
        """Return the sight of the same view over receivers of which only some rows changed.

        What this sight found of every receiver is kept; only the boxes in
        ``rows`` are tested again.

        Parameters
        ----------
        bounds : numpy.ndarray
            ``(n, 2, 3)`` the receivers' world bounds now, ``n`` as before.
        whole : numpy.ndarray
            ``(2, 3)`` the box round them all.
        rows : list of int
            The receivers whose bounds changed.

        Returns
        -------
        ViewSight
            A new sight sharing this one's witnesses.
        """
        sight = ViewSight(bounds, whole, self._planes, self._witnesses)
        if sight._every is None and self._every is not None:
            every = self._every.copy()
            every[rows] = boxes_seen(bounds[rows], self._planes)
            sight._every = every
            sight.tested += len(rows)
        return sight

    @property
    def every(self) -> np.ndarray:
        """``(n,)`` bool: which receivers the view may see (conservative, as culling is)."""
        if self._every is None:
            self._every = boxes_in_frustum(self._bounds, self._planes)
            self.tested += len(self._every)
        return self._every

    def sees_some(self, among: np.ndarray | None = None) -> bool:
        """Return whether the view sees some receiver, or some where ``among`` is true.

        Parameters
        ----------
        among : numpy.ndarray, optional
            ``(n,)`` bool mask over the receivers (a light's reach).

        Returns
        -------
        bool
            The same answer as ``every`` (masked) gives, from the last
            witness's box alone when it is still seen.
        """
        key = 0 if among is None else id(among)
        row = self._witnesses.get(key)
        if row is not None and row < len(self._bounds) and (among is None or among[row]):
            if self._every is not None:  # every receiver tested already: read the witness's
                if self._every[row]:
                    return True
            else:
                self.tested += 1
                low, high = self._bounds[row].tolist()
                if box_seen(low, high, self._plane_rows):
                    return True
        seen = self.every if among is None else self.every & among
        rows = np.flatnonzero(seen)
        if not len(rows):
            return False
        if len(self._witnesses) > 64:
            self._witnesses.clear()
        self._witnesses[key] = int(rows[0])
        return True
