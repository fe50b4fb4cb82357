"""Merging the networks of one task into one function: the fast path of every scan.

:func:`merge_networks` runs a task's networks back to back in one function, for the executions nothing
pre-empts, and :func:`read_root_directly` lets that function read its tags from the tag dict.
"""

from __future__ import annotations

import ast
from collections.abc import Iterable

from plcsim.frontends.python.rewrite import ROOT_DICT

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
