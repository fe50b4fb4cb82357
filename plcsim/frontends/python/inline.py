"""Whole-task code generation: the boxes of a task's merged function written out where they are called.

In the merged function of a task (:mod:`~plcsim.frontends.python.merge`) a box call such as
``_t_dict["T1"].TON(IN=..., PT=40)`` costs a method call with keywords, an ``-|P|-`` contact a call that
looks its memory bit up by name, and every read of a timer's ``Q`` a property. They are most of a scan's
time. :func:`inline_boxes` replaces each of them, where the call is a whole statement, the test of an
``if`` or the value of an assignment, by the statements of the instruction's own body (the methods of
:class:`~plcsim.controllers.s7.instructions.timers.IecTimer`, :class:`~.counters.IecCounter` and ``P``/``N``
of :mod:`~.edges`, written out on the instance's attributes): the same stores in the same order, the same
conversions and messages (the rare paths, a value to convert, a counter leaving its range, call the
instance's own helpers), the S7 refresh of a timer's Q and ET when they are read kept. Every generated
statement carries the line of the call it replaces, so an error still names its network and line.

What is not written out is left as the call it was: a box with a PT or PV that is not a constant, an edge
memory bit that is neither a plain BOOL tag of the root nor a BOOL member of a data block of the root (an aliased
bit, a bit deeper in a struct), a call inside a larger expression (where Python's short-circuit decides whether it
runs at all).
"""

from __future__ import annotations

import ast
from typing import Any

from plcsim.controllers.s7.instructions.counters import CTU_WRITTEN_OUT
from plcsim.controllers.s7.instructions.edges import EDGE_RESULTS, EDGE_WRITTEN_OUT, check_bool
from plcsim.controllers.s7.instructions.timers import TIMER_READ, TIMER_READS, TOF_WRITTEN_OUT, TON_WRITTEN_OUT
from plcsim.frontends.python.rewrite import ROOT_DICT, TICK
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS
from plcsim.frontends.python.typecheck import Typing, safe_type
from plcsim.tags.table import FBType
from plcsim.tags.types import Bool, StructType

COERCE_BOOL = "_box_bool"
CHECK_EDGE = "_edge_bool"
HELPERS: dict[str, Any] = {COERCE_BOOL: Bool.coerce, CHECK_EDGE: check_bool}
"""The names generated code calls on its rare paths, for the namespace."""


def inline_boxes(func: ast.FunctionDef, root: StructType, aliased: frozenset[str], shadowed: set[str]) -> bool:
    """Write out the boxes of ``func`` (a merged function after :func:`read_root_directly`) in place.

    ``root`` is the tag schema (an instance's type says which box it is), ``aliased`` the tags that alias
    memory, ``shadowed`` the names the program defines itself (its own ``P`` is not the contact).
    Returns whether anything was written out."""
    if not func.body or not binds_root_dict(func.body[0]):
        return False  # the code reaches its tags through ``_t_dict``, bound by the first statement
    writer = _Writer(root, aliased, shadowed, func)
    func.body = writer.top_level(func.body)
    if writer.count:
        ast.fix_missing_locations(func)
    return writer.count > 0


def binds_root_dict(stmt: ast.stmt) -> bool:
    """Whether ``stmt`` is ``_t_dict = ...``: the first statement of a merged function that reads its tags
    through the tag dict."""
    return (
        isinstance(stmt, ast.Assign)
        and len(stmt.targets) == 1
        and isinstance(stmt.targets[0], ast.Name)
        and stmt.targets[0].id == ROOT_DICT
    )


class _Writer:
    def __init__(self, root: StructType, aliased: frozenset[str], shadowed: set[str], func: ast.FunctionDef):
        self.root, self.aliased, self.shadowed = root, aliased, shadowed
        self.typing = Typing(root, aliased)
        self.env: dict[str, Any] = {ROOT_DICT: root, **dict.fromkeys(self._bool_locals(func), Bool)}
        """What :meth:`is_bool` types names by: the tag dict, and the locals that only ever hold Bools."""
        self.count = 0
        self.fresh: dict[str, str] = {}
        """Timer -> the local holding it, for the timers whose TON or TOF has run at this point of every
        execution with nothing since that could change them (see :meth:`top_level`)."""
        self.box: tuple[str, str] | None = None
        """The timer and its local of the TON or TOF the current statement itself writes out."""

    # -- static Bool --------------------------------------------------------------------------------

    def is_bool(self, node: ast.expr, env: dict[str, Any] | None = None) -> bool:
        """Whether ``node`` always gives True or False, as the rewrite's typing knows it (a Bool tag, ``not``,
        a comparison, ``and``/``or`` of such, an edge contact): a box then needs no check of its operand."""
        for sub in ast.walk(node):
            if isinstance(sub, ast.Call) and isinstance(sub.func, ast.Name) and sub.func.id in self.shadowed:
                return False  # the program's own function, whatever its name
        return safe_type(self.typing, node, self.env if env is None else env) is Bool

    def _bool_locals(self, func: ast.FunctionDef) -> set[str]:
        """The locals of ``func`` that every assignment gives a Bool (``edge = P(...)``); a name bound any
        other way (a loop, a tuple, ``+=``, ``:=``, a parameter) is none."""
        values: dict[str, list[ast.expr | None]] = {}
        simple: set[int] = set()
        for node in ast.walk(func):  # breadth first: an Assign comes before its target names
            if isinstance(node, ast.Assign) and all(isinstance(t, ast.Name) for t in node.targets):
                for target in node.targets:
                    values.setdefault(target.id, []).append(node.value)  # type: ignore[union-attr]
                    simple.add(id(target))
            elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store) and id(node) not in simple:
                values.setdefault(node.id, []).append(None)
            elif isinstance(node, ast.arg):
                values.setdefault(node.arg, []).append(None)
        names = {name for name, vals in values.items() if None not in vals}
        while True:
            env = {ROOT_DICT: self.root, **dict.fromkeys(names, Bool)}
            keep = {name for name in names if all(self.is_bool(v, env) for v in values[name])}  # type: ignore[arg-type]
            if keep == names:
                return names
            names = keep

    # -- statements -------------------------------------------------------------------------------

    def top_level(self, body: list[ast.stmt]) -> list[ast.stmt]:
        """:meth:`statements` for the function's own body, which also reads a timer's Q and ET as stored
        where its box ran before them in the same call: the clock stands still while a merged task runs,
        so the refresh a read would do computes what the box just stored (unless its PT was written since,
        which only a call or a member store can do: after either, the reads refresh again)."""
        out: list[ast.stmt] = []
        for stmt in body:
            if not self._keeps_timers(stmt):
                self.fresh.clear()
            out.extend(self.statement(stmt))
            if self.box is not None:
                key, local = self.box
                self.fresh[key] = local
        return out

    def _keeps_timers(self, stmt: ast.stmt) -> bool:
        """Whether ``stmt`` calls nothing but boxes, edge contacts and the generated conversions, and
        stores into no member (so it can change a timer only through its boxes)."""
        for node in ast.walk(stmt):
            if isinstance(node, ast.Call):
                func = node.func
                if isinstance(func, ast.Name):
                    name = func.id
                    if name in self.shadowed or not (
                        name in SAFE_FUNCTIONS or name.startswith("_to_") or name == TICK or name in EDGE_RESULTS
                    ):
                        return False
                elif not (
                    isinstance(func, ast.Attribute)
                    and func.attr in ("TON", "TOF", "CTU")
                    and self.instance(func.value) is not None
                ):
                    return False
            elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
                return False
        return True

    def statements(self, body: list[ast.stmt]) -> list[ast.stmt]:
        out: list[ast.stmt] = []
        for stmt in body:
            out.extend(self.statement(stmt))
        return out

    def statement(self, stmt: ast.stmt) -> list[ast.stmt]:
        for name in ("body", "orelse", "finalbody"):
            if isinstance(getattr(stmt, name, None), list):
                setattr(stmt, name, self.statements(getattr(stmt, name)))
        for handler in getattr(stmt, "handlers", []):
            handler.body = self.statements(handler.body)
        self.box = None
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Call):
            written = self.call(stmt.value, stmt)
            if written is not None:
                return _without_result(written[0], written[1].id)  # type: ignore[attr-defined]
        elif isinstance(stmt, ast.If) and isinstance(stmt.test, ast.Call):
            written = self.call(stmt.test, stmt)
            if written is not None:
                stmt.test = written[1]
                return [*written[0], stmt]
        elif isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.value, ast.Call):
            written = self.call(stmt.value, stmt)
            if written is not None:
                stmt.value = written[1]
                return [*written[0], stmt]
        self._reads(stmt)
        return [stmt]

    def _reads(self, stmt: ast.stmt) -> None:
        """Timer Q reads in the statement's expressions (not in its nested statements, already done)."""
        reads = _TimerReads(self)
        for name, value in ast.iter_fields(stmt):
            if name in ("body", "orelse", "finalbody", "handlers"):
                continue
            if isinstance(value, ast.AST):
                setattr(stmt, name, reads.visit(value))
            elif isinstance(value, list):
                setattr(stmt, name, [reads.visit(v) if isinstance(v, ast.AST) else v for v in value])

    # -- calls ------------------------------------------------------------------------------------

    def call(self, call: ast.Call, where: ast.stmt) -> tuple[list[ast.stmt], ast.expr] | None:
        """The statements of a box call and the name holding its result, or None to leave it a call."""
        func = call.func
        if isinstance(func, ast.Attribute) and func.attr in ("TON", "TOF", "CTU") and not call.args:
            instance = self.instance(func.value)
            words = {kw.arg: kw.value for kw in call.keywords}
            if instance is None or len(words) != len(call.keywords):
                return None
            preset = words.get("PV" if func.attr == "CTU" else "PT")
            if not (isinstance(preset, ast.Constant) and preset.value.__class__ is int):
                return None
            if func.attr == "CTU":
                if instance != "IEC_COUNTER" or set(words) - {"CU", "R", "PV"} or "CU" not in words:
                    return None
                temps = {"CU": "_cu", "R": "_rs"}
                arguments = [(temps[kw.arg], kw.value) for kw in call.keywords if kw.arg in temps]  # in call order
                if "R" not in words:
                    arguments.append(("_rs", ast.Constant(False)))
                checked = {name for name, value in arguments if self.is_bool(value)}
                return self.expand(
                    CTU_WRITTEN_OUT, where, checked, INSTANCE=func.value, PRESET=preset, ARGUMENTS=arguments
                )
            if instance != "IEC_TIMER" or set(words) != {"IN", "PT"}:
                return None
            template = TON_WRITTEN_OUT if func.attr == "TON" else TOF_WRITTEN_OUT
            checked = {"_x"} if self.is_bool(words["IN"]) else set()
            written = self.expand(template, where, checked, INSTANCE=func.value, IN=words["IN"], PRESET=preset)
            self.box = (func.value.slice.value, f"_i_{self.count}")  # type: ignore[attr-defined]
            return written
        if isinstance(func, ast.Name) and func.id in EDGE_RESULTS and func.id not in self.shadowed:
            if call.keywords or len(call.args) != 2:
                return None
            bit = call.args[1]
            place = self.plain_bit(bit.value) if isinstance(bit, ast.Constant) and isinstance(bit.value, str) else None
            if place is None:
                return None
            block, key = place
            template = EDGE_WRITTEN_OUT.replace("RESULT", EDGE_RESULTS[func.id])
            if block is not None:  # the bit in a data block's dict: the same stores, one step further
                template = template.replace(f"{ROOT_DICT}[BIT]", f"{ROOT_DICT}[BLOCK].__dict__[BIT]")
            return self.expand(
                template,
                where,
                {"_x"} if self.is_bool(call.args[0]) else set(),
                OPERAND=call.args[0],
                NAME=ast.Constant(func.id),
                BLOCK=ast.Constant(block),
                BIT=ast.Constant(key),
            )
        return None

    def instance(self, node: ast.expr) -> str | None:
        """The box type of ``_t_dict["NAME"]`` when NAME is a timer or counter instance of the root."""
        if not (
            isinstance(node, ast.Subscript)
            and isinstance(node.value, ast.Name)
            and node.value.id == ROOT_DICT
            and isinstance(node.slice, ast.Constant)
        ):
            return None
        member = self.root.members.get(node.slice.value)
        mtype = getattr(member, "type", None)
        return mtype.name if isinstance(mtype, FBType) else None

    def plain_bit(self, name: str) -> tuple[str | None, str] | None:
        """Where the edge memory bit ``name`` lives, when it is a BOOL that aliases nothing: ``(None, name)`` for
        a tag of the root, ``(block, member)`` for a member of a data block of the root (``"DATA.SB"``, the
        container and key the edge instruction's lookup finds for it); None for any other bit."""
        block, dot, key = name.rpartition(".")
        if dot and not (block.isidentifier() and key.isidentifier()):
            return None
        members = self.root.members
        if dot:
            owner = members.get(block)
            if owner is None or not isinstance(owner.type, StructType):
                return None
            members = owner.type.members
        member = members.get(key)
        if member is None or member.type is not Bool or name in self.aliased:
            return None
        return (block or None), key

    def expand(self, template: str, where: ast.stmt, bools: set[str], **parts: Any) -> tuple[list[ast.stmt], ast.expr]:
        """The template's statements with its parts put in and its temporaries made unique; without the
        checks of the operands in ``bools`` (the template's names of operands that are Bools already)."""
        self.count += 1
        suffix = f"_{self.count}"
        body = ast.parse(template.strip()).body
        body = _Fill(parts, suffix, frozenset(bools)).statements(body)
        for stmt in body:
            for node in ast.walk(stmt):
                if hasattr(node, "lineno"):
                    ast.copy_location(node, where)
        return body, ast.copy_location(ast.Name("_r" + suffix, ast.Load()), where)


class _Fill(ast.NodeTransformer):
    """Put the parts into a template: ``INSTANCE``, ``IN`` ... by their nodes, ``ARGUMENTS`` by statements;
    the template's own names (``_i``, ``_x`` ...) get the call's suffix."""

    def __init__(self, parts: dict[str, Any], suffix: str, bools: frozenset[str] = frozenset()):
        self.parts, self.suffix, self.bools = parts, suffix, bools

    def statements(self, body: list[ast.stmt]) -> list[ast.stmt]:
        out: list[ast.stmt] = []
        for stmt in body:
            checked = _checked_names(stmt.test) if isinstance(stmt, ast.If) else None
            if checked is not None and checked <= self.bools:
                continue  # the check of operands that are Bools already
            if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Name) and stmt.value.id == "ARGUMENTS":
                out.extend(
                    ast.Assign([ast.Name(name + self.suffix, ast.Store())], value)
                    for name, value in self.parts["ARGUMENTS"]
                )  # the call's own expressions, not the template's: nothing in them is renamed
            else:
                out.append(self.visit(stmt))
        return out

    def visit_Name(self, node: ast.Name) -> ast.AST:
        part = self.parts.get(node.id)
        if part is not None and node.id != "ARGUMENTS":
            return part
        if node.id.startswith("_") and node.id not in (ROOT_DICT, COERCE_BOOL, CHECK_EDGE):
            return ast.Name(node.id + self.suffix, node.ctx)
        return node

    def generic_visit(self, node: ast.AST) -> ast.AST:
        for field, value in ast.iter_fields(node):
            if isinstance(value, list):
                if field in ("body", "orelse"):
                    setattr(node, field, self.statements(value))
                else:
                    setattr(node, field, [self.visit(v) if isinstance(v, ast.AST) else v for v in value])
            elif isinstance(value, ast.AST):
                setattr(node, field, self.visit(value))
        return node


def _without_result(body: list[ast.stmt], result: str) -> list[ast.stmt]:
    """A box's statements without their stores into ``result``, for a box whose result nothing reads (a
    call that is a whole statement): what they store is read from a slot, which cannot fail."""
    out: list[ast.stmt] = []
    for stmt in body:
        if isinstance(stmt, ast.Assign):
            stmt.targets = [t for t in stmt.targets if not (isinstance(t, ast.Name) and t.id == result)]
            if not stmt.targets:
                continue
        elif isinstance(stmt, ast.If):
            stmt.body = _without_result(stmt.body, result) or [ast.copy_location(ast.Pass(), stmt)]
            stmt.orelse = _without_result(stmt.orelse, result)
        out.append(stmt)
    return out


def _checked_names(test: ast.expr) -> set[str] | None:
    """The names a template's check ``_x is not True and _x is not False`` (or several joined by ``or``)
    tests; None for any other test."""
    if isinstance(test, ast.BoolOp) and isinstance(test.op, ast.Or):
        parts = [_checked_names(v) for v in test.values]
        return None if None in parts else set().union(*parts)  # type: ignore[arg-type]
    if not (isinstance(test, ast.BoolOp) and isinstance(test.op, ast.And) and len(test.values) == 2):
        return None
    names = set()
    for compare, constant in zip(test.values, (True, False), strict=True):
        if not (
            isinstance(compare, ast.Compare)
            and isinstance(compare.left, ast.Name)
            and len(compare.ops) == 1
            and isinstance(compare.ops[0], ast.IsNot)
            and isinstance(compare.comparators[0], ast.Constant)
            and compare.comparators[0].value is constant
        ):
            return None
        names.add(compare.left.id)
    return names if len(names) == 1 else None


class _TimerReads(ast.NodeTransformer):
    """``_t_dict["T1"].Q`` (a load) -> the stored Q unless the timer runs (then the refreshing property)."""

    def __init__(self, writer: _Writer):
        self.writer = writer

    def visit_Attribute(self, node: ast.Attribute) -> ast.AST:
        self.generic_visit(node)
        if (
            isinstance(node.ctx, ast.Load)
            and node.attr in TIMER_READS
            and self.writer.instance(node.value) == "IEC_TIMER"
        ):
            local = self.writer.fresh.get(node.value.slice.value)  # type: ignore[attr-defined]
            if local is not None:  # its box has just run: the stored value is the refreshed one
                return ast.copy_location(
                    ast.Attribute(ast.Name(local, ast.Load()), TIMER_READS[node.attr], ast.Load()), node
                )
            self.writer.count += 1
            text = TIMER_READ.replace("_q", TIMER_READS[node.attr]).replace(".Q)", f".{node.attr})")
            read = ast.parse(text, mode="eval").body
            read = _Fill({"INSTANCE": node.value}, f"_{self.writer.count}").visit(read)
            for sub in ast.walk(read):
                if hasattr(sub, "lineno"):
                    ast.copy_location(sub, node)
            return read
        return node

    def _leave(self, node: ast.AST) -> ast.AST:
        return node  # a walrus binds differently (or not at all) in a lambda's or a comprehension's scope

    visit_Lambda = visit_ListComp = visit_SetComp = visit_DictComp = visit_GeneratorExp = _leave
