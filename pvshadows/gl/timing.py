"""GPU time of a pass, from ``GL_TIME_ELAPSED`` queries."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import numpy as np
import vtk

from pvshadows.gl.binding import opengl_for
from pvshadows.report import PassReport


class PassTimer:
    """Measures passes on the GPU; results are read once, after the frame.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the passes.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl = opengl_for(window)
        self._free: list[int] = []
        self._pending: list[tuple[int, PassReport]] = []

    @contextmanager
    def measure(self, report: PassReport) -> Iterator[None]:
        """Time the GL work issued inside the block into ``report.ms``.

        Parameters
        ----------
        report : PassReport
            Receives its ``ms`` when :meth:`collect` runs.

        Yields
        ------
        None
        """
        gl = self._gl
        query = self._free.pop() if self._free else int(np.asarray(gl.glGenQueries(1)).ravel()[0])
        gl.glBeginQuery(gl.GL_TIME_ELAPSED, query)
        try:
            yield
        finally:
            gl.glEndQuery(gl.GL_TIME_ELAPSED)
            self._pending.append((query, report))

    def collect(self) -> None:
        """Read the finished queries into their reports (waits for the GPU)."""
        gl = self._gl
        for query, report in self._pending:
            report.ms = (
                float(np.asarray(gl.glGetQueryObjectuiv(query, gl.GL_QUERY_RESULT)).ravel()[0])
                * 1e-6
            )
            self._free.append(query)
        self._pending.clear()

    def release(self) -> None:
        """Delete the query objects."""
        queries = self._free + [query for query, _ in self._pending]
        if queries:
            self._gl.glDeleteQueries(len(queries), queries)
        self._free.clear()
        self._pending.clear()
