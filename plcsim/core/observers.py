"""Observer hooks as lists of subscribers: a recorder, a live panel and a test watch one CPU together.

A hook's :attr:`Subscribers.call` is what the CPU calls: None without subscribers, the one subscriber
itself with one (the hot path of a recorded run pays nothing for the list), a fan-out with more.

>>> seen = []
>>> hook = Subscribers()
>>> hook.add(lambda x: seen.append(("recorder", x)))
>>> hook.assign(lambda x: seen.append(("panel", x)))
>>> hook.call(1)
>>> hook.assign(lambda x: seen.append(("other panel", x)))  # replaces only the assigned subscriber
>>> hook.call(2)
>>> seen
[('recorder', 1), ('panel', 1), ('recorder', 2), ('other panel', 2)]
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any


class Subscribers:
    """The subscribers of one event, called in the order they subscribed."""

    __slots__ = ("_subscribers", "assigned", "call")

    def __init__(self) -> None:
        self._subscribers: list[Callable[..., None]] = []
        self.assigned: Callable[..., None] | None = None
        """The subscriber set by assignment (``cpu.on_scan_end = hook``); assigning again replaces it."""
        self.call: Callable[..., None] | None = None

    def add(self, subscriber: Callable[..., None]) -> None:
        """Subscribe (after those already subscribed)."""
        self._subscribers.append(subscriber)
        self._update()

    def remove(self, subscriber: Callable[..., None]) -> None:
        """Unsubscribe (a ValueError if it is not subscribed)."""
        self._subscribers.remove(subscriber)
        self._update()

    def assign(self, subscriber: Callable[..., None] | None) -> None:
        """Replace the assigned subscriber (None: remove it), leaving every other one subscribed."""
        if self.assigned is not None:
            self._subscribers.remove(self.assigned)
        self.assigned = subscriber
        if subscriber is not None:
            self._subscribers.append(subscriber)
        self._update()

    def __len__(self) -> int:
        return len(self._subscribers)

    def _update(self) -> None:
        subscribers = tuple(self._subscribers)
        if len(subscribers) <= 1:
            self.call = subscribers[0] if subscribers else None
            return

        def fan_out(*args: Any) -> None:
            for subscriber in subscribers:
                subscriber(*args)

        self.call = fan_out


def assigned_hook(event: str, doc: str) -> property:
    """A property for one subscriber set by assignment (``cpu.on_scan_end = hook``) on the hook ``event``."""

    def get(owner: Any) -> Callable[..., None] | None:
        return getattr(owner, event).assigned

    def set_(owner: Any, subscriber: Callable[..., None] | None) -> None:
        getattr(owner, event).assign(subscriber)

    return property(get, set_, doc=doc)
