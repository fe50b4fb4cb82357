"""How a user program is written and bound to the CPU's tasks.

A program is a Python file in the PLC subset. Module-level assignments declare the program's own
tags and instances; functions are networks; names ``OB1``, ``OB30`` ... ``OB38`` and ``OB100`` bind
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
import re
import textwrap
import traceback
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plcsim import types as plc_types
from plcsim.compiler import (
    ALLOWED_BUILTINS,
    FB_STORE,
    MERGED_ROOT,
    STORE,
    TICK,
    Analysis,
    StoreRewriter,
    Typing,
    analyse,
    check_subset,
    coerce_name,
    merge_networks,
    parse,
)
from plcsim.errors import DeclarationError, PlcError, ProgramError
from plcsim.instructions import BOOL_RESULTS, CPU_BOUND, FB_TYPES, PURE_INSTRUCTIONS
from plcsim.literals import time_ms, to_ns
from plcsim.tags import DB, DataBlock, Tag, TagTable
from plcsim.types import ArrayType, DataType, ElementaryType, Member, StringType, StructType

MAX_LABELS_S7_1200 = 32
DEFAULT_INTERRUPT_PERIOD = "100ms"
DEFAULT_INTERRUPT_PRIORITY = 8


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
    period: str | int = DEFAULT_INTERRUPT_PERIOD
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


DECLARATION_NAMES: dict[str, Any] = {
    **{t.name: t for t in plc_types.ELEMENTARY.values()},
    "TOD": plc_types.TimeOfDay,
    "String": plc_types.String,
    "DTL": plc_types.DTL,
    "Array": Array,
    "Struct": Struct,
    "UDT": UDT,
    "Tag": Tag,
    "DB": DB,
    "CyclicInterrupt": CyclicInterrupt,
    "label": label,
    "TIME": TIME,
    **FB_TYPES,
}
"""Names a program may use at module level to declare tags, DBs, instances and tasks."""

PROGRAM_NAMES = set(DECLARATION_NAMES) | set(PURE_INSTRUCTIONS) | CPU_BOUND
"""Every name a program sees besides its own and the allowed builtins."""


@dataclass(frozen=True)
class NetworkSpec:
    """One network: the function that implements it, its title and label."""

    name: str
    title: str
    label: str | None
    lineno: int


@dataclass
class TaskSpec:
    """One OB of the program: kind (``cyclic``, ``interrupt``, ``startup``), networks and timing."""

    name: str
    kind: str
    networks: list[NetworkSpec]
    period_ns: int = 0
    phase_ns: int = 0
    priority: int = 1
    duration_ns: int | None = None


_OB_RE = re.compile(r"^OB(\d+)$")


def task_kind(name: str) -> tuple[str, int]:
    """Kind and default priority of an OB by its number (S7-1200 numbering)."""
    number = int(_OB_RE.match(name).group(1))  # type: ignore[union-attr]
    if number == 1:
        return "cyclic", 1
    if 30 <= number <= 38:
        return "interrupt", DEFAULT_INTERRUPT_PRIORITY
    if number == 100:
        return "startup", 1
    raise ProgramError(
        f"{name} is not supported: use OB1 (program cycle), OB30..OB38 (cyclic interrupts) or OB100 (startup)"
    )


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
    """A user program: its declarations and its tasks, checked against the PLC subset of Python."""

    def __init__(
        self, source: str, filename: str = "<program>", *, extra_declarations: Mapping[str, Any] | None = None
    ):
        self.source = source
        self.filename = filename
        self.tree = parse(source, filename)
        check_subset(self.tree, filename, PROGRAM_NAMES)
        self.functions = {s.name: s for s in self.tree.body if isinstance(s, ast.FunctionDef)}
        self.declarations: dict[str, Any] = dict(extra_declarations or {})
        self.types: dict[str, StructType] = {}
        self.tasks: dict[str, TaskSpec] = {}
        self._collect()

    # -- constructors -------------------------------------------------------------------------

    @classmethod
    def from_source(cls, source: str, filename: str = "<program>") -> Program:
        """Load a program from text."""
        return cls(textwrap.dedent(source), filename)

    @classmethod
    def from_file(cls, path: str | Path) -> Program:
        """Load a program from a ``.py`` file (errors name the file and line)."""
        path = Path(path)
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as exc:
            raise ProgramError(f"cannot read program {path}: {exc.strerror}") from None
        return cls(text, str(path))

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
        namespace = declaration_namespace()
        try:
            exec(compile(self.tree, self.filename, "exec"), namespace)
        except PlcError as exc:
            raise type(exc)(f"{self.filename}, line {_error_line(exc, self.filename)}: {exc}") from None
        except Exception as exc:  # noqa: BLE001 - any error in a student's declarations is reported
            raise ProgramError(
                f"{self.filename}, line {_error_line(exc, self.filename)}: {type(exc).__name__}: {exc}"
            ) from None
        labels = {name: f.plc_label for name, f in namespace.items() if hasattr(f, "plc_label")}
        self._declaration_lines = {
            t.id: stmt.lineno
            for stmt in self.tree.body
            if isinstance(stmt, ast.Assign)
            for t in stmt.targets
            if isinstance(t, ast.Name)
        }
        for name in _assigned_in_order(self.tree):
            value = namespace.get(name)
            if _OB_RE.match(name):
                self.tasks[name] = self._task(name, value, labels)
            elif isinstance(value, (Tag, DataBlock, Member)):
                if name in self.declarations:
                    raise DeclarationError(f"{self.filename}: {name!r} is declared twice")
                self.declarations[name] = value
            elif isinstance(value, StructType) and value.name in ("UDT", "Struct"):
                value.name = name
                self.types[name] = value
            elif isinstance(value, (ElementaryType, StringType, StructType)):
                raise DeclarationError(
                    f"{self.filename}: {name} = {value.name} declares no tag; write {name} = {value.name}() "
                    f"for a symbolic tag or {name} = Tag('%M10.0', {value.name}) for an addressed one"
                )
        for name in self.functions:
            if _OB_RE.match(name) and name not in self.tasks:
                self.tasks[name] = self._task(name, namespace[name], labels)

    def _task(self, name: str, value: Any, labels: dict[str, str]) -> TaskSpec:
        kind, priority = task_kind(name)
        period, phase, duration = 0, 0, None
        if isinstance(value, CyclicInterrupt):
            if kind != "interrupt":
                raise ProgramError(
                    f"{self.filename}: {name} is not a cyclic-interrupt OB; CyclicInterrupt is for OB30..OB38"
                )
            period = to_ns(value.period, f"{name} period")
            phase = to_ns(value.phase, f"{name} phase")
            if period <= 0:
                raise ProgramError(f"{self.filename}: {name} needs a positive period, e.g. period='1s'")
            priority = value.priority
            duration = None if value.duration is None else to_ns(value.duration, f"{name} duration")
            value = value.networks
        elif kind == "interrupt":
            period = to_ns(DEFAULT_INTERRUPT_PERIOD)
        funcs = list(value) if isinstance(value, list | tuple) else [value]
        networks = []
        seen_labels: dict[str, str] = {}
        for func in funcs:
            fname = getattr(func, "__name__", None)
            node = self.functions.get(fname) if fname else None
            if node is None:
                raise ProgramError(
                    f"{self.filename}: {name} must be a network function or a list of them, got {func!r}"
                )
            if len(node.args.args) != 1:
                raise ProgramError(
                    f"{self.filename}, line {node.lineno}: network {fname} must take exactly one parameter, "
                    f"the tags (def {fname}(t): ...)"
                )
            lab = labels.get(fname)
            if lab is not None:
                if lab in seen_labels:
                    raise ProgramError(
                        f"{self.filename}: label {lab!r} is used twice in {name}; a label is unique per block"
                    )
                seen_labels[lab] = fname
            doc = ast.get_docstring(node) or ""
            networks.append(NetworkSpec(fname, doc.strip().splitlines()[0] if doc else fname, lab, node.lineno))
        if len(seen_labels) > MAX_LABELS_S7_1200:
            raise ProgramError(
                f"{self.filename}: {name} has {len(seen_labels)} labels; an S7-1200 block allows {MAX_LABELS_S7_1200}"
            )
        return TaskSpec(name, kind, networks, period, phase, priority, duration)

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
    ) -> CompiledProgram:
        """Compile against a tag table that already holds this program's declarations."""
        root_params = {}
        for task in self.tasks.values():
            for net in task.networks:
                root_params[net.name] = self.functions[net.name].args.args[0].arg
        typing = Typing(table.schema(), aliased, self.filename, root_params)
        analysis = analyse(self.tree, typing)
        tree = ast.parse(self.source, self.filename)
        merged: dict[str, str] = {}
        for task in self.tasks.values():
            funcs = [self.functions[n.name] for n in task.networks]
            if len(funcs) > 1:
                combined = merge_networks(funcs, task.name, root_params)
                if combined is not None:
                    tree.body.append(combined)
                    typing.root_params[combined.name] = MERGED_ROOT
                    merged[task.name] = combined.name
        rewriter = StoreRewriter(typing)
        tree = ast.fix_missing_locations(rewriter.visit(tree))
        code = compile(tree, self.filename, "exec")
        warnings = list(analysis.warnings)
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


def _assigned_in_order(tree: ast.Module) -> list[str]:
    names: list[str] = []
    for stmt in tree.body:
        targets: list[ast.expr] = []
        if isinstance(stmt, ast.Assign):
            targets = stmt.targets
        elif isinstance(stmt, ast.AnnAssign):
            targets = [stmt.target]
        for target in targets:
            if isinstance(target, ast.Name) and target.id not in names:
                names.append(target.id)
    return names


def _error_line(exc: BaseException, filename: str) -> int | str:
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        if frame.filename == filename:
            return frame.lineno or "?"
    return "?"


def _not_here(name: str) -> Callable[..., Any]:
    def stub(*args: Any, **kwargs: Any) -> Any:
        raise ProgramError(f"{name} can only run inside a network, not while the program is declared")

    return stub


def safe_builtins() -> dict[str, Any]:
    """The builtins a program may use."""
    return {name: getattr(builtins, name) for name in ALLOWED_BUILTINS if hasattr(builtins, name)}


def declaration_namespace() -> dict[str, Any]:
    """The names visible while a program's module level runs (declarations only)."""
    namespace: dict[str, Any] = {"__builtins__": safe_builtins(), **DECLARATION_NAMES, **PURE_INSTRUCTIONS}
    for name in CPU_BOUND:
        namespace[name] = _not_here(name)
    namespace[TICK] = _module_tick()
    namespace[STORE] = _not_here("storing into a tag")
    namespace[FB_STORE] = _not_here("storing into an instance")
    return namespace


def _module_tick(budget: int = 1_000_000) -> Callable[[], None]:
    count = [0]

    def tick() -> None:
        count[0] += 1
        if count[0] > budget:
            raise ProgramError("a loop at module level runs too long; declarations must not loop")

    return tick


def runtime_namespace(compiled: CompiledProgram, bound: Mapping[str, Any]) -> dict[str, Any]:
    """The names a compiled program runs with: declarations, instructions, conversions and ``bound``."""
    namespace: dict[str, Any] = {"__builtins__": safe_builtins(), **DECLARATION_NAMES, **PURE_INSTRUCTIONS}
    namespace["label"] = lambda name: lambda func: func
    for dtype in plc_types.ELEMENTARY.values():
        namespace[coerce_name(dtype)] = dtype.coerce
    namespace.update(bound)
    missing = (CPU_BOUND | {TICK, STORE, FB_STORE}) - set(namespace)
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
