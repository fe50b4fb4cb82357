"""A component's moving shapes, rebuilt only when what they show has changed.

A simulation samples a rig's ``dynamic_drawables()`` 25 times per simulated second; between two frames most of a
rig stands still (a beam stays free, a retracted piston stays back, a bin keeps its count). Building the shapes
(numpy arrays, dataclasses) costs a few µs each, so a component hands its drawing function to a :class:`Sketch`
together with a key of the state it draws; the same key gives the same (shared, never modified) drawables.

>>> built = []
>>> s = Sketch(lambda: built.append(1) or ["shape"])
>>> s(("free",)), s(("free",)), s(("cut",)), len(built)
(['shape'], ['shape'], ['shape'], 2)
"""

from __future__ import annotations

from collections.abc import Callable, Hashable

from plcsim.plant import Drawable

_UNDRAWN = object()


class Sketch:
    """``sketch(key)``: the drawables ``build()`` made for this ``key``, built again when the key changes."""

    def __init__(self, build: Callable[[], list[Drawable]]) -> None:
        self.build = build
        self.key: Hashable = _UNDRAWN
        self.drawn: list[Drawable] = []

    def __call__(self, key: Hashable) -> list[Drawable]:
        if key != self.key:
            self.key, self.drawn = key, self.build()
        return self.drawn
