"""``cached``: :func:`functools.cached_property` without Python 3.11's lock.

On Python 3.11, ``functools.cached_property`` takes a lock on the first read
of each object's value (Python 3.12 dropped it). Frames make a few new light
poses and fits each, and a moved actor a new snapshot with some twenty
values read once each: the lock cost more than most of those values. This
subclass works the value out and stores it in the object's ``__dict__``, as
``cached_property`` does, without the lock; like every value pvshadows
caches, it is read from one thread.
"""

from __future__ import annotations

from functools import cached_property
from typing import Any, TypeVar, overload

T = TypeVar("T")


class cached(cached_property[T]):
    """A value worked out on first read and kept on the object, as ``cached_property``.

    Examples
    --------
    >>> from pvshadows._cached import cached
    >>> class Box:
    ...     reads = 0
    ...
    ...     @cached
    ...     def size(self) -> int:
    ...         Box.reads += 1
    ...         return 3
    >>> box = Box()
    >>> box.size, box.size, Box.reads
    (3, 3, 1)
    """

    @overload
    def __get__(self, instance: None, owner: type[Any] | None = None) -> cached[T]: ...

    @overload
    def __get__(self, instance: object, owner: type[Any] | None = None) -> T: ...

    def __get__(self, instance: object | None, owner: type[Any] | None = None) -> Any:
        if instance is None:
            return self
        assert self.attrname is not None  # set by __set_name__ when the class is made
        value = instance.__dict__[self.attrname] = self.func(instance)
        return value
