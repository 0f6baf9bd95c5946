"""A progress bar with the time left, on stderr, for ``pvshadows bench``."""

from __future__ import annotations

import sys
import time
from typing import TextIO


def _clock(seconds: float) -> str:
    minutes, seconds = divmod(round(seconds), 60)
    return f"{minutes}:{seconds:02d}"


class ProgressBar:
    """Cases done out of the total, time spent and time left, redrawn in place on a terminal.

    On a terminal the bar is one line redrawn in place; elsewhere (a log, a
    docs build) each step prints one line. Lines printed through
    :meth:`line` go above the bar.

    Parameters
    ----------
    total : int
        Steps to come.
    stream : file, optional
        Where the bar goes (default ``sys.stderr``).
    width : int, default: 30
        Characters of the bar itself.

    Examples
    --------
    >>> import io
    >>> from pvshadows.tools.bench_progress import ProgressBar
    >>> out = io.StringIO()
    >>> bar = ProgressBar(4, stream=out)
    >>> bar.step("one case")
    >>> out.getvalue().startswith("bench [#######")
    True
    """

    def __init__(self, total: int, *, stream: TextIO | None = None, width: int = 30) -> None:
        self.total = max(int(total), 1)
        self.done = 0
        self._stream = stream if stream is not None else sys.stderr
        self._width = width
        self._started = time.perf_counter()
        self._drawn = False
        self._tty = bool(getattr(self._stream, "isatty", lambda: False)())

    def text(self, label: str = "") -> str:
        """Return the bar as it reads now, e.g. ``bench [####----] 3/8, 0:41 spent, ~1:08 left``.

        Parameters
        ----------
        label : str, optional
            What is being measured, appended to the bar.

        Returns
        -------
        str
            One line.
        """
        spent = time.perf_counter() - self._started
        filled = round(self._width * self.done / self.total)
        bar = "#" * filled + "-" * (self._width - filled)
        left = "?" if not self.done else _clock(spent / self.done * (self.total - self.done))
        words = f"bench [{bar}] {self.done}/{self.total}, {_clock(spent)} spent, ~{left} left"
        return f"{words}  {label}".rstrip()

    def step(self, label: str = "") -> None:
        """Count one step done and redraw.

        Parameters
        ----------
        label : str, optional
            What was just measured.
        """
        self.done = min(self.done + 1, self.total)
        self._draw(label)

    def show(self, label: str = "") -> None:
        """Draw the bar as it stands, with what is being measured.

        Parameters
        ----------
        label : str, optional
            What is under way.
        """
        self._draw(label)

    def line(self, text: str) -> None:
        """Print a line of results above the bar (to stdout), then redraw the bar.

        Parameters
        ----------
        text : str
            The line.
        """
        self._clear()
        print(text, flush=True)
        if self._tty and self._drawn:
            self._draw("")

    def close(self) -> None:
        """End the bar's line."""
        if self._tty and self._drawn:
            self._stream.write("\n")
            self._stream.flush()
            self._drawn = False

    def _clear(self) -> None:
        if self._tty and self._drawn:
            self._stream.write("\r\x1b[2K")
            self._stream.flush()

    def _draw(self, label: str) -> None:
        if self._tty:
            self._stream.write("\r\x1b[2K" + self.text(label)[:160])
        else:
            self._stream.write(self.text(label) + "\n")
        self._stream.flush()
        self._drawn = True
