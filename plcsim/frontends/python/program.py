"""How a user program is written and bound to the CPU's tasks.

A program is a Python file in the PLC subset. Module-level assignments declare the program's own
tags and instances (they are evaluated by :mod:`plcsim.frontends.python.module_level`, never executed); functions are
networks; names ``OB1``, ``OB30`` ... ``OB38`` and ``OB100`` bind
networks to tasks::

    POM = Tag("%M10.0")                 # a PLC tag at an absolute address
    CISLO = Int(0)                      # a symbolic tag (no address)
    TON_A = IEC_TIMER()                 # a timer instance

    def start_belt(t):
        \"\"\"Network 1: an object at S1 starts the belt.\"\"\"
        if t.S1:
            t.D1 = True                 # SET D1

    def stop_belt(t):
        if t.S2:
            t.D1 = False                # RESET D1

    OB1 = [start_belt, stop_belt]       # networks in execution order
    OB30 = CyclicInterrupt(blink, period="1s")

``def OB1(t): ...`` alone is an OB1 with one network. ``@label("lbl10")`` marks a jump target.

>>> p = Program.from_source("def OB1(t):\\n    t.LED = t.TLACIDLO\\n")
>>> [n.name for n in p.tasks["OB1"].networks]
['OB1']
"""

from __future__ import annotations

import ast
import builtins
import inspect
import textwrap
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from plcsim.controllers.loaded import (
    LinkTarget,
    LoadedNetwork,
    LoadedProgram,
    LoadedTask,
    NetworkSpec,
    ProgramFacts,
    TaskSpec,
)
from plcsim.controllers.s7.instructions import BOOL_RESULTS, CPU_BOUND, FB_TYPES, PURE_INSTRUCTIONS
from plcsim.controllers.s7.profile import DEFAULT_INTERRUPT_PRIORITY, is_ob_name, ob_number, task_kind
from plcsim.core.errors import DeclarationError, NoOB1Error, PlcError, ProgramError, SubsetError
from plcsim.core.literals import time_ms, to_ns
from plcsim.frontends.python.analysis import Analysis, analyse
from plcsim.frontends.python.merge import MERGED_ROOT, merge_networks, read_root_directly
from plcsim.frontends.python.module_level import NetworkRef, evaluate_module
from plcsim.frontends.python.rewrite import FB_STORE, ROOT_GUARD, STORE, TICK, StoreRewriter, coerce_name
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS, bounded_range
from plcsim.frontends.python.subset import ALLOWED_BUILTINS, check_subset, parse
from plcsim.frontends.python.typecheck import Typing
from plcsim.frontends.text import read_program_text
from plcsim.tags import types as plc_types
from plcsim.tags.memory import parse_address
from plcsim.tags.table import DB, DataBlock, Tag, TagTable
from plcsim.tags.types import ArrayType, DataType, ElementaryType, Member, StringType, StructType, value_count

MAX_LABELS_S7_1200 = 32
MAX_VALUES = 1_000_000
"""The most values a program may declare (an S7-1200 has 50..150 KB of work memory: far fewer)."""
MAX_MERGED_STATEMENTS = 5000
"""Above this many statements an OB's networks are not merged into one function (see merge_networks):
the merge speeds up scans of ordinary programs and would only slow down loading a huge one."""
COMPILED_KEPT = 4
"""How many compilations (tag tables and options) a program keeps for its next downloads."""


def label(name: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Mark a network as a jump target: ``@label("lbl10")`` (one label per network, unique per OB)."""
    if not isinstance(name, str) or not name:
        raise DeclarationError(f"a label must be a non-empty string, not {name!r}")

    def mark(func: Callable[..., Any]) -> Callable[..., Any]:
        func.plc_label = name  # type: ignore[attr-defined]
        return func

    return mark


@dataclass(frozen=True)
class CyclicInterrupt:
    """A cyclic-interrupt OB (OB30..OB38): its networks, period, phase and priority.

    ``OB30 = CyclicInterrupt([read_button, count], period="1s")``; the first call comes at the
    STOP->RUN instant plus the phase.
    """

    networks: Any
    period: str | int | None = None
    """None: the hardware configuration's period (``CPUConfig.periods``), else 100 ms."""
    phase: str | int = "0ms"
    priority: int = DEFAULT_INTERRUPT_PRIORITY
    duration: str | int | None = None


def Array(lo: int, hi: int, element: DataType | Member) -> ArrayType:
    """``Array[lo..hi] of element`` for DB members: ``Array(0, 3, Int)``."""
    return ArrayType(lo, hi, element)


def Struct(**members: DataType | Member) -> StructType:
    """An anonymous STRUCT for a DB member: ``Struct(OBS=Bool, POCET=Int)``."""
    return StructType("Struct", members)


def UDT(**members: DataType | Member) -> StructType:
    """A PLC data type (named after the variable it is assigned to): ``NASA = UDT(OBS=Bool)``."""
    return StructType("UDT", members)


def TIME(literal: str) -> int:
    """A TIME literal as milliseconds, for comparisons with ET: ``t.T1.ET > TIME("500ms")``."""
    return time_ms(literal)


TYPE_NAMES: dict[str, Any] = {
    **{t.name: t for t in plc_types.ELEMENTARY.values()},
    "TOD": plc_types.TimeOfDay,
    "String": plc_types.String,
    "DTL": plc_types.DTL,
}
"""Data types: declared at module level, and named in networks (``CONVERT(x, Int)``)."""

DECLARATION_ONLY: dict[str, Any] = {
    "Array": Array,
    "Struct": Struct,
    "UDT": UDT,
    "Tag": Tag,
    "DB": DB,
    "CyclicInterrupt": CyclicInterrupt,
    "label": label,
    **FB_TYPES,
}
"""Names that declare something; a network cannot use them (it sees the declared tag as t.NAME)."""

DECLARATION_NAMES: dict[str, Any] = {**TYPE_NAMES, **DECLARATION_ONLY, "TIME": TIME}
"""Names a program may use at module level to declare tags, DBs, instances and tasks."""

PROGRAM_NAMES = set(DECLARATION_NAMES) | set(PURE_INSTRUCTIONS) | CPU_BOUND
"""Every name a program sees besides its own and the allowed builtins."""


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


class Program:
    """A user program: its declarations and its tasks, checked against the PLC subset of Python.

    The checked syntax tree is the only form of the program that is ever compiled: ``source`` and
    ``tree`` are read-only, and the module level is evaluated as declarations, never executed.
    """

    def __init__(
        self, source: str, filename: str = "<program>", *, extra_declarations: Mapping[str, Any] | None = None
    ):
        self._source = source
        self._filename = filename
        self._tree = parse(source, filename)
        check_subset(self._tree, filename, PROGRAM_NAMES, DECLARATION_ONLY)
        self.functions = {s.name: s for s in self._tree.body if isinstance(s, ast.FunctionDef)}
        self.declarations: dict[str, Any] = dict(extra_declarations or {})
        self.types: dict[str, StructType] = {}
        self.tasks: dict[str, TaskSpec] = {}
        self.constants: dict[str, Any] = {}
        self._compiled: list[tuple[tuple[Any, ...], CompiledProgram]] = []
        self._collect()

    @property
    def source(self) -> str:
        """The program text as loaded (for display; what runs is compiled from :attr:`tree`)."""
        return self._source

    @property
    def filename(self) -> str:
        """The file the program came from (every error names it)."""
        return self._filename

    @property
    def tree(self) -> ast.Module:
        """The syntax tree that passed the subset check; compiling starts from a copy of it."""
        return self._tree

    # -- constructors -------------------------------------------------------------------------

    @classmethod
    def from_source(cls, source: str, filename: str = "<program>") -> Program:
        """Load a program from text."""
        return cls(textwrap.dedent(source), filename)

    @classmethod
    def from_file(cls, path: str | Path) -> Program:
        """Load a program from a ``.py`` file (errors name the file and line; see :func:`read_program_text`)."""
        path = Path(path)
        return cls(read_program_text(path), str(path))

    @classmethod
    def from_functions(cls, tags: Mapping[str, Any] | None = None, **obs: Any) -> Program:
        """Build a program from Python functions defined elsewhere (a notebook cell, a test).

        The functions' source is compiled like a program file, so they may use only ``t`` and
        plcsim's instructions. ``tags`` adds declarations (``{"POM": Tag("%M10.0")}``).

        >>> def OB1(t):
        ...     t.LED = t.TLACIDLO
        >>> Program.from_functions(OB1=OB1).tasks["OB1"].networks[0].name
        'OB1'
        """
        chunks: list[str] = []
        seen: set[str] = set()
        bindings: list[str] = []

        def add(func: Any) -> str:
            if not callable(func) or not hasattr(func, "__code__"):
                raise ProgramError(f"expected a function, got {func!r}")
            if func.__name__ not in seen:
                seen.add(func.__name__)
                chunks.append(textwrap.dedent(inspect.getsource(func)))
            return func.__name__

        for ob, value in obs.items():
            if isinstance(value, CyclicInterrupt):
                nets = value.networks if isinstance(value.networks, list | tuple) else [value.networks]
                names = [add(f) for f in nets]
                bindings.append(
                    f"{ob} = CyclicInterrupt([{', '.join(names)}], period={value.period!r}, "
                    f"phase={value.phase!r}, priority={value.priority!r}, duration={value.duration!r})"
                )
            elif isinstance(value, list | tuple):
                bindings.append(f"{ob} = [{', '.join(add(f) for f in value)}]")
            else:
                name = add(value)
                if name != ob:
                    bindings.append(f"{ob} = {name}")
        source = "\n\n".join(chunks + bindings) + "\n"
        return cls(source, "<functions>", extra_declarations=tags)

    # -- phase 1: declarations and tasks --------------------------------------------------------

    def _collect(self) -> None:
        values = evaluate_module(self._tree, self._filename, DECLARATION_NAMES)
        for name, line in values.lines.items():
            if name in values.constants and name in PROGRAM_NAMES | ALLOWED_BUILTINS:
                raise SubsetError(
                    f"{self._filename}, line {line}: {name} is the name of an instruction, a type or a builtin; "
                    f"choose another name for the constant"
                )
        self.constants = values.constants
        self._declaration_lines = values.lines
        for name in values.order:
            if is_ob_name(name):
                continue
            value = values.declared.get(name)
            line = values.lines[name]
            if isinstance(value, (Tag, DataBlock, Member)):
                if name in self.declarations:
                    raise DeclarationError(f"{self._filename}, line {line}: {name!r} is declared twice")
                self.declarations[name] = value
            elif isinstance(value, StructType) and value.name in ("UDT", "Struct"):
                value.name = name
                self.types[name] = value
            elif isinstance(value, (ElementaryType, StringType, StructType)):
                raise DeclarationError(
                    f"{self._filename}, line {line}: {name} = {value.name} declares no tag; write "
                    f"{name} = {value.name}() for a symbolic tag or {name} = Tag('%M10.0', {value.name}) "
                    f"for an addressed one"
                )
        self._check_size(values.lines)
        for name, value in values.bindings.items():
            self.tasks[name] = self._task(name, value, values.labels, values.lines[name])
        for name in self.functions:
            if is_ob_name(name) and name not in self.tasks:
                self.tasks[name] = self._task(name, NetworkRef(name), values.labels, self.functions[name].lineno)
        if "OB1" not in self.tasks:  # a program of interrupts only is valid; one of no OB, or an ob1, is not
            message = no_ob1_message(self._filename, self._tree, bool(self.tasks))
            if message:
                raise NoOB1Error(message)

    def _check_size(self, lines: Mapping[str, int]) -> None:
        """Refuse declarations that would fill the host's memory (``Array(0, 100000000, Int)``)."""
        total = 0
        for name, decl in self.declarations.items():
            members = decl.members.values() if isinstance(decl, DataBlock) else [decl]
            total += sum(value_count(m.type) if isinstance(m, Member) else 1 for m in members)
            if total > MAX_VALUES:
                raise DeclarationError(
                    f"{self._filename}, line {lines.get(name, '?')}: {name} brings the program to {total} "
                    f"values; a program may declare at most {MAX_VALUES} (an S7-1200's work memory holds far fewer)"
                )

    def _task(self, name: str, value: Any, labels: dict[str, str], line: int) -> TaskSpec:
        where = f"{self._filename}, line {line}"
        try:
            kind, priority = task_kind(name)
        except ProgramError as exc:
            raise ProgramError(f"{where}: {exc}") from None
        period, phase, duration = None, 0, None
        if isinstance(value, CyclicInterrupt):
            if kind != "interrupt":
                raise ProgramError(f"{where}: {name} is not a cyclic-interrupt OB; CyclicInterrupt is for OB30..OB38")
            try:
                period = None if value.period is None else to_ns(value.period, f"{name} period")
                phase = to_ns(value.phase, f"{name} phase")
                duration = None if value.duration is None else to_ns(value.duration, f"{name} duration")
            except PlcError as exc:
                raise type(exc)(f"{where}: {exc}") from None
            if period is not None and period <= 0:
                raise ProgramError(f"{where}: {name} needs a positive period, e.g. period='1s'")
            if not isinstance(value.priority, int) or isinstance(value.priority, bool):
                raise ProgramError(f"{where}: {name} priority must be a whole number, e.g. priority=8")
            priority = value.priority
            value = value.networks
        funcs = list(value) if isinstance(value, list | tuple) else [value]
        networks = []
        seen_labels: dict[str, str] = {}
        for func in funcs:
            node = self.functions.get(func) if isinstance(func, NetworkRef) else None
            if node is None:
                raise ProgramError(f"{where}: {name} must be a network function or a list of them, got {func!r}")
            fname = node.name
            if len(node.args.args) != 1 or node.args.kwonlyargs or node.args.posonlyargs or node.args.defaults:
                raise ProgramError(
                    f"{self._filename}, line {node.lineno}: network {fname} must take exactly one parameter, "
                    f"the tags (def {fname}(t): ...)"
                )
            lab = labels.get(fname)
            if lab is not None:
                if lab in seen_labels:
                    raise ProgramError(f"{where}: label {lab!r} is used twice in {name}; a label is unique per block")
                seen_labels[lab] = fname
            doc = ast.get_docstring(node) or ""
            networks.append(NetworkSpec(fname, doc.strip().splitlines()[0] if doc else fname, lab, node.lineno))
        if len(seen_labels) > MAX_LABELS_S7_1200:
            raise ProgramError(
                f"{where}: {name} has {len(seen_labels)} labels; an S7-1200 block allows {MAX_LABELS_S7_1200}"
            )
        return TaskSpec(name, kind, networks, period, phase, priority, duration, ob_number(name))

    def absolute_addresses(self) -> list[str]:
        """The absolute addresses (``"%M10.0"``) the program's text names, declared or not."""
        found = []
        for node in ast.walk(self._tree):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value.strip().startswith("%"):
                try:
                    parse_address(node.value)
                except PlcError:
                    continue
                found.append(node.value)
        return found

    # -- phase 2: compile against a tag table -----------------------------------------------------

    def declare_into(self, table: TagTable) -> TagTable:
        """A copy of ``table`` with this program's declarations added."""
        merged = table.copy()
        for name, decl in self.declarations.items():
            if name in merged:
                prev = merged[name]
                raise DeclarationError(
                    f"{self.filename}: {name!r} is already declared by {prev.source or 'the exercise'}; "
                    f"use the existing tag or choose another name"
                )
            try:
                merged.add(name, decl, source=self.filename)
            except PlcError as exc:
                line = self._declaration_lines.get(name, "?")
                raise type(exc)(f"{self.filename}, line {line}: {name}: {exc}") from None
        return merged

    def compile(
        self,
        table: TagTable,
        aliased: frozenset[str] = frozenset(),
        *,
        strict_timers: bool = True,
        family: str = "S7-1200",
        input_writes: str = "warn",
    ) -> CompiledProgram:
        """Compile against a tag table that already holds this program's declarations.

        A store into an input tag (%I) is a warning, or with ``input_writes="error"`` a ProgramError.

        The result is kept for an equal table and options: a grade downloads the same program once per
        scenario, and compiling a large one costs a tenth of a second each time. Each call gets its
        own warnings list and timer set (the code and the analysis are never changed once built)."""
        key = (table.entries, aliased, strict_timers, family, input_writes)
        for known, compiled in self._compiled:
            if known == key:
                return replace(compiled, warnings=list(compiled.warnings), inert_timers=set(compiled.inert_timers))
        compiled = self._compile(table, aliased, strict_timers, family, input_writes)
        self._compiled = [*self._compiled[-(COMPILED_KEPT - 1) :], ((dict(table.entries), *key[1:]), compiled)]
        return replace(compiled, warnings=list(compiled.warnings), inert_timers=set(compiled.inert_timers))

    def _compile(
        self, table: TagTable, aliased: frozenset[str], strict_timers: bool, family: str, input_writes: str
    ) -> CompiledProgram:
        root_params = {}
        for task in self.tasks.values():
            for net in task.networks:
                root_params[net.name] = self.functions[net.name].args.args[0].arg
        typing = Typing(table.schema(), aliased, self.filename, root_params)
        analysis = analyse(self.tree, typing)
        tree = runtime_module(self._tree)
        merged: dict[str, str] = {}
        for task in self.tasks.values():
            funcs = [self.functions[n.name] for n in task.networks]
            if len(funcs) > 1 and sum(len(f.body) for f in funcs) <= MAX_MERGED_STATEMENTS:
                combined = merge_networks(funcs, task.name, root_params)
                if combined is not None:
                    tree.body.append(combined)
                    typing.root_params[combined.name] = MERGED_ROOT
                    merged[task.name] = combined.name
        rewriter = StoreRewriter(typing)
        tree = ast.fix_missing_locations(rewriter.visit(tree))
        for stmt in tree.body:
            if isinstance(stmt, ast.FunctionDef) and stmt.name in merged.values():
                read_root_directly(stmt, typing.root.members)
        code = compile(tree, self.filename, "exec")
        warnings = list(analysis.warnings)
        for line, name in self._input_stores(table, root_params):
            message = (
                f"{self._filename}, line {line}: the program writes the input {name} "
                f"({table[name].address}); an input is what the sensor delivers, the program should only read it"
            )
            if input_writes == "error":
                raise ProgramError(message)
            warnings.append(message + " (the write changes only the program's process image, not the plant)")
        self._check_jumps(analysis)
        if family == "S7-1200":
            for node in ast.walk(self.tree):
                if isinstance(node, ast.Name) and node.id in ("SCALE", "UNSCALE"):
                    raise ProgramError(
                        f"{self.filename}, line {node.lineno}: {node.id} is not available on the S7-1200 "
                        f"(textbook §3.3); use NORM_X and SCALE_X"
                    )
        inert: set[str] = set()
        for path in sorted(analysis.unused_timers()):
            warnings.append(
                f"{self.filename}: timer {path} runs but its Q and ET are used nowhere; on an S7-1200 such a "
                f"timer does not start (textbook §3.6.1, Fig. 3.197)"
                + ("" if strict_timers else "; the CPU runs it anyway (textbook_strict_timers=False)")
            )
            if strict_timers:
                inert.add(path)
        return CompiledProgram(self, code, analysis, rewriter.coercers, inert, warnings, merged)

    def link(self, target: LinkTarget) -> LoadedProgram:
        """Compile against the CPU's table and run the code once to define the networks (the front end's
        half of a download): the loaded program the runtime runs."""
        cfg = target.config
        compiled = self.compile(
            target.table,
            target.aliased,
            strict_timers=cfg.textbook_strict_timers,
            family=cfg.family,
            input_writes=cfg.input_writes,
        )
        namespace = runtime_namespace(compiled, target.instructions)
        exec(compiled.code, namespace)
        analysis = compiled.analysis
        tasks = []
        for spec in self.tasks.values():
            networks = []
            used: set[str] = set()
            for net in spec.networks:
                node = self.functions[net.name]
                networks.append(LoadedNetwork(namespace[net.name], (node.lineno, node.end_lineno or 0)))
                used |= analysis.tags_used(net.name)
            merged = compiled.merged.get(spec.name)
            tasks.append(LoadedTask(spec, networks, namespace[merged] if merged else None, frozenset(used)))
        facts = analysis.functions.values()
        return LoadedProgram(
            self.filename,
            tasks,
            ProgramFacts(
                frozenset().union(*(f.reads for f in facts)),
                frozenset().union(*(f.writes for f in facts)),
                frozenset().union(*(f.calls for f in facts)),
            ),
            compiled.warnings,
            compiled.inert_timers,
            compiled,
        )

    def _input_stores(self, table: TagTable, root_params: Mapping[str, str]) -> list[tuple[int, str]]:
        """(line, tag) of every store into an input tag: t.IN = ..., t["IN"] = ..., MOVE(x, "IN")."""
        inputs = {e.name for e in table if e.address is not None and e.address.area == "I"}
        found: list[tuple[int, str]] = []
        for func in self.functions.values():
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

    def _check_jumps(self, analysis: Analysis) -> None:
        for task in self.tasks.values():
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
                            f"{self.filename}, line {line}: JMP to {target!r}, but no network of {task.name} "
                            f"carries that label{known}"
                        )

    def __repr__(self) -> str:
        return f"<Program {self.filename}: {', '.join(self.tasks) or 'no tasks'}>"


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


def no_ob1_message(filename: str, tree: ast.Module, has_tasks: bool) -> str:
    """Why a program has no OB1, and how to write one (a lower-case ``def ob1`` is named); empty when a
    program without OB1 is fine (it has other OBs and nothing that looks like a misspelt OB1)."""
    near = [
        s
        for s in tree.body
        if isinstance(s, ast.FunctionDef | ast.Assign)
        and any(n.upper() == "OB1" for n in ([s.name] if isinstance(s, ast.FunctionDef) else _target_names(s)))
    ]
    if near:
        wrong = near[0].name if isinstance(near[0], ast.FunctionDef) else _target_names(near[0])[0]
        return (
            f"{filename}, line {near[0].lineno}: no OB1: {wrong} is not OB1 (the name is case-sensitive); "
            f"did you mean OB1? Write def OB1(t): ... or OB1 = [network, ...]"
        )
    if has_tasks:
        return ""
    what = "the file holds no code (it is empty or only comments)" if not tree.body else "nothing is bound to OB1"
    return (
        f"{filename}: no OB1: {what}. The program cycle OB1 runs the networks; write "
        f"def OB1(t): ... for one network, or define networks (def start_belt(t): ...) and list them: "
        f"OB1 = [start_belt, stop_belt]"
    )


def _target_text(node: ast.expr, root: str) -> str | None:
    """The tag a MOVE output names: ``"LED"`` or ``t.LED``."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == root:
        return node.attr
    return None


def _target_names(stmt: ast.Assign) -> list[str]:
    return [t.id for t in stmt.targets if isinstance(t, ast.Name)]


def safe_builtins() -> dict[str, Any]:
    """The builtins a program may use."""
    allowed = {name: getattr(builtins, name) for name in ALLOWED_BUILTINS if hasattr(builtins, name)}
    allowed["range"] = bounded_range
    return allowed


def runtime_namespace(compiled: CompiledProgram, bound: Mapping[str, Any]) -> dict[str, Any]:
    """The names a compiled program runs with: types, instructions, conversions, constants and ``bound``.

    Nothing in it lets a network change what another program sees: the types' members are read-only,
    attribute stores go through :data:`~plcsim.frontends.python.rewrite.STORE`, and declaration-only names
    are absent."""
    namespace: dict[str, Any] = {"__builtins__": safe_builtins(), **TYPE_NAMES, "TIME": TIME, **PURE_INSTRUCTIONS}
    for dtype in plc_types.ELEMENTARY.values():
        namespace[coerce_name(dtype)] = dtype.coerce
    namespace.update(SAFE_FUNCTIONS)
    namespace.update(compiled.program.constants)
    namespace.update(bound)
    missing = (CPU_BOUND | {TICK, STORE, FB_STORE, ROOT_GUARD}) - set(namespace)
    if missing:
        raise ProgramError(f"internal: the CPU did not provide {sorted(missing)}")
    return namespace


__all__ = [
    "Program",
    "CyclicInterrupt",
    "label",
    "TaskSpec",
    "NetworkSpec",
    "CompiledProgram",
    "Array",
    "Struct",
    "UDT",
    "TIME",
    "BOOL_RESULTS",
]
