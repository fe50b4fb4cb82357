"""The rewrite of a checked program into the code the CPU runs: typed stores and a watchdog.

:class:`StoreRewriter` turns every store into a tag into a converted store (an INT wraps, a BOOL
refuses a number; a constant is converted once, at load; a REAL rounds a float through :data:`REAL_CELL`),
checks tag names against the tag table at load time (a typo is reported with the nearest names before the
program runs), puts a watchdog tick into every loop, and turns ``**``, ``*``, ``<<`` and ``%`` into the
bounded operators of :mod:`plcsim.frontends.python.safe_math` (a ``*`` with a float constant stays a ``*``).
The code it writes calls the runtime's hooks by the names below (:data:`TICK`, :data:`ROOT_GUARD`,
:data:`STORE`, :data:`FB_STORE`); :mod:`plcsim.frontends.python.link` binds them when it links.
"""

from __future__ import annotations

import ast
from typing import Any

from plcsim.controllers.s7.instructions import BLOCKS, FUNCTIONS, block_named
from plcsim.core.errors import PlcTypeError, ProgramError, SubsetError, UnknownTagError, did_you_mean
from plcsim.core.literals import time_ms
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS, SAFE_OPS
from plcsim.frontends.python.subset import place
from plcsim.frontends.python.typecheck import Typing, safe_type
from plcsim.tags.table import FBType
from plcsim.tags.types import FLOAT32_MAX, Bool, ElementaryType, Real, StructType, Time

ROOT_DICT = "_t_dict"
ROOT_GUARD = "_tags_of"
"""Returns the tag object's member dict, after checking that it was given the CPU's tags."""
TICK = "_tick"
STORE = "_store"
FB_STORE = "_fb_store"
REAL_CELL = "_f32"
"""A one-item ``array('f')`` of the program's namespace: a finite float stored into it and read back is rounded to
single precision by the C cast, IEEE round-to-nearest-even, exactly as :data:`~plcsim.tags.types.Real`'s conversion
rounds it (the same cast inside :mod:`struct`), in two subscripts instead of a call."""
REAL_STORE = f"""
_real = VALUE
if _real.__class__ is float and -{FLOAT32_MAX!r} <= _real <= {FLOAT32_MAX!r}:
    {REAL_CELL}[0] = _real
    _real = {REAL_CELL}[0]
else:
    _real = CONVERT(_real, WHERE)
TARGET = _real
"""
"""A store into a REAL whose value is no constant: a float within the REAL's range is rounded through
:data:`REAL_CELL`; anything else (an int, a NaN, an infinity, a float beyond the range, a value that is no
number) takes the conversion every other store takes, with its messages."""
_NAMED_OPERANDS = {f.name: f.named for f in FUNCTIONS.values() if f.named}
"""Arguments of edge instructions that name a memory bit; ``t.SB1`` there means the tag's name."""
_BOX_TYPES = {box: block.name for block in BLOCKS.values() for box in block.boxes}
"""The instance type each box belongs to (``TON`` -> ``IEC_TIMER``), from the instructions' descriptions."""


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
                        f"{place(self.typing.filename, node)}: do not assign to {node.id}, it holds the tags"
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
            keep = {name for name in candidates if all(safe_type(self.typing, v, env) is Bool for v in values[name])}  # type: ignore[arg-type]
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
                    raise ProgramError(f"{place(self.typing.filename, kw.value)}: {exc}") from None
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
            f"{place(self.typing.filename, node)}: no instance {name!r}{near}; "
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
                raise SubsetError(f"{place(self.typing.filename, node)}: {exc}") from None
            except Exception:  # noqa: BLE001 - Python itself reports a bad constant operation at run time
                value = None
            if isinstance(value, int | float | str):
                return ast.copy_location(ast.Constant(value), node)
        if name == "_mul" and any(
            isinstance(o, ast.Constant) and o.value.__class__ is float for o in (node.left, node.right)
        ):
            return node  # a float operand: _mul multiplies at once (a float cannot repeat a text or grow an int)
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
                        f"{place(self.typing.filename, operand)}: {exc}; a TIME is compared with a TIME "
                        f"literal such as '500ms' or TIME('1s500ms')"
                    ) from None
                if i == 0:
                    node.left = folded
                else:
                    node.comparators[i - 1] = folded
        return node

    def _is_time(self, node: ast.expr) -> bool:
        return safe_type(self.typing, node, self.env) in (Time,)

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
                    f"{place(self.typing.filename, node)}: assign tags one at a time (t.A = ...; t.B = ...)"
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
                        f"{place(self.typing.filename, node)}: {key} of a {base.name} is computed by its box; "
                        f"it cannot be written" + (" (reset a timer with RT(...))" if base.name == "IEC_TIMER" else "")
                    )
                self.typing.member_type(base, key, node)
            return self._call_stmt(FB_STORE, [base_node, ast.Constant(key), value], node)
        if not isinstance(base, StructType):
            if _tag_path(base_node, self.root_name or "") is not None:  # t.T1.TON.x, t.COUNT.x: no members
                raise ProgramError(
                    f"{place(self.typing.filename, node)}: {ast.unparse(base_node)} has no members to assign; "
                    f"store into a tag (t.NAME = ...) or a data-block member (t.DB.member = ...)"
                )
            return self._call_stmt(STORE, [base_node, ast.Constant(key), value], node)
        mtype = self.typing.member_type(base, key, node)
        is_root = base is self.typing.root
        if (key if is_root else f"{base.name}.{key}") in self.typing.aliased:
            return self._call_stmt(STORE, [base_node, ast.Constant(key), value], node)
        if not isinstance(mtype, ElementaryType):
            return self._call_stmt(STORE, [base_node, ast.Constant(key), value], node)
        convert = None
        if not (mtype is Bool and self.typing.type_of(value, self.env) is Bool):
            self.coercers.add(mtype)
            path = _tag_path(base_node, self.root_name or "")
            where = key if is_root else f"{path or ast.unparse(base_node)}.{key}"
            constant = self._check_constant(mtype, value, where, node)
            if constant:  # converted once, here: the store writes the value the conversion gives it each time
                value = ast.Constant(constant[0])
            elif mtype is Real:
                convert = ast.Name(coerce_name(mtype), ast.Load()), ast.Constant(where)
            else:
                value = ast.Call(ast.Name(coerce_name(mtype), ast.Load()), [value, ast.Constant(where)], [])
        if is_root and isinstance(base_node, ast.Name) and base_node.id == self.root_name:
            self.uses_root_dict = True
            dict_node: ast.expr = ast.Name(ROOT_DICT, ast.Load())
        else:
            self.uses_root_dict = True  # the chain starts at the tags: check that they are the CPU's
            dict_node = ast.Attribute(base_node, "__dict__", ast.Load())
        target = ast.Subscript(dict_node, ast.Constant(key), ast.Store())
        if convert is not None:
            parts = {"VALUE": value, "CONVERT": convert[0], "WHERE": convert[1], "TARGET": target}
            return _Parts(parts).statements(REAL_STORE, node)
        return ast.copy_location(ast.Assign([target], value), node)  # the module's locations are fixed once, after

    def _check_constant(self, mtype: ElementaryType, value: ast.expr, where: str, node: ast.stmt) -> tuple[Any, ...]:
        """The constant ``value`` converted, in a tuple (empty for a value that is no constant). A constant that
        the store would refuse at run time (``t.DB.FLAG = 1`` into a Bool) is refused now, at load, naming the
        file and line: the CPU would otherwise go to STOP on the first scan that stores it."""
        try:
            constant = ast.literal_eval(value)
        except (ValueError, TypeError, SyntaxError, MemoryError, RecursionError):
            return ()  # not a constant: the store converts (or refuses) it when it runs
        try:
            return (mtype.coerce(constant, where),)
        except PlcTypeError as exc:
            raise ProgramError(f"{place(self.typing.filename, node)}: {exc}") from None

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


class _Parts(ast.NodeTransformer):
    """A template's statements with its upper-case names replaced by the nodes given for them."""

    def __init__(self, parts: dict[str, ast.expr]):
        self.parts = parts

    def statements(self, template: str, where: ast.stmt) -> list[ast.stmt]:
        """The statements, the template's own nodes at the line of ``where`` (the parts keep theirs)."""
        body = ast.parse(template.strip()).body
        for stmt in body:
            for node in ast.walk(stmt):
                if hasattr(node, "lineno"):
                    ast.copy_location(node, where)
        return [self.visit(stmt) for stmt in body]

    def visit_Name(self, node: ast.Name) -> ast.AST:
        return self.parts.get(node.id, node)


def _as_list(x: ast.AST | list[ast.stmt]) -> list[ast.stmt]:
    return x if isinstance(x, list) else [x]  # type: ignore[list-item]


def _copy_load(node: ast.expr) -> ast.expr:
    copy = ast.parse(ast.unparse(node), mode="eval").body
    return ast.copy_location(copy, node)
