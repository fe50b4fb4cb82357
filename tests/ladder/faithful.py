"""Running a program and its drawn ladder side by side on the same states (the faithfulness proof).

:func:`twin_cpus` loads the program into one CPU and what its drawing does (:func:`ladder_source`) into
another; :func:`run_side_by_side` gives both the same tag values and clock, runs their networks one by
one and names the first network after which the two disagree.
"""

from __future__ import annotations

import ast
from typing import Any

from plcsim import CPU
from plcsim.controllers.s7.instructions import block_of
from plcsim.frontends.python.program import Program
from plcsim.ladder import build_ladder
from plcsim.ladder.semantics import PREFIX, ladder_source
from plcsim.tags.table import TagTable
from plcsim.tags.types import Bool, ElementaryType
from plcsim.tags.values import PlcArray, PlcStruct

INTEGERS = {"SInt", "Int", "DInt", "USInt", "UInt", "UDInt", "Byte", "Word", "DWord", "LInt", "ULInt", "LWord"}


def twin_cpus(program: Program, table: TagTable, **options: Any) -> tuple[CPU, CPU, str]:
    """A CPU running ``program`` and one running its ladder, and the ladder's program text."""
    for node in ast.walk(program.tree):
        assert not (isinstance(node, ast.Name) and node.id.startswith(PREFIX)), "a local shadows the ladder's RLOs"
    blocks = build_ladder(program, table)
    source = ladder_source(program, blocks)
    drawn = Program(source, program.filename)
    return CPU(table.copy(), program, **options), CPU(table.copy(), drawn, **options), source


def scalar_paths(cpu: CPU) -> dict[str, ElementaryType]:
    """Every tag and structure member a watch table can write, with its type (instances left out)."""
    found: dict[str, ElementaryType] = {}

    def visit(value: Any, path: str, dtype: Any) -> None:
        if isinstance(value, PlcStruct):
            for name, member in value._type.members.items():
                visit(value[name], f"{path}.{name}" if path else name, member.type)
        elif isinstance(value, PlcArray):
            for i, item in enumerate(value):
                visit(item, f"{path}[{i}]", value._type.element)
        elif isinstance(dtype, ElementaryType) and (dtype is Bool or dtype.name in INTEGERS | {"Real", "LReal"}):
            found[path] = dtype

    visit(cpu.t, "", None)
    return {p: t for p, t in found.items() if not p.startswith(("%", "Clock_", "FirstScan", "DiagStatus", "Always"))}


def state(cpu: CPU) -> dict[str, Any]:
    """Everything a program can read: tag values and the instances' members as a program reads them.

    A program reads a timer's Q and ET fresh (an S7-1200 timer updates when they are read); LAD reads
    every contact, Python skips what ``or`` decides without, so the value a timer last computed may be
    fresher in the ladder. Reading every member here (in both CPUs alike) compares what the logic sees."""
    out: dict[str, Any] = {}

    def visit(value: Any, path: str) -> None:
        if isinstance(value, PlcStruct):
            for name in value._type.members:
                visit(value[name], f"{path}.{name}")
        elif isinstance(value, PlcArray):
            for i, item in enumerate(value):
                visit(item, f"{path}[{i}]")
        elif block_of(value) is not None:
            for member in block_of(value).readable:
                out[f"{path}.{member}"] = getattr(value, member)
        else:
            out[path] = value

    visit(cpu.t, "t")
    return out


def run_side_by_side(original: CPU, drawn: CPU, steps: list[tuple[dict[str, Any], int]]) -> None:
    """Apply each step's writes and clock advance to both CPUs, run every network of every task on both,
    and fail naming the network (and the values it started from) after which they differ."""
    for number, (writes, advance_ms) in enumerate(steps):
        for cpu in (original, drawn):
            cpu.clock.now += advance_ms * 1_000_000
            for path, value in writes.items():
                cpu.write(path, value)
        for task_a, task_b in zip(original.loaded.tasks, drawn.loaded.tasks, strict=True):
            for k, (net_a, net_b) in enumerate(zip(task_a.networks, task_b.networks, strict=True)):
                before = state(original)
                outcome = []
                for cpu, net in ((original, net_a), (drawn, net_b)):
                    try:
                        net.run(cpu.t)
                        outcome.append(None)
                    except Exception as exc:  # noqa: BLE001 - a jump, a fault: both must end alike
                        outcome.append(f"{type(exc).__name__}: {exc}")
                name = task_a.spec.networks[k].name
                assert outcome[0] == outcome[1], f"step {number}, network {name}: {outcome[0]} != {outcome[1]}"
                a, b = state(original), state(drawn)
                if a != b:
                    differ = {p: (a[p], b.get(p)) for p in a if a[p] != b.get(p)}
                    changed = {p: before[p] for p in differ if p in before}
                    raise AssertionError(
                        f"step {number}: after network {name} the ladder differs from the program "
                        f"(program, ladder): {differ}; before the network: {changed}"
                    )
                if outcome[0] is not None:
                    break
