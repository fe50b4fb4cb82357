"""From a student's Python file to code the CPU runs: the PLC subset, typed stores, the watchdog.

Three jobs, each a pass over the syntax tree:

1. :func:`check_subset` accepts only the PLC subset of Python: no imports, classes, exceptions,
   ``global``, comprehensions or names starting with ``_``; only a few builtins (``abs``, ``min``,
   ``max``, ``range`` ...). A violation is a :class:`SubsetError` naming the line and the fix.
2. :class:`StoreRewriter` turns every store into a tag into a converted store (an INT wraps, a
   BOOL refuses a number), checks tag names against the tag table at load time (a typo is reported
   with the nearest names before the program runs), and puts a watchdog tick into every loop.
3. :func:`analyse` collects what graders and the timer rule need: which tags each function uses,
   SET/RESET coils, timers whose Q and ET are never read, edge calls hidden behind ``and``/``or``.
"""

from __future__ import annotations

import ast
import builtins
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from plcsim.errors import ProgramError, SubsetError, UnknownTagError, did_you_mean
from plcsim.instructions import BOOL_RESULTS, FB_BOXES, FB_MEMBERS, FB_WRITABLE
from plcsim.literals import time_ms
from plcsim.memory import parse_address
from plcsim.tags import FBType
from plcsim.types import ArrayType, Bool, ElementaryType, StructType, Time

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

_FORBIDDEN_NODES: dict[type, str] = {
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
}
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
_FORBIDDEN_ATTRS = {"format", "format_map", "mro", "gi_frame", "f_globals", "f_locals", "tb_frame"}


def _where(filename: str, node: ast.AST) -> str:
    return f"{filename}, line {getattr(node, 'lineno', '?')}"


def parse(source: str, filename: str) -> ast.Module:
    """Parse the program; a syntax error becomes a ProgramError with its line and a pointer."""
    try:
        return ast.parse(source, filename=filename)
    except SyntaxError as exc:
        line = (exc.text or "").rstrip("\n")
        pointer = " " * max(0, (exc.offset or 1) - 1) + "^"
        raise ProgramError(
            f"{filename}, line {exc.lineno}: syntax error: {exc.msg}\n    {line}\n    {pointer}"
        ) from None


def check_subset(tree: ast.Module, filename: str, known_names: Iterable[str]) -> None:
    """Reject anything outside the PLC subset of Python, naming the line and the fix."""
    known = set(known_names) | ALLOWED_BUILTINS
    module_names = _module_level_names(tree)
    functions: list[ast.FunctionDef] = []
    for node in ast.walk(tree):
        reason = _FORBIDDEN_NODES.get(type(node))
        if reason:
            raise SubsetError(f"{_where(filename, node)}: {reason}")
        if isinstance(node, ast.Name) and node.id.startswith("_"):
            raise SubsetError(f"{_where(filename, node)}: names starting with _ are reserved ({node.id})")
        if isinstance(node, ast.Attribute) and (node.attr.startswith("_") or node.attr in _FORBIDDEN_ATTRS):
            raise SubsetError(f"{_where(filename, node)}: the attribute .{node.attr} is not available in PLC programs")
        if isinstance(node, ast.arg) and node.arg.startswith("_"):
            raise SubsetError(f"{_where(filename, node)}: names starting with _ are reserved ({node.arg})")
        if isinstance(node, ast.FunctionDef):
            if node.name.startswith("_"):
                raise SubsetError(f"{_where(filename, node)}: names starting with _ are reserved ({node.name})")
            if node.args.vararg or node.args.kwarg:
                raise SubsetError(f"{_where(filename, node)}: *args and **kwargs are not part of PLC programs")
            functions.append(node)
    for func in functions:  # names last, so that `try ... except Exception` is reported as the try it is
        _check_names(func, filename, known | module_names)
    for stmt in tree.body:
        if isinstance(stmt, ast.FunctionDef):
            continue
        for node in ast.walk(stmt):
            if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in known | module_names:
                raise _unknown_name(node, filename, known | module_names)


def _module_level_names(tree: ast.Module) -> set[str]:
    names: set[str] = set()
    for stmt in tree.body:
        if isinstance(stmt, ast.FunctionDef):
            names.add(stmt.name)
        elif isinstance(stmt, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
            targets = stmt.targets if isinstance(stmt, ast.Assign) else [stmt.target]
            for target in targets:
                for node in ast.walk(target):
                    if isinstance(node, ast.Name):
                        names.add(node.id)
        elif isinstance(stmt, (ast.For, ast.If, ast.While)):
            for node in ast.walk(stmt):
                if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
                    names.add(node.id)
    return names


def _check_names(func: ast.FunctionDef, filename: str, visible: set[str]) -> None:
    local = {a.arg for a in func.args.args + func.args.kwonlyargs + func.args.posonlyargs}
    for node in ast.walk(func):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            local.add(node.id)
        elif isinstance(node, ast.FunctionDef) and node is not func:
            local.add(node.name)
            local |= {a.arg for a in node.args.args}
    for node in ast.walk(func):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in local | visible:
            raise _unknown_name(node, filename, local | visible)


def _builtins_list() -> str:
    return ", ".join(sorted(ALLOWED_BUILTINS - {"True", "False", "None"}))


def _unknown_name(node: ast.Name, filename: str, visible: set[str]) -> ProgramError:
    if node.id in _DANGEROUS or hasattr(builtins, node.id):
        return SubsetError(
            f"{_where(filename, node)}: {node.id} is not available in PLC programs "
            f"(no file, network or interpreter access; allowed builtins: {_builtins_list()})"
        )
    return ProgramError(f"{_where(filename, node)}: unknown name {node.id!r}{did_you_mean(node.id, visible)}")


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
                if isinstance(base, FBType) and func.attr in FB_BOXES.get(base.name, ()):
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
            members = FB_MEMBERS.get(base.name, {})
            if attr in FB_BOXES.get(base.name, ()):
                return None
            if attr not in members:
                boxes = sorted(FB_BOXES.get(base.name, ()))
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
TICK = "_tick"
STORE = "_store"
FB_STORE = "_fb_store"


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
            for sub in ast.walk(node):
                if isinstance(sub, ast.Name) and sub.id == root and isinstance(sub.ctx, ast.Store):
                    raise ProgramError(
                        f"{_where(self.typing.filename, sub)}: do not assign to {root}, it holds the tags"
                    )
        self.env.update(self._bool_locals(node))
        self.generic_visit(node)
        if self.uses_root_dict:
            hoist = ast.parse(f"{ROOT_DICT} = {self.root_name}.__dict__").body[0]
            ast.copy_location(hoist, node)
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
        """Local variables that only ever hold Bools (``edge = P(...)``), so storing them needs no check."""
        values: dict[str, list[ast.expr | None]] = {}
        for node in ast.walk(func):
            if isinstance(node, ast.Assign):
                for target in node.targets:
                    if isinstance(target, ast.Name):
                        values.setdefault(target.id, []).append(node.value)
                    else:
                        for sub in ast.walk(target):
                            if isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Store):
                                values.setdefault(sub.id, []).append(None)
            elif isinstance(node, (ast.AugAssign, ast.AnnAssign, ast.For)):
                for sub in ast.walk(node.target):
                    if isinstance(sub, ast.Name):
                        values.setdefault(sub.id, []).append(None)
        params = {a.arg for a in func.args.args}
        candidates = {name for name, vals in values.items() if name not in params and None not in vals}
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
        self.generic_visit(node)
        for kw in node.keywords:
            if kw.arg == "PT" and isinstance(kw.value, ast.Constant) and isinstance(kw.value.value, str):
                try:
                    kw.value = ast.copy_location(ast.Constant(time_ms(kw.value.value)), kw.value)
                except Exception as exc:  # noqa: BLE001 - any bad literal is reported at its line
                    raise ProgramError(f"{_where(self.typing.filename, kw.value)}: {exc}") from None
        return node

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
            value = ast.copy_location(ast.BinOp(load, node.op, node.value), node)
            ast.fix_missing_locations(value)
            return self._assign(node.target, value, node)
        node.target = self.visit(node.target)
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
            if key not in FB_WRITABLE.get(base.name, set()):
                members = FB_MEMBERS.get(base.name, {})
                if key in members:
                    raise ProgramError(
                        f"{_where(self.typing.filename, node)}: {key} of a {base.name} is computed by its box; "
                        f"it cannot be written" + (" (reset a timer with RT(...))" if base.name == "IEC_TIMER" else "")
                    )
                self.typing.member_type(base, key, node)
            return self._call_stmt(FB_STORE, [base_node, ast.Constant(key), value], node)
        if not isinstance(base, StructType):
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
            dict_node = ast.Attribute(base_node, "__dict__", ast.Load())
        store = ast.Assign([ast.Subscript(dict_node, ast.Constant(key), ast.Store())], value)
        return ast.fix_missing_locations(ast.copy_location(store, node))

    def _call_stmt(self, func: str, args: list[ast.expr], node: ast.stmt) -> ast.stmt:
        call = ast.Expr(ast.Call(ast.Name(func, ast.Load()), args, []))
        return ast.fix_missing_locations(ast.copy_location(call, node))


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
        called = {inst for inst, box, _ in self.box_calls if box in FB_BOXES["IEC_TIMER"]}
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
        used_values = _used_call_values(stmt)
        for node in ast.walk(stmt):
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
                    if isinstance(base, FBType) and func.attr in FB_BOXES.get(base.name, ()):
                        path = ast.unparse(func.value)
                        result.box_calls.append((path, func.attr, node.lineno))
                        if id(node) in used_values:
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


def _used_call_values(func: ast.FunctionDef) -> set[int]:
    """ids of Call nodes whose value is used (not a bare expression statement)."""
    bare = {id(s.value) for s in ast.walk(func) if isinstance(s, ast.Expr)}
    return {id(n) for n in ast.walk(func) if isinstance(n, ast.Call) and id(n) not in bare}


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
