"""Translucent casters in the map techniques: split from the opaque ones, drawn into a companion.

A light's opaque casters stay in its depth map. Only when some of its
casters are translucent does the light get a transmittance companion
(:mod:`pvshadows.gl.transmittance_textures`), drawn by
:class:`~pvshadows.passes.transmittance.TransmittancePass` with the depth
map's projection, and drawn again only when the translucent casters, their
transmittances or the projection changed.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from operator import attrgetter

from pvshadows import _vtk as vtk
from pvshadows.gl.transmittance_textures import TransmittanceCube, TransmittanceTexture
from pvshadows.model.report import PassReport
from pvshadows.passes.transmittance import PASS_NAME, TransmittancePass
from pvshadows.scene.actor_state import ActorState
from pvshadows.scene.snapshot import Snapshot

_TRANSMITTANCE = attrgetter("transmittance")


def split_casters(
    casters: list[ActorState], snapshot: Snapshot | None = None
) -> tuple[list[ActorState], list[ActorState]]:
    """Split casters into the opaque ones and the translucent ones.

    Parameters
    ----------
    casters : list of ActorState
        A light's casters.
    snapshot : Snapshot, optional
        The snapshot they belong to: it tells at once, without a look at each
        state, when all are opaque (the common case).

    Returns
    -------
    opaque, translucent : list of ActorState
        Those that let no light through, and those that let some but not
        all through; a caster with transmittance 1 casts nothing and is in
        neither.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from pvshadows.techniques.translucent import split_casters
    >>> glass, stone, air = (SimpleNamespace(transmittance=t) for t in (0.7, 0.0, 1.0))
    >>> split_casters([glass, stone, air]) == ([stone], [glass])
    True
    """
    if snapshot is not None:
        if not snapshot.some_caster_translucent:
            return casters, []
        if not snapshot.caster_transmittance[snapshot.caster_rows(casters)].any():
            return casters, []
    elif not any(map(_TRANSMITTANCE, casters)):
        return casters, []
    opaque = [c for c in casters if c.transmittance <= 0.0]
    translucent = [c for c in casters if 0.0 < c.transmittance < 1.0]
    return opaque, translucent


def translucent_key(casters: list[ActorState]) -> tuple:
    """Return a value that changes when the translucent casters' shapes or transmittances change.

    Parameters
    ----------
    casters : list of ActorState
        The translucent casters.

    Returns
    -------
    tuple
        Each caster's :meth:`~pvshadows.scene.actor_state.ActorState.key` and transmittance.
    """
    return tuple((*c.key(), c.transmittance) for c in casters)


@dataclass
class Companion:
    """A light's transmittance companion and what it was last drawn for."""

    texture: TransmittanceTexture
    key: tuple | None = None
    frame: int = -1

    def release(self) -> None:
        """Release the companion."""
        self.texture.release()


class Companions:
    """Makes, draws and reuses the transmittance companions of a technique's lights.

    Parameters
    ----------
    window : vtk.vtkOpenGLRenderWindow
        The window whose context owns them.
    """

    def __init__(self, window: vtk.vtkOpenGLRenderWindow) -> None:
        self._window = window
        #: The pass that draws them.
        self.drawer = TransmittancePass(window)

    def update(
        self,
        held: Companion | None,
        *,
        resolution: int,
        cube: bool,
        key: tuple,
        frame: int,
        draw: Callable[[TransmittanceTexture], list[PassReport]],
    ) -> tuple[Companion, list[PassReport]]:
        """Bring one light's companion up to date.

        Parameters
        ----------
        held : Companion or None
            The light's companion so far.
        resolution : int
            Its depth map's resolution.
        cube : bool
            A cube (point light) rather than a 2D map.
        key : tuple
            The projection and :func:`translucent_key` of its casters: the
            companion is drawn again only when it changed.
        frame : int
            This frame's number.
        draw : callable
            Draws the casters into the texture it gets; returns the reports.

        Returns
        -------
        companion : Companion
            The light's companion from now on.
        reports : list of PassReport
            The pass run or reused.
        """
        if (
            held is None
            or held.texture.resolution != resolution
            or cube != isinstance(held.texture, TransmittanceCube)
        ):
            if held is not None:
                held.release()
            kind = TransmittanceCube if cube else TransmittanceTexture
            held = Companion(kind(self._window, resolution))
        if held.key == key:
            detail = f"translucent casters and projection unchanged since frame {held.frame}"
            return held, [PassReport(PASS_NAME, "reused", detail)]
        reports = draw(held.texture)
        held.key, held.frame = key, frame
        return held, reports

    def release(self) -> None:
        """Release the pass's programs (each light's companion goes with its state)."""
        self.drawer.release()
