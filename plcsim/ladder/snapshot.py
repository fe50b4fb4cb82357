"""A scan taken from a trace, as the tags a rung reads: the ladder of a failed check drawn with the values
of the scan where it failed (the grade report's picture beside the timing diagram).

Only what the trace recorded is known; a contact on anything else is drawn unmonitored (black), never
guessed.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable
from typing import Any

from plcsim.frontends.python.program import Program


class UnrecordedError(LookupError):
    """The trace did not record this signal."""


class TraceTags:
    """The values of one instant of a trace, read as ``t.NAME``, ``t.DATA.MEMBER``, ``t.TON_A.Q``."""

    __slots__ = ("_names", "_prefix", "_trace", "_t_ns")

    def __init__(self, trace: Any, t_ns: int, prefix: str = "", names: frozenset[str] | None = None):
        self._trace, self._t_ns, self._prefix = trace, t_ns, prefix
        self._names = names if names is not None else frozenset(trace.names)

    def _at(self, path: str) -> Any:
        if path in self._names:
            return self._trace.value_at(path, self._t_ns)
        if any(n.startswith(path + ".") or n.startswith(path + "[") for n in self._names):
            return TraceTags(self._trace, self._t_ns, path, self._names)
        raise UnrecordedError(path)

    def __getattr__(self, name: str) -> Any:
        return self._at(f"{self._prefix}.{name}" if self._prefix else name)

    def __getitem__(self, key: Any) -> Any:
        return self._at(f"{self._prefix}[{key}]" if not isinstance(key, str) else key)

    def member(self, name: str) -> Any:
        """An instance member (``Q``, ``ET``, ``CV``) as recorded, or None."""
        try:
            value = getattr(self, name)
        except UnrecordedError:
            return None
        return None if isinstance(value, TraceTags) else value

    def __bool__(self) -> bool:
        raise UnrecordedError(self._prefix)


def networks_writing(program: Program, signals: Iterable[str]) -> set[str]:
    """The networks whose statements store into one of ``signals`` (a tag, a DB member's DB, an instance
    whose member is named: ``TON_A.Q`` -> the networks calling ``TON_A``'s box)."""
    roots = {s.split(".")[0].split("[")[0] for s in signals}
    found = set()
    for task in program.tasks.values():
        for net in task.networks:
            func = program.functions[net.name]
            root = func.args.args[0].arg if func.args.args else "t"
            for node in ast.walk(func):
                base = node
                stored = isinstance(node, ast.Attribute | ast.Subscript) and isinstance(node.ctx, ast.Store)
                called = isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
                if called:
                    base = node.func.value  # type: ignore[union-attr]
                if not (stored or called):
                    continue
                while isinstance(base, ast.Attribute | ast.Subscript) and not (
                    isinstance(base.value, ast.Name) and base.value.id == root
                ):
                    base = base.value
                if isinstance(base, ast.Attribute) and base.attr in roots:
                    found.add(net.name)
    return found
