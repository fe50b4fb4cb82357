"""From a student's Python file to code the CPU runs: the PLC subset, typed stores, the watchdog.

Three jobs, each a pass over the syntax tree:

1. :func:`check_subset` accepts only the PLC subset of Python, a whitelist of syntax
   (:data:`ALLOWED_NODES`; imports, classes, exceptions, ``global``, comprehensions ... are refused
   with a reason a student understands, anything newer by default), no names starting with ``_``,
   no rebinding of an instruction's name, stores only into tags and local variables, bounded
   nesting and bounded constants; only a few builtins (``abs``, ``min``, ``max``, ``range`` ...).
   A violation is a :class:`SubsetError` naming the line and the fix.
2. :class:`StoreRewriter` turns every store into a tag into a converted store (an INT wraps, a
   BOOL refuses a number), checks tag names against the tag table at load time (a typo is reported
   with the nearest names before the program runs), puts a watchdog tick into every loop, and
   turns ``**``, ``*``, ``<<`` and ``%`` into the bounded operators of :mod:`plcsim.frontends.python.safe_math`.
3. :func:`analyse` collects what graders and the timer rule need: which tags each function uses,
   SET/RESET coils, timers whose Q and ET are never read, edge calls hidden behind ``and``/``or``.
"""

from __future__ import annotations

import ast
import builtins
import io
import operator
import tokenize
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from typing import Any

from plcsim.controllers.s7.instructions import BOOL_RESULTS, block_named, box_hint
from plcsim.core.errors import ProgramError, SubsetError, UnknownTagError, did_you_mean
from plcsim.core.literals import time_ms
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS
from plcsim.tags.memory import parse_address
from plcsim.tags.table import FBType
from plcsim.tags.types import ArrayType, Bool, ElementaryType, StructType, Time

ALLOWED_BUILTINS = {
    "abs",
    "min",
    "max",
    "range",
    "len",
    "int",
    "float",
    "bool",
    "round",
    "sum",
    "any",
    "all",
    "enumerate",
    "zip",
    "True",
    "False",
    "None",
}

_REFUSED_NODES: dict[type, str] = {
    ast.Import: "imports are not part of PLC programs; every instruction (TON, P, MOVE ...) is already available",
    ast.ImportFrom: "imports are not part of PLC programs; every instruction (TON, P, MOVE ...) is already available",
    ast.ClassDef: "classes are not part of PLC programs; use a DB(...) or a struct for data",
    ast.Lambda: "lambda is not part of PLC programs; write a def",
    ast.Global: "global is not allowed: keep state in tags (t.NAME), which the CPU retains and traces",
    ast.Nonlocal: "nonlocal is not allowed: keep state in tags (t.NAME)",
    ast.Try: "try/except is not part of PLC programs: an error stops the CPU and is reported",
    ast.Raise: "raise is not part of PLC programs",
    ast.With: "with is not part of PLC programs",
    ast.AsyncFunctionDef: "async functions are not part of PLC programs",
    ast.Await: "await is not part of PLC programs",
    ast.Yield: "yield is not part of PLC programs; split the program into networks instead",
    ast.YieldFrom: "yield is not part of PLC programs; split the program into networks instead",
    ast.Delete: "del is not part of PLC programs",
    ast.ListComp: "comprehensions are not part of PLC programs; use a for loop",
    ast.SetComp: "comprehensions are not part of PLC programs; use a for loop",
    ast.DictComp: "comprehensions are not part of PLC programs; use a for loop",
    ast.GeneratorExp: "generator expressions are not part of PLC programs; use a for loop",
    ast.JoinedStr: "f-strings are not part of PLC programs",
    ast.Assert: "assert is not part of PLC programs",
    ast.NamedExpr: "the := operator is not part of PLC programs; assign on its own line",
    ast.Starred: "* unpacking is not part of PLC programs",
    ast.Set: "sets are not part of PLC programs",
    ast.Match: "match is not part of PLC programs; use if/elif",
    ast.AnnAssign: "annotated assignments (x: int = ...) are not part of PLC programs; write x = ...",
    ast.MatMult: "the @ operator is not part of PLC programs",
}
"""Common constructs outside the subset, with the reason a student is given."""

ALLOWED_NODES: frozenset[type] = frozenset(
    {
        # statements
        ast.Module, ast.FunctionDef, ast.Assign, ast.AugAssign, ast.Return, ast.If, ast.For, ast.While,
        ast.Break, ast.Continue, ast.Pass, ast.Expr,
        # expressions
        ast.BoolOp, ast.BinOp, ast.UnaryOp, ast.IfExp, ast.Compare, ast.Call, ast.Constant, ast.Attribute,
        ast.Subscript, ast.Slice, ast.Name, ast.List, ast.Tuple, ast.Dict, ast.keyword, ast.arguments, ast.arg,
        ast.Load, ast.Store,
        # operators
        ast.And, ast.Or, ast.Add, ast.Sub, ast.Mult, ast.Div, ast.FloorDiv, ast.Mod, ast.Pow, ast.LShift,
        ast.RShift, ast.BitOr, ast.BitXor, ast.BitAnd, ast.Invert, ast.Not, ast.UAdd, ast.USub, ast.Eq,
        ast.NotEq, ast.Lt, ast.LtE, ast.Gt, ast.GtE, ast.Is, ast.IsNot, ast.In, ast.NotIn,
    }
)  # fmt: skip
"""The syntax of the PLC subset; any other node (including syntax a newer Python adds) is refused."""

MAX_NESTING = 100
"""How deeply expressions and blocks may nest (deeper is refused, long before the compiler's own limit)."""

_DANGEROUS = {
    "open",
    "exec",
    "eval",
    "compile",
    "__import__",
    "getattr",
    "setattr",
    "delattr",
    "globals",
    "locals",
    "vars",
    "input",
    "breakpoint",
    "exit",
    "quit",
    "help",
    "dir",
    "type",
    "object",
    "memoryview",
    "print",
    "super",
    "classmethod",
    "staticmethod",
    "property",
    "id",
    "hash",
    "iter",
    "next",
    "isinstance",
    "issubclass",
    "callable",
    "format",
    "repr",
    "ascii",
    "chr",
    "ord",
}
_FORBIDDEN_ATTRS = {
    "format",
    "format_map",
    "mro",
    "gi_frame",
    "f_globals",
    "f_locals",
    "tb_frame",
    # text and byte builders whose size is an argument: "x".ljust(10**9) is a gigabyte in one call
    "ljust",
    "rjust",
    "center",
    "zfill",
    "expandtabs",
    "to_bytes",
}


def _where(filename: str, node: ast.AST) -> str:
    return f"{filename}, line {getattr(node, 'lineno', '?')}"


def parse(source: str, filename: str) -> ast.Module:
    """Parse the program; a syntax error becomes a ProgramError with its line and a pointer."""
    try:
        return ast.parse(source.removeprefix("\ufeff"), filename=filename)
    except SyntaxError as exc:
        line = (exc.text or "").rstrip("\n")
        pointer = " " * max(0, (exc.offset or 1) - 1) + "^"
        raise ProgramError(
            f"{filename}, line {exc.lineno}: syntax error: {exc.msg}\n    {line}\n    {pointer}"
        ) from None
    except (RecursionError, MemoryError):
        raise SubsetError(
            f"{filename}, line {_busiest_line(source)}: the code is nested too deeply for Python to read; "
            f"split the expression into several assignments"
        ) from None


def _busiest_line(source: str) -> int | str:
    """The line whose statement has the most operators and brackets (where a too-deep expression is)."""
    counts: dict[int, int] = {}
    start = 1
    try:
        for tok in tokenize.generate_tokens(io.StringIO(source).readline):
            if tok.type == tokenize.OP:
                counts[start] = counts.get(start, 0) + 1
            elif tok.type in (tokenize.NEWLINE, tokenize.NL):
                start = tok.end[0] + 1
    except (tokenize.TokenError, SyntaxError):
        pass
    return max(counts, key=counts.__getitem__) if counts else "?"


def check_subset(
    tree: ast.Module, filename: str, known_names: Iterable[str], declaration_only: Iterable[str] = ()
) -> None:
    """Reject anything outside the PLC subset of Python, naming the line and the fix.

    A file with several violations is refused at its first one by line, the one a student reads
    first. ``declaration_only`` names (``Tag``, ``DB``, ``IEC_TIMER`` ...) may be used at module level only.
    """
    found = min(_violations(tree, filename, known_names, declaration_only), key=_line_order, default=None)
    if found is not None:
        raise found[1]


Violation = tuple[int | str, ProgramError]
"""A subset violation: its line and the error that names it."""


def _line_order(violation: Violation) -> float:
    line = violation[0]
    return line if isinstance(line, int) else float("inf")


def _violations(
    tree: ast.Module, filename: str, known_names: Iterable[str], declaration_only: Iterable[str]
) -> Iterator[Violation]:
    """Every statement's first violation of the syntax rules, then of the name rules."""
    known = set(known_names) | ALLOWED_BUILTINS
    reserved = known - {"True", "False", "None"}
    module_names = _module_level_names(tree)
    declared = {id(t) for s in tree.body if isinstance(s, ast.Assign) for t in s.targets}  # seen as t.NAME
    memo: dict[int, Any] = {}  # constant values of the sub-expressions folded so far
    try:
        for node, line in _nodes_not_too_deep(tree, filename):
            problem = _syntax_violation(node, line, filename, reserved, declared, memo)
            if problem is not None:
                yield line, problem
    except SubsetError as exc:  # nested too deeply: nothing below that line can be read
        yield _error_line(exc), exc
    visible = known | module_names
    own_tags = _declared_tags(tree)
    decl_only = set(declaration_only) | own_tags
    for stmt in tree.body:
        try:
            if isinstance(stmt, ast.FunctionDef):
                _check_function(stmt, filename, visible, decl_only, own_tags)
                continue
            for node in ast.walk(stmt):
                if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in visible:
                    raise _unknown_name(node, filename, visible)
        except ProgramError as exc:
            yield _error_line(exc), exc


def _error_line(exc: ProgramError) -> int | str:
    """The line an error of this module names: each starts ``file, line N:`` (see :func:`_where`)."""
    head = str(exc).split(": ", 1)[0]
    number = head.rpartition(", line ")[2]
    return int(number) if number.isdigit() else "?"


def _syntax_violation(
    node: Any, line: int | str, filename: str, reserved: set[str], declared: set[int], memo: dict[int, Any]
) -> ProgramError | None:
    """What is wrong with one node's syntax, or None."""
    kind = type(node)
    try:
        if kind not in ALLOWED_NODES:
            reason = _REFUSED_NODES.get(kind, f"{kind.__name__} syntax is not part of PLC programs")
            return SubsetError(f"{filename}, line {line}: {reason}")
        if kind is ast.Name and node.id.startswith("_"):
            return SubsetError(f"{_where(filename, node)}: names starting with _ are reserved ({node.id})")
        if kind is ast.Attribute and (node.attr.startswith("_") or node.attr in _FORBIDDEN_ATTRS):
            return SubsetError(f"{_where(filename, node)}: the attribute .{node.attr} is not available in PLC programs")
        if kind is ast.arg:
            _check_binding(node.arg, node, filename, reserved)
        if kind is ast.FunctionDef:
            _check_binding(node.name, node, filename, reserved)
            if node.args.vararg or node.args.kwarg:
                return SubsetError(f"{_where(filename, node)}: *args and **kwargs are not part of PLC programs")
        if kind is ast.Name and isinstance(node.ctx, ast.Store) and id(node) not in declared:
            _check_binding(node.id, node, filename, reserved)
        if kind is ast.BinOp or kind is ast.UnaryOp:
            try:
                _fold(node, memo, 0)
            except ProgramError as exc:
                return SubsetError(f"{filename}, line {line}: {exc}")
        if kind is ast.For and not all(isinstance(n, ast.Name | ast.Tuple | ast.Store) for n in ast.walk(node.target)):
            return SubsetError(
                f"{_where(filename, node)}: a for loop counts with a plain variable (for i in range(...)); "
                f"store into a tag inside the loop"
            )
    except SubsetError as exc:  # a binding of a reserved name
        return exc
    return None


_NOT_CONSTANT = object()
_PLAIN_OPS: dict[type, Any] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.BitOr: operator.or_,
    ast.BitAnd: operator.and_,
    ast.BitXor: operator.xor,
    ast.RShift: operator.rshift,
}


def _fold(node: ast.expr, memo: dict[int, Any], depth: int) -> Any:
    """The value of a constant expression with the bounded operators, or _NOT_CONSTANT; ``9**9**9`` is
    refused here (a ProgramError), at load time. Deeper than MAX_NESTING it gives up (the nesting check
    refuses such code anyway)."""
    if isinstance(node, ast.Constant):
        return node.value
    if id(node) in memo:
        return memo[id(node)]
    if depth > MAX_NESTING:
        return _NOT_CONSTANT
    value: Any = _NOT_CONSTANT
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.USub | ast.UAdd | ast.Invert):
        operand = _fold(node.operand, memo, depth + 1)
        if isinstance(operand, int | float) and not (isinstance(node.op, ast.Invert) and isinstance(operand, float)):
            value = (
                -operand if isinstance(node.op, ast.USub) else ~operand if isinstance(node.op, ast.Invert) else operand
            )
    elif isinstance(node, ast.BinOp):
        left, right = _fold(node.left, memo, depth + 1), _fold(node.right, memo, depth + 1)
        if left is not _NOT_CONSTANT and right is not _NOT_CONSTANT:
            safe = SAFE_OPS.get(type(node.op))
            func = SAFE_FUNCTIONS[safe] if safe else _PLAIN_OPS.get(type(node.op))
            try:
                value = func(left, right) if func else _NOT_CONSTANT
            except ProgramError:
                raise
            except Exception:  # noqa: BLE001 - 1/0 or "a" - 1 is reported by Python when the line runs
                value = _NOT_CONSTANT
    memo[id(node)] = value
    return value


def _declared_tags(tree: ast.Module) -> set[str]:
    """Module-level names bound to a declaration (``SEEN = Int(0)``): a network reads them as t.SEEN."""
    return {
        target.id
        for stmt in tree.body
        if isinstance(stmt, ast.Assign)
        and isinstance(stmt.value, ast.Call)
        and not (isinstance(stmt.value.func, ast.Name) and stmt.value.func.id == "TIME")
        for target in stmt.targets
        if isinstance(target, ast.Name) and not target.id.startswith("OB")
    }


def _check_binding(name: str, node: ast.AST, filename: str, reserved: set[str]) -> None:
    if name.startswith("_"):
        raise SubsetError(f"{_where(filename, node)}: names starting with _ are reserved ({name})")
    if name in reserved:
        raise SubsetError(
            f"{_where(filename, node)}: {name} is the name of an instruction, a type or a builtin; "
            f"choose another name (for example {name.lower()}_value)"
        )


def _nodes_not_too_deep(tree: ast.Module, filename: str) -> Iterator[tuple[ast.AST, int | str]]:
    """Every node of ``tree`` with its line (an operator has the line of its expression), refusing
    nesting deeper than MAX_NESTING (iteratively: depth costs nothing)."""
    todo: list[tuple[ast.AST, int, int | str]] = [(tree, 0, "?")]
    while todo:
        node, depth, line = todo.pop()
        line = getattr(node, "lineno", line)
        if depth > MAX_NESTING:
            raise SubsetError(
                f"{filename}, line {line}: the code is nested too deeply (more than {MAX_NESTING} levels); "
                f"split the expression into several assignments"
            )
        yield node, line
        todo.extend((child, depth + 1, line) for child in ast.iter_child_nodes(node))


def _module_level_names(tree: ast.Module) -> set[str]:
    names: set[str] = set()
    for stmt in tree.body:
        if isinstance(stmt, ast.FunctionDef):
            names.add(stmt.name)
        elif isinstance(stmt, ast.Assign):
            for target in stmt.targets:
                for node in ast.walk(target):
                    if isinstance(node, ast.Name):
                        names.add(node.id)
    return names


def _check_function(
    func: ast.FunctionDef, filename: str, visible: set[str], declaration_only: set[str], own_tags: set[str]
) -> None:
    local = {a.arg for a in func.args.args + func.args.kwonlyargs + func.args.posonlyargs}
    inside = [n for part in (func.args, *func.body) for n in ast.walk(part)]  # not the decorators: @label
    for node in inside:
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            local.add(node.id)
        elif isinstance(node, ast.FunctionDef) and node is not func:
            local.add(node.name)
            local |= {a.arg for a in node.args.args + node.args.kwonlyargs + node.args.posonlyargs}
            if node.decorator_list:
                raise SubsetError(
                    f"{_where(filename, node.decorator_list[0])}: decorators are not allowed on inner functions"
                )
    for node in inside:
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
            if node.id not in local and node.id not in visible:
                raise _unknown_name(node, filename, local | visible)
            if node.id in declaration_only and node.id not in local:
                if node.id in own_tags:
                    raise SubsetError(
                        f"{_where(filename, node)}: {node.id} is a tag of the program; in a network it is t.{node.id}"
                    )
                raise SubsetError(
                    f"{_where(filename, node)}: {node.id} declares a tag or an instance; declare it at module "
                    f"level (NAME = {node.id}(...)) and use it in a network as t.NAME"
                )
        elif isinstance(node, (ast.Attribute, ast.Subscript)) and isinstance(node.ctx, ast.Store):
            root = node.value
            while isinstance(root, (ast.Attribute, ast.Subscript)):
                root = root.value
            if not (isinstance(root, ast.Name) and root.id in local):
                raise SubsetError(
                    f"{_where(filename, node)}: {ast.unparse(node)} cannot be assigned; a program stores only "
                    f"into its tags (t.NAME = ..., t.DB.member = ...) and its own variables"
                )


def _builtins_list() -> str:
    return ", ".join(sorted(ALLOWED_BUILTINS - {"True", "False", "None"}))


def _unknown_name(node: ast.Name, filename: str, visible: set[str]) -> ProgramError:
    if node.id in _DANGEROUS or hasattr(builtins, node.id):
        return SubsetError(
            f"{_where(filename, node)}: {node.id} is not available in PLC programs "
            f"(no file, network or interpreter access; allowed builtins: {_builtins_list()})"
        )
    return ProgramError(
        f"{_where(filename, node)}: unknown name {node.id!r}{box_hint(node.id) or did_you_mean(node.id, visible)}"
        " (every name a program can use: plcsim reference, docs/instructions.md)"
    )


# --------------------------------------------------------------------------------------------
# Static types of expressions
# --------------------------------------------------------------------------------------------


@dataclass
class Typing:
    """What the compiler knows statically: the root tag schema and which tags alias memory.

    ``aliased`` names root tags (``"POM"``) and members of non-optimized DBs (``"DATA.INT_1"``)
    whose bytes another tag shares; stores into them must go through byte memory.
    """

    root: StructType
    aliased: frozenset[str] = frozenset()
    filename: str = "<program>"
    root_params: dict[str, str] = field(default_factory=dict)

    def type_of(self, node: ast.expr, env: dict[str, Any]) -> Any:
        """The static type of an expression: a DataType, an FB instance type, or None when unknown."""
        if isinstance(node, ast.Name):
            return env.get(node.id)
        if isinstance(node, ast.Constant):
            return Bool if isinstance(node.value, bool) else None
        if isinstance(node, ast.Attribute):
            base = self.type_of(node.value, env)
            return self.member_type(base, node.attr, node)
        if isinstance(node, ast.Subscript):
            base = self.type_of(node.value, env)
            if isinstance(base, ArrayType):
                return base.element
            if base is self.root and isinstance(node.slice, ast.Constant) and isinstance(node.slice.value, str):
                return self.root_item_type(node.slice.value, node)
            return None
        if isinstance(node, ast.Compare):
            return Bool
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            return Bool
        if isinstance(node, ast.BoolOp):
            return Bool if all(self.type_of(v, env) is Bool for v in node.values) else None
        if isinstance(node, ast.IfExp):
            body, orelse = self.type_of(node.body, env), self.type_of(node.orelse, env)
            return body if body is orelse else None
        if isinstance(node, ast.Call):
            func = node.func
            if isinstance(func, ast.Name) and func.id in BOOL_RESULTS:
                return Bool
            if isinstance(func, ast.Attribute):
                base = self.type_of(func.value, env)
                if isinstance(base, FBType) and func.attr in _boxes(base):
                    return Bool
        return None

    def member_type(self, base: Any, attr: str, node: ast.AST) -> Any:
        """The type of ``base.attr``; an unknown tag or member is a load-time error with suggestions."""
        if isinstance(base, StructType):
            member = base.members.get(attr)
            if member is None:
                what = "no tag" if base is self.root else f"{base.name} has no member"
                raise UnknownTagError(
                    f"{_where(self.filename, node)}: {what} {attr!r}{did_you_mean(attr, base.members)}"
                )
            return member.type
        if isinstance(base, FBType):
            block = block_named(base.name)
            members = block.readable if block is not None else {}
            if attr in _boxes(base):
                return None
            if attr not in members:
                boxes = sorted(_boxes(base))
                raise UnknownTagError(
                    f"{_where(self.filename, node)}: a {base.name} instance has no member {attr!r}"
                    f"{did_you_mean(attr, list(members) + boxes)} (members: {', '.join(members)}; "
                    f"boxes: {', '.join(boxes)})"
                )
            kind = members[attr]
            return Bool if kind == "Bool" else Time if kind == "Time" else None
        return None

    def root_item_type(self, key: str, node: ast.AST) -> Any:
        """The type of ``t["NAME"]`` or ``t["%MW10"]``."""
        if key in self.root.members:
            return self.root.members[key].type
        if key.lstrip().startswith("%"):
            return parse_address(key).default_type()
        raise UnknownTagError(f"{_where(self.filename, node)}: no tag {key!r}{did_you_mean(key, self.root.members)}")


# --------------------------------------------------------------------------------------------
# Rewriting
# --------------------------------------------------------------------------------------------

ROOT_DICT = "_t_dict"
ROOT_GUARD = "_tags_of"
"""Returns the tag object's member dict, after checking that it was given the CPU's tags."""
TICK = "_tick"
STORE = "_store"
FB_STORE = "_fb_store"
SAFE_OPS = {ast.Pow: "_pow", ast.Mult: "_mul", ast.LShift: "_lshift", ast.Mod: "_mod"}
"""Operators whose result can grow without bound; the CPU supplies bounded versions (see safe_math)."""
_NAMED_OPERANDS = {"P": (1,), "N": (1,), "P_TRIG": (1,), "N_TRIG": (1,), "P_COIL": (1, 2), "N_COIL": (1, 2)}
"""Arguments of edge instructions that name a memory bit; ``t.SB1`` there means the tag's name."""
_BOX_TYPES = {
    "TON": "IEC_TIMER",
    "TOF": "IEC_TIMER",
    "TP": "IEC_TIMER",
    "TONR": "IEC_TIMER",
    "CTU": "IEC_COUNTER",
    "CTD": "IEC_COUNTER",
    "CTUD": "IEC_COUNTER",
    "R_TRIG": "R_TRIG",
    "F_TRIG": "F_TRIG",
}


def _boxes(fb: FBType) -> tuple[str, ...]:
    """The box methods of an instance type (none for a type plcsim does not describe)."""
    block = block_named(fb.name)
    return block.boxes if block is not None else ()


def coerce_name(dtype: ElementaryType) -> str:
    """The namespace name of a type's conversion function."""
    return f"_to_{dtype.name}"


class StoreRewriter(ast.NodeTransformer):
    """Turn stores into converted stores, check names, add watchdog ticks, fold PT literals."""

    def __init__(self, typing: Typing):
        self.typing = typing
        self.env: dict[str, Any] = {}
        self.root_name: str | None = None
        self.uses_root_dict = False
        self.coercers: set[ElementaryType] = set()

    # -- functions ---------------------------------------------------------------------------

    def visit_FunctionDef(self, node: ast.FunctionDef) -> ast.FunctionDef:
        outer = (self.env, self.root_name, self.uses_root_dict)
        self.env = {}
        self.root_name = None
        self.uses_root_dict = False
        params = [a.arg for a in node.args.args]
        root = self.typing.root_params.get(node.name)
        if root is None and params and params[0] == "t":
            root = "t"
        if root is not None:
            self.root_name = root
            self.env[root] = self.typing.root
        self.env.update(self._bool_locals(node))  # also refuses a store into the root name
        self.generic_visit(node)
        if self.uses_root_dict:
            guard = ast.Call(ast.Name(ROOT_GUARD, ast.Load()), [ast.Name(self.root_name, ast.Load())], [])
            hoist = ast.copy_location(ast.Assign([ast.Name(ROOT_DICT, ast.Store())], guard), node)
            docstring = (
                1
                if (
                    node.body
                    and isinstance(node.body[0], ast.Expr)
                    and isinstance(getattr(node.body[0], "value", None), ast.Constant)
                    and isinstance(node.body[0].value.value, str)
                )
                else 0
            )
            node.body.insert(docstring, hoist)
        self.env, self.root_name, self.uses_root_dict = outer
        return node

    def _bool_locals(self, func: ast.FunctionDef) -> dict[str, Any]:
        """Local variables that only ever hold Bools (``edge = P(...)``), so storing them needs no check.

        A name bound any other way (a for loop, a tuple, an inner def, a parameter, +=) is not one."""
        values: dict[str, list[ast.expr | None]] = {}
        simple: set[int] = set()
        for node in ast.walk(func):  # breadth first: an Assign comes before its target names
            if isinstance(node, ast.Assign) and all(isinstance(t, ast.Name) for t in node.targets):
                for target in node.targets:
                    values.setdefault(target.id, []).append(node.value)
                    simple.add(id(target))
            elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                if node.id == self.root_name:
                    raise ProgramError(
                        f"{_where(self.typing.filename, node)}: do not assign to {node.id}, it holds the tags"
                    )
                if id(node) not in simple:
                    values.setdefault(node.id, []).append(None)
            elif isinstance(node, ast.FunctionDef) and node is not func:
                values.setdefault(node.name, []).append(None)
            elif isinstance(node, ast.arg):
                values.setdefault(node.arg, []).append(None)
        candidates = {name for name, vals in values.items() if None not in vals}
        while True:
            env = {**self.env, **{name: Bool for name in candidates}}
            keep = {name for name in candidates if all(_safe_type(self.typing, v, env) is Bool for v in values[name])}  # type: ignore[arg-type]
            if keep == candidates:
                return {name: Bool for name in keep}
            candidates = keep

    # -- loops get a watchdog tick ------------------------------------------------------------

    def _tick(self, node: ast.stmt) -> ast.stmt:
        tick = ast.Expr(ast.Call(ast.Name(TICK, ast.Load()), [], []))
        return ast.copy_location(tick, node)

    def visit_For(self, node: ast.For) -> ast.For:
        self.generic_visit(node)
        node.body.insert(0, self._tick(node))
        return node

    def visit_While(self, node: ast.While) -> ast.While:
        self.generic_visit(node)
        node.body.insert(0, self._tick(node))
        return node

    # -- loads are checked ----------------------------------------------------------------------

    def visit_Attribute(self, node: ast.Attribute) -> ast.AST:
        if isinstance(node.ctx, ast.Load):
            self.typing.type_of(node, self.env)  # raises on an unknown tag
        self.generic_visit(node)
        return node

    def visit_Subscript(self, node: ast.Subscript) -> ast.AST:
        self.typing.type_of(node, self.env)
        self.generic_visit(node)
        return node

    def visit_Call(self, node: ast.Call) -> ast.AST:
        self._undeclared_instance(node)
        self._names_for_tags(node)
        self.generic_visit(node)
        for kw in node.keywords:
            if kw.arg == "PT" and isinstance(kw.value, ast.Constant) and isinstance(kw.value.value, str):
                try:
                    kw.value = ast.copy_location(ast.Constant(time_ms(kw.value.value)), kw.value)
                except Exception as exc:  # noqa: BLE001 - any bad literal is reported at its line
                    raise ProgramError(f"{_where(self.typing.filename, kw.value)}: {exc}") from None
        return node

    def _undeclared_instance(self, node: ast.Call) -> None:
        """``t.TRIG(CLK=...)`` or ``t.TON_X.TON(...)`` with no instance declared: say how to declare it."""
        func = node.func
        if not isinstance(func, ast.Attribute) or self.root_name is None:
            return
        if isinstance(func.value, ast.Name) and func.value.id == self.root_name:
            name, box = func.attr, None
        elif (
            isinstance(func.value, ast.Attribute)
            and isinstance(func.value.value, ast.Name)
            and func.value.value.id == self.root_name
        ):
            name, box = func.value.attr, func.attr
        else:
            return
        if name in self.typing.root.members:
            return
        words = {kw.arg for kw in node.keywords}
        fb = _BOX_TYPES.get(box or "") or (
            "R_TRIG"
            if "CLK" in words
            else "IEC_COUNTER"
            if words & {"CU", "CD", "PV"}
            else "IEC_TIMER"
            if words & {"IN", "PT"}
            else None
        )
        if box is None and fb is None:
            return
        fb = fb or "IEC_TIMER"
        call = box or {"IEC_TIMER": "TON", "IEC_COUNTER": "CTU"}.get(fb, fb)
        near = did_you_mean(name, self.typing.root.members)
        raise UnknownTagError(
            f"{_where(self.typing.filename, node)}: no instance {name!r}{near}; "
            f"declare it at module level: `{name} = {fb}()`, then call t.{name}.{call}(...)"
        )

    def _names_for_tags(self, node: ast.Call) -> None:
        """Edge memory bits and MOVE outputs are tags the instruction writes: ``t.SB1`` there means "SB1"."""
        func = node.func
        if not isinstance(func, ast.Name) or self.root_name is None:
            return
        positions = _NAMED_OPERANDS.get(func.id) or (range(1, len(node.args)) if func.id == "MOVE" else ())
        for i in positions:
            if i < len(node.args):
                path = _tag_path(node.args[i], self.root_name)
                if path is not None:
                    self.typing.type_of(node.args[i], self.env)  # an unknown tag is reported here
                    node.args[i] = ast.copy_location(ast.Constant(path), node.args[i])

    # -- operators that can grow without bound, and TIME literals in comparisons ---------------

    def visit_BinOp(self, node: ast.BinOp) -> ast.AST:
        self.generic_visit(node)
        name = SAFE_OPS.get(type(node.op))
        if name is None:
            return node
        if isinstance(node.left, ast.Constant) and isinstance(node.right, ast.Constant):
            try:  # fold here, so that 9**9**9 is refused when the program is loaded
                value = SAFE_FUNCTIONS[name](node.left.value, node.right.value)
            except ProgramError as exc:
                raise SubsetError(f"{_where(self.typing.filename, node)}: {exc}") from None
            except Exception:  # noqa: BLE001 - Python itself reports a bad constant operation at run time
                value = None
            if isinstance(value, int | float | str):
                return ast.copy_location(ast.Constant(value), node)
        call = ast.Call(ast.Name(name, ast.Load()), [node.left, node.right], [])
        return ast.copy_location(call, node)

    def visit_Compare(self, node: ast.Compare) -> ast.AST:
        self.generic_visit(node)
        operands = [node.left, *node.comparators]
        timed = [self._is_time(o) for o in operands]
        if not any(timed):
            return node
        for i, operand in enumerate(operands):
            if isinstance(operand, ast.Constant) and isinstance(operand.value, str):
                near = (i > 0 and timed[i - 1]) or (i + 1 < len(operands) and timed[i + 1])
                if not near:
                    continue
                try:
                    folded = ast.copy_location(ast.Constant(time_ms(operand.value)), operand)
                except Exception as exc:  # noqa: BLE001 - any bad literal is reported at its line
                    raise ProgramError(
                        f"{_where(self.typing.filename, operand)}: {exc}; a TIME is compared with a TIME "
                        f"literal such as '500ms' or TIME('1s500ms')"
                    ) from None
                if i == 0:
                    node.left = folded
                else:
                    node.comparators[i - 1] = folded
        return node

    def _is_time(self, node: ast.expr) -> bool:
        return _safe_type(self.typing, node, self.env) in (Time,)

    # -- stores ------------------------------------------------------------------------------

    def visit_Assign(self, node: ast.Assign) -> ast.AST | list[ast.stmt]:
        node.value = self.visit(node.value)
        if len(node.targets) == 1:
            return self._assign(node.targets[0], node.value, node)
        temp = ast.Name("_chain", ast.Store())
        out: list[ast.stmt] = [ast.copy_location(ast.Assign([temp], node.value), node)]
        for target in node.targets:
            out.extend(_as_list(self._assign(target, ast.Name("_chain", ast.Load()), node)))
        return out

    def visit_AugAssign(self, node: ast.AugAssign) -> ast.AST | list[ast.stmt]:
        node.value = self.visit(node.value)
        if isinstance(node.target, ast.Attribute):
            load = ast.Attribute(_copy_load(node.target.value), node.target.attr, ast.Load())
            value = ast.fix_missing_locations(ast.copy_location(ast.BinOp(load, node.op, node.value), node))
            return self._assign(node.target, self.visit_BinOp(value), node)  # type: ignore[arg-type]
        node.target = self.visit(node.target)
        if type(node.op) in SAFE_OPS:
            load = _copy_load(node.target)
            value = ast.fix_missing_locations(ast.copy_location(ast.BinOp(load, node.op, node.value), node))
            store = ast.Assign([node.target], self.visit_BinOp(value))  # type: ignore[arg-type]
            return ast.fix_missing_locations(ast.copy_location(store, node))
        return node

    def _assign(self, target: ast.expr, value: ast.expr, node: ast.stmt) -> ast.AST | list[ast.stmt]:
        if isinstance(target, (ast.Tuple, ast.List)):
            if not all(isinstance(el, ast.Name) for el in target.elts):
                raise ProgramError(
                    f"{_where(self.typing.filename, node)}: assign tags one at a time (t.A = ...; t.B = ...)"
                )
            return ast.copy_location(ast.Assign([target], value), node)
        if not isinstance(target, ast.Attribute):
            target = self.visit(target)
            return ast.copy_location(ast.Assign([target], value), node)
        base_node = self.visit(target.value)
        base = self.typing.type_of(base_node, self.env)
        key = target.attr
        if isinstance(base, FBType):
            block = block_named(base.name)
            if block is None or key not in block.writable:
                if block is not None and key in block.readable:
                    raise ProgramError(
                        f"{_where(self.typing.filename, node)}: {key} of a {base.name} is computed by its box; "
                        f"it cannot be written" + (" (reset a timer with RT(...))" if base.name == "IEC_TIMER" else "")
                    )
                self.typing.member_type(base, key, node)
            return self._call_stmt(FB_STORE, [base_node, ast.Constant(key), value], node)
        if not isinstance(base, StructType):
            if _tag_path(base_node, self.root_name or "") is not None:  # t.T1.TON.x, t.COUNT.x: no members
                raise ProgramError(
                    f"{_where(self.typing.filename, node)}: {ast.unparse(base_node)} has no members to assign; "
                    f"store into a tag (t.NAME = ...) or a data-block member (t.DB.member = ...)"
                )
            return self._call_stmt(STORE, [base_node, ast.Constant(key), value], node)
        mtype = self.typing.member_type(base, key, node)
        is_root = base is self.typing.root
        if (key if is_root else f"{base.name}.{key}") in self.typing.aliased:
            return self._call_stmt(STORE, [base_node, ast.Constant(key), value], node)
        if not isinstance(mtype, ElementaryType):
            return self._call_stmt(STORE, [base_node, ast.Constant(key), value], node)
        if not (mtype is Bool and self.typing.type_of(value, self.env) is Bool):
            self.coercers.add(mtype)
            where = key if is_root else f"{ast.unparse(base_node)}.{key}"
            value = ast.Call(ast.Name(coerce_name(mtype), ast.Load()), [value, ast.Constant(where)], [])
        if is_root and isinstance(base_node, ast.Name) and base_node.id == self.root_name:
            self.uses_root_dict = True
            dict_node: ast.expr = ast.Name(ROOT_DICT, ast.Load())
        else:
            self.uses_root_dict = True  # the chain starts at the tags: check that they are the CPU's
            dict_node = ast.Attribute(base_node, "__dict__", ast.Load())
        store = ast.Assign([ast.Subscript(dict_node, ast.Constant(key), ast.Store())], value)
        return ast.copy_location(store, node)  # the whole module's locations are fixed once, after rewriting

    def _call_stmt(self, func: str, args: list[ast.expr], node: ast.stmt) -> ast.stmt:
        call = ast.Expr(ast.Call(ast.Name(func, ast.Load()), args, []))
        return ast.copy_location(call, node)


def _tag_path(node: ast.expr, root: str) -> str | None:
    """``t.DATA.SB`` -> ``"DATA.SB"``, ``t.DATA.ARR[2]`` -> ``"DATA.ARR[2]"`` (attributes and constant
    indices from the root), else None."""
    parts: list[str] = []
    while True:
        if isinstance(node, ast.Attribute):
            parts.append("." + node.attr)
        elif isinstance(node, ast.Subscript) and isinstance(node.slice, ast.Constant) and type(node.slice.value) is int:
            parts.append(f"[{node.slice.value}]")
        else:
            break
        node = node.value  # type: ignore[union-attr]
    if isinstance(node, ast.Name) and node.id == root and parts and parts[-1].startswith("."):
        return "".join(reversed(parts))[1:]
    return None


def _as_list(x: ast.AST | list[ast.stmt]) -> list[ast.stmt]:
    return x if isinstance(x, list) else [x]  # type: ignore[list-item]


def _copy_load(node: ast.expr) -> ast.expr:
    copy = ast.parse(ast.unparse(node), mode="eval").body
    return ast.copy_location(copy, node)


# --------------------------------------------------------------------------------------------
# Analysis
# --------------------------------------------------------------------------------------------


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


_EDGE_FUNCS = {"P", "N", "P_TRIG", "N_TRIG", "P_COIL", "N_COIL"}


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
                    base = _safe_type(typing, func.value, env)
                    if isinstance(base, FBType) and func.attr in _boxes(base):
                        path = ast.unparse(func.value)
                        result.box_calls.append((path, func.attr, node.lineno))
                        if id(node) not in bare:
                            result.timer_reads.add(path)
            if isinstance(node, ast.Attribute) and node.attr in ("Q", "ET") and isinstance(node.ctx, ast.Load):
                base = _safe_type(typing, node.value, env)
                if isinstance(base, FBType) and base.name == "IEC_TIMER":
                    result.timer_reads.add(ast.unparse(node.value))
            if isinstance(node, ast.If):
                _collect_coils(node, result, typing, env)
            if isinstance(node, (ast.BoolOp, ast.IfExp)):
                _short_circuit_warnings(node, typing, env, result)
    return result


def _safe_type(typing: Typing, node: ast.expr, env: dict[str, Any]) -> Any:
    try:
        return typing.type_of(node, env)
    except UnknownTagError:
        return None


def _collect_coils(node: ast.If, result: Analysis, typing: Typing, env: dict[str, Any]) -> None:
    for branch in (node.body, node.orelse):
        for stmt in branch:
            if (
                isinstance(stmt, ast.Assign)
                and isinstance(stmt.value, ast.Constant)
                and isinstance(stmt.value.value, bool)
            ):
                for target in stmt.targets:
                    if isinstance(target, ast.Attribute) and _safe_type(typing, target, env) is Bool:
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
            elif isinstance(func, ast.Attribute) and isinstance(_safe_type(typing, func.value, env), FBType):
                name = f"{ast.unparse(func.value)}.{func.attr}"
            if name:
                op = "and/or" if isinstance(node, ast.BoolOp) else "if/else"
                result.warnings.append(
                    f"{typing.filename}, line {sub.lineno}: {name}(...) sits behind {op}: Python skips it when "
                    f"the left side decides, so it does not run every scan as in LAD; call it on its own line "
                    f"first (x = {name}(...)) and combine the result"
                )


# --------------------------------------------------------------------------------------------
# Merging the networks of one OB
# --------------------------------------------------------------------------------------------

MERGED_ROOT = "_t"


def merged_name(task: str) -> str:
    """The namespace name of a task's merged networks."""
    return f"_merged_{task}"


def merge_networks(functions: list[ast.FunctionDef], task: str, root_params: dict[str, str]) -> ast.FunctionDef | None:
    """One function running the networks of a task back to back, for executions nothing pre-empts.

    Each network's locals are renamed apart so the networks cannot see each other's variables. A
    network with ``return`` or a nested ``def`` is not merged (returns None): the CPU then calls the
    networks one by one, as it always does when an interrupt falls inside the execution.
    """
    body: list[ast.stmt] = []
    for index, func in enumerate(functions):
        if any(isinstance(n, (ast.Return, ast.FunctionDef)) for n in ast.walk(func) if n is not func):
            return None
        root = root_params.get(func.name, "t")
        local = {n.id for n in ast.walk(func) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        local |= {a.arg for a in func.args.args}
        renames = {name: f"_n{index}_{name}" for name in local if name != root}
        renames[root] = MERGED_ROOT
        statements = func.body
        if statements and isinstance(statements[0], ast.Expr) and isinstance(statements[0].value, ast.Constant):
            statements = statements[1:]
        for stmt in statements:
            copied = ast.parse(ast.unparse(stmt)).body[0]
            _relocate(copied, stmt)
            for node in ast.walk(copied):
                if isinstance(node, ast.Name) and node.id in renames:
                    node.id = renames[node.id]
            body.append(copied)
    if not body:
        body = [ast.Pass()]
    args = ast.arguments(posonlyargs=[], args=[ast.arg(MERGED_ROOT)], kwonlyargs=[], kw_defaults=[], defaults=[])
    merged = ast.FunctionDef(name=merged_name(task), args=args, body=body, decorator_list=[], returns=None)
    merged.lineno = functions[0].lineno if functions else 1
    merged.col_offset = 0
    merged.end_lineno = max((f.end_lineno or f.lineno) for f in functions) if functions else 1
    merged.end_col_offset = 0
    return ast.fix_missing_locations(merged)


def _relocate(copied: ast.AST, original: ast.AST) -> None:
    """Give a re-parsed copy the line numbers of the original, node by node."""
    for new, old in zip(ast.walk(copied), ast.walk(original)):
        if hasattr(old, "lineno") and hasattr(new, "lineno"):
            ast.copy_location(new, old)


def read_root_directly(merged: ast.FunctionDef, members: Iterable[str]) -> None:
    """Let a merged function (after :class:`StoreRewriter`) read its tags from the tag dict: ``_t.S1``
    becomes ``_t_dict["S1"]``, one dict lookup instead of an attribute read through the tag object.

    Only for merged functions: the CPU alone calls them, always with its tags (their name starts with
    ``_``, so a program cannot), so the hoisted dict needs no guard; every name was checked against the
    tag table while rewriting, so the lookup cannot miss."""
    reads = _RootReads(set(members))
    merged.body = [reads.visit(stmt) for stmt in merged.body]
    if not reads.used:
        return
    tags_dict = ast.Attribute(ast.Name(MERGED_ROOT, ast.Load()), "__dict__", ast.Load())
    hoist = ast.Assign([ast.Name(ROOT_DICT, ast.Store())], tags_dict)
    first = merged.body[0]
    if isinstance(first, ast.Assign) and isinstance(first.targets[0], ast.Name) and first.targets[0].id == ROOT_DICT:
        merged.body[0] = ast.copy_location(hoist, first)  # in place of the guard StoreRewriter hoisted
    else:
        merged.body.insert(0, ast.copy_location(hoist, merged))
    ast.fix_missing_locations(merged)


class _RootReads(ast.NodeTransformer):
    """``_t.NAME`` (a load of a tag) -> ``_t_dict["NAME"]``."""

    def __init__(self, members: set[str]):
        self.members = members
        self.used = False

    def visit_Attribute(self, node: ast.Attribute) -> ast.AST:
        self.generic_visit(node)
        value = node.value
        if (
            isinstance(node.ctx, ast.Load)
            and isinstance(value, ast.Name)
            and value.id == MERGED_ROOT
            and node.attr in self.members
        ):
            self.used = True
            read = ast.Subscript(ast.Name(ROOT_DICT, ast.Load()), ast.Constant(node.attr), ast.Load())
            return ast.copy_location(read, node)
        return node
