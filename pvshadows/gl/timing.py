"""GPU time of a pass, from a pair of ``GL_TIMESTAMP`` queries around it.

Results are read when the GPU has them (``GL_QUERY_RESULT_AVAILABLE``),
usually a frame or two after the pass, so reading them never makes the CPU
wait for the GPU in a normal frame. A pass's :class:`PassReport` gets its
``ms`` then; a query still not ready :data:`MAX_FRAMES_IN_FLIGHT` frames
later is waited for, as engines bound the frames the GPU may lag behind.

The query calls go through plain ctypes bindings
(:func:`pvshadows.gl.raw_calls.raw_calls`): PyOpenGL's argument converters
would cost more than the calls, five of them per pass and frame.
"""

from __future__ import annotations

import ctypes
import time

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.gl.binding import opengl_for
from pvshadows.gl.raw_calls import raw_calls
from pvshadows.model.report import PassReport

#: Frames a pass's timing may wait for the GPU before it is read with a wait.
MAX_FRAMES_IN_FLIGHT = 3
#: ``GL_TIMESTAMP``, ``GL_QUERY_RESULT`` and ``GL_QUERY_RESULT_AVAILABLE``.
_TIMESTAMP, _RESULT, _RESULT_AVAILABLE = 0x8E28, 0x8866, 0x8867


class PassTimer:
    """Measures passes on the GPU; results are read when ready, without stalling.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context runs the passes.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._gl = opengl_for(window)
        self._calls = raw_calls()
        #: ``glQueryCounter``, through plain ctypes.
        self.query_counter = self._calls.query_counter
        self._free: list[int] = []
        self._pending: list[tuple[int, int, PassReport, int]] = []
        self._frame = 0
        #: Results read with a wait because the GPU had not finished them in time.
        self.waited = 0

    def measure(self, report: PassReport) -> _Measured:
        """Time the GL work issued inside the ``with`` block into ``report.ms``.

        The CPU time of issuing it goes to ``report.cpu_ms`` at once.

        Parameters
        ----------
        report : PassReport
            Receives its ``ms`` when :meth:`collect` runs.

        Returns
        -------
        context manager
            Brackets the pass with two timestamp queries.
        """
        if len(self._free) < 2:
            self._free.extend(int(q) for q in np.asarray(self._gl.glGenQueries(2)).ravel())
        return _Measured(self, report, self._free.pop(), self._free.pop())

    def _ended(self, start: int, end: int, report: PassReport, began: float) -> None:
        self.query_counter(end, _TIMESTAMP)
        self._pending.append((start, end, report, self._frame))
        report.cpu_ms += (time.thread_time() - began) * 1e3

    def collect(self, *, wait: bool = False) -> None:
        """Read the queries the GPU has finished into their reports; keep the others.

        Called after each frame. A query issued :data:`MAX_FRAMES_IN_FLIGHT`
        or more frames ago is read even if that means waiting.

        Parameters
        ----------
        wait : bool, default: False
            Wait for every pending query (tests and shutdown).
        """
        self._frame += 1
        if not self._pending:
            return
        result = self._calls.query_result
        ready, begun, ended = ctypes.c_uint64(0), ctypes.c_uint64(0), ctypes.c_uint64(0)
        kept = []
        for start, end, report, frame in self._pending:
            late = wait or self._frame - frame >= MAX_FRAMES_IN_FLIGHT
            if not late:
                result(end, _RESULT_AVAILABLE, ctypes.byref(ready))
                if not ready.value:
                    kept.append((start, end, report, frame))
                    continue
            elif not wait:
                self.waited += 1
            result(start, _RESULT, ctypes.byref(begun))
            result(end, _RESULT, ctypes.byref(ended))
            report.ms = (ended.value - begun.value) * 1e-6
            self._free.extend((start, end))
        self._pending = kept

    def release(self) -> None:
        """Delete the query objects."""
        queries = self._free + [q for start, end, _, _ in self._pending for q in (start, end)]
        if queries:
            self._gl.glDeleteQueries(len(queries), queries)
        self._free.clear()
        self._pending.clear()


class _Measured:
    """The ``with`` block of :meth:`PassTimer.measure` (a class: a generator costs more calls)."""

    __slots__ = ("_began", "_counter", "_end", "_report", "_start", "_timer")

    def __init__(self, timer: PassTimer, report: PassReport, start: int, end: int) -> None:
        self._timer, self._report, self._start, self._end = timer, report, start, end
        self._counter = timer.query_counter
        self._began = 0.0

    def __enter__(self) -> None:
        self._began = time.thread_time()
        self._counter(self._start, _TIMESTAMP)

    def __exit__(self, *exc: object) -> None:
        self._timer._ended(self._start, self._end, self._report, self._began)
