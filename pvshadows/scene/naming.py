"""How messages name an actor: by its PyVista name, in O(1) per actor."""

from __future__ import annotations

import math

import pyvista as pv

from pvshadows import _vtk as vtk
from pvshadows.scene.triangles import vtk_id

#: What PyVista puts in the names it makes up for actors added without ``name=``.
_AUTOMATIC = "(Addr="


class ActorNames:
    """Names actors the way a user does: by the ``name=`` given to ``add_mesh``.

    A map from actor to name is built from the plotter's renderers once and
    kept; a lookup is one dictionary read plus a check that the renderer
    still holds the actor under that name. Only an actor the map does not
    know (added or renamed since) rebuilds it; an actor added to a renderer
    without PyVista is remembered as unnamed.

    Parameters
    ----------
    plotter : pyvista.Plotter
        The plotter whose actors are named.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.naming import ActorNames
    >>> pl = pv.Plotter(off_screen=True)
    >>> box = pl.add_mesh(pv.Cube(), name="box")
    >>> sphere = pl.add_mesh(pv.Sphere(center=(0, 0, 2)))
    >>> names = ActorNames(pl)
    >>> names(box)
    "actor 'box'"
    >>> names(sphere)
    'the unnamed PolyData actor around (0, 0, 2)'
    """

    def __init__(self, plotter: pv.Plotter) -> None:
        self._plotter = plotter
        self._known: dict[str, tuple[str | None, dict | None]] = {}

    def __call__(self, actor: vtk.vtkActor) -> str:
        """Return how messages name ``actor``.

        Parameters
        ----------
        actor : vtk.vtkActor
            An actor of the plotter (or one added to a renderer directly).

        Returns
        -------
        str
            ``"actor 'NAME'"`` for a named actor; for one added without
            ``name=``, its kind of mesh and where it is.
        """
        key = vtk_id(actor)
        if not self._holds(key):
            self._known = self._read()
            self._known.setdefault(key, (None, None))
        name = self._known[key][0]
        if name is not None and _AUTOMATIC not in name:
            return f"actor {name!r}"
        mapper = actor.GetMapper()
        data = mapper.GetInputDataObject(0, 0) if mapper is not None else None
        kind = type(pv.wrap(data)).__name__ if data is not None else "mesh-less"
        centre = actor.GetCenter()
        if not all(math.isfinite(value) for value in centre):
            return f"the unnamed {kind} actor"
        where = ", ".join(f"{value:.3g}" for value in centre)
        return f"the unnamed {kind} actor around ({where})"

    def _holds(self, key: str) -> bool:
        known = self._known.get(key)
        if known is None:
            return False
        name, actors = known
        if actors is None:
            return True  # not among PyVista's actors when last read
        held = actors.get(name)
        return held is not None and vtk_id(held) == key

    def _read(self) -> dict[str, tuple[str | None, dict | None]]:
        known = {}
        for renderer in self._plotter.renderers:
            actors = renderer.actors
            for name, actor in actors.items():
                known[vtk_id(actor)] = (name, actors)
        return known
