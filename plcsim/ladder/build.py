"""Reading a Python program's networks as ladder rungs (see :mod:`plcsim.ladder.model`).

Each statement of a network becomes one rung, or a text box when it has no ladder form. The rule that
keeps a drawing faithful: LAD evaluates every contact of a rung, Python skips what ``and``/``or`` or an
``if`` decides without, so an instruction with an effect (an edge contact, a box) is drawn only where
Python runs it in every scan too: first in the rung. Elsewhere the statement is a text box.
"""

from __future__ import annotations

import ast
import inspect
import textwrap
from typing import Any

from plcsim.controllers.s7.instructions import BLOCKS, CPU_BOUND, FUNCTIONS, PURE_INSTRUCTIONS
from plcsim.frontends.python.program import Program
from plcsim.frontends.python.typecheck import Typing, safe_type
from plcsim.ladder.model import (
    Alias,
    Block,
    Box,
    CallCoil,
    Coil,
    Compare,
    Contact,
    Element,
    Fork,
    FunctionContact,
    Invert,
    Network,
    Operation,
    Parallel,
    Part,
    Rung,
    Series,
    TextBox,
)
from plcsim.tags.table import FBType, TagTable
from plcsim.tags.types import Bool, StructType

_BOXES = {box: block for block in BLOCKS.values() for box in block.boxes}
_EDGE_CONTACTS = {"P", "N"}
_BOX_OUTPUTS = {"CTU": ("Q", "CV"), "CTD": ("Q", "CV"), "CTUD": ("QU", "QD", "CV")} | {
    timer: ("Q", "ET") for timer in BLOCKS["IEC_TIMER"].boxes
}
"""A box's output pins as the manual draws them, the one the rung continues from first."""
_COMPARE = {ast.Eq: "==", ast.NotEq: "<>", ast.Lt: "<", ast.LtE: "<=", ast.Gt: ">", ast.GtE: ">="}
_ARITHMETIC = {ast.Add: "ADD", ast.Sub: "SUB", ast.Mult: "MUL", ast.Div: "DIV", ast.FloorDiv: "DIV", ast.Mod: "MOD"}
_BOOL_FUNCTIONS = frozenset(f.name for f in FUNCTIONS.values() if f.returns_bool and not f.needs_cpu)
_COIL_CALLS = {"JMP", "RET", "RT", "PT"}
"""Instructions a program calls as statements that LAD draws as coils."""
_VALUE_CALLS = frozenset(f.name for f in FUNCTIONS.values() if f.needs_cpu and not f.named) - {"MOVE"}
"""Instructions with an effect that return a value (RD_LOC_T): a box with EN when stored."""
_IMPURE_NAMES = CPU_BOUND | _COIL_CALLS


class NotLadder(Exception):  # noqa: N818 - a reason, not an error: the statement becomes a text box
    """A statement with no faithful ladder form; the message says why (shown under its text box)."""


def build_ladder(program: Program, table: TagTable | None = None) -> list[Block]:
    """The ladder of every task of ``program``; ``table`` (an exercise's tags) tells Bool coils from MOVEs
    where the program alone cannot (``t.X = t.Y``)."""
    table = program.declare_into(table if table is not None else TagTable())
    root_params = {name: func.args.args[0].arg for name, func in program.functions.items() if func.args.args}
    typing = Typing(table.schema(), frozenset(), program.filename, root_params)
    lines = program.source.splitlines()
    blocks = []
    for task in program.tasks.values():
        block = Block(task.name)
        for number, spec in enumerate(task.networks, start=1):
            func = program.functions[spec.name]
            doc = ast.get_docstring(func) or ""
            comment = "\n".join(doc.strip().splitlines()[1:]).strip()
            reader = _NetworkReader(func, typing, lines, set(program.functions))
            block.networks.append(
                Network(number, spec.name, spec.title, comment, spec.label, reader.parts(), func.lineno, reader.root)
            )
        blocks.append(block)
    return blocks


class _NetworkReader:
    """Reads one network function, statement by statement."""

    def __init__(self, func: ast.FunctionDef, typing: Typing, lines: list[str], functions: set[str]):
        self.func = func
        self.typing = typing
        self.lines = lines
        self.functions = functions
        self.root = func.args.args[0].arg if func.args.args else "t"
        self.env: dict[str, Any] = {self.root: typing.root}
        self.aliases: dict[str, str] = {}

    # -- statements ------------------------------------------------------------------------------

    def parts(self) -> list[Part]:
        body = list(self.func.body)
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]  # the docstring: the network's title and comment
        aliases = self._alias_names(body)
        parts: list[Part] = []
        for stmt in body:
            span = (stmt.lineno, stmt.end_lineno or stmt.lineno)
            if isinstance(stmt, ast.Assign) and _single_name(stmt) in aliases:
                name = _single_name(stmt)
                self.aliases[name] = self.operand(stmt.value)
                self.env[name] = safe_type(self.typing, stmt.value, self.env)
                parts.append(Alias(name, self.aliases[name], stmt, span))
                continue
            try:
                parts.append(Rung(Series(tuple(self.top_statement(stmt))), span))
            except NotLadder as why:
                text = textwrap.dedent("\n".join(self.lines[span[0] - 1 : span[1]]))
                if parts and isinstance(parts[-1], TextBox):
                    last = parts.pop()
                    parts.append(
                        TextBox(
                            last.text + "\n" + text, (*last.statements, stmt), (last.lines[0], span[1]), last.reason
                        )
                    )
                else:
                    parts.append(TextBox(text, (stmt,), span, str(why)))
        return parts

    def _alias_names(self, body: list[ast.stmt]) -> set[str]:
        """Locals bound once to a structure of the tags (``d = t.DATA``) and used as ``d.MEMBER``."""
        bound: dict[str, int] = {}
        candidates = set()
        for node in ast.walk(ast.Module(body=body, type_ignores=[])):
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                bound[node.id] = bound.get(node.id, 0) + 1
        for stmt in body:
            name = _single_name(stmt) if isinstance(stmt, ast.Assign) else None
            if (
                name
                and self._is_tag_path(stmt.value)
                and not isinstance(safe_type(self.typing, stmt.value, self.env), type(Bool))
            ):
                candidates.add(name)
        used_as_base = {
            n.value.id
            for n in ast.walk(ast.Module(body=body, type_ignores=[]))
            if isinstance(n, ast.Attribute) and isinstance(n.value, ast.Name)
        }
        return {n for n in candidates if bound.get(n) == 1 and n in used_as_base}

    def top_statement(self, stmt: ast.stmt) -> list[Element]:
        """A statement at the network's top level, run in every scan: its rung's elements."""
        if isinstance(stmt, ast.If):
            if stmt.orelse:
                raise NotLadder("an if with else/elif has no single rung; LAD writes it as two rungs")
            return [*self.contacts(stmt.test, first=True), *self.outputs(stmt.body)]
        if isinstance(stmt, ast.Assign):
            target = self._target(stmt)
            if self._is_bool_store(target, stmt.value) and not _is_bool_constant(stmt.value):
                return [*self.contacts(stmt.value, first=True), Coil("=", self.operand(target), target)]
            return [self.operation(stmt, target, stmt.value)]
        if isinstance(stmt, ast.AugAssign):
            return [self.operation(stmt, self._target(stmt), stmt)]
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Call):
            call = stmt.value
            if self._box(call) is not None:
                return self.contacts(call, first=True)
            return [self.call_output(stmt)]
        raise NotLadder(f"a {type(stmt).__name__.lower()} statement has no ladder form")

    def outputs(self, body: list[ast.stmt]) -> list[Element]:
        """The outputs of an ``if``'s body: one path, or a fork of paths run top to bottom."""
        branches = [self.output(stmt) for stmt in body]
        if len(branches) == 1:
            return branches[0]
        return [Fork(tuple(Series(tuple(b)) for b in branches))]

    def output(self, stmt: ast.stmt) -> list[Element]:
        if isinstance(stmt, ast.If):
            if stmt.orelse:
                raise NotLadder("an if with else/elif has no single rung; LAD writes it as two rungs")
            return [*self.contacts(stmt.test, first=False), *self.outputs(stmt.body)]
        if isinstance(stmt, ast.Assign):
            target = self._target(stmt)
            if _is_bool_constant(stmt.value) and self._is_bool_store(target, stmt.value):
                return [Coil("S" if stmt.value.value else "R", self.operand(target), target)]  # type: ignore[attr-defined]
            return [self.operation(stmt, target, stmt.value)]
        if isinstance(stmt, ast.AugAssign):
            return [self.operation(stmt, self._target(stmt), stmt)]
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Call) and self._box(stmt.value) is None:
            return [self.call_output(stmt)]
        raise NotLadder(
            "a box called under a condition runs only when the condition holds; in LAD a box runs in every scan"
            if isinstance(stmt, ast.Expr)
            else f"a {type(stmt).__name__.lower()} statement has no ladder form"
        )

    def call_output(self, stmt: ast.Expr) -> Element:
        """An instruction called as a statement: a coil (JMP, RET, RT, PT) or a MOVE box."""
        call = stmt.value
        assert isinstance(call, ast.Call)
        name = call.func.id if isinstance(call.func, ast.Name) else None
        if name in _COIL_CALLS and not call.keywords and all(self._pure(a) for a in call.args):
            operand = self.operand(call.args[0]) if call.args else ""
            if name == "JMP" and call.args and isinstance(call.args[0], ast.Constant):
                operand = str(call.args[0].value)
            if name == "PT" and len(call.args) == 2:
                operand = f"{operand} := {self.operand(call.args[1])}"
            return CallCoil(name, operand, stmt)
        if name == "MOVE" and len(call.args) >= 2 and not call.keywords and self._pure(call.args[0]):
            dests = tuple(
                (f"OUT{i}", f'"{d.value}"' if isinstance(d, ast.Constant) else self.operand(d))
                for i, d in enumerate(call.args[1:], start=1)
            )
            return Operation("MOVE", (("IN", self.operand(call.args[0])),), dests, stmt)
        raise NotLadder(f"the call {ast.unparse(call.func)}(...) has no ladder form here")

    def operation(self, stmt: ast.stmt, target: ast.expr, value: ast.expr | ast.AugAssign) -> Operation:
        """A store drawn as a box with EN (it runs only when EN has power, as the statement does)."""
        out = self.operand(target)
        if isinstance(value, ast.AugAssign):
            if not self._pure(value.value) or type(value.op) not in _ARITHMETIC:
                raise NotLadder("this compound assignment has no box")
            pins = (("IN1", out), ("IN2", self.operand(value.value)))
            return Operation(_ARITHMETIC[type(value.op)], pins, (("OUT", out),), stmt)
        if (
            isinstance(value, ast.Call)
            and isinstance(value.func, ast.Name)
            and value.func.id in _VALUE_CALLS
            and all(self._pure(a) for a in value.args)
            and not value.keywords
        ):
            pins = self._pins(value, None)
            return Operation(value.func.id, pins, (("OUT" if value.args else "RET_VAL", out),), stmt)
        if not self._pure(value):
            raise NotLadder("the value calls an instruction with an effect; LAD needs it on a rung of its own")
        if self._is_leaf(value):
            return Operation("MOVE", (("IN", self.operand(value)),), (("OUT1", out),), stmt)
        if (
            isinstance(value, ast.BinOp)
            and type(value.op) in _ARITHMETIC
            and self._is_leaf(value.left)
            and self._is_leaf(value.right)
        ):
            pins = (("IN1", self.operand(value.left)), ("IN2", self.operand(value.right)))
            return Operation(_ARITHMETIC[type(value.op)], pins, (("OUT", out),), stmt)
        if (
            isinstance(value, ast.Call)
            and isinstance(value.func, ast.Name)
            and value.func.id in PURE_INSTRUCTIONS
            and all(self._is_leaf(a) for a in value.args)
            and all(self._is_leaf(k.value) for k in value.keywords)
        ):
            pins = self._pins(value, PURE_INSTRUCTIONS[value.func.id])
            return Operation(value.func.id, pins, (("OUT", out),), stmt)
        return Operation("CALCULATE", (("", self.operand(value)),), (("OUT", out),), stmt)

    # -- contact networks --------------------------------------------------------------------------

    def contacts(self, expr: ast.expr, first: bool) -> list[Element]:
        """The series of elements for a condition. ``first``: Python evaluates it in every scan (it comes
        first in its rung), so an instruction with an effect may stand here."""
        if isinstance(expr, ast.BoolOp) and isinstance(expr.op, ast.And):
            return [e for i, v in enumerate(expr.values) for e in self.contacts(v, first and i == 0)]
        if isinstance(expr, ast.BoolOp):
            return [
                Parallel(tuple(Series(tuple(self.contacts(v, first and i == 0))) for i, v in enumerate(expr.values)))
            ]
        if isinstance(expr, ast.UnaryOp) and isinstance(expr.op, ast.Not):
            return self.negated(expr.operand, first)
        if isinstance(expr, ast.Compare):
            if len(expr.ops) != 1 or type(expr.ops[0]) not in _COMPARE or not self._pure(expr):
                raise NotLadder("a chained or non-numeric comparison has no compare contact")
            return [
                Compare(_COMPARE[type(expr.ops[0])], self.operand(expr.left), self.operand(expr.comparators[0]), expr)
            ]
        if isinstance(expr, ast.Call):
            return self.call_contacts(expr, first)
        if self._is_leaf(expr):
            return [Contact("NO", self.operand(expr), expr)]
        raise NotLadder(f"{ast.unparse(expr)} has no contact form")

    def negated(self, expr: ast.expr, first: bool) -> list[Element]:
        """NOT pushed to the contacts (De Morgan), as the course draws it: NC contacts in series or parallel."""
        if isinstance(expr, ast.UnaryOp) and isinstance(expr.op, ast.Not):
            return self.contacts(expr.operand, first)
        if isinstance(expr, ast.BoolOp) and isinstance(expr.op, ast.Or):
            return [e for i, v in enumerate(expr.values) for e in self.negated(v, first and i == 0)]
        if isinstance(expr, ast.BoolOp):
            return [
                Parallel(tuple(Series(tuple(self.negated(v, first and i == 0))) for i, v in enumerate(expr.values)))
            ]
        if self._is_leaf(expr) and not isinstance(expr, ast.Constant):
            return [Contact("NC", self.operand(expr), expr)]
        return [Invert(Series(tuple(self.contacts(expr, first))))]

    def call_contacts(self, call: ast.Call, first: bool) -> list[Element]:
        func = call.func
        name = func.id if isinstance(func, ast.Name) else None
        if name in _EDGE_CONTACTS:
            if not first:
                raise NotLadder(
                    f"{name}(...) behind and/or runs only when the left side lets it; in LAD it runs always"
                )
            if len(call.args) != 2 or call.keywords or not self._is_leaf(call.args[0]):
                raise NotLadder(f"{name} is drawn as a contact on one operand")
            mem = call.args[1]
            memory = f'"{mem.value}"' if isinstance(mem, ast.Constant) else self.operand(mem)
            return [Contact(name, self.operand(call.args[0]), call, memory)]
        if name in _BOOL_FUNCTIONS:
            if not self._pure(call):
                raise NotLadder(f"{name}'s operands call an instruction with an effect")
            return [FunctionContact(name, self._pins(call, PURE_INSTRUCTIONS[name]), call)]
        box = self._box(call)
        if box is not None:
            if not first:
                raise NotLadder(
                    f"the box {ast.unparse(func)} behind and/or runs only when the left side lets it; "
                    "in LAD it runs always"
                )
            block, method = box
            params = [p for p in inspect.signature(getattr(block.instance, method)).parameters if p != "self"]
            args = dict(zip(params, call.args, strict=False)) | {k.arg: k.value for k in call.keywords if k.arg}
            if len(call.args) > len(params) or any(k.arg is None for k in call.keywords):
                raise NotLadder("the box's arguments are not all named")
            if not params:  # a mechanism's begin()/end(): no input the rung could drive
                raise NotLadder(f"the box {ast.unparse(func)} has no input for the rung")
            rung_pin = params[0]
            if rung_pin not in args:
                raise NotLadder(f"the box gets no {rung_pin}: nothing for the rung to feed")
            for pin, value in args.items():
                if pin != rung_pin and not self._pure(value):
                    raise NotLadder(f"the box's {pin} calls an instruction with an effect")
            feed = self.contacts(args[rung_pin], first=True)
            pins = tuple((p, self.operand(v), v) for p, v in args.items() if p != rung_pin)
            outputs = _BOX_OUTPUTS.get(method, ("Q",))
            assert isinstance(func, ast.Attribute)
            shown = self.operand(func.value)
            return [*feed, Box(method, shown, rung_pin, pins, outputs, call, func.value)]
        raise NotLadder(f"{ast.unparse(func)}(...) has no contact form")

    # -- operands ----------------------------------------------------------------------------------

    def operand(self, expr: ast.expr) -> str:
        """An operand as TIA shows it: ``"S1"``, ``"DATA".POZ1``, ``"TON_A".Q``, ``#local``, ``T#10s``."""
        if isinstance(expr, ast.Attribute):
            if isinstance(expr.value, ast.Name) and expr.value.id == self.root:
                return f'"{expr.attr}"'
            return f"{self.operand(expr.value)}.{expr.attr}"
        if isinstance(expr, ast.Subscript):
            if isinstance(expr.value, ast.Name) and expr.value.id == self.root and isinstance(expr.slice, ast.Constant):
                return f'"{expr.slice.value}"'
            return f"{self.operand(expr.value)}[{self.operand(expr.slice)}]"
        if isinstance(expr, ast.Name):
            if expr.id in self.aliases:
                return self.aliases[expr.id]
            return expr.id if expr.id.isupper() or expr.id == self.root else f"#{expr.id}"
        if isinstance(expr, ast.Constant):
            if isinstance(expr.value, bool):
                return "TRUE" if expr.value else "FALSE"
            if isinstance(expr.value, str):
                return f"T#{expr.value}" if expr.value[:1].isdigit() else repr(expr.value)
            return repr(expr.value)
        return _Shown(self).visit_text(expr)

    def _pins(self, call: ast.Call, run: Any) -> tuple[tuple[str, str], ...]:
        try:
            params = list(inspect.signature(run).parameters) if run is not None else []
        except (TypeError, ValueError):
            params = []
        named = [(params[i] if i < len(params) else f"IN{i + 1}", self.operand(a)) for i, a in enumerate(call.args)]
        return (*named, *((k.arg or "", self.operand(k.value)) for k in call.keywords))

    # -- what an expression is -----------------------------------------------------------------------

    def _is_tag_path(self, expr: ast.expr) -> bool:
        while isinstance(expr, ast.Attribute | ast.Subscript):
            expr = expr.value
        return isinstance(expr, ast.Name) and (expr.id == self.root or expr.id in self.aliases)

    def _is_leaf(self, expr: ast.expr) -> bool:
        """An operand: a tag path, a local, a constant (no call, no operator)."""
        if isinstance(expr, ast.Constant):
            return True
        if isinstance(expr, ast.Name):
            return expr.id != self.root
        if isinstance(expr, ast.UnaryOp) and isinstance(expr.op, ast.USub) and isinstance(expr.operand, ast.Constant):
            return True
        if isinstance(expr, ast.Subscript):
            return self._is_tag_path(expr) and self._pure(expr.slice)
        return isinstance(expr, ast.Attribute) and self._is_tag_path(expr)

    def _pure(self, expr: ast.expr) -> bool:
        """Evaluating ``expr`` changes nothing: no box, no edge instruction, no MOVE, no call of a network."""
        for node in ast.walk(expr):
            if isinstance(node, ast.NamedExpr | ast.Lambda | ast.Await | ast.Yield | ast.YieldFrom):
                return False
            if isinstance(node, ast.Call) and (
                not isinstance(node.func, ast.Name) or node.func.id in _IMPURE_NAMES | self.functions
            ):
                return False
        return True

    def _box(self, call: ast.Call) -> tuple[Any, str] | None:
        func = call.func
        if not isinstance(func, ast.Attribute) or func.attr not in _BOXES:
            return None
        kind = safe_type(self.typing, func.value, self.env)
        block = _BOXES[func.attr]
        if isinstance(kind, FBType) and kind.name != block.name and func.attr not in ("R_TRIG", "F_TRIG"):
            return None
        return block, func.attr

    def _target(self, stmt: ast.Assign | ast.AugAssign) -> ast.expr:
        targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
        if len(targets) != 1 or not (self._is_leaf(targets[0]) and not isinstance(targets[0], ast.Constant)):
            raise NotLadder("only one tag or local can be the target of a rung")
        return targets[0]

    def _is_bool_store(self, target: ast.expr, value: ast.expr) -> bool:
        """Whether ``target = value`` is a coil (a Bool) rather than a MOVE."""
        kind = safe_type(self.typing, target, self.env)
        if kind is not None and not isinstance(kind, FBType | StructType):
            return kind is Bool
        if isinstance(value, ast.BoolOp | ast.Compare) or _is_bool_constant(value):
            return True
        if isinstance(value, ast.UnaryOp) and isinstance(value.op, ast.Not):
            return True
        if isinstance(value, ast.Call):
            name = value.func.id if isinstance(value.func, ast.Name) else None
            return name in _BOOL_FUNCTIONS | _EDGE_CONTACTS or self._box(value) is not None
        return safe_type(self.typing, value, self.env) is Bool


class _Shown:
    """An expression's text with its operands as TIA shows them (for CALCULATE and pin values)."""

    def __init__(self, reader: _NetworkReader):
        self.reader = reader

    def visit_text(self, expr: ast.expr) -> str:
        reader = self.reader

        class Replace(ast.NodeTransformer):
            def generic_visit(self, node: ast.AST) -> ast.AST:
                if isinstance(node, ast.Attribute | ast.Subscript | ast.Name) and reader._is_leaf(node):  # type: ignore[arg-type]
                    return ast.Name(reader.operand(node), ast.Load())  # type: ignore[arg-type]
                if isinstance(node, ast.Constant) and isinstance(node.value, bool | str):
                    return ast.Name(reader.operand(node), ast.Load())
                return super().generic_visit(node)

        copy = ast.parse(ast.unparse(expr), mode="eval").body
        return (
            ast.unparse(Replace().visit(copy)).replace(" and ", " AND ").replace(" or ", " OR ").replace("not ", "NOT ")
        )


def _single_name(stmt: ast.stmt) -> str:
    if isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name):
        return stmt.targets[0].id
    return ""


def _is_bool_constant(expr: ast.expr) -> bool:
    return isinstance(expr, ast.Constant) and isinstance(expr.value, bool)
