"""Tags as locals: a task's merged function keeps the tags it uses often in local variables.

After :func:`~plcsim.frontends.python.merge.read_root_directly` and
:func:`~plcsim.frontends.python.inline.inline_boxes` a merged function reaches every tag through the tag
dict, ``_t_dict["Q0"]``: three operations a read, where a local costs one (the hand-inlined Python of the
benchmarks keeps its tags in locals). :func:`localize_tags` cuts the function's top-level statements into
runs that nothing outside the function can look into, and in each run gives a tag read often a local::

    _t_dict["Q0"] = _tag_Q0 = _tag_I0 or ...      # a store writes through: the dict, then the local
    _tag_Level = _t_dict["Level"]                   # or the tag is read once, before its first use
    _t_dict["Q9"] = _tag_Level >= 70
    _t_dict["Q10"] = _tag_Level < 20

Every store still goes into the dict when it runs, so the dict is at every moment what it was before: a fault
(any exception, the watchdog, a JMP) finds the tags exactly as the statements before it stored them, with
nothing to write back. The local only saves the reads, and only within a run: only this code changes the
tag dict while a run executes. A statement that lets other code see or change the tags (a call of the
program's own functions, of an instruction bound to the CPU such as ``MOVE`` or ``P``, of a store hook for a
DB member or an aliased tag; any use of the tag object or of the dict other than a constant key; a
comprehension, which has a scope of its own) is left as it was, between two runs, and the next run reads
its tags again. Typed stores keep their conversions; the local takes the converted value.

A data block (a struct of the root) reached twice or more in a run gets a local for its member dict, read and
written by subscripts (``_dict_DB["member"]``) instead of attribute reads through the block's object::

    _dict_OS_X = _t_dict["OS_X"].__dict__
    if _dict_OS_X["ziadana"] > _dict_OS_X["aktualna"]:
        _dict_OS_X["bol_pohyb_vpravo"] = True
"""

from __future__ import annotations

import ast
from collections.abc import Collection

from plcsim.controllers.s7.instructions import PURE_INSTRUCTIONS
from plcsim.frontends.python.inline import CHECK_EDGE, COERCE_BOOL, binds_root_dict
from plcsim.frontends.python.merge import MERGED_ROOT
from plcsim.frontends.python.rewrite import ROOT_DICT, TICK
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS
from plcsim.frontends.python.subset import ALLOWED_BUILTINS
from plcsim.tags.table import FBType
from plcsim.tags.types import StructType
from plcsim.tags.values import PlcStruct

_PURE_CALLS = (
    frozenset(SAFE_FUNCTIONS) | frozenset(PURE_INSTRUCTIONS) | ALLOWED_BUILTINS | {TICK, COERCE_BOOL, CHECK_EDGE}
)
"""Functions that see only their arguments: no tag can change in them but through an argument's object."""
_SCOPES = (ast.Lambda, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp)
_TEMPLATE_INSTANCE = "_i_"
"""The prefix of the locals :mod:`~plcsim.frontends.python.inline` holds a box's instance in."""


def localize_tags(func: ast.FunctionDef, root: StructType, shadowed: Collection[str]) -> None:
    """Give the runs of ``func`` (a merged function after :func:`inline_boxes`) locals for the tags they
    read often, in place.

    ``root`` is the tag schema, ``shadowed`` the names the program defines itself (its own ``abs`` is no
    builtin)."""
    if not func.body or not binds_root_dict(func.body[0]):
        return
    body: list[ast.stmt] = [func.body[0]]
    run: list[ast.stmt] = []
    for stmt in [*func.body[1:], None]:
        if stmt is not None and _closed(stmt, root, shadowed):
            run.append(stmt)
            continue
        body.extend(_localized(run, root))
        run = []
        if stmt is not None:
            body.append(stmt)
    func.body = body
    ast.fix_missing_locations(func)


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


def _localized(run: list[ast.stmt], root: StructType) -> list[ast.stmt]:
    """The run with locals for the member dicts of its blocks (:func:`_with_block_dicts`), then for the tags
    where they pay (:func:`_with_tag_locals`)."""
    return _with_tag_locals(_with_block_dicts(run, root), root)


def _block_key(node: ast.AST, root: StructType) -> str | None:
    """NAME of ``_t_dict["NAME"]`` when NAME is a struct of the root (a data block): its value is a
    :class:`~plcsim.tags.values.PlcStruct`, whose members live in its ``__dict__``."""
    key = _tag_key(node, root)
    return key if key is not None and isinstance(root.members[key].type, StructType) else None


def _member_read(node: ast.AST, root: StructType) -> tuple[str, str] | None:
    """(block, member) of ``_t_dict["BLOCK"].member`` read, when ``__dict__["member"]`` is what the read finds:
    a declared member (every one is in the dict) that no attribute of the class shadows."""
    if not (isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Load)):
        return None
    block = _block_key(node.value, root)
    if block is None:
        return None
    attr = node.attr
    if attr == "__dict__" or (attr in root.members[block].type.members and not hasattr(PlcStruct, attr)):  # type: ignore[attr-defined]
        return block, attr
    return None


def _with_block_dicts(run: list[ast.stmt], root: StructType) -> list[ast.stmt]:
    """The run with a local for the member dict of each block it reaches twice or more (``_t_dict["DB"].__dict__``,
    a store into a member, or ``_t_dict["DB"].member``, a read): one subscript of the local instead of a lookup of
    the block and an attribute read through it. The block's object, and so its dict, is the same for the whole
    run: nothing in it stores into the tag itself (a whole struct is stored through a call, which ends a run)."""
    uses: dict[str, int] = {}
    first: dict[str, int] = {}
    replaced: set[str] = set()  # blocks the run stores into as tags: they keep their lookups
    for index, stmt in enumerate(run):
        for node in ast.walk(stmt):
            read = _member_read(node, root)
            if read is not None:
                uses[read[0]] = uses.get(read[0], 0) + 1
                first.setdefault(read[0], index)
            elif isinstance(node, ast.Subscript) and not isinstance(node.ctx, ast.Load):
                block = _block_key(node, root)
                if block is not None:
                    replaced.add(block)
    names = {
        block: _local_name(block, number, "_dict")
        for number, block in enumerate(first)
        if uses[block] > 1 and block not in replaced
    }
    if not names:
        return run
    out: list[ast.stmt] = []
    reads = _BlockDicts(root, names)
    for index, stmt in enumerate(run):
        for block in names:
            if first[block] == index:
                value = ast.Attribute(_subscript(block, ast.Load()), "__dict__", ast.Load())
                out.append(ast.copy_location(ast.Assign([ast.Name(names[block], ast.Store())], value), stmt))
        out.append(reads.visit(stmt))
    return out


def _with_tag_locals(run: list[ast.stmt], root: StructType) -> list[ast.stmt]:
    """The run with locals for the tags where they pay: each read of the local saves two operations, each
    store costs two more (the local beside the dict), so does a first use that copies the tag into a local
    (``_i_1 = _t_dict["T1"]``), a read before the first use four."""
    reads: dict[str, int] = {}
    stores: dict[str, int] = {}
    first: dict[str, int] = {}  # tag -> the index of the first statement using it
    simple: set[int] = set()  # the subscripts that are the one target of an Assign
    other: set[str] = set()  # tags stored some other way (a tuple, ``+=``): they get no local
    for index, stmt in enumerate(run):
        for node in ast.walk(stmt):
            if isinstance(node, ast.Assign) and len(node.targets) == 1:
                simple.add(id(node.targets[0]))
            key = _tag_key(node, root)
            if key is None:
                continue
            first.setdefault(key, index)
            if isinstance(node.ctx, ast.Load):  # type: ignore[attr-defined]
                reads[key] = reads.get(key, 0) + 1
            elif id(node) in simple:
                stores[key] = stores.get(key, 0) + 1
            else:
                other.add(key)
    names: dict[str, str] = {}
    loads: dict[int, list[str]] = {}
    copies: dict[int, str] = {}
    for number, key in enumerate(first):
        statement = run[first[key]]
        defined, copied = _defines(statement, key, root), _copies(statement, key, root)
        cost = 2 * stores.get(key, 0) + (0 if defined else 2 if copied else 4)
        if 2 * (reads.get(key, 0) - copied) > cost and key not in other:  # a copy keeps its own read
            names[key] = _local_name(key, number)
            if copied:
                copies[first[key]] = key
            elif not defined:
                loads.setdefault(first[key], []).append(key)
    if not names:
        return run
    out: list[ast.stmt] = []
    locals_ = _Locals(root, names)
    for index, stmt in enumerate(run):
        for key in loads.get(index, ()):
            load = ast.Assign([ast.Name(names[key], ast.Store())], _subscript(key, ast.Load()))
            out.append(ast.copy_location(load, stmt))
        if index in copies:  # ``_i_1 = _tag_T1 = _t_dict["T1"]``: the read gives the local its value
            stmt.targets.append(ast.copy_location(ast.Name(names[copies[index]], ast.Store()), stmt))  # type: ignore[attr-defined]
            out.append(stmt)
        else:
            out.append(locals_.visit(stmt))
    return out


def _copies(stmt: ast.stmt, key: str, root: StructType) -> bool:
    """Whether ``stmt`` is ``name = _t_dict[key]``, a read that can give the local its first value too."""
    return (
        isinstance(stmt, ast.Assign)
        and len(stmt.targets) == 1
        and isinstance(stmt.targets[0], ast.Name)
        and _tag_key(stmt.value, root) == key
    )


def _defines(stmt: ast.stmt, key: str, root: StructType) -> bool:
    """Whether ``stmt`` is a store into the tag ``key`` whose value does not read it: the store itself then
    gives the local its first value, on every path."""
    return (
        isinstance(stmt, ast.Assign)
        and len(stmt.targets) == 1
        and _tag_key(stmt.targets[0], root) == key
        and not any(_tag_key(node, root) == key for node in ast.walk(stmt.value))
    )


def _local_name(key: str, index: int, prefix: str = "_tag") -> str:
    return f"{prefix}_{key}" if key.isidentifier() else f"{prefix}{index}"


def _subscript(key: str, ctx: ast.expr_context) -> ast.Subscript:
    return ast.Subscript(ast.Name(ROOT_DICT, ast.Load()), ast.Constant(key), ctx)


class _BlockDicts(ast.NodeTransformer):
    """``_t_dict["DB"].__dict__`` -> the local holding it, ``_t_dict["DB"].member`` (a read) -> ``local["member"]``."""

    def __init__(self, root: StructType, names: dict[str, str]):
        self.root, self.names = root, names

    def visit_Attribute(self, node: ast.Attribute) -> ast.AST:
        read = _member_read(node, self.root)
        if read is None or read[0] not in self.names:
            return self.generic_visit(node)
        local = ast.Name(self.names[read[0]], ast.Load())
        if read[1] == "__dict__":
            return ast.copy_location(local, node)
        return ast.copy_location(ast.Subscript(local, ast.Constant(read[1]), ast.Load()), node)


class _Locals(ast.NodeTransformer):
    """``_t_dict["NAME"]`` read -> the local holding NAME; a store into it also stores into the local."""

    def __init__(self, root: StructType, names: dict[str, str]):
        self.root, self.names = root, names

    def visit_Assign(self, node: ast.Assign) -> ast.AST:
        self.generic_visit(node)
        key = _tag_key(node.targets[0], self.root) if len(node.targets) == 1 else None
        if key in self.names:
            local = ast.copy_location(ast.Name(self.names[key], ast.Store()), node.targets[0])
            node.targets.append(local)  # the dict first, then the local, as Python assigns a chain
        return node

    def visit_Subscript(self, node: ast.Subscript) -> ast.AST:
        key = _tag_key(node, self.root)
        if key is None or key not in self.names or not isinstance(node.ctx, ast.Load):
            return self.generic_visit(node)
        return ast.copy_location(ast.Name(self.names[key], ast.Load()), node)
