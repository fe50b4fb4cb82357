"""The module level of a program, evaluated without running it: declarations, task bindings, labels.

A program's module level only declares: ``NAME = Constructor(literal, ...)``, ``OB1 = [networks]``,
``OB30 = CyclicInterrupt(...)``, ``def`` networks with an optional ``@label("x")``, docstrings and
named constants (``LIMIT = 10``). This evaluator reads exactly those forms from the syntax tree and
calls the constructors itself, so no code of the program runs while it is declared and nothing the
program names can be reached by attribute or changed.

>>> import ast
>>> tree = ast.parse("LIMIT = 10\\nOB1 = [net]\\ndef net(t):\\n    pass\\n")
>>> values = evaluate_module(tree, "lab.py", {})
>>> values.constants, values.bindings["OB1"]
({'LIMIT': 10}, ['net'])
"""

from __future__ import annotations

import ast
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from plcsim.controllers.s7.instructions import box_hint
from plcsim.core.errors import PlcError, ProgramError, SubsetError

ALLOWED_FORMS = (
    "a module level only declares: NAME = Int(0) / Tag('%M10.0') / IEC_TIMER() / DB(...) ..., "
    "OB1 = [network, ...], OB30 = CyclicInterrupt(...), a constant (LIMIT = 10), "
    "def network(t): ... (optionally with @label('x')) and docstrings"
)
MAX_CONSTANT_CHARS = 10_000
"""The longest string literal a declaration accepts (a comment or a start value, never a data set)."""


@dataclass
class ModuleValues:
    """What the module level declares, in source order."""

    declared: dict[str, Any] = field(default_factory=dict)
    """Name -> the value its constructor returned (a Tag, a Member, a DataBlock, a type ...)."""
    bindings: dict[str, Any] = field(default_factory=dict)
    """OB name -> a network name, a list of them, or a CyclicInterrupt of names."""
    constants: dict[str, Any] = field(default_factory=dict)
    labels: dict[str, str] = field(default_factory=dict)
    lines: dict[str, int] = field(default_factory=dict)
    order: list[str] = field(default_factory=list)


class NetworkRef(str):
    """The name of a network function, as a declaration argument (``CyclicInterrupt(blink)``)."""

    __slots__ = ()


def evaluate_module(tree: ast.Module, filename: str, constructors: Mapping[str, Callable[..., Any]]) -> ModuleValues:
    """Evaluate the module level of ``tree``; anything but a declaration is a SubsetError with its line."""
    functions = {s.name for s in tree.body if isinstance(s, ast.FunctionDef)}
    evaluator = _Evaluator(filename, constructors, functions)
    values = ModuleValues()
    for stmt in tree.body:
        if isinstance(stmt, ast.FunctionDef):
            label = evaluator.label_of(stmt)
            if label is not None:
                values.labels[stmt.name] = label
            continue
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Constant) and isinstance(stmt.value.value, str):
            continue  # a docstring or a comment block
        if isinstance(stmt, ast.Expr) and isinstance(stmt.value, ast.Call):
            raise SubsetError(
                f"{filename}, line {stmt.lineno}: {ast.unparse(stmt.value.func)}(...) is called at module level; "
                f"instructions run only inside a network (def network(t): ...); {ALLOWED_FORMS}"
            )
        if not (isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name)):
            raise SubsetError(f"{filename}, line {stmt.lineno}: {_describe(stmt)} at module level; {ALLOWED_FORMS}")
        name = stmt.targets[0].id
        if name in values.lines:
            raise SubsetError(
                f"{filename}, line {stmt.lineno}: {name} is already declared on line {values.lines[name]}; "
                f"declare each name once"
            )
        if name in functions and not _is_ob(name):  # OB1 = [OB1, count] lists the network OB1: fine
            raise SubsetError(f"{filename}, line {stmt.lineno}: {name} is already the name of a network; rename one")
        value = evaluator.value(stmt.value, top=True)
        values.lines[name] = stmt.lineno
        values.order.append(name)
        if _is_ob(name):
            values.bindings[name] = value
        elif isinstance(value, int | float | str) and not isinstance(value, NetworkRef):
            values.constants[name] = value  # LIMIT = 10, NEG = -3, DELAY = TIME("5s")
        else:
            values.declared[name] = value
        evaluator.known[name] = value
    return values


def _is_ob(name: str) -> bool:
    return name.startswith("OB") and name[2:].isdigit()


def _describe(stmt: ast.stmt) -> str:
    words = {
        ast.For: "a for loop",
        ast.While: "a while loop",
        ast.If: "an if statement",
        ast.Expr: "an expression or call",
        ast.AugAssign: "an augmented assignment (+= ...)",
        ast.AnnAssign: "an annotated assignment",
        ast.Assign: "this assignment",
    }
    return words.get(type(stmt), f"a {type(stmt).__name__} statement")


class _Evaluator:
    def __init__(self, filename: str, constructors: Mapping[str, Callable[..., Any]], functions: set[str]):
        self.filename = filename
        self.constructors = constructors
        self.functions = functions
        self.known: dict[str, Any] = {}

    def refuse(self, node: ast.AST, what: str) -> SubsetError:
        return SubsetError(f"{self.filename}, line {getattr(node, 'lineno', '?')}: {what}; {ALLOWED_FORMS}")

    def label_of(self, func: ast.FunctionDef) -> str | None:
        label = None
        for deco in func.decorator_list:
            if not (
                isinstance(deco, ast.Call)
                and isinstance(deco.func, ast.Name)
                and deco.func.id == "label"
                and len(deco.args) == 1
                and not deco.keywords
                and isinstance(deco.args[0], ast.Constant)
            ):
                raise self.refuse(deco, f"the decorator @{ast.unparse(deco)} is not allowed (only @label('name'))")
            if label is not None:
                raise SubsetError(
                    f"{self.filename}, line {deco.lineno}: network {func.name} has two labels; one label per network"
                )
            label = deco.args[0].value
            if not isinstance(label, str) or not label:
                raise SubsetError(
                    f"{self.filename}, line {deco.lineno}: a label must be a non-empty string, not {label!r}"
                )
        return label

    def value(self, node: ast.expr, top: bool = False) -> Any:
        if isinstance(node, ast.Constant):
            if isinstance(node.value, str | bytes) and len(node.value) > MAX_CONSTANT_CHARS:
                raise SubsetError(
                    f"{self.filename}, line {node.lineno}: a text of {len(node.value)} characters is too long "
                    f"for a declaration (at most {MAX_CONSTANT_CHARS})"
                )
            if isinstance(node.value, bytes) or node.value is Ellipsis:
                raise self.refuse(node, f"{ast.unparse(node)} is not a PLC value")
            return node.value
        if (
            isinstance(node, ast.UnaryOp)
            and isinstance(node.op, ast.USub | ast.UAdd)
            and isinstance(node.operand, ast.Constant)
            and isinstance(node.operand.value, int | float)
            and not isinstance(node.operand.value, bool)
        ):
            return -node.operand.value if isinstance(node.op, ast.USub) else node.operand.value
        if isinstance(node, ast.Name):
            return self.name(node)
        if isinstance(node, ast.List | ast.Tuple):
            return [self.value(el) for el in node.elts]
        if isinstance(node, ast.Call):
            return self.call(node)
        raise self.refuse(node, f"{ast.unparse(node)} cannot be evaluated in a declaration")

    def name(self, node: ast.Name) -> Any:
        if node.id in self.functions:
            return NetworkRef(node.id)
        if node.id in self.constructors:
            return self.constructors[node.id]
        if node.id in self.known:
            return self.known[node.id]
        if node.id in ("True", "False", "None"):
            return {"True": True, "False": False, "None": None}[node.id]
        raise ProgramError(
            f"{self.filename}, line {node.lineno}: unknown name {node.id!r} in a declaration{box_hint(node.id)} "
            f"(a network must be defined with def, a type declared before it is used)"
        )

    def call(self, node: ast.Call) -> Any:
        func = node.func
        if not isinstance(func, ast.Name) or func.id not in self.constructors or func.id == "label":
            raise self.refuse(node, f"{ast.unparse(func)}(...) is not a declaration")
        args = [self.value(a) for a in node.args]
        kwargs = {}
        for kw in node.keywords:
            if kw.arg is None:
                raise self.refuse(kw.value, "** unpacking is not part of PLC programs")
            kwargs[kw.arg] = self.value(kw.value)
        try:
            return self.constructors[func.id](*args, **kwargs)
        except PlcError as exc:
            raise type(exc)(f"{self.filename}, line {node.lineno}: {exc}") from None
        except (TypeError, ValueError, OverflowError) as exc:
            raise ProgramError(f"{self.filename}, line {node.lineno}: {func.id}(...): {exc}") from None
