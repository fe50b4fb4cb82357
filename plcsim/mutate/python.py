"""The mutation operators of Python programs (S7): the slips students make, planted one at a time.

Every mutant is the reference program with one small change of its source (an AST transform,
regenerated with :func:`ast.unparse`), the kind of slip a student makes:

=============== ================================================================================
negate          a contact negated: a Bool tag read ``t.X`` <-> ``not t.X``
nc-as-no        an input wired NC read as if it were NO: every read of it negated at once
timer           TON <-> TOF <-> TP
edge            an edge removed: ``P(x, "M")`` / ``N(...)`` / ``R_TRIG(CLK=x)`` -> the plain signal ``x``
edge-kind       a rising edge for a falling one: P <-> N, P_TRIG <-> N_TRIG, R_TRIG <-> F_TRIG
preset          a PT/PV preset, a ``TIME("..")`` or an integer compared with, moved by one step
boundary        a comparison at its boundary: < <-> <=, > <-> >=, == <-> !=
coil            SET for RESET: ``t.X = True`` <-> ``t.X = False``
and-or          a series connection for a parallel one: ``and`` <-> ``or``
drop-operand    one operand of an ``and``/``or`` dropped: a forgotten contact (``a and b`` -> ``a``), such as an
                interlock
negate-operand  one operand of an ``and``/``or`` negated, whatever it is (a comparison, an edge, a bracket): an NO
                contact where an NC one is needed (on a tag read, the same mutant as negate's)
swap            two adjacent networks of an OB, or two adjacent if-blocks of a network, exchanged
drop            a network of an OB, or one statement of a block, dropped
move            a network moved to the end of its OB
task            a cyclic interrupt's networks (OB30) run in OB1 instead, every scan
=============== ================================================================================

A preset moves by the preset step of :mod:`plcsim.mutate.mutant`. The timer boxes and the edge boxes
come from the S7 instruction descriptions (:data:`plcsim.controllers.s7.instructions.BLOCKS`): the
timer boxes that take just IN and PT (TONR's reset R makes it no slip for them), and the boxes of the
edge instances. :mod:`plcsim.mutate.engine` grades the mutants; this module only derives them.

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
import inspect
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any

from plcsim.controllers.s7.instructions import BLOCKS, EdgeTrigger
from plcsim.core.errors import PlcError
from plcsim.frontends.python.program import Program
from plcsim.frontends.python.typecheck import Typing
from plcsim.mutate.mutant import Mutant, preset_steps
from plcsim.tags.table import TagTable
from plcsim.tags.types import Bool

if TYPE_CHECKING:
    from plcsim.exercise.model import Exercise


def _takes_in_and_pt(box: str) -> bool:
    """Whether the timer box ``box`` takes IN and PT only: TON, TOF and TP do, TONR takes a reset R too."""
    return list(inspect.signature(getattr(BLOCKS["IEC_TIMER"].instance, box)).parameters) == ["self", "IN", "PT"]


_TIMERS = tuple(box for box in BLOCKS["IEC_TIMER"].boxes if _takes_in_and_pt(box))
_EDGE_FUNCS = {"P": "N", "N": "P", "P_TRIG": "N_TRIG", "N_TRIG": "P_TRIG"}
_EDGE_TRIGGERS = [box for block in BLOCKS.values() if block.instance is EdgeTrigger for box in block.boxes]
_EDGE_BOXES = dict(zip(_EDGE_TRIGGERS, reversed(_EDGE_TRIGGERS)))  # R_TRIG for F_TRIG, and back
_BOUNDARY = {ast.Lt: ast.LtE, ast.LtE: ast.Lt, ast.Gt: ast.GtE, ast.GtE: ast.Gt, ast.Eq: ast.NotEq, ast.NotEq: ast.Eq}
_PRESETS = ("PT", "PV")

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
            yield from _operand_sites(node, index)
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


def _operand_sites(node: ast.BoolOp, index: dict[int, int]) -> Iterator[Site]:
    """Each operand of an ``and``/``or`` dropped (a forgotten contact: ``a and b and c`` -> ``a and c``) and
    negated (an NO contact where an NC one is needed, for any operand: a comparison, an edge, a bracket; a
    negated tag read is the same mutant as the operator negate's and is left out as a duplicate)."""
    k = index[id(node)]
    for i, operand in enumerate(node.values):
        rest = [v for j, v in enumerate(node.values) if j != i]
        after = rest[0] if len(rest) == 1 else ast.BoolOp(node.op, rest)
        yield "drop-operand", operand.lineno, f"{_text(node)} → {_text(after)}", _drop_operand(k, i)
        if isinstance(operand, ast.UnaryOp) and isinstance(operand.op, ast.Not):
            flipped: ast.expr = operand.operand
        else:
            flipped = ast.UnaryOp(ast.Not(), operand)
        negated = ast.BoolOp(node.op, [*node.values[:i], flipped, *node.values[i + 1 :]])
        yield "negate-operand", operand.lineno, f"{_text(node)} → {_text(negated)}", _negate_operand(k, i)


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


def _drop_operand(k_boolop: int, i: int) -> Edit:
    """One operand of the ``and``/``or`` at ``k_boolop`` left out; of two, the other stands alone."""

    def edit(nodes: list[ast.AST]) -> None:
        node = nodes[k_boolop]
        node.values.pop(i)  # type: ignore[attr-defined]
        if len(node.values) == 1:  # type: ignore[attr-defined]
            _replace(nodes, node, node.values[0])  # type: ignore[attr-defined]

    return edit


def _negate_operand(k_boolop: int, i: int) -> Edit:
    """The ``i``-th operand of the ``and``/``or`` at ``k_boolop`` negated (``not x`` -> ``x``)."""

    def edit(nodes: list[ast.AST]) -> None:
        values = nodes[k_boolop].values  # type: ignore[attr-defined]
        operand = values[i]
        negated = isinstance(operand, ast.UnaryOp) and isinstance(operand.op, ast.Not)
        values[i] = operand.operand if negated else ast.UnaryOp(ast.Not(), operand)

    return edit


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


def reference_mutants(exercise: Exercise) -> list[Mutant]:
    """The mutants of an exercise's Python reference (its NC inputs from the I/O table)."""
    path = Path(exercise.reference.path)
    nc = [row.tag for row in exercise.io if row.wiring == "NC" and row.direction == "input"]
    return derive_mutants(path.read_text(encoding="utf-8"), exercise.tag_table(), nc_inputs=nc, filename=str(path))


def load_mutant(source: str, filename: str, exercise: Exercise) -> Program:
    """A mutant as a program of the Python front end (PlcError if it does not load; it needs nothing of the
    exercise, which an instruction-list mutant assembles against)."""
    return Program(source, filename)


__all__ = ["derive_mutants", "reference_mutants", "load_mutant"]
