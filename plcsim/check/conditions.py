"""Conditions: true or false in each scan (trace row): a tag, a comparison, and, or, not."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from plcsim.check.base import Context, Names, signals_of
from plcsim.core.errors import ConfigurationError

# --------------------------------------------------------------------------------------------
# Conditions: a Bool per trace row
# --------------------------------------------------------------------------------------------


class Condition:
    """True or false in each scan (trace row)."""

    def rows(self, ctx: Context) -> np.ndarray:  # pragma: no cover - overridden
        raise NotImplementedError

    def describe(self) -> str:  # pragma: no cover - overridden
        raise NotImplementedError

    def signals(self) -> list[str]:
        return []

    def names(self) -> Names:
        """A condition reads only signals."""
        return Names(tuple(self.signals()))

    def __invert__(self) -> Condition:
        return Not(self)


def as_condition(item: str | Condition) -> Condition:
    """A tag name means "that Bool tag is TRUE"."""
    if isinstance(item, Condition):
        return item
    if isinstance(item, str):
        return On(item)
    raise ConfigurationError(f"expected a condition such as 'D1', off('D1') or value('CV') > 0, not {item!r}")


@dataclass(frozen=True)
class On(Condition):
    name: str

    def rows(self, ctx: Context) -> np.ndarray:
        return ctx.trace.column(self.name).astype(bool)

    def describe(self) -> str:
        return self.name

    def signals(self) -> list[str]:
        return [self.name]


@dataclass(frozen=True)
class Not(Condition):
    inner: Condition

    def rows(self, ctx: Context) -> np.ndarray:
        return ~self.inner.rows(ctx)

    def describe(self) -> str:
        inner = self.inner.describe()
        return f"not {inner}" if " " not in inner else f"not ({inner})"

    def signals(self) -> list[str]:
        return self.inner.signals()


@dataclass(frozen=True)
class AllOf(Condition):
    parts: tuple[Condition, ...]

    def rows(self, ctx: Context) -> np.ndarray:
        out = np.ones(len(ctx.trace), dtype=bool)
        for p in self.parts:
            out &= p.rows(ctx)
        return out

    def describe(self) -> str:
        return " and ".join(_paren(p) for p in self.parts)

    def signals(self) -> list[str]:
        return signals_of(*self.parts)


@dataclass(frozen=True)
class AnyOf(Condition):
    parts: tuple[Condition, ...]

    def rows(self, ctx: Context) -> np.ndarray:
        out = np.zeros(len(ctx.trace), dtype=bool)
        for p in self.parts:
            out |= p.rows(ctx)
        return out

    def describe(self) -> str:
        return " or ".join(_paren(p) for p in self.parts)

    def signals(self) -> list[str]:
        return signals_of(*self.parts)


def _paren(c: Condition) -> str:
    text = c.describe()
    return f"({text})" if " and " in text or " or " in text else text


@dataclass(frozen=True)
class Compare(Condition):
    name: str
    op: str
    other: Any

    def rows(self, ctx: Context) -> np.ndarray:
        left = ctx.trace.column(self.name).astype(np.float64)
        right = ctx.trace.column(self.other.name).astype(np.float64) if isinstance(self.other, Value) else self.other
        return {
            "<": np.less,
            "<=": np.less_equal,
            ">": np.greater,
            ">=": np.greater_equal,
            "==": np.equal,
            "!=": np.not_equal,
        }[self.op](left, right)

    def describe(self) -> str:
        other = self.other.name if isinstance(self.other, Value) else repr(self.other)
        return f"{self.name} {self.op} {other}"

    def signals(self) -> list[str]:
        return [self.name] + ([self.other.name] if isinstance(self.other, Value) else [])


@dataclass(frozen=True)
class Value:
    """A numeric signal to compare: ``value("CISLO") > 0``, ``value("LED") == value("TLACIDLO")``."""

    name: str

    def __gt__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, ">", other)

    def __ge__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, ">=", other)

    def __lt__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "<", other)

    def __le__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "<=", other)

    def __eq__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "==", other)

    def __ne__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "!=", other)

    def __hash__(self) -> int:
        return hash(self.name)


def value(name: str) -> Value:
    """A numeric tag to compare."""
    return Value(name)


def off(name: str) -> Condition:
    """The Bool tag is FALSE."""
    return Not(On(name))


def on(name: str) -> Condition:
    """The Bool tag is TRUE (a plain name means the same)."""
    return On(name)


def all_of(*items: str | Condition) -> Condition:
    """Every condition holds in the scan."""
    return AllOf(tuple(as_condition(i) for i in items))


def any_of(*items: str | Condition) -> Condition:
    """At least one condition holds in the scan."""
    return AnyOf(tuple(as_condition(i) for i in items))


def not_(item: str | Condition) -> Condition:
    """The condition does not hold."""
    return Not(as_condition(item))


def implies(a: str | Condition, b: str | Condition) -> Condition:
    """In every scan where ``a`` holds, ``b`` holds too."""
    return AnyOf((Not(as_condition(a)), as_condition(b)))


def same(a: str, b: str) -> Condition:
    """Two tags have the same value in the scan (an output follows an input)."""
    return Compare(a, "==", Value(b))
