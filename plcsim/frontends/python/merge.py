"""Merging the networks of one task into one function: the fast path of every scan.

:func:`merge_networks` runs a task's networks back to back in one function, for the executions nothing
pre-empts, and :func:`read_root_directly` lets that function read its tags from the tag dict. A local that
provably always names one data block (``s = t.DB`` first, never bound again) reads and writes in the merged
function as the block itself (``s.X`` runs as ``t.DB.X``), so that its stores are typed and its reads are known.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable

from plcsim.controllers.loaded import merged_local
from plcsim.controllers.s7.instructions import FUNCTIONS
from plcsim.frontends.python.rewrite import ROOT_DICT
from plcsim.tags.types import ElementaryType, StructType, Time

MERGED_ROOT = "_t"
_TAG_OPERANDS = frozenset({f.name for f in FUNCTIONS.values() if f.named} | {"MOVE"})
"""Instructions where ``t.DB.X`` as an argument can mean the tag's name, not its value (see StoreRewriter)."""


def merged_name(task: str) -> str:
    """The namespace name of a task's merged networks."""
    return f"_merged_{task}"


def merge_networks(
    functions: list[ast.FunctionDef], task: str, root_params: dict[str, str], schema: StructType
) -> ast.FunctionDef | None:
    """One function running the networks of a task back to back, for executions nothing pre-empts.

    Each network's locals are renamed apart so the networks cannot see each other's variables; a local that
    names a data block of ``schema`` (the root tags) everywhere it is read (:func:`_block_aliases`) is read and
    written as the block. A network with ``return`` or a nested ``def`` is not merged (returns None): the CPU
    then calls the networks one by one, as it always does when an interrupt falls inside the execution.
    """
    body: list[ast.stmt] = []
    for index, func in enumerate(functions):
        if any(isinstance(n, (ast.Return, ast.FunctionDef)) for n in ast.walk(func) if n is not func):
            return None
        root = root_params.get(func.name, "t")
        aliases = _block_aliases(func, root, schema)
        local = {n.id for n in ast.walk(func) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)}
        local |= {a.arg for a in func.args.args}
        renames = {name: merged_local(index, name) for name in local if name != root}
        renames[root] = MERGED_ROOT
        statements = func.body
        if statements and isinstance(statements[0], ast.Expr) and isinstance(statements[0].value, ast.Constant):
            statements = statements[1:]
        for stmt in statements:
            copied = ast.parse(ast.unparse(stmt)).body[0]
            _relocate(copied, stmt)
            if aliases:
                _AsBlock(root, aliases).visit(copied)
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


def _block_aliases(func: ast.FunctionDef, root: str, schema: StructType) -> dict[str, str]:
    """NAME -> BLOCK for each local of ``func`` that provably always names the data block ``root.BLOCK``
    wherever it is read, so that ``NAME.X`` may run as ``root.BLOCK.X`` with the same effect and messages.

    NAME is bound once, by ``NAME = root.BLOCK`` at the top level of the body (BLOCK a struct of ``schema``), and
    in no other way anywhere (no other target, parameter, ``del``, ``except ... as``, ``global``), and read only
    after that statement. Every ``NAME.X`` names an elementary member X of the block, no TIME (a TIME compared
    with a text is folded only where the typing knows it), outside the operands that name tags
    (``P(..., NAME.X)``), read or the target of ``=`` or ``+=``; a constant stored into ``NAME.X`` converts (a
    constant the conversion refuses is refused when the program loads if written ``root.BLOCK.X``, when it runs
    if written ``NAME.X``). A bare ``NAME`` (``f(NAME)``) still names the block: the local keeps its binding.
    Anything else keeps the local as it is."""
    bindings: dict[str, list[tuple[int, ast.Assign]]] = {}
    for index, stmt in enumerate(func.body):
        if (
            isinstance(stmt, ast.Assign)
            and len(stmt.targets) == 1
            and isinstance(stmt.targets[0], ast.Name)
            and isinstance(stmt.value, ast.Attribute)
            and isinstance(stmt.value.value, ast.Name)
            and stmt.value.value.id == root
        ):
            member = schema.members.get(stmt.value.attr)
            if member is not None and isinstance(member.type, StructType):
                bindings.setdefault(stmt.targets[0].id, []).append((index, stmt))
    candidates = {name: found[0] for name, found in bindings.items() if len(found) == 1 and name != root}
    if not candidates:
        return {}
    stores: set[int] = set()  # the attribute targets of an Assign or AugAssign
    operands: set[int] = set()  # every node inside an argument of an instruction that may take a tag's name
    for node in ast.walk(func):
        if isinstance(node, ast.Assign):
            stores |= {id(t) for t in node.targets if isinstance(t, ast.Attribute)}
        elif isinstance(node, ast.AugAssign):
            stores.add(id(node.target))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in _TAG_OPERANDS:
            operands |= {id(n) for arg in [*node.args, *node.keywords] for n in ast.walk(arg)}
    bad: set[str] = set()
    for index, stmt in enumerate(func.body):
        for node in ast.walk(stmt):
            for field in ("name", "asname", "rest", "arg"):
                if getattr(node, field, None) in candidates:
                    bad.add(getattr(node, field))
            bad.update(n for n in getattr(node, "names", ()) if isinstance(n, str) and n in candidates)
            if (
                isinstance(node, ast.Name)
                and node.id in candidates
                and node is not candidates[node.id][1].targets[0]
                and (not isinstance(node.ctx, ast.Load) or index <= candidates[node.id][0])
            ):
                bad.add(node.id)  # bound again, deleted, or read before (or in) its binding
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in candidates:
                name = node.value.id
                block = schema.members[candidates[name][1].value.attr].type  # type: ignore[attr-defined]
                member = block.members.get(node.attr)
                if (
                    member is None
                    or not isinstance(member.type, ElementaryType)
                    or member.type is Time
                    or id(node) in operands
                    or not (isinstance(node.ctx, ast.Load) or id(node) in stores)
                ):
                    bad.add(name)
        if isinstance(stmt, ast.Assign):
            for target in stmt.targets:
                if _alias_member(target, candidates) and not _converts(stmt.value, target, candidates, schema):
                    bad.add(target.value.id)  # type: ignore[attr-defined]
    for node in ast.walk(func):  # uses the top-level walk above cannot see: the parameters
        if isinstance(node, ast.arg) and node.arg in candidates:
            bad.add(node.arg)
    return {name: found[1].value.attr for name, found in candidates.items() if name not in bad}  # type: ignore[attr-defined]


def _alias_member(node: ast.expr, candidates: dict[str, tuple[int, ast.Assign]]) -> bool:
    return isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in candidates


def _converts(
    value: ast.expr, target: ast.expr, candidates: dict[str, tuple[int, ast.Assign]], schema: StructType
) -> bool:
    """Whether storing ``value`` into the member ``target`` names is refused by no check at load: ``value``
    reads something (it is converted when it runs), or it is a constant its member's type converts."""
    if any(isinstance(n, ast.Name | ast.Attribute | ast.Subscript | ast.Call) for n in ast.walk(value)):
        return True
    block = schema.members[candidates[target.value.id][1].value.attr].type  # type: ignore[attr-defined]
    mtype = block.members[target.attr].type  # type: ignore[attr-defined]
    try:
        mtype.coerce(ast.literal_eval(value), "")
    except Exception:  # noqa: BLE001 - no constant, or one the conversion refuses: the local stays as it is
        return False
    return True


class _AsBlock(ast.NodeTransformer):
    """``NAME.X`` -> ``root.BLOCK.X`` for the block aliases of :func:`_block_aliases`."""

    def __init__(self, root: str, aliases: dict[str, str]):
        self.root, self.aliases = root, aliases

    def visit_Attribute(self, node: ast.Attribute) -> ast.AST:
        value = node.value
        if isinstance(value, ast.Name) and value.id in self.aliases:
            block = ast.Attribute(ast.Name(self.root, ast.Load()), self.aliases[value.id], ast.Load())
            node.value = ast.copy_location(block, value)
            ast.copy_location(block.value, value)
            return node
        return self.generic_visit(node)


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
