"""Which landing checks a frame tries, by what the view's frustum meets.

VTK draws only what the view meets, and a
:class:`~pvshadows.shaders.landing.LandingCheck` learns only from what VTK
draws: a receiver's OpenGL mapper exists once VTK first drew it, and a
program is handed over only at a draw. So the checks still waiting for a
mapper are tried where the view meets them (:class:`WaitingChecks`), and a
watcher the view does not meet hands its watch to a follower it does
(:class:`Watchers`), each with one box test over the receivers concerned,
and again only for a new view.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterator
from typing import TYPE_CHECKING

import numpy as np

from pvshadows import _vtk as vtk
from pvshadows.scene.culling import boxes_seen

if TYPE_CHECKING:
    from pvshadows.shaders.landing import LandingCheck


class Watchers:
    """The landing check watching a program for each shader variant and edits of one renderer.

    A watcher VTK did not draw in the frame it began to watch in (out of the
    view's frustum) hands the watch to a follower the view meets, so that
    receivers VTK draws are not left waiting for one it does not. A watcher
    in view keeps its watch: handing it round would put an observer on
    every mapper in turn.

    Attributes
    ----------
    frame : int
        Frames begun (calls of :meth:`hand_over_unseen`).
    handed_over : int
        Watches handed to a follower so far.

    Examples
    --------
    >>> from pvshadows.shaders.landing_views import Watchers
    >>> watchers = Watchers()
    >>> watchers.hand_over_unseen(None)
    >>> watchers.frame, len(watchers)
    (1, 0)
    """

    def __init__(self) -> None:
        self._by_key: dict[Hashable, LandingCheck] = {}
        #: The frame in which each watcher began to watch for others.
        self._since: dict[LandingCheck, int] = {}
        #: The watchers not known to have read a program yet (a frame walks only these)
        #: and, once stacked, their followers' count of changes then, the boxes (the
        #: watcher's first) and the planes last tried.
        self._unread: dict[LandingCheck, tuple[int, np.ndarray, np.ndarray | None] | None] = {}
        self.frame = 0
        self.handed_over = 0

    def __len__(self) -> int:
        return len(self._by_key)

    def get(self, key: Hashable) -> LandingCheck | None:
        """Return the watcher of ``key`` (a shader variant and its edits), or ``None``."""
        return self._by_key.get(key)

    def register(self, key: Hashable, check: LandingCheck) -> None:
        """Make ``check`` the watcher of ``key`` from this frame on."""
        self._by_key[key] = check
        self._unread[check] = None
        self._since[check] = self.frame

    def drop(self, key: Hashable) -> None:
        """Forget the watcher of ``key``."""
        check = self._by_key.pop(key, None)
        if check is not None:
            self._unread.pop(check, None)
            self._since.pop(check, None)

    def hand_over_unseen(self, planes: np.ndarray | None) -> None:
        """Begin a frame: move each watch unread since an earlier frame to a follower in view.

        Only a watcher out of the view's frustum hands its watch over (VTK
        did not draw it); one in view, still unread, keeps it. The boxes of
        a watcher and its followers are read once while its followers stay
        the same, and tested again only against a new view.

        Parameters
        ----------
        planes : numpy.ndarray or None
            ``(6, 4)`` the view's frustum planes; ``None`` (no view known)
            hands nothing over.
        """
        self.frame += 1
        if planes is None:
            return
        for check, kept in list(self._unread.items()):
            if check.settled or check.failed:
                del self._unread[check]
                continue
            if self._since[check] >= self.frame:
                continue
            followers = check.followers
            if kept is None or kept[0] != check.followers_changed:
                bounds = np.array([vtk.vtkActor.GetBounds(c.actor) for c in [check, *followers]])
                kept = (check.followers_changed, bounds.reshape(-1, 3, 2).transpose(0, 2, 1), None)
            elif kept[2] is planes:
                continue  # this view was tried
            self._unread[check] = (kept[0], kept[1], planes)
            if not followers:
                continue
            seen = boxes_seen(kept[1], planes)
            if seen[0]:
                continue
            in_view = (f for f, sees in zip(followers, seen[1:], strict=True) if sees)
            successor = next((f for f in in_view if f.can_watch()), None)
            if successor is not None:
                check.hand_over(successor)
                self.handed_over += 1


class WaitingChecks:
    """Landing checks of receivers that VTK has not drawn yet, tried where the view meets them.

    VTK makes a receiver's OpenGL mapper when it first draws it, so a
    receiver edited before then has no program to watch. VTK draws only what
    the view's frustum meets: a receiver is tried again only once the view
    meets its bounds, all found in one test over the waiting receivers'
    bounds (stacked once while the same receivers wait). While the view
    stays the one of the last try, only the receivers that came to wait
    since, or were tried then and wait still, are tested: the others were
    out of it. So a frame costs the waiting receivers in view and those
    just edited, not every receiver never drawn (a zoomed-in view of a
    large assembly leaves most of it undrawn for as long as it stays so).

    Attributes
    ----------
    tries : int
        Checks tried since this object was made.
    tested : int
        Waiting receivers' bounds tested against a view since then.

    Examples
    --------
    >>> import numpy as np
    >>> import pyvista as pv
    >>> import vtk
    >>> from pvshadows.scene.culling import frustum_planes
    >>> from pvshadows.shaders.landing import LandingCheck
    >>> from pvshadows.shaders.landing_views import WaitingChecks
    >>> pl = pv.Plotter(off_screen=True)
    >>> actor = pl.add_mesh(pv.Sphere())
    >>> waiting = WaitingChecks()
    >>> waiting.wait("sphere", LandingCheck(actor), np.array([[-0.5, -0.5, -0.5], [0.5, 0.5, 0.5]]))
    >>> camera = vtk.vtkCamera()  # at z = 1, looking down -z: it sees the sphere
    >>> view = frustum_planes(camera, 1.0)
    >>> camera.SetFocalPoint(0.0, 0.0, 2.0)  # looking up +z: it does not
    >>> away = frustum_planes(camera, 1.0)
    >>> waiting.try_in_view(away)
    >>> waiting.tries, len(waiting)
    (0, 1)
    >>> waiting.try_in_view(view)  # in view, but VTK has not drawn it yet
    >>> waiting.tries, len(waiting)
    (1, 1)
    >>> pl.ren_win.Render()
    >>> waiting.try_in_view(view)
    >>> waiting.tries, len(waiting)
    (2, 0)
    """

    def __init__(self) -> None:
        self._waiting: dict[str, tuple[LandingCheck, np.ndarray | None]] = {}
        #: The waiting keys without bounds, those with, their rows and their bounds stacked.
        self._stack: tuple[list[str], list[str], dict[str, int], np.ndarray] | None = None
        #: The planes of the last try: every waiting receiver not in ``_untested`` is out of them.
        self._tried_view: np.ndarray | None = None
        #: Waiting receivers to test even in the last try's view (new, moved, or in it then).
        self._untested: set[str] = set()
        self.tries = self.tested = 0

    def __len__(self) -> int:
        return len(self._waiting)

    def __iter__(self) -> Iterator[str]:
        return iter(self._waiting)

    def wait(self, key: str, check: LandingCheck, bounds: np.ndarray | None) -> None:
        """Keep a receiver's check until its mapper exists.

        Parameters
        ----------
        key : str
            The receiver's key.
        check : LandingCheck
            Its check, whose :meth:`LandingCheck.attach` found no mapper.
        bounds : numpy.ndarray or None
            ``(2, 3)`` its world bounds; ``None`` for one tried every frame.
        """
        kept = self._waiting.get(key)
        self._waiting[key] = (check, bounds)
        self._untested.add(key)
        stack = self._stack
        if stack is None or kept is None or (kept[1] is None) != (bounds is None):
            self._stack = None
        elif bounds is not None:
            stack[3][stack[2][key]] = bounds

    def forget(self, key: str) -> None:
        """Stop waiting for a receiver.

        Parameters
        ----------
        key : str
            The receiver's key.
        """
        if self._waiting.pop(key, None) is not None:
            self._stack = None
            self._untested.discard(key)

    def try_in_view(self, planes: np.ndarray | None) -> None:
        """Attach the checks of the waiting receivers VTK may have drawn since.

        Parameters
        ----------
        planes : numpy.ndarray or None
            ``(6, 4)`` the view's frustum planes; ``None`` tries every one.
        """
        same_view = planes is not None and planes is self._tried_view
        if not self._waiting or (same_view and not self._untested):
            return
        if self._stack is None:
            unboxed = [key for key, (_, bounds) in self._waiting.items() if bounds is None]
            keys = [key for key, (_, bounds) in self._waiting.items() if bounds is not None]
            stacked = np.array([self._waiting[key][1] for key in keys]).reshape(-1, 2, 3)
            self._stack = (unboxed, keys, {key: row for row, key in enumerate(keys)}, stacked)
        unboxed, keys, rows, stacked = self._stack
        if planes is None:
            tried = unboxed + keys
        elif same_view:  # the others were out of this view at the last try
            candidates = sorted(rows[key] for key in self._untested if key in rows)
            self.tested += len(candidates)
            seen = boxes_seen(stacked[candidates], planes)
            boxed = [keys[row] for row, hit in zip(candidates, seen, strict=True) if hit]
            tried = [key for key in unboxed if key in self._untested] + boxed
        else:
            self.tested += len(keys)
            seen = boxes_seen(stacked, planes)
            tried = unboxed + [key for key, hit in zip(keys, seen, strict=True) if hit]
        self.tries += len(tried)
        attached = [key for key in tried if self._waiting[key][0].attach()]
        for key in attached:
            del self._waiting[key]
        if attached:
            self._stack = None
        self._tried_view = planes
        self._untested = (set(tried) | set(unboxed)) - set(attached)
