"""Online monitoring: the power flow of every drawn rung at the CPU's state now (TIA's "Monitoring on").

LAD's result of logic operation (RLO) is computed left to right at every point of a rung from the tags'
values as the last scan left them; boxes show their instance's Q, ET, CV as last computed. Reading never
changes the CPU: timers are read as last computed (no refresh) and nothing is written, so watching a run
leaves its trace bit for bit the same. An edge contact shows no power (its edge is over by the end of the
scan, as a sampled online view also shows it most of the time); a local (``#x``) is not monitored.
"""

from __future__ import annotations

import ast
from typing import Any

from plcsim.controllers.s7.instructions import PURE_INSTRUCTIONS, block_of
from plcsim.core.literals import format_ns
from plcsim.frontends.python.link import safe_builtins
from plcsim.ladder.model import (
    Alias,
    Box,
    CallCoil,
    Coil,
    Compare,
    Contact,
    Fork,
    FunctionContact,
    Invert,
    Network,
    Operation,
    Parallel,
    Rung,
    Series,
)
from plcsim.ladder.snapshot import TraceTags
from plcsim.tags.values import PlcArray, PlcStruct

Power = bool | None


class _ReadOnly:
    """The tags as a rung reads them, without side effects: instances' members as last computed."""

    __slots__ = ("_value",)

    def __init__(self, value: Any):
        self._value = value

    def __getattr__(self, name: str) -> Any:
        value = self._value
        if isinstance(value, TraceTags):
            return getattr(value, name)
        if block_of(value) is not None:
            return getattr(value, value.trace_source(name))
        return _wrap(getattr(value, name))

    def __getitem__(self, key: Any) -> Any:
        return _wrap(self._value[key])


def _wrap(value: Any) -> Any:
    if isinstance(value, TraceTags):
        return value
    return _ReadOnly(value) if isinstance(value, PlcStruct | PlcArray) or block_of(value) is not None else value


class PowerFlow:
    """The power at each element of ``networks`` for the CPU's tags now: call it as a drawing's ``flow``
    (element -> power at its left and right) and :meth:`value` as its ``values``."""

    def __init__(self, networks: list[Network], tags: Any, constants: dict[str, Any] | None = None):
        self.power: dict[int, tuple[Power, Power]] = {}
        self.instances: dict[str, Any] = {}
        self._globals = {"__builtins__": safe_builtins(), **PURE_INSTRUCTIONS, **(constants or {})}
        self._codes: dict[int, Any] = {}
        for net in networks:
            self._network(net, tags)

    def __call__(self, element: Any) -> tuple[Power, Power]:
        return self.power.get(id(element), (None, None))

    def value(self, instance: str, pin: str) -> str | None:
        """A box pin's value now (``ET`` as ``T#1s200ms``, ``CV`` as a number)."""
        owner = self.instances.get(instance)
        if isinstance(owner, TraceTags) and pin:
            recorded = owner.member(pin)
            if recorded is None or pin in ("PT", "PV"):
                return None
            if pin == "ET":
                return "T#" + format_ns(int(recorded) * 1_000_000).replace(" ", "")
            return ("TRUE" if recorded else "FALSE") if isinstance(recorded, bool) else str(recorded)
        if owner is None or block_of(owner) is None or not pin:
            return None
        member = block_of(owner).member(pin)  # type: ignore[union-attr]
        if member is None:
            return None
        value = getattr(owner, owner.trace_source(pin))
        if member.type == "Time":
            return "T#" + format_ns(int(value) * 1_000_000).replace(" ", "")
        if member.type == "Bool":
            return "TRUE" if value else "FALSE"
        return str(value)

    # -- evaluation ---------------------------------------------------------------------------------

    def _network(self, net: Network, tags: Any) -> None:
        env: dict[str, Any] = {net.root: _ReadOnly(tags)}
        for part in net.parts:
            if isinstance(part, Alias):
                value = self._eval(part.statement.value, env)  # type: ignore[attr-defined]
                if value is not None:
                    env[part.name] = value
            elif isinstance(part, Rung):
                self._series(part.series, True, env)

    def _eval(self, expr: ast.expr, env: dict[str, Any]) -> Any:
        code = self._codes.get(id(expr))
        if code is None:
            code = self._codes[id(expr)] = compile(ast.Expression(expr), "<ladder>", "eval")
        try:
            return eval(code, self._globals, env)  # a pure expression the ladder drew, on read-only tags
        except Exception:  # noqa: BLE001 - a local or a fault: not monitored
            return None

    def _series(self, series: Series, power: Power, env: dict[str, Any]) -> Power:
        for item in series.items:
            before = power
            if isinstance(item, Contact):
                if item.kind in ("P", "N"):
                    power = _and(power, False)
                else:
                    value = self._eval(item.source, env)
                    contact = None if value is None else bool(value) == (item.kind == "NO")
                    power = _and(power, contact)
            elif isinstance(item, Compare | FunctionContact):
                value = self._eval(item.source, env)
                power = _and(power, None if value is None else bool(value))
            elif isinstance(item, Invert):
                inner = self._series(item.inner, True, env)
                power = _and(power, None if inner is None else not inner)
            elif isinstance(item, Parallel):
                results = [self._series(b, power, env) for b in item.branches]
                power = True if any(r is True for r in results) else None if None in results else False
            elif isinstance(item, Box):
                owner = self._eval(item.instance_source, env)
                first = item.outputs[0] if item.outputs else "Q"
                if isinstance(owner, _ReadOnly) and block_of(owner._value) is not None:
                    inner = owner._value
                    self.instances[item.instance] = inner
                    power = bool(getattr(inner, inner.trace_source(first)))
                elif isinstance(owner, TraceTags):
                    self.instances[item.instance] = owner
                    q = owner.member(first)
                    power = None if q is None else bool(q)
                else:
                    power = None
            elif isinstance(item, Fork):
                for branch in item.branches:
                    self._series(branch, power, env)
            elif isinstance(item, Coil | Operation | CallCoil):
                pass
            self.power[id(item)] = (before, power)
        self.power[id(series)] = (power, power)
        return power


def _and(left: Power, right: Power) -> Power:
    if left is False or right is False:
        return False
    if left is None or right is None:
        return None
    return True
