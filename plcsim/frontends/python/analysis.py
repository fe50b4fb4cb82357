"""Facts about a program for the CPU, the graders and the timer rule, read from its checked tree.

:func:`analyse` collects which tags each function uses (the process-image partitions of the interrupt
tasks), SET/RESET coils, timers whose Q and ET are never read (textbook §3.6.1), jumps, and edge calls
hidden behind ``and``/``or`` (a warning: Python skips them).
"""

from __future__ import annotations

import ast
from dataclasses import dataclass, field
from typing import Any

from plcsim.controllers.s7.instructions import FUNCTIONS, block_named
from plcsim.frontends.python.typecheck import Typing, instance_boxes, safe_type
from plcsim.tags.table import FBType
from plcsim.tags.types import Bool


@dataclass
class FunctionFacts:
    """What one function of the program reads, writes and calls."""

    name: str
    lineno: int
    reads: set[str] = field(default_factory=set)
    writes: set[str] = field(default_factory=set)
    calls: set[str] = field(default_factory=set)
    jumps: list[tuple[str, int]] = field(default_factory=list)


@dataclass
class Analysis:
    """Facts about a whole program, for the CPU (process-image partitions, the timer rule) and graders."""

    functions: dict[str, FunctionFacts] = field(default_factory=dict)
    set_coils: list[tuple[str, int]] = field(default_factory=list)
    reset_coils: list[tuple[str, int]] = field(default_factory=list)
    box_calls: list[tuple[str, str, int]] = field(default_factory=list)
    edge_calls: list[tuple[str, int]] = field(default_factory=list)
    timer_reads: set[str] = field(default_factory=set)
    warnings: list[str] = field(default_factory=list)

    def tags_used(self, function: str) -> set[str]:
        """Root tags a function and the functions it calls read or write."""
        seen, todo, tags = set(), [function], set()
        while todo:
            name = todo.pop()
            if name in seen or name not in self.functions:
                continue
            seen.add(name)
            facts = self.functions[name]
            tags |= facts.reads | facts.writes
            todo.extend(facts.calls)
        return tags

    def unused_timers(self) -> set[str]:
        """Timer instances whose box runs but whose Q and ET are used nowhere (textbook §3.6.1)."""
        timer_boxes = block_named("IEC_TIMER").boxes  # type: ignore[union-attr]
        called = {inst for inst, box, _ in self.box_calls if box in timer_boxes}
        return called - self.timer_reads

    def uses(self, instruction: str) -> bool:
        """True if the program uses SET, RESET, an edge instruction or a given box anywhere."""
        if instruction == "SET":
            return bool(self.set_coils)
        if instruction == "RESET":
            return bool(self.reset_coils)
        if instruction in ("P", "N", "P_TRIG", "N_TRIG", "R_TRIG", "F_TRIG", "EDGE"):
            return (
                any(instruction in (kind, "EDGE") for kind, _ in self.edge_calls)
                or any(box == instruction for _, box, _ in self.box_calls)
                or (instruction == "EDGE" and any(box in ("R_TRIG", "F_TRIG") for _, box, _ in self.box_calls))
            )
        return any(box == instruction for _, box, _ in self.box_calls)


_EDGE_FUNCS = frozenset(f.name for f in FUNCTIONS.values() if f.named)
"""The instructions with an edge memory bit."""


def analyse(tree: ast.Module, typing: Typing) -> Analysis:
    """Collect tag usage, coils, timer reads and short-circuit warnings from the original tree."""
    result = Analysis()
    module_funcs = {s.name for s in tree.body if isinstance(s, ast.FunctionDef)}
    for stmt in tree.body:
        if not isinstance(stmt, ast.FunctionDef):
            continue
        facts = FunctionFacts(stmt.name, stmt.lineno)
        result.functions[stmt.name] = facts
        params = [a.arg for a in stmt.args.args]
        root = typing.root_params.get(stmt.name) or ("t" if params and params[0] == "t" else None)
        env = {root: typing.root} if root else {}
        bare: set[int] = set()  # calls whose value is thrown away (ast.walk meets an Expr before its call)
        for node in ast.walk(stmt):
            if isinstance(node, ast.Expr):
                bare.add(id(node.value))
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == root:
                (facts.writes if isinstance(node.ctx, ast.Store) else facts.reads).add(node.attr)
            if (
                isinstance(node, ast.Subscript)
                and isinstance(node.value, ast.Name)
                and node.value.id == root
                and isinstance(node.slice, ast.Constant)
                and isinstance(node.slice.value, str)
            ):
                (facts.writes if isinstance(node.ctx, ast.Store) else facts.reads).add(node.slice.value)
            if isinstance(node, ast.Call):
                func = node.func
                if isinstance(func, ast.Name):
                    if func.id in module_funcs:
                        facts.calls.add(func.id)
                    if func.id in _EDGE_FUNCS:
                        result.edge_calls.append((func.id, node.lineno))
                    if func.id == "JMP" and node.args and isinstance(node.args[0], ast.Constant):
                        facts.jumps.append((node.args[0].value, node.lineno))
                elif isinstance(func, ast.Attribute):
                    base = safe_type(typing, func.value, env)
                    if isinstance(base, FBType) and func.attr in instance_boxes(base):
                        path = ast.unparse(func.value)
                        result.box_calls.append((path, func.attr, node.lineno))
                        if id(node) not in bare:
                            result.timer_reads.add(path)
            if isinstance(node, ast.Attribute) and node.attr in ("Q", "ET") and isinstance(node.ctx, ast.Load):
                base = safe_type(typing, node.value, env)
                if isinstance(base, FBType) and base.name == "IEC_TIMER":
                    result.timer_reads.add(ast.unparse(node.value))
            if isinstance(node, ast.If):
                _collect_coils(node, result, typing, env)
            if isinstance(node, (ast.BoolOp, ast.IfExp)):
                _short_circuit_warnings(node, typing, env, result)
    return result


def _collect_coils(node: ast.If, result: Analysis, typing: Typing, env: dict[str, Any]) -> None:
    for branch in (node.body, node.orelse):
        for stmt in branch:
            if (
                isinstance(stmt, ast.Assign)
                and isinstance(stmt.value, ast.Constant)
                and isinstance(stmt.value.value, bool)
            ):
                for target in stmt.targets:
                    if isinstance(target, ast.Attribute) and safe_type(typing, target, env) is Bool:
                        kind = result.set_coils if stmt.value.value else result.reset_coils
                        kind.append((ast.unparse(target), stmt.lineno))


def _short_circuit_warnings(
    node: ast.BoolOp | ast.IfExp, typing: Typing, env: dict[str, Any], result: Analysis
) -> None:
    hidden = node.values[1:] if isinstance(node, ast.BoolOp) else [node.body, node.orelse]
    for part in hidden:
        for sub in ast.walk(part):
            if not isinstance(sub, ast.Call):
                continue
            func = sub.func
            name = None
            if isinstance(func, ast.Name) and func.id in _EDGE_FUNCS:
                name = func.id
            elif isinstance(func, ast.Attribute) and isinstance(safe_type(typing, func.value, env), FBType):
                name = f"{ast.unparse(func.value)}.{func.attr}"
            if name:
                op = "and/or" if isinstance(node, ast.BoolOp) else "if/else"
                result.warnings.append(
                    f"{typing.filename}, line {sub.lineno}: {name}(...) sits behind {op}: Python skips it when "
                    f"the left side decides, so it does not run every scan as in LAD; call it on its own line "
                    f"first (x = {name}(...)) and combine the result"
                )
