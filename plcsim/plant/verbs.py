"""A rig's own scenario verbs (``set_colour``, ``jam_piston``): part of the rig protocol, so that a rig brings one
with nothing but :mod:`plcsim.plant` and adding one needs no edit in plcsim.

Calling a :class:`RigVerb` builds a scenario action, and actions are the scenario layer's, which lies above the
plant's: :mod:`plcsim.scenario.verbs` hands its builder to :func:`build_actions_with` when it is imported (and
``import plcsim`` imports it), so this module never imports the scenario.
"""

from __future__ import annotations

import string
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from plcsim.core.errors import ConfigurationError

ActionBuilder = Callable[..., Any]
"""``builder(verb, target, t, when, delay, **args)``: the scenario action a call of the rig verb ``verb`` stands for."""

_build_action: ActionBuilder | None = None


def build_actions_with(builder: ActionBuilder) -> None:
    """Make ``builder`` build the action of every call of a rig verb (:mod:`plcsim.scenario.verbs` does, on import)."""
    global _build_action
    _build_action = builder


@dataclass(frozen=True)
class RigVerb:
    """A scenario verb a rig brings (``set_colour``, ``jam_piston``), so that adding one needs no edit in plcsim.

    The rig lists it in its ``VERBS``; the exercise calls it to build an action, like any other verb::

        JAM_PISTON = RigVerb("jam_piston", "jam_piston", "piston", "jam piston {target}", targets="pistons")
        Scenario("jammed", place("p1", at="table", t="0.5s"), JAM_PISTON("P1", t="1s"), duration="5s")

    Attributes:
        name: the verb (the kind of its trace event, what ``action(name)`` in a check counts).
        method: the plant method that carries it out, called as ``method(target, **args)``.
        role: what the target names (``piston``, ``part``), for messages.
        phrase: how the action is worded, formatted with ``target`` and the action's keyword arguments (it names
            every argument the verb takes: :attr:`arguments`).
        targets: the plant attribute holding the names a target may be (a mapping or a set); empty with
            ``role="part"``: the target is a part of the scenario (its plant id is passed to the method).
        state: True if whether it can be done depends on the run (a part that is gone): a failure is then
            recorded as ``action failed``; otherwise it is the instructor's mistake and raises.
        doc: what it does, for the rig's documentation.
        controller: True for a verb the controller brings rather than the rig (the Tecomat's ``interrupt``):
            it lists it in its own ``VERBS``, ``method`` and ``targets`` are the controller's, and a run on a
            controller without it is refused before it starts (:func:`plcsim.scenario.names.controller_verb_problems`).
        fault: True for a verb that injects a fault (a jammed piston, a failed compressor): a scenario using it is
            outside the machine's normal operation, and declares the task's words for it (``Scenario(outside=...)``).
    """

    name: str
    method: str
    role: str
    phrase: str
    targets: str = ""
    state: bool = False
    doc: str = ""
    controller: bool = False
    fault: bool = False

    def __call__(self, target: str, t: Any = None, *, when: Any = None, delay: Any = 0, **args: Any) -> Any:
        """The scenario action (a :class:`plcsim.scenario.verbs.Action`) of this verb on ``target``, at ``t`` or
        ``when`` a trigger fires, like any verb of :mod:`plcsim.scenario`."""
        if _build_action is None:
            raise ConfigurationError(f"rig verb {self.name!r}: its actions are built by plcsim.scenario; import it")
        return _build_action(self, target, t, when, delay, **args)

    @property
    def arguments(self) -> tuple[str, ...]:
        """The keyword arguments it takes: those its phrase names besides the target (``offset`` of
        ``"set the ambient light on {target} to {offset:+g} raw"``), the rig's declared vocabulary for them."""
        fields = (f for _, f, _, _ in string.Formatter().parse(self.phrase) if f and f != "target")
        return tuple(dict.fromkeys(fields))

    @property
    def on_parts(self) -> bool:
        return self.role == "part" and not self.targets

    def valid_targets(self, plant: Any) -> list[str]:
        """The names its target may be on ``plant`` (parts aside)."""
        return [] if self.on_parts else list(getattr(plant, self.targets))
