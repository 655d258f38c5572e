"""A word from another thread to a Qt object, delivered on the GUI thread if the object is still there.

A thread that is done with its work (importing pyvista, typesetting a formula) tells the widget that
asked for it through :func:`tell`.  The one object that carries the word lives as long as the program:
an object the widget owned, deleted with the widget while the thread emitted its signal, crashed the
program.  The widget is held by a weak reference, and nothing is delivered to one deleted meanwhile.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable
from functools import lru_cache

import shiboken6
from PySide6.QtCore import QObject, Signal, Slot


class _Messenger(QObject):
    told = Signal(object, object)  # a weak reference to the widget, what to do with it

    def __init__(self):
        super().__init__()
        self.told.connect(self._deliver)  # queued onto the GUI thread, where this object lives

    @Slot(object, object)
    def _deliver(self, target: weakref.ref, call: Callable) -> None:
        widget = target()
        if widget is not None and shiboken6.isValid(widget):
            call(widget)


@lru_cache(maxsize=1)
def messenger() -> _Messenger:
    """The one messenger (its ``told`` signal carries every word).  First asked for on the GUI thread:
    a widget asks for it before it starts a thread that will :func:`tell` it."""
    return _Messenger()


def tell(target: weakref.ref, call: Callable) -> None:
    """``call(widget)`` on the GUI thread, if ``target()`` still gives a widget then; from any thread."""
    messenger().told.emit(target, call)
