"""Tags as locals: a task's merged function reads its tags into local variables and stores them back.

After :func:`~plcsim.frontends.python.merge.read_root_directly` and
:func:`~plcsim.frontends.python.inline.inline_boxes` a merged function reaches every tag through the tag
dict, ``_t_dict["Q0"]``: three operations a read or a store, where a local costs one (the hand-inlined
Python of the benchmarks does the same). :func:`localize_tags` cuts the function's top-level statements
into runs that nothing outside the function can look into, and gives each run its tags as locals::

    _tag_I0, _tag_Q0 = _get_OB1_0(_t_dict)       # one C call reads them all
    try:
        _tag_Q0 = _tag_I0 or _tag_Q0              # the run, on locals
    finally:
        _t_dict.update({"Q0": _tag_Q0})           # stored back, also when the run raises

Only this code reads or writes the tag dict while a run executes, so the dict ends each run as the stores
into it would have left it: written back on the error path too (a fault, the watchdog, a JMP), the CPU
finds the tags as the statements before the fault stored them. A statement that lets other code see or
change the tags (a call of the program's own functions, of an instruction bound to the CPU such as
``MOVE`` or ``P``, of a store hook for a DB member or an aliased tag; any use of the tag object or of the
dict other than a constant key; a comprehension, which has a scope of its own) is left as it was, between
two runs: the run before stores back before it, the run after reads again after it. Typed stores keep
their conversions; only the place they store into changes.
"""

from __future__ import annotations

import ast
from collections.abc import Collection
from operator import itemgetter
from typing import Any

from plcsim.controllers.s7.instructions import PURE_INSTRUCTIONS
from plcsim.frontends.python.inline import CHECK_EDGE, COERCE_BOOL
from plcsim.frontends.python.merge import MERGED_ROOT
from plcsim.frontends.python.rewrite import ROOT_DICT, TICK
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS
from plcsim.frontends.python.subset import ALLOWED_BUILTINS
from plcsim.tags.table import FBType
from plcsim.tags.types import StructType

ITEMGETTER = "_itemgetter"
HELPERS: dict[str, Any] = {ITEMGETTER: itemgetter}
"""The names the generated module code calls, for the namespace."""
_PURE_CALLS = (
    frozenset(SAFE_FUNCTIONS) | frozenset(PURE_INSTRUCTIONS) | ALLOWED_BUILTINS | {TICK, COERCE_BOOL, CHECK_EDGE}
)
"""Functions that see only their arguments: no tag can change in them but through an argument's object."""
_SCOPES = (ast.Lambda, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)
_STORES_AT_ONCE = 15
"""Tags a store back puts into one dict display: CPython builds a display of up to 15 constant keys in one
operation, a larger one key by key."""
_TEMPLATE_INSTANCE = "_i_"
"""The prefix of the locals :mod:`~plcsim.frontends.python.inline` holds a box's instance in."""


def localize_tags(func: ast.FunctionDef, root: StructType, shadowed: Collection[str]) -> list[ast.stmt]:
    """Give the runs of ``func`` (a merged function after :func:`inline_boxes`) their tags as locals, in
    place; returns the module-level statements the new code needs (one ``itemgetter`` a run), to be run
    before it.

    ``root`` is the tag schema, ``shadowed`` the names the program defines itself (its own ``abs`` is no
    builtin). A run with too few tag accesses to gain is left as it is."""
    if not func.body or not _binds_root_dict(func.body[0]):
        return []
    body: list[ast.stmt] = [func.body[0]]
    module: list[ast.stmt] = []
    run: list[ast.stmt] = []
    for stmt in [*func.body[1:], None]:
        if stmt is not None and _closed(stmt, root, shadowed):
            run.append(stmt)
            continue
        if run:
            body.extend(_localized(run, root, f"{func.name}_tags{len(module)}", module))
            run = []
        if stmt is not None:
            body.append(stmt)
    func.body = body
    ast.fix_missing_locations(func)
    return module


def _binds_root_dict(stmt: ast.stmt) -> bool:
    return (
        isinstance(stmt, ast.Assign)
        and len(stmt.targets) == 1
        and isinstance(stmt.targets[0], ast.Name)
        and stmt.targets[0].id == ROOT_DICT
    )


def _tag_key(node: ast.AST, root: StructType) -> str | None:
    """NAME of ``_t_dict["NAME"]`` when NAME is a tag of the root, else None."""
    if (
        isinstance(node, ast.Subscript)
        and isinstance(node.value, ast.Name)
        and node.value.id == ROOT_DICT
        and isinstance(node.slice, ast.Constant)
        and isinstance(node.slice.value, str)
        and node.slice.value in root.members
    ):
        return node.slice.value
    return None


def _closed(stmt: ast.stmt, root: StructType, shadowed: Collection[str]) -> bool:
    """Whether nothing but ``stmt``'s own code can read or change the tags while it runs."""
    keyed = {id(n.value) for n in ast.walk(stmt) if _tag_key(n, root) is not None}
    for node in ast.walk(stmt):
        if isinstance(node, _SCOPES):
            return False
        if isinstance(node, ast.Name) and (node.id == MERGED_ROOT or (node.id == ROOT_DICT and id(node) not in keyed)):
            return False  # the tag object itself, or the dict beyond a constant key
        if isinstance(node, ast.Call) and not _pure_call(node.func, root, shadowed):
            return False
    return True


def _pure_call(func: ast.expr, root: StructType, shadowed: Collection[str]) -> bool:
    """A call of a function that sees only its arguments, or of a box method (a timer, a counter, an edge
    trigger: it changes its instance, never a tag)."""
    if isinstance(func, ast.Name):
        return func.id not in shadowed and (func.id in _PURE_CALLS or func.id.startswith("_to_"))
    if not isinstance(func, ast.Attribute):
        return False
    receiver = func.value
    if isinstance(receiver, ast.Name):
        return receiver.id.startswith(_TEMPLATE_INSTANCE)
    key = _tag_key(receiver, root)
    return key is not None and isinstance(root.members[key].type, FBType)


def _localized(run: list[ast.stmt], root: StructType, getter: str, module: list[ast.stmt]) -> list[ast.stmt]:
    """The run on locals between a read of its tags and a store back of those it writes; the run itself
    where that would not pay (each access saves two operations, each tag costs one to read and one to
    store back, the read and the store back a few more)."""
    reads: dict[str, None] = {}
    written: dict[str, None] = {}
    accesses = 0
    for stmt in run:
        for node in ast.walk(stmt):
            key = _tag_key(node, root)
            if key is not None:
                accesses += 1
                reads[key] = None
                if isinstance(node.ctx, ast.Store):  # type: ignore[attr-defined]
                    written[key] = None
    if 2 * accesses <= len(reads) + len(written) + 12:
        return run
    names = {key: _local_name(key, k) for k, key in enumerate(reads)}
    on_locals = [_Locals(root, names).visit(stmt) for stmt in run]
    first = run[0]
    if len(reads) == 1:
        (key,) = reads
        load: ast.stmt = ast.Assign([ast.Name(names[key], ast.Store())], _subscript(key, ast.Load()))
    else:
        getters = ast.Call(ast.Name(ITEMGETTER, ast.Load()), [ast.Constant(key) for key in reads], [])
        module.append(
            ast.fix_missing_locations(ast.copy_location(ast.Assign([ast.Name(getter, ast.Store())], getters), first))
        )
        targets = ast.Tuple([ast.Name(names[key], ast.Store()) for key in reads], ast.Store())
        load = ast.Assign([targets], ast.Call(ast.Name(getter, ast.Load()), [ast.Name(ROOT_DICT, ast.Load())], []))
    out = [ast.copy_location(load, first)]
    if not written:
        return out + on_locals
    stores: list[ast.stmt] = []
    keys = list(written)
    for start in range(0, len(keys), _STORES_AT_ONCE):
        chunk = keys[start : start + _STORES_AT_ONCE]
        if len(chunk) == 1:
            store: ast.stmt = ast.Assign([_subscript(chunk[0], ast.Store())], ast.Name(names[chunk[0]], ast.Load()))
        else:
            update = ast.Attribute(ast.Name(ROOT_DICT, ast.Load()), "update", ast.Load())
            values = ast.Dict([ast.Constant(k) for k in chunk], [ast.Name(names[k], ast.Load()) for k in chunk])
            store = ast.Expr(ast.Call(update, [values], []))
        stores.append(ast.copy_location(store, first))
    guarded = ast.Try(body=on_locals, handlers=[], orelse=[], finalbody=stores)
    return [*out, ast.copy_location(guarded, first)]


def _local_name(key: str, index: int) -> str:
    return f"_tag_{key}" if key.isidentifier() else f"_tag{index}"


def _subscript(key: str, ctx: ast.expr_context) -> ast.Subscript:
    return ast.Subscript(ast.Name(ROOT_DICT, ast.Load()), ast.Constant(key), ctx)


class _Locals(ast.NodeTransformer):
    """``_t_dict["NAME"]`` -> the local holding NAME (a load or a store)."""

    def __init__(self, root: StructType, names: dict[str, str]):
        self.root, self.names = root, names

    def visit_Subscript(self, node: ast.Subscript) -> ast.AST:
        key = _tag_key(node, self.root)
        if key is None:
            return self.generic_visit(node)
        return ast.copy_location(ast.Name(self.names[key], node.ctx), node)
