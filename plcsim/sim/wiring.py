"""Wiring: plant signals to PLC addresses, the way an electrician connects a training rig.

A sensor reports its physical state (a light barrier is True while interrupted). Wired **NO**, the
PLC input is TRUE while the sensor is actuated; wired **NC**, it is TRUE while the sensor is *not*
actuated, and a broken wire reads like "actuated" (textbook 4.3.2, 4.3.10). Analog signals are scaled
to the module's raw range (0..27 648). Faults live here too: stuck-at, wire break and contact chatter.

>>> Wire("S1", "S1", "NC").level(True)
False
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from plcsim.core.errors import ConfigurationError, did_you_mean
from plcsim.core.literals import to_ns
from plcsim.plant.protocol import Plant, SignalSpec
from plcsim.tags.table import TagTable


class WiringError(ConfigurationError):
    """A wire to a signal or tag that does not exist, an address used twice, a sensor on an output."""


@dataclass(frozen=True)
class Wire:
    """One connection between a plant signal and a PLC tag.

    Attributes:
        signal: the plant's signal name.
        tag: the PLC tag (an %I tag for a sensor, a %Q tag for an actuator).
        contact: ``NO`` or ``NC`` for a Boolean sensor.
        raw: the raw module range of an analog signal (Siemens: 0..27 648).
        noise: standard deviation of analog noise, in raw units (seeded).
    """

    signal: str
    tag: str
    contact: str = "NO"
    raw: tuple[int, int] = (0, 27_648)
    noise: float = 0.0

    def level(self, actuated: bool) -> bool:
        """The electrical level at the PLC input for a physical state."""
        return (not actuated) if self.contact == "NC" else actuated


def NO(signal: str, tag: str | None = None) -> Wire:
    """A normally-open contact: the input is TRUE while the sensor is actuated."""
    return Wire(signal, tag or signal, "NO")


def NC(signal: str, tag: str | None = None) -> Wire:
    """A normally-closed contact: the input is TRUE while the sensor is not actuated."""
    return Wire(signal, tag or signal, "NC")


def analog(signal: str, tag: str | None = None, raw: tuple[int, int] = (0, 27_648), noise: float = 0.0) -> Wire:
    """An analog input or output scaled to the raw module range."""
    return Wire(signal, tag or signal, "NO", raw, noise)


@dataclass
class _Fault:
    kind: str  # "stuck", "wire break", "chatter"
    value: Any = None
    transitions: tuple[int, int] = (3, 5)
    width_ns: tuple[int, int] = (2_000_000, 10_000_000)


class Wiring:
    """The connections of one rig to one CPU, with injected faults.

    Args:
        plant: the machine.
        table: the CPU's tag table (``cpu.table``).
        wires: the connections.
        seed: seed of chatter and analog noise.
    """

    def __init__(self, plant: Plant, table: TagTable, wires: Iterable[Wire], *, seed: int = 0):
        self.plant = plant
        self.wires = list(wires)
        self.rng = random.Random(seed)
        self._validate(table)
        self.by_signal = {w.signal: w for w in self.wires}
        self.by_tag = {w.tag: w for w in self.wires}
        self._inputs_bool: list[tuple[str, str, bool]] = []
        self._inputs_analog: list[tuple[Wire, SignalSpec]] = []
        self._outputs: list[tuple[Wire, SignalSpec]] = []
        for w in self.wires:
            spec = plant.signals[w.signal]
            if spec.direction == "sensor":
                if spec.kind == "bool":
                    self._inputs_bool.append((w.signal, w.tag, w.contact == "NC"))
                else:
                    self._inputs_analog.append((w, spec))
            else:
                self._outputs.append((w, spec))
        self._copy_inputs = _input_copier(self._inputs_bool, self._inputs_analog, plant, self.rng)
        self.faults: dict[str, _Fault] = {}
        self._chatter: dict[str, list[tuple[int, int]]] = {}
        self.step_inputs: Callable[[dict[str, Any], int], None] = self._copy_inputs
        """What the simulator calls in every step: :meth:`read_inputs`, or without a fault its fault-free copy
        itself (one call less per step; the fault methods switch between them)."""
        self._last_physical: dict[str, Any] = {}
        self._sent: dict[str, Any] = {}
        self._outputs_seen: Mapping[str, Any] | None = None

    # -- validation ---------------------------------------------------------------------------

    def _validate(self, table: TagTable) -> None:
        signals = self.plant.signals
        seen_tags: dict[str, str] = {}
        seen_addr: dict[str, str] = {}
        seen_signals: set[str] = set()
        for w in self.wires:
            if w.signal not in signals:
                raise WiringError(
                    f"wiring: {self.plant.name} has no signal {w.signal!r}"
                    f"{did_you_mean(w.signal, signals)}; its signals: {', '.join(signals)}"
                )
            if w.signal in seen_signals:
                raise WiringError(f"wiring: signal {w.signal!r} is wired twice")
            seen_signals.add(w.signal)
            if w.tag not in table:
                raise WiringError(
                    f"wiring: {w.signal} goes to tag {w.tag!r}, which is not in the tag table"
                    f"{did_you_mean(w.tag, [e.name for e in table])}"
                )
            entry = table[w.tag]
            if entry.address is None:
                raise WiringError(f"wiring: tag {w.tag!r} has no address; a wire needs an %I or %Q tag")
            spec = signals[w.signal]
            area = entry.address.area
            if spec.direction == "sensor" and area != "I":
                raise WiringError(
                    f"wiring: sensor {w.signal} is wired to {w.tag} at {entry.address}; sensors go to inputs (%I)"
                )
            if spec.direction == "actuator" and area != "Q":
                raise WiringError(
                    f"wiring: actuator {w.signal} is wired to {w.tag} at {entry.address}; "
                    f"actuators are driven by outputs (%Q)"
                )
            if w.tag in seen_tags:
                raise WiringError(f"wiring: tag {w.tag!r} is wired to both {seen_tags[w.tag]} and {w.signal}")
            seen_tags[w.tag] = w.signal
            addr = str(entry.address)
            if addr in seen_addr:
                raise WiringError(
                    f"wiring: address {addr} is already used by {seen_addr[addr]}; "
                    f"{w.signal} needs an address of its own"
                )
            seen_addr[addr] = w.signal
            if w.contact not in ("NO", "NC"):
                raise WiringError(f"wiring: {w.signal}: contact must be 'NO' or 'NC', not {w.contact!r}")
            if spec.kind == "bool" and entry.member.type.name != "Bool":
                raise WiringError(f"wiring: {w.signal} is a Boolean signal but {w.tag} is {entry.member.type.name}")

    def signal_for(self, name: str) -> str:
        """The plant signal named by a signal or tag name."""
        if name in self.by_signal:
            return name
        if name in self.by_tag:
            return self.by_tag[name].signal
        known = list(self.by_signal) + list(self.by_tag)
        raise WiringError(f"no wired signal or tag {name!r}{did_you_mean(name, known)}")

    # -- the hot path -------------------------------------------------------------------------

    def read_inputs(self, inputs: dict[str, Any], now_ns: int) -> None:
        """Copy the sensors' electrical levels into the CPU's input terminals."""
        if self.faults or self._chatter:
            sensors = self.plant.sensors
            for signal, tag, invert in self._inputs_bool:
                inputs[tag] = self._faulted_level(signal, invert, sensors[signal], now_ns)
            for wire, spec in self._inputs_analog:
                inputs[wire.tag] = self._raw(wire, spec, sensors[wire.signal], wire.signal)
            return
        self._copy_inputs(inputs, now_ns)

    @property
    def faulted(self) -> bool:
        """Whether a fault acts on a wire (then :attr:`step_inputs` is :meth:`read_inputs`, which needs the time)."""
        return self.step_inputs is not self._copy_inputs

    def _faults_changed(self) -> None:
        self.step_inputs = self.read_inputs if self.faults or self._chatter else self._copy_inputs

    def write_outputs(self, outputs: Mapping[str, Any]) -> None:
        """Send changed PLC outputs to the plant's actuators."""
        plant = self.plant
        sent = self._sent
        self._outputs_seen = outputs
        for wire, spec in self._outputs:
            value = outputs[wire.tag]
            fault = self.faults.get(wire.signal)
            if fault is not None and fault.kind == "stuck":
                value = fault.value
            elif fault is not None and fault.kind == "wire break":
                value = False if spec.kind == "bool" else 0
            if spec.kind == "analog":
                lo_raw, hi_raw = wire.raw
                value = spec.lo + (value - lo_raw) / (hi_raw - lo_raw) * (spec.hi - spec.lo)
            if sent.get(wire.signal, _UNSET) != value:
                sent[wire.signal] = value
                plant.actuate(wire.signal, value)

    def _faulted_level(self, signal: str, invert: bool, physical: bool, now_ns: int) -> bool:
        fault = self.faults.get(signal)
        if fault is not None:
            if fault.kind == "stuck":
                return fault.value
            if fault.kind == "wire break":
                return False
            if fault.kind == "chatter":
                last = self._last_physical.get(signal)
                if last is not None and last != physical:
                    self._chatter[signal] = self._bounces(fault, now_ns)
                self._last_physical[signal] = physical
        level = (not physical) if invert else physical
        bounces = self._chatter.get(signal)
        if bounces:
            while bounces and bounces[0][1] <= now_ns:
                bounces.pop(0)
            if bounces and bounces[0][0] <= now_ns:
                return not level
        return level

    def _bounces(self, fault: _Fault, now_ns: int) -> list[tuple[int, int]]:
        """Contact bounce after a change at ``now_ns``: the input takes the new level at once, then
        falls back to the old one for a few short intervals (the inverted stretches returned here)."""
        count = self.rng.randint(*fault.transitions)
        out, t = [], now_ns
        for k in range(count):
            width = self.rng.randint(*fault.width_ns)
            if k % 2 == 1:
                out.append((t, t + width))
            t += width
        return out

    def _raw(self, wire: Wire, spec: SignalSpec, value: float, signal: str) -> int:
        fault = self.faults.get(signal)
        if fault is not None:
            if fault.kind == "stuck":
                return int(fault.value)
            if fault.kind == "wire break":
                return 32_767  # S7 analog modules report overflow on a broken wire
        lo_raw, hi_raw = wire.raw
        raw = lo_raw + (value - spec.lo) / (spec.hi - spec.lo) * (hi_raw - lo_raw)
        if wire.noise:
            raw += self.rng.gauss(0.0, wire.noise)
        return max(-32_768, min(32_767, round(raw)))

    # -- faults -------------------------------------------------------------------------------

    def stick(self, name: str, value: Any) -> None:
        """Stuck-at: the PLC input (or the actuator) sees ``value`` whatever happens."""
        signal = self.signal_for(name)
        self.faults[signal] = _Fault("stuck", value)
        self._faults_changed()
        self._sent.pop(signal, None)
        self._resend()

    def break_wire(self, name: str) -> None:
        """Wire break: the input reads FALSE (an NC sensor then reads 'actuated'); an actuator gets nothing."""
        signal = self.signal_for(name)
        self.faults[signal] = _Fault("wire break")
        self._faults_changed()
        self._sent.pop(signal, None)
        self._resend()

    def chatter(
        self, name: str, transitions: tuple[int, int] = (3, 5), width: tuple[str | int, str | int] = ("2ms", "10ms")
    ) -> None:
        """Contact bounce: every change of the sensor comes with a few extra short toggles."""
        signal = self.signal_for(name)
        self.faults[signal] = _Fault("chatter", transitions=transitions, width_ns=(to_ns(width[0]), to_ns(width[1])))
        self._last_physical[signal] = self.plant.sensors.get(signal)
        self._faults_changed()

    def clear(self, name: str | None = None) -> None:
        """Remove a fault (or all faults)."""
        signals = list(self.faults) if name is None else [self.signal_for(name)]
        for signal in signals:
            self.faults.pop(signal, None)
            self._chatter.pop(signal, None)
            self._sent.pop(signal, None)
        self._faults_changed()
        self._resend()

    def _resend(self) -> None:
        """A fault on an actuator acts at once, not only at the PLC's next output change."""
        if self._outputs_seen is not None:
            self.write_outputs(self._outputs_seen)

    def describe(self) -> list[dict[str, str]]:
        """The wiring as rows: signal, tag, contact, meaning."""
        rows = []
        for w in self.wires:
            spec = self.plant.signals[w.signal]
            rows.append(
                {
                    "signal": w.signal,
                    "tag": w.tag,
                    "contact": w.contact if spec.kind == "bool" else "analog",
                    "direction": spec.direction,
                    "doc": spec.doc,
                }
            )
        return rows


_UNSET = object()


def _input_copier(
    levels: list[tuple[str, str, bool]], analogs: list[tuple[Wire, SignalSpec]], plant: Any, rng: random.Random
) -> Callable[[dict[str, Any], int], None]:
    """One function copying every sensor to its input, the fault-free loop of :meth:`Wiring.read_inputs`
    written out once per wiring: Boolean sensors NC-inverted, analog ones scaled as :meth:`Wiring._raw`
    scales them (the same operations in the same order, the same noise draws). Built from the wiring's
    signal and tag names (``repr`` literals) and numbers, never from a program's text. It takes what
    :meth:`Wiring.read_inputs` takes, reading ``plant.sensors`` and drawing the noise from ``rng``.

    >>> from types import SimpleNamespace
    >>> plant, image = SimpleNamespace(sensors={"S1": True, "S2": True, "T": 50.0}), {}
    >>> copy = _input_copier([("S1", "I_S1", False), ("S2", "I_S2", True)], [], plant, random.Random(0))
    >>> copy(image, 0)
    >>> image
    {'I_S1': True, 'I_S2': False}
    >>> spec = SignalSpec("T", "sensor", "analog", lo=0.0, hi=100.0)
    >>> copy = _input_copier([], [(analog("T", "IW_T"), spec)], plant, random.Random(0))
    >>> copy(image, 0)
    >>> image["IW_T"], plant.sensors.update(T=100.0), copy(image, 0), image["IW_T"]
    (13824, None, None, 27648)
    """
    lines = ["    s = p.sensors"]
    lines += [f"    i[{tag!r}] = {'not ' if invert else ''}s[{signal!r}]" for signal, tag, invert in levels]
    scope: dict[str, Any] = {"__builtins__": {}, "max": max, "min": min, "round": round, "p": plant, "r": rng}
    for k, (wire, spec) in enumerate(analogs):
        lo_raw, hi_raw = wire.raw
        scope.update({f"lo{k}": spec.lo, f"span{k}": spec.hi - spec.lo})
        scope.update({f"raw{k}": lo_raw, f"rspan{k}": hi_raw - lo_raw})
        raw = f"raw{k} + (v - lo{k}) / span{k} * rspan{k}" + (f" + r.gauss(0.0, noise{k})" if wire.noise else "")
        scaled = f"max(-32_768, min(32_767, round({raw})))"
        lines.append(f"    v = s[{wire.signal!r}]")
        if wire.noise:  # a fresh draw in every step
            scope[f"noise{k}"] = wire.noise
            lines.append(f"    i[{wire.tag!r}] = {scaled}")
        else:  # a function of the value alone: computed again only when the value changed
            scope[f"last{k}"] = [_UNSET, None]
            lines += [
                f"    if v != last{k}[0]:",
                f"        last{k}[0], last{k}[1] = v, {scaled}",
                f"    i[{wire.tag!r}] = last{k}[1]",
            ]
    exec("def copy(i, now_ns):\n" + "\n".join(lines), scope)  # built from wiring names
    return scope["copy"]
