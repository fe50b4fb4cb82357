"""Compiling a read program against one tag table: the passes in their order, and the checks that need it.

A :class:`~plcsim.frontends.python.program.Program` holds the checked syntax tree; :func:`compile_program`
types it against the CPU's tag table (:mod:`~plcsim.frontends.python.typecheck`), analyses it
(:mod:`~plcsim.frontends.python.analysis`), merges each task's networks
(:mod:`~plcsim.frontends.python.merge`), rewrites the stores (:mod:`~plcsim.frontends.python.rewrite`), writes
out the boxes of each merged task (:mod:`~plcsim.frontends.python.inline`), keeps the tags it reads often in
locals (:mod:`~plcsim.frontends.python.localize`) and compiles the result, then
refuses or warns about what only the table shows: stores into inputs, jumps to missing labels, SCALE and
UNSCALE on an S7-1200, timers whose Q and ET go unread.
"""

from __future__ import annotations

import ast
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from plcsim.core.errors import ProgramError
from plcsim.frontends.python.analysis import Analysis, analyse
from plcsim.frontends.python.inline import inline_boxes
from plcsim.frontends.python.localize import localize_tags
from plcsim.frontends.python.merge import MERGED_ROOT, merge_networks, read_root_directly
from plcsim.frontends.python.rewrite import StoreRewriter
from plcsim.frontends.python.typecheck import Typing
from plcsim.tags.table import TagTable
from plcsim.tags.types import ElementaryType

if TYPE_CHECKING:
    from plcsim.frontends.python.program import Program

MAX_MERGED_STATEMENTS = 5000
"""Above this many statements an OB's networks are not merged into one function (see merge_networks):
the merge speeds up scans of ordinary programs and would only slow down loading a huge one."""
INLINE_BOXES = True
"""Whether a merged function has its timers, counters and edge contacts written out
(:func:`~plcsim.frontends.python.inline.inline_boxes`); off only to compare the two in tests."""
LOCAL_TAGS = True
"""Whether a merged function keeps the tags it reads often in locals
(:func:`~plcsim.frontends.python.localize.localize_tags`); off only to compare the two in tests."""


@dataclass
class CompiledProgram:
    """A program compiled against one tag table: code, facts and the timers the textbook rule stops."""

    program: Program
    code: Any
    analysis: Analysis
    coercers: set[ElementaryType]
    inert_timers: set[str]
    warnings: list[str] = field(default_factory=list)
    merged: dict[str, str] = field(default_factory=dict)
    """Task name -> the namespace name of its merged networks (see :func:`merge_networks`)."""


def compile_program(
    program: Program, table: TagTable, aliased: frozenset[str], strict_timers: bool, family: str, input_writes: str
) -> CompiledProgram:
    """Compile ``program`` against a tag table that already holds its declarations (see
    :meth:`~plcsim.frontends.python.program.Program.compile`, which keeps the result)."""
    root_params = {}
    for task in program.tasks.values():
        for net in task.networks:
            root_params[net.name] = program.functions[net.name].args.args[0].arg
    typing = Typing(table.schema(), aliased, program.filename, root_params, table.aliases)
    checked = with_declared_names(program.tree, table, root_params)
    analysis = analyse(checked, typing)
    tree = runtime_module(checked)
    functions = {f.name: f for f in checked.body if isinstance(f, ast.FunctionDef)}
    merged: dict[str, str] = {}
    for task in program.tasks.values():
        funcs = [functions[n.name] for n in task.networks]
        if len(funcs) > 1 and sum(len(f.body) for f in funcs) <= MAX_MERGED_STATEMENTS:
            combined = merge_networks(funcs, task.name, root_params, typing.root)
            if combined is not None:
                tree.body.append(combined)
                typing.root_params[combined.name] = MERGED_ROOT
                merged[task.name] = combined.name
    rewriter = StoreRewriter(typing)
    tree = ast.fix_missing_locations(rewriter.visit(tree))
    shadowed = set(program.functions) | set(program.constants)
    for stmt in tree.body:
        if isinstance(stmt, ast.FunctionDef) and stmt.name in merged.values():
            read_root_directly(stmt, typing.root.members)
            if INLINE_BOXES:
                inline_boxes(stmt, typing.root, typing.aliased, shadowed)
            if LOCAL_TAGS:
                localize_tags(stmt, typing.root, shadowed)
    code = compile(tree, program.filename, "exec")
    warnings = list(analysis.warnings)
    for line, name in _input_stores(program, table, root_params):
        message = (
            f"{program.filename}, line {line}: the program writes the input {name} "
            f"({table[name].address}); an input is what the sensor delivers, the program should only read it"
        )
        if input_writes == "error":
            raise ProgramError(message)
        warnings.append(message + " (the write changes only the program's process image, not the plant)")
    _check_jumps(program, analysis)
    if family == "S7-1200":
        for node in ast.walk(program.tree):
            if isinstance(node, ast.Name) and node.id in ("SCALE", "UNSCALE"):
                raise ProgramError(
                    f"{program.filename}, line {node.lineno}: {node.id} is not available on the S7-1200 "
                    f"(textbook §3.3); use NORM_X and SCALE_X"
                )
    inert: set[str] = set()
    for path in sorted(analysis.unused_timers()):
        warnings.append(
            f"{program.filename}: timer {path} runs but its Q and ET are used nowhere; on an S7-1200 such a "
            f"timer does not start (textbook §3.6.1, Fig. 3.197)"
            + ("" if strict_timers else "; the CPU runs it anyway (textbook_strict_timers=False)")
        )
        if strict_timers:
            inert.add(path)
    return CompiledProgram(program, code, analysis, rewriter.coercers, inert, warnings, merged)


def with_declared_names(tree: ast.Module, table: TagTable, root_params: Mapping[str, str]) -> ast.Module:
    """The tree with every alias of the table (``t.Dopravník``, ``t["Dopravník"]``, ``t.DATA.POZ3_OBS_Farba_1``)
    written as the name it stands for; the tree itself when the program uses none."""
    if not table.aliases:
        return tree
    declared = table.entries
    renamed = copy_tree(tree)
    roots = set(root_params.values())
    changed = False
    for node in ast.walk(renamed):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in roots:
            target = table.aliases.get(node.attr) if node.attr not in declared else None
            if target is not None and "." not in target:
                node.attr, changed = target, True
        elif isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in roots:
            key = getattr(node.slice, "value", None)
            target = table.aliases.get(key) if isinstance(key, str) and key not in declared else None
            if target is not None and "." not in target:
                node.slice, changed = ast.copy_location(ast.Constant(target), node.slice), True
        elif (
            isinstance(node, ast.Attribute)
            and isinstance(node.value, ast.Attribute)
            and isinstance(node.value.value, ast.Name)
            and node.value.value.id in roots
        ):
            target = table.aliases.get(f"{node.value.attr}.{node.attr}")
            if target is not None and target.partition(".")[0] == node.value.attr:
                node.attr, changed = target.partition(".")[2], True
    return renamed if changed else tree


def runtime_module(tree: ast.Module) -> ast.Module:
    """What runs: a copy of the checked tree's network functions, without decorators (labels are
    already collected) and without the module-level declarations (evaluated, never executed)."""
    body = []
    for stmt in tree.body:
        if isinstance(stmt, ast.FunctionDef):
            func = copy_tree(stmt)
            func.decorator_list = []
            body.append(func)
    return ast.Module(body=body, type_ignores=[])


def copy_tree(node: Any) -> Any:
    """A deep copy of a syntax tree (several times faster than copy.deepcopy; depth is bounded by the
    subset check)."""
    if isinstance(node, list):
        return [copy_tree(item) for item in node]
    if not isinstance(node, ast.AST):
        return node
    new = node.__class__()
    for name in node._fields:
        setattr(new, name, copy_tree(getattr(node, name, None)))
    for name in node._attributes:
        if hasattr(node, name):
            setattr(new, name, getattr(node, name))
    return new


def _input_stores(program: Program, table: TagTable, root_params: Mapping[str, str]) -> list[tuple[int, str]]:
    """(line, tag) of every store into an input tag: t.IN = ..., t["IN"] = ..., MOVE(x, "IN")."""
    inputs = {e.name for e in table if e.address is not None and e.address.area == "I"}
    found: list[tuple[int, str]] = []
    for func in program.functions.values():
        root = root_params.get(func.name, "t")
        for node in ast.walk(func):
            name = None
            if isinstance(node, ast.Attribute | ast.Subscript) and isinstance(node.ctx, ast.Store):
                if isinstance(node.value, ast.Name) and node.value.id == root:
                    key = node.attr if isinstance(node, ast.Attribute) else getattr(node.slice, "value", None)
                    name = key if key in inputs else None
            elif isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "MOVE":
                outs = [_target_text(a, root) for a in node.args[1:]]
                name = next((o for o in outs if o in inputs), None)
            if name is not None:
                found.append((node.lineno, name))
    return sorted(found)


def _check_jumps(program: Program, analysis: Analysis) -> None:
    for task in program.tasks.values():
        labels = {n.label for n in task.networks if n.label}
        for net in task.networks:
            for target, line in analysis.functions[net.name].jumps:
                if target not in labels:
                    known = (
                        f"; labels in {task.name}: {', '.join(sorted(labels))}"
                        if labels
                        else f"; {task.name} has no labels (mark a network with @label({target!r}))"
                    )
                    raise ProgramError(
                        f"{program.filename}, line {line}: JMP to {target!r}, but no network of {task.name} "
                        f"carries that label{known}"
                    )


def _target_text(node: ast.expr, root: str) -> str | None:
    """The tag a MOVE output names: ``"LED"`` or ``t.LED``."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == root:
        return node.attr
    return None
