"""Mutation testing of an exercise's checks: plant the slips students make into the reference
solution and see whether the checks catch each one.

Every mutant is the reference program with one small change of its source (an AST transform,
regenerated with :func:`ast.unparse`), the kind of slip a student makes:

========== ==================================================================================
negate     a contact negated: a Bool tag read ``t.X`` <-> ``not t.X``
nc-as-no   an input wired NC read as if it were NO: every read of it negated at once
timer      TON <-> TOF <-> TP
edge       an edge removed: ``P(x, "M")`` / ``N(...)`` / ``R_TRIG(CLK=x)`` -> the plain signal ``x``
edge-kind  a rising edge for a falling one: P <-> N, P_TRIG <-> N_TRIG, R_TRIG <-> F_TRIG
preset     a PT/PV preset, a ``TIME("..")`` or an integer compared with, moved by one step
boundary   a comparison at its boundary: < <-> <=, > <-> >=, == <-> !=
coil       SET for RESET: ``t.X = True`` <-> ``t.X = False``
and-or     a series connection for a parallel one: ``and`` <-> ``or``
swap       two adjacent networks of an OB, or two adjacent if-blocks of a network, exchanged
drop       a network of an OB, or one statement of a block, dropped
move       a network moved to the end of its OB
task       a cyclic interrupt's networks (OB30) run in OB1 instead, every scan
========== ==================================================================================

A preset step is one unit in the decimal place below the value's leading digit, at least one
unit of the literal (10 s -> 9 s / 11 s, 3 s -> 2.9 s / 3.1 s, 100 ms -> 90 ms / 110 ms, PV 3 -> 2 / 4):
about a tenth of the preset, the size of slip that a check's tolerance should not absorb.

A Tecomat instruction-list reference (``.il``) gets the mutants of :mod:`plcsim.mutate.il` (the same
slips in its instructions), loaded through the Tecomat front end and graded and classified as below.

Each mutant is graded with :func:`plcsim.grading.grader.grade` (in this process: the mutants derive from
the trusted reference) on seeds 1..N. It is **killed** if some check fails on some seed that the
reference passes on that seed, **stillborn** if it does not load (counted apart, not as killed).
A surviving mutant is **equivalent** if its behaviour equals the reference's in every scenario and
seed: the same changes of every tag of the exercise's I/O table and data blocks at the same times
and the same events (the program's own tags, such as a timer's ET, and the edge memory bits the
reference names are the edge and timer instructions' bookkeeping, which no check reads; the CPU's
clock and system bits do not depend on the program). A survivor's report names the tags that
differ. Equivalent means "no scenario tells it apart": read those too, a scenario may be missing.
A survivor the exercise declares a correct program by the spec's words (its ``spec_equivalent``,
with the reason: the falling edge of Clock_1Hz is a one-second pulse too) is **explained**; a
declaration that names no mutant is an error (:class:`~plcsim.core.errors.ExerciseError`), and one whose
mutant a check kills is reported as misleading (a check is stricter than the spec, or the
declaration is wrong). Score = killed / (killed + survived): explained mutants are left out.

>>> from plcsim.tags.table import Tag, TagTable
>>> table = TagTable()
>>> _ = table.add("S1", Tag("%I0.0"))
>>> _ = table.add("D1", Tag("%Q0.0"))
>>> [str(m) for m in derive_mutants("def OB1(t):\\n    t.D1 = t.S1\\n", table)]
['line 2: t.S1 → not t.S1']
"""

from __future__ import annotations

import ast
import copy
import hashlib
import json
import math
import multiprocessing
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from plcsim.controllers.loaded import SourceProgram
from plcsim.controllers.s7.cpu import CLOCK_BITS, SYSTEM_BITS
from plcsim.core.errors import ExerciseError, PlcError, did_you_mean
from plcsim.core.literals import time_ms
from plcsim.exercise.model import Exercise
from plcsim.frontends.python.compiler import Typing
from plcsim.frontends.python.program import Program
from plcsim.grading.grader import grade
from plcsim.grading.report import Report
from plcsim.tags.table import TagTable
from plcsim.tags.types import Bool

KILLED, SURVIVED, EXPLAINED, EQUIVALENT, STILLBORN = "killed", "survived", "explained", "equivalent", "stillborn"
STATUSES = (KILLED, SURVIVED, EXPLAINED, EQUIVALENT, STILLBORN)

_TIMERS = ("TON", "TOF", "TP")
_EDGE_FUNCS = {"P": "N", "N": "P", "P_TRIG": "N_TRIG", "N_TRIG": "P_TRIG"}
_EDGE_BOXES = {"R_TRIG": "F_TRIG", "F_TRIG": "R_TRIG"}
_BOUNDARY = {ast.Lt: ast.LtE, ast.LtE: ast.Lt, ast.Gt: ast.GtE, ast.GtE: ast.Gt, ast.Eq: ast.NotEq, ast.NotEq: ast.Eq}
_PRESETS = ("PT", "PV")
_CPU_BITS = {name for _, name, _ in CLOCK_BITS} | {name for _, name in SYSTEM_BITS}


@dataclass(frozen=True)
class Mutant:
    """One mutant of a program: what changed, where, and the mutated source."""

    number: int
    operator: str
    line: int
    description: str
    source: str

    def __str__(self) -> str:
        return f"line {self.line}: {self.description}"


# --------------------------------------------------------------------------------------------
# Deriving mutants
# --------------------------------------------------------------------------------------------

Edit = Callable[[list[ast.AST]], None]
"""Applies a change to a fresh copy of the tree, given as its nodes in :func:`ast.walk` order."""
Site = tuple[str, int, str, Edit]
"""Where a mutant can be made: operator, line, description and the edit that makes it."""


def derive_mutants(
    source: str, table: TagTable, *, nc_inputs: Iterable[str] = (), filename: str = "<reference>"
) -> list[Mutant]:
    """Every mutant of ``source`` (a program in the PLC subset, compiled against ``table``).

    ``nc_inputs`` are the inputs wired NC in the exercise's I/O table. Mutants whose source equals
    the original or an earlier mutant are left out; the order is deterministic.
    """
    program = Program(source, filename)
    typing = Typing(program.declare_into(table).schema())
    tree = program.tree
    original = ast.unparse(tree)
    seen = {original}
    found: list[tuple[str, int, str, str]] = []
    for operator, line, description, edit in _sites(tree, typing, set(nc_inputs)):
        mutated = copy.deepcopy(tree)
        edit(list(ast.walk(mutated)))
        text = ast.unparse(ast.fix_missing_locations(mutated))
        if text not in seen:
            seen.add(text)
            found.append((operator, line, description, text + "\n"))
    found.sort(key=lambda m: m[1])  # stable: by line, then in the order derived
    return [Mutant(k, *m) for k, m in enumerate(found, 1)]


def _sites(tree: ast.Module, typing: Typing, nc_inputs: set[str]) -> Iterator[Site]:
    nodes = list(ast.walk(tree))
    index = {id(n): k for k, n in enumerate(nodes)}
    parents = {id(child): node for node in nodes for child in ast.iter_child_nodes(node)}
    functions = [s for s in tree.body if isinstance(s, ast.FunctionDef) and s.args.args]
    reads = [(read, f) for f in functions for read in _bool_reads(f, typing)]
    yield from _nc_as_no(reads, nc_inputs, index, parents)
    for read, _ in reads:
        yield _negate(read, index, parents)
    for node in nodes:
        if isinstance(node, ast.Call):
            yield from _call_sites(node, index, parents)
        elif isinstance(node, ast.Compare):
            yield from _compare_sites(node, index)
        elif isinstance(node, ast.Assign) and _is_coil(node):
            k, value = index[id(node)], node.value.value  # type: ignore[attr-defined]
            yield (
                "coil",
                node.lineno,
                f"{_text(node)} → {_text(node.targets[0])} = {not value}",
                _set_value(k, not value),
            )
        elif isinstance(node, ast.BoolOp):
            other = ast.Or() if isinstance(node.op, ast.And) else ast.And()
            after = _text(ast.BoolOp(other, node.values))
            yield "and-or", node.lineno, f"{_text(node)} → {after}", _set_attr(index[id(node)], "op", other)
    for node in (n for f in functions for n in ast.walk(f)):
        for name in ("body", "orelse"):
            block = getattr(node, name, None)
            if isinstance(block, list) and block and isinstance(block[0], ast.stmt):
                yield from _block_sites(node, name, block, index)
    yield from _network_sites(tree, index)


def _bool_reads(func: ast.FunctionDef, typing: Typing) -> list[ast.Attribute]:
    """The Bool tag reads (``t.X``, ``t.DB.X``, ``t.TON_A.Q``) of one network, outermost chains only."""
    root = func.args.args[0].arg
    env = {root: typing.root}
    inner = {id(n.value) for n in ast.walk(func) if isinstance(n, ast.Attribute)}
    out = []
    for node in ast.walk(func):
        if isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Load) and id(node) not in inner:
            base = node
            while isinstance(base, ast.Attribute):
                base = base.value
            if isinstance(base, ast.Name) and base.id == root and _type(typing, node, env) is Bool:
                out.append(node)
    return out


def _type(typing: Typing, node: ast.expr, env: dict[str, Any]) -> Any:
    try:
        return typing.type_of(node, env)
    except PlcError:
        return None


def _toggle(k_read: int, k_not: int | None) -> Edit:
    """``t.X`` -> ``not t.X``, or ``not t.X`` -> ``t.X`` (``k_not``: the enclosing ``not``)."""

    def edit(nodes: list[ast.AST]) -> None:
        if k_not is None:
            read = nodes[k_read]
            _replace(nodes, read, ast.UnaryOp(ast.Not(), read))
        else:
            _replace(nodes, nodes[k_not], nodes[k_read])

    return edit


def _negate(read: ast.Attribute, index: dict[int, int], parents: dict[int, ast.AST]) -> Site:
    parent = parents.get(id(read))
    if isinstance(parent, ast.UnaryOp) and isinstance(parent.op, ast.Not):
        return "negate", read.lineno, f"not {_text(read)} → {_text(read)}", _toggle(index[id(read)], index[id(parent)])
    return "negate", read.lineno, f"{_text(read)} → not {_text(read)}", _toggle(index[id(read)], None)


def _nc_as_no(
    reads: list[tuple[ast.Attribute, ast.FunctionDef]],
    nc_inputs: set[str],
    index: dict[int, int],
    parents: dict[int, ast.AST],
) -> Iterator[Site]:
    for name in sorted(nc_inputs):
        mine = [r for r, f in reads if r.attr == name and isinstance(r.value, ast.Name)]
        if not mine:
            continue
        edits = [_negate(r, index, parents)[3] for r in mine]

        def edit(nodes: list[ast.AST], edits: list[Edit] = edits) -> None:
            for e in edits:
                e(nodes)

        lines = ", ".join(str(r.lineno) for r in mine)
        where = f"line {lines}" if len(mine) == 1 else f"lines {lines}"
        yield "nc-as-no", mine[0].lineno, f"NC input {name} read as NO: every read negated ({where})", edit


def _call_sites(node: ast.Call, index: dict[int, int], parents: dict[int, ast.AST]) -> Iterator[Site]:
    k = index[id(node)]
    func = node.func
    if isinstance(func, ast.Attribute) and func.attr in _TIMERS and any(kw.arg == "IN" for kw in node.keywords):
        for other in _TIMERS:
            if other != func.attr:
                yield "timer", node.lineno, f"{_text(func.value)}: {func.attr} → {other}", _rename(k, other)
    if isinstance(func, ast.Name) and func.id in _EDGE_FUNCS and node.args:
        signal = node.args[0]
        yield "edge", node.lineno, f"{_text(node)} → {_text(signal)}", _unwrap(k, index[id(signal)])
        other = _EDGE_FUNCS[func.id]
        yield "edge-kind", node.lineno, f"{_text(node)} → {other}{_text(node)[len(func.id) :]}", _rename(k, other)
    if isinstance(func, ast.Attribute) and func.attr in _EDGE_BOXES:
        clk = next((kw.value for kw in node.keywords if kw.arg == "CLK"), node.args[0] if node.args else None)
        if clk is not None and not isinstance(parents.get(id(node)), ast.Expr):
            yield "edge", node.lineno, f"{_text(node)} → {_text(clk)}", _unwrap(k, index[id(clk)])
        other = _EDGE_BOXES[func.attr]
        yield "edge-kind", node.lineno, f"{_text(func.value)}: {func.attr} → {other}", _rename(k, other)
    for kw in node.keywords:
        if kw.arg in _PRESETS and isinstance(kw.value, ast.Constant):
            yield from _preset_sites(kw.value, f"{kw.arg} ", index)
    if isinstance(func, ast.Name) and func.id == "TIME" and node.args and isinstance(node.args[0], ast.Constant):
        yield from _preset_sites(node.args[0], "TIME ", index)


def _compare_sites(node: ast.Compare, index: dict[int, int]) -> Iterator[Site]:
    k = index[id(node)]
    for i, op in enumerate(node.ops):
        other = _BOUNDARY.get(type(op))
        if other is not None:
            after = ast.Compare(node.left, [*node.ops[:i], other(), *node.ops[i + 1 :]], node.comparators)
            yield "boundary", node.lineno, f"{_text(node)} → {_text(after)}", _set_op(k, i, other)
    for operand in [node.left, *node.comparators]:
        if isinstance(operand, ast.Constant) and type(operand.value) is int:
            for new in preset_steps(operand.value):
                after = _text(_with_constant(node, operand, new))
                yield "preset", node.lineno, f"{_text(node)} → {after}", _set_attr(index[id(operand)], "value", new)


def _with_constant(node: ast.Compare, old: ast.Constant, new: int) -> ast.Compare:
    swap = {id(old): ast.Constant(new)}
    return ast.Compare(swap.get(id(node.left), node.left), node.ops, [swap.get(id(c), c) for c in node.comparators])


def _preset_sites(const: ast.Constant, what: str, index: dict[int, int]) -> Iterator[Site]:
    value = const.value
    for new in preset_steps(value):
        yield "preset", const.lineno, f"{what}{value!r} → {new!r}", _set_attr(index[id(const)], "value", new)


def preset_steps(value: Any) -> list[Any]:
    """The preset one step below and above ``value`` (see the module docstring)."""
    if isinstance(value, bool):
        return []
    if isinstance(value, int):
        step = max(1, _tenth_of_magnitude(abs(value)))
        return [v for v in (value - step, value + step) if v >= 0 or value < 0]
    if isinstance(value, str):
        try:
            ms = time_ms(value)
        except PlcError:
            return []
        step = max(1, _tenth_of_magnitude(ms))
        return [_time_literal(v) for v in (ms - step, ms + step) if v >= 0]
    return []


def _tenth_of_magnitude(n: int) -> int:
    return 10 ** (int(math.log10(n)) - 1) if n >= 10 else 0


def _time_literal(ms: int) -> str:
    return f"{ms // 1000}s" if ms % 1000 == 0 and ms else f"{ms}ms"


def _is_coil(node: ast.Assign) -> bool:
    return (
        len(node.targets) == 1
        and isinstance(node.targets[0], ast.Attribute)
        and isinstance(node.value, ast.Constant)
        and isinstance(node.value.value, bool)
    )


def _block_sites(owner: ast.AST, field_name: str, block: list[ast.stmt], index: dict[int, int]) -> Iterator[Site]:
    """Adjacent if-blocks swapped, and single statements dropped, in one statement list."""
    k = index[id(owner)]
    body = [s for s in block if not _is_docstring(s)]
    offset = len(block) - len(body)
    for i in range(len(body) - 1):
        a, b = body[i], body[i + 1]
        if isinstance(a, ast.If) and isinstance(b, ast.If):
            yield (
                "swap",
                a.lineno,
                f"if-blocks at lines {a.lineno} and {b.lineno} swapped",
                _swap_block(k, field_name, offset + i),
            )
    if len(body) > 1:
        for i, stmt in enumerate(body):
            yield "drop", stmt.lineno, f"statement dropped: {_text(stmt)}", _drop_block(k, field_name, offset + i)


def _network_sites(tree: ast.Module, index: dict[int, int]) -> Iterator[Site]:
    """Networks of an OB (``OB1 = [a, b]``, ``CyclicInterrupt([a, b], ...)``) swapped, dropped, moved;
    a cyclic interrupt's networks run in OB1 instead (when the program has no OB1)."""
    has_ob1 = any(
        (isinstance(s, ast.FunctionDef) and s.name == "OB1")
        or (isinstance(s, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "OB1" for t in s.targets))
        for s in tree.body
    )
    for stmt in tree.body:
        if not (isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name)):
            continue
        ob = stmt.targets[0].id
        value = stmt.value
        if not has_ob1 and isinstance(value, ast.Call) and _is_name(value.func, "CyclicInterrupt") and value.args:
            every = next((_text(kw.value) for kw in value.keywords if kw.arg == "period"), "period")
            what = f"{ob}: its networks run in OB1, every scan, instead of every {every}"
            yield "task", stmt.lineno, what, _to_ob1(index[id(stmt)])
        networks = _network_list(stmt.value)
        if networks is None or len(networks.elts) < 2:
            continue
        k = index[id(networks)]
        names = [_text(e) for e in networks.elts]
        line = stmt.lineno
        n = len(names)
        for i in range(n - 1):
            yield "swap", line, f"{ob}: networks {names[i]} and {names[i + 1]} swapped", _swap_block(k, "elts", i)
        for i in range(n):
            yield "drop", line, f"{ob}: network {names[i]} dropped", _drop_block(k, "elts", i)
        for i in range(n - 1):
            yield "move", line, f"{ob}: network {names[i]} moved to the end", _move_last(k, i)


def _network_list(value: ast.expr) -> ast.List | None:
    if isinstance(value, ast.List):
        return value
    if isinstance(value, ast.Call) and _is_name(value.func, "CyclicInterrupt"):
        first = value.args[0] if value.args else next((kw.value for kw in value.keywords if kw.arg == "networks"), None)
        return first if isinstance(first, ast.List) else None
    return None


def _is_name(node: ast.expr, name: str) -> bool:
    return isinstance(node, ast.Name) and node.id == name


def _is_docstring(stmt: ast.stmt) -> bool:
    return isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant) and isinstance(stmt.value.value, str)


# -- edits (each works on the copy's nodes, found by their walk index) -------------------------


def _replace(nodes: list[ast.AST], old: ast.AST, new: ast.AST) -> None:
    for parent in nodes:
        for name, value in ast.iter_fields(parent):
            if value is old:
                setattr(parent, name, new)
                return
            if isinstance(value, list):
                for i, item in enumerate(value):
                    if item is old:
                        value[i] = new
                        return
    raise ValueError("internal: the node to replace has no parent")


def _unwrap(k_call: int, k_inner: int) -> Edit:
    return lambda nodes: _replace(nodes, nodes[k_call], nodes[k_inner])


def _rename(k_call: int, name: str) -> Edit:
    def edit(nodes: list[ast.AST]) -> None:
        func = nodes[k_call].func  # type: ignore[attr-defined]
        if isinstance(func, ast.Name):
            func.id = name
        else:
            func.attr = name

    return edit


def _set_attr(k: int, name: str, value: Any) -> Edit:
    return lambda nodes: setattr(nodes[k], name, value)


def _set_value(k_assign: int, value: bool) -> Edit:
    return lambda nodes: setattr(nodes[k_assign].value, "value", value)  # type: ignore[attr-defined]


def _set_op(k_compare: int, i: int, op: type[ast.cmpop]) -> Edit:
    return lambda nodes: nodes[k_compare].ops.__setitem__(i, op())  # type: ignore[attr-defined]


def _swap_block(k: int, field_name: str, i: int) -> Edit:
    def edit(nodes: list[ast.AST]) -> None:
        block = getattr(nodes[k], field_name)
        block[i], block[i + 1] = block[i + 1], block[i]

    return edit


def _drop_block(k: int, field_name: str, i: int) -> Edit:
    return lambda nodes: getattr(nodes[k], field_name).pop(i)


def _to_ob1(k_assign: int) -> Edit:
    def edit(nodes: list[ast.AST]) -> None:
        stmt = nodes[k_assign]
        stmt.targets[0].id = "OB1"  # type: ignore[attr-defined]
        stmt.value = stmt.value.args[0]  # type: ignore[attr-defined]

    return edit


def _move_last(k: int, i: int) -> Edit:
    def edit(nodes: list[ast.AST]) -> None:
        elts = nodes[k].elts  # type: ignore[attr-defined]
        elts.append(elts.pop(i))

    return edit


def _text(node: ast.AST, limit: int = 60) -> str:
    text = ast.unparse(node).splitlines()[0]
    return text if len(text) <= limit else text[: limit - 1] + "…"


# --------------------------------------------------------------------------------------------
# Grading mutants
# --------------------------------------------------------------------------------------------


@dataclass
class Outcome:
    """What became of one mutant: its status and why (the check that killed it, the load error), and
    the exercise's reason when it declares the mutant a correct program."""

    mutant: Mutant
    status: str
    detail: str = ""
    reason: str = ""


@dataclass
class MutationReport:
    """The mutants of one exercise's reference and their outcomes."""

    exercise: str
    title: str
    seeds: list[int]
    outcomes: list[Outcome] = field(default_factory=list)
    reference_failures: list[str] = field(default_factory=list)
    misleading: list[str] = field(default_factory=list)
    elapsed_s: float = 0.0

    def count(self, status: str) -> int:
        return sum(o.status == status for o in self.outcomes)

    def of(self, status: str) -> list[Outcome]:
        return [o for o in self.outcomes if o.status == status]

    @property
    def score(self) -> float | None:
        """Killed / mutants that change behaviour (None when no mutant does)."""
        changed = self.count(KILLED) + self.count(SURVIVED)
        return self.count(KILLED) / changed if changed else None

    def to_dict(self) -> dict[str, Any]:
        data = asdict(self)
        data["score"] = self.score
        data["counts"] = {s: self.count(s) for s in STATUSES}
        for o in data["outcomes"]:
            o["mutant"]["label"] = f"line {o['mutant']['line']}: {o['mutant']['description']}"
        return data

    def to_json(self, path: str | Path | None = None) -> str:
        text = json.dumps(self.to_dict(), indent=2)
        if path is not None:
            Path(path).write_text(text, encoding="utf-8")
        return text


def exercise_mutants(exercise: Exercise) -> list[Mutant]:
    """The mutants of an exercise's reference solution (its NC inputs from the I/O table).

    Raises :class:`~plcsim.core.errors.ExerciseError` if the exercise's ``spec_equivalent`` names a mutant
    the reference does not have (see :func:`declared_equivalents`).
    """
    path = Path(exercise.reference.path)
    if path.suffix == ".il":
        from plcsim.frontends.il import IlProgram
        from plcsim.mutate.il import derive_il_mutants

        mutants = derive_il_mutants(IlProgram.from_file(path).text)
    elif path.suffix == ".py":
        nc = [row.tag for row in exercise.io if row.wiring == "NC" and row.direction == "input"]
        mutants = derive_mutants(
            path.read_text(encoding="utf-8"), exercise.tag_table(), nc_inputs=nc, filename=str(path)
        )
    else:
        raise PlcError(
            f"exercise {exercise.number}: its reference {path.name} is neither a Python (S7) nor an "
            f"instruction-list (Tecomat, .il) program; mutation testing derives mutants of those two only"
        )
    declared_equivalents(exercise, mutants)
    return mutants


def declared_equivalents(exercise: Exercise, mutants: Sequence[Mutant]) -> dict[tuple[int, str], str]:
    """The exercise's ``spec_equivalent`` matched to ``mutants`` (its reference's): {(line, description): reason}.

    A key is a mutant's description, or ``"line N: description"``. A key that matches no mutant is
    stale (the reference or an operator changed) and one that matches several is ambiguous: both
    raise :class:`~plcsim.core.errors.ExerciseError` naming the exercise's file and line.
    """
    out: dict[tuple[int, str], str] = {}
    problems = []
    for key, reason in exercise.spec_equivalent.items():
        matches = [m for m in mutants if key in (m.description, str(m))]
        if len(matches) == 1:
            out[matches[0].line, matches[0].description] = reason
        elif not matches:
            hint = did_you_mean(key, [m.description for m in mutants])
            problems.append(f"spec_equivalent names {key!r}, which is no mutant of the reference{hint}")
        else:
            lines = ", ".join(str(m.line) for m in matches)
            problems.append(f"spec_equivalent {key!r} names the mutants of lines {lines}: write 'line N: {key}'")
    if problems:
        listed = "; ".join(problems)
        raise ExerciseError(f"{exercise.defined_at}: exercise {exercise.number}: {listed}", problems)
    return out


def mutate_exercise(
    exercise: Exercise,
    *,
    seeds: int = 3,
    jobs: int = 1,
    mutants: Sequence[Mutant] | None = None,
    progress: Callable[[int, int, Outcome], None] | None = None,
) -> MutationReport:
    """Grade every mutant of the exercise's reference on seeds 1..``seeds``; ``jobs`` mutants at a time."""
    started = time.perf_counter()
    every = exercise_mutants(exercise)
    reasons = declared_equivalents(exercise, every)
    chosen = list(mutants) if mutants is not None else every
    job = _Job(exercise, list(range(1, seeds + 1)))
    report = MutationReport(exercise.number, exercise.title, job.seeds, reference_failures=job.reference_failures())
    outcomes: list[Outcome] = []
    for outcome in _map(job, chosen, jobs):
        outcomes.append(outcome)
        if progress is not None:
            progress(len(outcomes), len(chosen), outcome)
    report.outcomes = sorted(outcomes, key=lambda o: o.mutant.number)
    for outcome in report.outcomes:
        _explain(outcome, reasons.get((outcome.mutant.line, outcome.mutant.description)), report.misleading)
    report.elapsed_s = time.perf_counter() - started
    return report


def _explain(outcome: Outcome, reason: str | None, misleading: list[str]) -> None:
    """Apply the exercise's declaration to one outcome: a survivor is explained; a killed or
    stillborn mutant makes the declaration misleading (an equivalent one stays equivalent)."""
    if reason is None:
        return
    outcome.reason = reason
    if outcome.status == SURVIVED:
        outcome.status = EXPLAINED
    elif outcome.status in (KILLED, STILLBORN):
        misleading.append(
            f"{outcome.mutant}: declared a correct program ({reason}), but {outcome.status} ({outcome.detail}):"
            " a check is stricter than the spec, or the declaration is wrong"
        )


class _Job:
    """The reference's verdicts and behaviour per seed, and the grading of one mutant against them."""

    def __init__(self, exercise: Exercise, seeds: list[int]):
        self.exercise = exercise
        self.seeds = seeds
        self.reference = exercise.reference.program()
        self.il = Path(exercise.reference.path).suffix == ".il"
        self.ignore = edge_memories(self.reference) if isinstance(self.reference, Program) else set()
        self._failed = {s: _failures(grade(exercise, self.reference, seed=s)) for s in seeds}
        self._behaviour: dict[tuple[int, str], dict[str, str]] = {}

    def reference_failures(self) -> list[str]:
        return [f"seed {s}: {f}" for s in self.seeds for f in sorted(self._failed[s])]

    def outcome(self, mutant: Mutant) -> Outcome:
        try:
            program = self.load(mutant)
        except PlcError as exc:
            return Outcome(mutant, STILLBORN, str(exc))
        for seed in self.seeds:
            report = grade(self.exercise, program, seed=seed)
            if report.error is not None:
                return Outcome(mutant, STILLBORN, report.error)
            new = sorted(_failures(report) - self._failed[seed])
            if new:
                return Outcome(mutant, KILLED, f"seed {seed}: {new[0]}")
        for seed in self.seeds:
            for scenario in self.exercise.scenarios:
                key = (seed, scenario.name)
                if key not in self._behaviour:
                    self._behaviour[key] = self._run(self.reference, scenario.name, seed)
                mine = self._run(program, scenario.name, seed)
                differ = sorted(
                    k for k in mine.keys() | self._behaviour[key].keys() if mine.get(k) != self._behaviour[key].get(k)
                )
                if differ:
                    shown = ", ".join(differ[:4]) + (" ..." if len(differ) > 4 else "")
                    return Outcome(
                        mutant,
                        SURVIVED,
                        f"every check passes, but these differ: {shown} (seed {seed}, scenario {scenario.name!r})",
                    )
        return Outcome(mutant, EQUIVALENT, "the same behaviour as the reference in every scenario and seed")

    def load(self, mutant: Mutant) -> SourceProgram:
        """The mutant as a program of the reference's front end (PlcError if it does not load)."""
        name = f"<mutant {mutant.number}>"
        if self.il:
            from plcsim.mutate.il import load_il

            return load_il(mutant.source, name, self.exercise.tag_table())
        return Program(mutant.source, name)

    def _run(self, program: SourceProgram, scenario: str, seed: int) -> dict[str, str]:
        sim = self.exercise.simulation(program, scenario, seed=seed)
        error = ""
        try:
            sim.run()
        except PlcError as exc:
            error = str(exc)
        return behaviour(self.exercise, sim.trace, error, self.ignore, getattr(program, "filename", ""))


def _failures(report: Report) -> set[str]:
    return {f"scenario {c.scenario!r}: {c.check}" for c in report.failed()}


def edge_memories(program: Program) -> set[str]:
    """The tags a program names as edge memory (``P(x, "SB1")``): the edge instruction's bookkeeping."""
    out = set()
    for node in ast.walk(program.tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            k = {"P": 1, "N": 1, "P_TRIG": 1, "N_TRIG": 1, "P_COIL": 2, "N_COIL": 2}.get(node.func.id)
            if k is not None and len(node.args) > k and isinstance(node.args[k], ast.Constant):
                out.add(str(node.args[k].value))
    return out


def behaviour(
    exercise: Exercise, trace: Any, error: str = "", ignore: Iterable[str] = (), filename: str = ""
) -> dict[str, str]:
    """What a check can see of a run, hashed per signal: when each exercise tag changed and to what,
    the events and the CPU's error (tags in ``ignore``, the CPU's clock and system bits left out;
    the program's ``filename`` in a message is read as ``<program>``: a mutant's name is not behaviour)."""
    heads = {row.tag for row in exercise.io} | set(exercise.dbs)
    skip = _CPU_BITS | set(ignore)
    events = json.dumps([asdict(e) for e in trace.events])
    if filename:
        events, error = (text.replace(json.dumps(filename)[1:-1], "<program>") for text in (events, error))
    out = {"events": _hash(events.encode()), "CPU error": error}
    for name in trace.names:
        if name.split(".")[0] in heads and name not in skip:
            col = trace.column(name).astype(np.float64)
            changed = np.concatenate(([True], col[1:] != col[:-1])) if len(col) else np.zeros(0, dtype=bool)
            out[name] = _hash(trace.signal_times(name)[changed].tobytes(), col[changed].tobytes())
    return out


def _hash(*chunks: bytes) -> str:
    h = hashlib.sha256()
    for chunk in chunks:
        h.update(chunk)
    return h.hexdigest()


_CURRENT: _Job | None = None  # the job a forked worker inherits (nothing is pickled but the mutant)


def _grade_in_worker(mutant: Mutant) -> Outcome:
    assert _CURRENT is not None
    return _CURRENT.outcome(mutant)


def _map(job: _Job, mutants: list[Mutant], jobs: int) -> Iterator[Outcome]:
    global _CURRENT
    if jobs <= 1 or len(mutants) < 2 or "fork" not in multiprocessing.get_all_start_methods():
        yield from map(job.outcome, mutants)
        return
    _CURRENT = job
    try:
        with ProcessPoolExecutor(max_workers=jobs, mp_context=multiprocessing.get_context("fork")) as pool:
            yield from pool.map(_grade_in_worker, mutants)
    finally:
        _CURRENT = None


# --------------------------------------------------------------------------------------------
# Terminal output
# --------------------------------------------------------------------------------------------


def print_mutation_report(report: MutationReport, console: Any) -> None:
    """The score, the surviving mutants (where the checks are weak) and the equivalent ones."""
    from rich.table import Table
    from rich.text import Text

    console.print(Text(f"mutation testing of {report.exercise} {report.title}", style="bold"))
    console.print(
        Text(
            f"{len(report.outcomes)} mutants of the reference, graded on seed{'s' if len(report.seeds) > 1 else ''} "
            f"{', '.join(map(str, report.seeds))} in {report.elapsed_s:.1f} s"
        )
    )
    if report.reference_failures:
        console.print(Text("the reference itself fails (these failures do not kill a mutant):", style="yellow"))
        for line in report.reference_failures:
            console.print(Text(f"  {line}"))
    for status, title, style in (
        (SURVIVED, "surviving mutants (behave differently, pass every check)", "red"),
        (EXPLAINED, "explained mutants (correct programs by the spec's words, not counted)", "cyan"),
        (EQUIVALENT, "equivalent mutants (no scenario tells them apart)", "yellow"),
        (STILLBORN, "mutants that do not load (not counted)", "dim"),
    ):
        rows = report.of(status)
        if not rows:
            continue
        console.print(Text(title, style=style))
        table = Table()
        for col in ("#", "line", "operator", "mutant"):
            table.add_column(col)
        for o in rows:
            why = o.reason if status == EXPLAINED else "" if status == EQUIVALENT else o.detail.splitlines()[0]
            what = o.mutant.description + (f"\n{why}" if why else "")
            table.add_row(str(o.mutant.number), str(o.mutant.line), o.mutant.operator, Text(what))
        console.print(table)
    if report.misleading:
        console.print(Text("misleading declarations (spec_equivalent names a mutant the checks kill):", style="red"))
        for line in report.misleading:
            console.print(Text(f"  {line}"))
    score = report.score
    shown = "n/a (no mutant changes behaviour)" if score is None else f"{100 * score:.0f} %"
    console.print(
        Text.assemble(
            ("mutation score: ", "bold"),
            (shown, "bold green" if score is not None and score >= 0.9 else "bold red"),
            f"  ({report.count(KILLED)} killed, {report.count(SURVIVED)} survived, {report.count(EXPLAINED)} explained,"
            f" {report.count(EQUIVALENT)} equivalent, {report.count(STILLBORN)} do not load)",
        )
    )


__all__ = [
    "Mutant",
    "Outcome",
    "MutationReport",
    "derive_mutants",
    "exercise_mutants",
    "declared_equivalents",
    "mutate_exercise",
    "behaviour",
    "edge_memories",
    "print_mutation_report",
    "KILLED",
    "SURVIVED",
    "EXPLAINED",
    "EQUIVALENT",
    "STILLBORN",
]
