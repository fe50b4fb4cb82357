"""The PLC subset of Python: which syntax, names and constants a student's program may use.

The first pass over a program's syntax tree, before anything is typed or rewritten. :func:`check_subset`
accepts only a whitelist of syntax (:data:`ALLOWED_NODES`; imports, classes, exceptions, ``global``,
comprehensions ... are refused with a reason a student understands, anything newer by default), no
names starting with ``_``, no rebinding of an instruction's name, stores only into tags and local
variables, bounded nesting and bounded constants; only a few builtins (``abs``, ``min``, ``max``,
``range`` ...). A violation is a :class:`SubsetError` naming the line and the fix, in the format
of :func:`place` that every later pass uses too.
"""

from __future__ import annotations

import ast
import builtins
import io
import operator
import tokenize
from collections.abc import Iterable, Iterator
from typing import Any

from plcsim.controllers.s7.instructions import box_hint
from plcsim.core.errors import ProgramError, SubsetError, did_you_mean
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS, SAFE_OPS

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


def place(filename: str, node: ast.AST) -> str:
    """``file, line N``: where a node is, as every error of the Python front end starts."""
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
    """The line an error of this module names: each starts ``file, line N:`` (see :func:`place`)."""
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
            return SubsetError(f"{place(filename, node)}: names starting with _ are reserved ({node.id})")
        if kind is ast.Attribute and (node.attr.startswith("_") or node.attr in _FORBIDDEN_ATTRS):
            return SubsetError(f"{place(filename, node)}: the attribute .{node.attr} is not available in PLC programs")
        if kind is ast.arg:
            _check_binding(node.arg, node, filename, reserved)
        if kind is ast.FunctionDef:
            _check_binding(node.name, node, filename, reserved)
            if node.args.vararg or node.args.kwarg:
                return SubsetError(f"{place(filename, node)}: *args and **kwargs are not part of PLC programs")
        if kind is ast.Name and isinstance(node.ctx, ast.Store) and id(node) not in declared:
            _check_binding(node.id, node, filename, reserved)
        if kind is ast.BinOp or kind is ast.UnaryOp:
            try:
                _fold(node, memo, 0)
            except ProgramError as exc:
                return SubsetError(f"{filename}, line {line}: {exc}")
        if kind is ast.For and not all(isinstance(n, ast.Name | ast.Tuple | ast.Store) for n in ast.walk(node.target)):
            return SubsetError(
                f"{place(filename, node)}: a for loop counts with a plain variable (for i in range(...)); "
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
        raise SubsetError(f"{place(filename, node)}: names starting with _ are reserved ({name})")
    if name in reserved:
        raise SubsetError(
            f"{place(filename, node)}: {name} is the name of an instruction, a type or a builtin; "
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
                    f"{place(filename, node.decorator_list[0])}: decorators are not allowed on inner functions"
                )
    for node in inside:
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load):
            if node.id not in local and node.id not in visible:
                raise _unknown_name(node, filename, local | visible)
            if node.id in declaration_only and node.id not in local:
                if node.id in own_tags:
                    raise SubsetError(
                        f"{place(filename, node)}: {node.id} is a tag of the program; in a network it is t.{node.id}"
                    )
                raise SubsetError(
                    f"{place(filename, node)}: {node.id} declares a tag or an instance; declare it at module "
                    f"level (NAME = {node.id}(...)) and use it in a network as t.NAME"
                )
        elif isinstance(node, (ast.Attribute, ast.Subscript)) and isinstance(node.ctx, ast.Store):
            root = node.value
            while isinstance(root, (ast.Attribute, ast.Subscript)):
                root = root.value
            if not (isinstance(root, ast.Name) and root.id in local):
                raise SubsetError(
                    f"{place(filename, node)}: {ast.unparse(node)} cannot be assigned; a program stores only "
                    f"into its tags (t.NAME = ..., t.DB.member = ...) and its own variables"
                )


def _builtins_list() -> str:
    return ", ".join(sorted(ALLOWED_BUILTINS - {"True", "False", "None"}))


def _unknown_name(node: ast.Name, filename: str, visible: set[str]) -> ProgramError:
    if node.id in _DANGEROUS or hasattr(builtins, node.id):
        return SubsetError(
            f"{place(filename, node)}: {node.id} is not available in PLC programs "
            f"(no file, network or interpreter access; allowed builtins: {_builtins_list()})"
        )
    return ProgramError(
        f"{place(filename, node)}: unknown name {node.id!r}{box_hint(node.id) or did_you_mean(node.id, visible)}"
        " (every name a program can use: plcsim reference, docs/instructions.md)"
    )
