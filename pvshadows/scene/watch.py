"""Which actors VTK modified since the last frame, told by VTK's own ``ModifiedEvent``.

Reading every actor's modification times each frame costs a call per actor,
its mapper and its input, and after VTK has drawn a frame of a thousand
actors those objects are out of the CPU's caches: about 1.5 ms a frame for
1 000 actors to learn that nothing changed. VTK raises ``ModifiedEvent`` on
an object each time its modification time moves, so an observer on each
object an actor's shadow depends on marks the actor a suspect the moment it
changes, and a frame in which nothing changed reads nothing.

Watched per actor: the actor (its place, scale, visibility, user matrix and
mapper), its property (opacity, lighting, representation), its user matrix or
transform, its mapper (its input and settings), the mapper's input, and,
where the input has them, its points, their array and its polygons and
strips (raw VTK code may modify these without modifying the dataset; PyVista
modifies the dataset too). A suspect's modification times are then read
(:class:`pvshadows.scene.reader.SceneReader`) to tell whether it changed.
"""

from __future__ import annotations

from collections.abc import Iterator

from pvshadows import _vtk as vtk


def watched_objects(
    actor: vtk.vtkActor, mapper: vtk.vtkMapper | None, data: vtk.vtkDataObject | None
) -> Iterator[vtk.vtkObject]:
    """Yield the VTK objects whose modification can change an actor's shadow.

    Parameters
    ----------
    actor : vtk.vtkActor
        The actor.
    mapper : vtk.vtkMapper or None
        Its mapper.
    data : vtk.vtkDataObject or None
        The mapper's input.

    Yields
    ------
    vtk.vtkObject
        The actor, its property, user matrix or transform, the mapper, the
        input, and the input's points, point array, polygons and strips.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.watch import watched_objects
    >>> pl = pv.Plotter(off_screen=True)
    >>> actor = pl.add_mesh(pv.Cube())
    >>> mapper = actor.GetMapper()
    >>> watched = watched_objects(actor, mapper, mapper.GetInputDataObject(0, 0))
    >>> names = [item.GetClassName() for item in watched]
    >>> names[:2], names[-5:]
    (['vtkOpenGLActor', 'vtkOpenGLProperty'], \
['vtkPolyData', 'vtkPoints', 'vtkFloatArray', 'vtkCellArray', 'vtkCellArray'])
    """
    yield actor
    yield actor.GetProperty()
    for placement in (actor.GetUserMatrix(), actor.GetUserTransform()):
        if placement is not None:
            yield placement
    if mapper is not None:
        yield mapper
    if data is None:
        return
    yield data
    points = data.GetPoints() if isinstance(data, vtk.vtkPointSet) else None
    if points is not None:
        yield points
        yield points.GetData()
    if isinstance(data, vtk.vtkPolyData):
        yield data.GetPolys()
        yield data.GetStrips()


class ModificationWatch:
    """Observers that mark actors, by their place in a list, as suspects when modified.

    Examples
    --------
    >>> import pyvista as pv
    >>> from pvshadows.scene.watch import ModificationWatch
    >>> actor = pv.Actor(mapper=pv.DataSetMapper(pv.Cube()))
    >>> watch = ModificationWatch()
    >>> watch.watch(0, [actor, actor.GetProperty()])
    >>> watch.take()
    set()
    >>> actor.prop.opacity = 0.5
    >>> watch.take()
    {0}
    >>> watch.clear()
    >>> actor.prop.opacity = 0.25
    >>> watch.take()
    set()
    """

    def __init__(self) -> None:
        self._suspects: set[int] = set()
        self._observers: dict[int, list[tuple[vtk.vtkObject, int]]] = {}

    def watch(self, index: int, objects: Iterator[vtk.vtkObject] | list[vtk.vtkObject]) -> None:
        """Watch ``objects`` for the actor at ``index``, in place of what was watched for it.

        An actor that moved or changed its points usually keeps the same
        objects: their observers then stay as they are, since adding and
        removing them costs more than the actor's whole new state.

        Parameters
        ----------
        index : int
            The actor's place in the renderer's actor list.
        objects : iterable of vtk.vtkObject
            What its shadow depends on (:func:`watched_objects`).
        """
        wanted = list(objects)
        kept = self._observers.get(index)
        if kept is not None and len(kept) == len(wanted):
            if all(item is old for item, (old, _) in zip(wanted, kept, strict=True)):
                return
        self.unwatch(index)
        suspects = self._suspects

        def mark(caller: vtk.vtkObject, event: str) -> None:
            suspects.add(index)

        self._observers[index] = [
            (item, item.AddObserver(vtk.vtkCommand.ModifiedEvent, mark)) for item in wanted
        ]

    def unwatch(self, index: int) -> None:
        """Stop watching the actor at ``index``.

        Parameters
        ----------
        index : int
            The actor's place in the renderer's actor list.
        """
        for item, tag in self._observers.pop(index, ()):
            item.RemoveObserver(tag)

    def take(self) -> set[int]:
        """Return the places of the actors modified since the last call, and forget them.

        Returns
        -------
        set of int
            Places in the renderer's actor list.
        """
        suspects = set(self._suspects)
        self._suspects.clear()
        return suspects

    def clear(self) -> None:
        """Remove every observer and forget every suspect."""
        for index in list(self._observers):
            self.unwatch(index)
        self._suspects.clear()
