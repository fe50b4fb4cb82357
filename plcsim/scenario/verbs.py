"""The scenario verbs: what the operator does and what goes wrong, as actions on a timeline an instructor can read.

>>> from plcsim.scenario import Scenario
>>> jam_run = Scenario(
...     "jam",
...     place("part", at="S1", t="0.5s"),
...     jam("part", t="2s"),
...     write("ACK", True, t="15s"),
...     duration="20s",
... )
>>> [a.describe() for a in jam_run.actions][:2]
["place 'part' at S1 at 500 ms", "jam 'part' at 2 s"]

Times are literals (``"2s"``) or seeded ranges (``"2s..3s"``); an action may instead wait for the
plant (``when=held("S2", "1s")``: after S2 has been interrupted for 1 s). Parts are placed with the
pose noise of the textbook rigs (±5 mm, ±5°) unless ``noise=False``. Each action remembers the
file and line that created it, so a bad name is reported where the instructor wrote it.

A rig's own verbs (:class:`~plcsim.plant.verbs.RigVerb`, part of the rig protocol) build their actions here too.
The timeline as a whole is :mod:`plcsim.scenario.planning`; the names it relies on are checked by
:mod:`plcsim.scenario.names`.
"""

from __future__ import annotations

import keyword
import math
import random
from dataclasses import dataclass, field
from typing import Any

from plcsim.core.errors import ExerciseError, PlcError, defined_at
from plcsim.core.literals import format_ns, to_ns
from plcsim.plant.protocol import MOTOR_JAM, OPERATOR, PART_FAULTS, PARTS, SENSOR_SHIFT
from plcsim.plant.verbs import RigVerb, build_actions_with


class ScenarioError(ExerciseError):
    """An action naming a station, signal, button or tag that does not exist, or a bad time: the instructor's
    mistake, never the student's."""


@dataclass(frozen=True)
class TimeSpec:
    """A time on the timeline: fixed, or drawn uniformly from ``lo..hi`` with the scenario's seed."""

    lo_ns: int
    hi_ns: int

    @classmethod
    def parse(cls, value: str | int | TimeSpec) -> TimeSpec:
        if isinstance(value, TimeSpec):
            return value
        if isinstance(value, str) and ".." in value:
            lo, hi = value.split("..", 1)
            spec = cls(to_ns(lo.strip()), to_ns(hi.strip()))
            if spec.hi_ns < spec.lo_ns:
                raise ScenarioError(f"time range {value!r} runs backwards")
        else:
            ns = to_ns(value, "time")
            spec = cls(ns, ns)
        if spec.lo_ns < 0:
            raise ScenarioError(f"time {value!r} is negative; times count from the start of the run (0 s)")
        return spec

    def draw(self, rng: random.Random) -> int:
        return self.lo_ns if self.lo_ns == self.hi_ns else rng.randint(self.lo_ns, self.hi_ns)

    def __str__(self) -> str:
        if self.lo_ns == self.hi_ns:
            return format_ns(self.lo_ns)
        return f"{format_ns(self.lo_ns)}..{format_ns(self.hi_ns)}"


@dataclass(frozen=True)
class OneOf:
    """A part property drawn with the scenario's seed from a few values (``place(..., bad=one_of(True, False))``),
    so that each grading seed gives another sequence of parts."""

    values: tuple[Any, ...]

    def draw(self, rng: random.Random) -> Any:
        return self.values[rng.randrange(len(self.values))]

    def __repr__(self) -> str:
        return f"one_of({', '.join(map(repr, self.values))})"


def one_of(*values: Any) -> OneOf:
    """A part property drawn from ``values`` with the scenario's seed, once per placement and run.

    >>> import random
    >>> bad = one_of(True, False)
    >>> bad, [bad.draw(random.Random(seed)) for seed in range(6)]
    (one_of(True, False), [False, True, True, True, True, False])
    """
    if not values:
        raise ScenarioError(f"{defined_at()}: one_of() needs at least one value to draw from")
    return OneOf(tuple(values))


@dataclass(frozen=True)
class Trigger:
    """Wait for the plant: a sensor held at a value for a time, or a plant event."""

    signal: str | None = None
    value: Any = True
    for_ns: int = 0
    event: str | None = None
    subject: str | None = None

    def describe(self) -> str:
        if self.event:
            return f"after '{self.event}'" + (f" of {self.subject}" if self.subject else "")
        state = "interrupted/actuated" if self.value is True else f"= {self.value}"
        return f"when {self.signal} has been {state} for {format_ns(self.for_ns)}"


def held(signal: str, duration: str | int = 0, value: Any = True) -> Trigger:
    """Trigger when a plant sensor has had ``value`` (default: actuated) for ``duration``."""
    return Trigger(
        signal=signal, value=value, for_ns=parse_at_line(TimeSpec.parse, duration, f"held({signal!r})").lo_ns
    )


def after_event(kind: str, subject: str | None = None) -> Trigger:
    """Trigger when the plant reports an event (``part entered``, ``part fell off`` ...)."""
    return Trigger(event=kind, subject=subject)


@dataclass
class Action:
    """One step of a scenario. ``verb`` says what, ``target`` on what, ``t`` or ``when`` says when."""

    verb: str
    target: str = ""
    t: TimeSpec | None = None
    when: Trigger | None = None
    delay: TimeSpec = field(default_factory=lambda: TimeSpec(0, 0))
    args: dict[str, Any] = field(default_factory=dict)
    defined_at: str = "?"
    rig: RigVerb | None = None  # a verb the rig brings (None: one of plcsim's own)

    def describe(self) -> str:
        what = self._core_phrase() if self.rig is None else self.rig.phrase.format(target=self.target, **self.args)
        if self.when is not None:
            when = self.when.describe() + (f" + {self.delay}" if self.delay.hi_ns else "")
        elif "hold" in self.args:  # the release of press(..., hold=...)
            when = f"{self.args['hold']} after the press"
        else:
            when = f"at {self.t}"
        return f"{what} {when}"

    def _core_phrase(self) -> str:
        return {
            "place": f"place {self.target!r} at {self.args.get('station')}",
            "press": f"press {self.target}",
            "release": f"release {self.target}",
            "switch": f"switch {self.target} {'on' if self.args.get('on') else 'off'}",
            "write": f"write {self.target} = {self.args.get('value')!r}",
            "force": f"force {self.target} = {self.args.get('value')!r}",
            "unforce": f"remove the force on {self.target}",
            "remove": f"remove {self.target!r}",
            "jam": f"jam {self.target!r}",
            "unjam": f"free {self.target!r}",
            "knock_off": f"knock {self.target!r} off",
            "stick": f"stick {self.target} at {self.args.get('value')!r}",
            "break_wire": f"break the wire of {self.target}",
            "chatter": f"make {self.target} chatter",
            "clear": f"clear the fault on {self.target}",
            "shift": f"shift sensor {self.target} by {self.args.get('mm')} mm",
            "jam_motor": f"jam motor {self.target}",
            "free_motor": f"free motor {self.target}",
            "stop_cpu": "switch the CPU to STOP",
            "start_cpu": "switch the CPU to RUN",
            "power_cycle": "power the CPU off and on",
            "download": f"download the program {self.args.get('file') or ''}".rstrip(),
        }.get(self.verb, self.verb)

    @property
    def fault(self) -> bool:
        """True if the action injects a fault (:data:`FAULT_VERBS`, or a rig verb declared ``fault=True``)."""
        return self.rig.fault if self.rig is not None else self.verb in FAULT_VERBS

    def names(self) -> list[tuple[str, str]]:
        """The names this action relies on, by role: ``[("station", "S1"), ("signal to wait for", "S2")]``."""
        out = [("station", self.args["station"])] if self.verb == "place" else []
        role = self.rig.role if self.rig is not None else TARGET_ROLES.get(self.verb)
        if role is not None:
            out.append((role, self.target))
        if self.when is not None and self.when.signal is not None:
            out.append(("signal to wait for", self.when.signal))
        if self.when is not None and self.when.event is not None:
            out.append(("plant event to wait for", self.when.event))
        if self.when is not None and self.when.subject is not None:
            out.append(("event subject (a part or plant name)", self.when.subject))
        return out


TARGET_ROLES = {
    "press": "button or switch",
    "release": "button or switch",
    "switch": "button or switch",
    "write": "tag",
    "force": "tag",
    "unforce": "tag",
    "remove": "part or station",
    "jam": "part",
    "unjam": "part",
    "knock_off": "part",
    "stick": "wired signal",
    "break_wire": "wired signal",
    "chatter": "wired signal",
    "clear": "wired signal",
    "shift": "sensor",
    "jam_motor": "motor",
    "free_motor": "motor",
}
"""What the target of each verb names (the verbs on the CPU have none)."""
VERBS = (*TARGET_ROLES, "place", "stop_cpu", "start_cpu", "power_cycle", "download")
"""Every verb of plcsim's own (the kinds of the scenario's trace events, with ``action failed`` and the rig's verbs)."""
FAULT_VERBS = frozenset({"jam", "knock_off", "stick", "break_wire", "chatter", "shift", "jam_motor"})
"""plcsim's verbs that inject a fault: a part jammed or knocked off, a sensor stuck, broken, chattering or off its
place, a motor jammed. A scenario using one is outside the operating conditions of the task unless the task says
what must happen then (see :mod:`plcsim.check.operating`); the verbs that clear a fault inject none."""

VERB_CAPABILITY = {
    "place": PARTS,
    "remove": PARTS,
    "jam": PART_FAULTS,
    "unjam": PART_FAULTS,
    "knock_off": PART_FAULTS,
    "press": OPERATOR,
    "release": OPERATOR,
    "switch": OPERATOR,
    "shift": SENSOR_SHIFT,
    "jam_motor": MOTOR_JAM,
    "free_motor": MOTOR_JAM,
}
"""The plant capability each of plcsim's verbs needs (a verb on a rig that lacks it is refused at load time)."""


PLACE_KEYS = frozenset(
    {"t", "verb", "target", "at", "station", "when", "delay", "noise", "offset_mm", "angle_deg", "part"}
)
"""The names a ``place`` action (and its row in a saved ``.toml``) uses itself: no part property may take one."""


def check_property_name(name: Any, where: str) -> None:
    """Refuse a part property's name that is not a plain Python name, or is one :data:`PLACE_KEYS` holds: a property
    is written as a keyword (``colour=2``) in a ``.py`` scenario and as a key beside the station in a ``.toml`` one,
    so that any other name could not be read back as the property it was."""
    if not (isinstance(name, str) and name.isidentifier() and not keyword.iskeyword(name)):
        raise ScenarioError(f"{where}: part property name {name!r} is not a Python name (e.g. colour=2)")
    if name in PLACE_KEYS:
        raise ScenarioError(
            f"{where}: part property name {name!r} is the action's own ({', '.join(sorted(PLACE_KEYS))})"
        )


def check_plain(value: Any, what: str) -> None:
    """Refuse a value a scenario file cannot hold as a literal: only booleans, integers, finite numbers, text and
    tuples or lists of them (what a page may send, as an exercise would write it)."""
    if isinstance(value, (list, tuple)):
        for item in value:
            check_plain(item, what)
    elif isinstance(value, float) and not math.isfinite(value):
        raise ScenarioError(f"{what}={value!r}: a number must be finite")
    elif value is not None and not isinstance(value, (bool, int, float, str)):
        raise ScenarioError(
            f"{what}={value!r}: a scenario holds numbers, true/false and text, not {type(value).__name__}"
        )


def parse_at_line(parse: Any, value: Any, what: str) -> Any:
    """``parse(value)``, an error in it reported at the instructor's line."""
    try:
        return parse(value)
    except PlcError as exc:
        raise ScenarioError(f"{defined_at()}: {what}: {exc}") from None


def _action(verb: str, target: str, t: Any, when: Trigger | None, delay: Any = 0, **args: Any) -> Action:
    if (t is None) == (when is None):
        raise ScenarioError(f"{defined_at()}: {verb} {target}: give exactly one of t='2s' or when=held(...)")
    spec = None if t is None else parse_at_line(TimeSpec.parse, t, f"{verb} {target}")
    delay_spec = parse_at_line(TimeSpec.parse, delay, f"{verb} {target}: delay")
    return Action(verb, target, spec, when, delay_spec, args, defined_at())


def _rig_action(verb: RigVerb, target: str, t: Any, when: Trigger | None, delay: Any, **args: Any) -> Action:
    """The action of a call of the rig verb ``verb`` (:class:`~plcsim.plant.verbs.RigVerb` builds it here); it takes
    the arguments its phrase names, no other."""
    takes = verb.arguments
    listed = ", ".join(takes) or "none"
    for name in args:
        if name not in takes:
            raise ScenarioError(f"{defined_at()}: {verb.name} {target}: no argument {name!r}; its arguments: {listed}")
    missing = [name for name in takes if name not in args]
    if missing:
        raise ScenarioError(f"{defined_at()}: {verb.name} {target}: give {', '.join(f'{m}=' for m in missing)}")
    action = _action(verb.name, target, t, when, delay, **args)
    action.rig = verb
    return action


build_actions_with(_rig_action)


def press(button: str, t: Any = None, *, hold: Any = None, when: Trigger | None = None, delay: Any = 0) -> list[Action]:
    """Press a push button at ``t``; with ``hold="200ms"`` release it again after that long."""
    actions = [_action("press", button, t, when, delay)]
    if hold is not None:
        if t is None:
            raise ScenarioError(f"{defined_at()}: press {button}: hold= needs a fixed t=")
        actions.append(
            Action(
                "release",
                button,
                None,
                None,
                TimeSpec(0, 0),
                {"after": actions[0], "hold": parse_at_line(TimeSpec.parse, hold, f"press {button}: hold")},
                defined_at(),
            )
        )
    return actions


def release(button: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Release a push button."""
    return _action("release", button, t, when, delay)


def switch(name: str, on: bool, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Turn a switch on or off."""
    return _action("switch", name, t, when, delay, on=on)


def write(tag: str, value: Any, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Write a tag once, as an HMI button or a watch table does (``ACK``, ``DATA.x``, ``NULUJ``)."""
    return _action("write", tag, t, when, delay, value=value)


def force(tag: str, value: Any, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Force a tag, as a force table does: the value holds at every image update, whatever the program writes."""
    return _action("force", tag, t, when, delay, value=value)


def unforce(tag: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Remove the force on a tag (it keeps the forced value until something writes it)."""
    return _action("unforce", tag, t, when, delay)


def place(
    part: str,
    *,
    at: str,
    t: Any = None,
    when: Trigger | None = None,
    delay: Any = 0,
    noise: bool = True,
    offset_mm: float | tuple[float, float] | None = None,
    angle_deg: float | tuple[float, float] | None = None,
    **properties: Any,
) -> Action:
    """Put a new part named ``part`` at station ``at`` (with ±5 mm / ±5° pose noise unless noise=False).

    ``offset_mm`` and ``angle_deg`` fix the pose error, or draw it from a range with the scenario's seed:
    ``place("p1", at="table", offset_mm=(0, 15), angle_deg=(-15, 15))`` (what the offset means is the rig's:
    along the belt, or away from a fence). A property may be drawn with the seed too:
    ``place("p1", at="S1", bad=one_of(True, False))`` (the ``part placed`` event then carries the value drawn).
    """
    for name in properties:
        check_property_name(name, f"place {part}")
    for what, v in (("offset_mm", offset_mm), ("angle_deg", angle_deg)):
        if isinstance(v, tuple) and not (len(v) == 2 and v[0] <= v[1]):
            raise ScenarioError(f"{defined_at()}: place {part}: {what}={v!r} must be a number or a (lo, hi) range")
    return _action(
        "place",
        part,
        t,
        when,
        delay,
        station=at,
        noise=noise,
        offset_mm=offset_mm,
        angle_deg=angle_deg,
        properties=properties,
    )


def remove(target: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Take a part away (by its name, or the station it is at)."""
    return _action("remove", target, t, when, delay)


def jam(part: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Hold a part where it is: the belt slips under it."""
    return _action("jam", part, t, when, delay)


def unjam(part: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Free a jammed part."""
    return _action("unjam", part, t, when, delay)


def knock_off(part: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Push a part off the machine."""
    return _action("knock_off", part, t, when, delay)


def stuck(signal: str, value: Any, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Stuck-at fault on a wired signal (by signal or tag name)."""
    return _action("stick", signal, t, when, delay, value=value)


def wire_break(signal: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Broken wire: the input reads FALSE (an NC sensor then reads 'object present')."""
    return _action("break_wire", signal, t, when, delay)


def chatter(
    signal: str,
    t: Any = None,
    *,
    when: Trigger | None = None,
    delay: Any = 0,
    transitions: tuple[int, int] = (3, 5),
    width: tuple[str, str] = ("2ms", "10ms"),
) -> Action:
    """Contact bounce on a sensor from ``t`` on: every change comes with a few short extra toggles."""
    return _action("chatter", signal, t, when, delay, transitions=transitions, width=width)


def clear(signal: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Remove a wiring fault."""
    return _action("clear", signal, t, when, delay)


def shift_sensor(sensor: str, mm: float, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Misalign a sensor by ``mm`` along the belt."""
    return _action("shift", sensor, t, when, delay, mm=mm)


def jam_motor(actuator: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Block a motor: commanded, it does not move."""
    return _action("jam_motor", actuator, t, when, delay)


def free_motor(actuator: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Unblock a jammed motor."""
    return _action("free_motor", actuator, t, when, delay)


def stop_cpu(t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Switch the CPU to STOP (the mode switch)."""
    return _action("stop_cpu", "CPU", t, when, delay)


def start_cpu(t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Switch the CPU to RUN."""
    return _action("start_cpu", "CPU", t, when, delay)


def power_cycle(t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Power the CPU off and on (retain tags survive)."""
    return _action("power_cycle", "CPU", t, when, delay)


def download(program: str, t: Any = None, *, file: str = "", when: Trigger | None = None, delay: Any = 0) -> Action:
    """Download a changed program into the running CPU: STOP, load, RUN, as TIA Portal's download does; the
    tags that keep their name and type keep their values (a download without reinitialization), the machine
    keeps running. ``program`` is the program's whole text (a replay needs no file); ``file`` names it."""
    if not isinstance(program, str) or not program.strip():
        raise ScenarioError(f"{defined_at()}: download needs the program's text")
    return _action("download", "CPU", t, when, delay, program=program, file=file)
