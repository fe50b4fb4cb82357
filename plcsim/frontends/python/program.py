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

:class:`Program` reads a file into its declarations and tasks; the names it may use are
:mod:`plcsim.frontends.python.names`, compiling it against a tag table is
:mod:`plcsim.frontends.python.pipeline` and linking it into a CPU :mod:`plcsim.frontends.python.link`.

>>> p = Program.from_source("def OB1(t):\\n    t.LED = t.TLACIDLO\\n")
>>> [n.name for n in p.tasks["OB1"].networks]
['OB1']
"""

from __future__ import annotations

import ast
import inspect
import textwrap
from collections.abc import Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

from plcsim.controllers.loaded import LinkTarget, LoadedProgram, NetworkSpec, TaskSpec
from plcsim.controllers.s7.profile import is_ob_name, ob_number, task_kind
from plcsim.core.errors import DeclarationError, NoOB1Error, PlcError, ProgramError, SubsetError
from plcsim.core.literals import to_ns
from plcsim.frontends.python.link import link_program
from plcsim.frontends.python.module_level import NetworkRef, evaluate_module
from plcsim.frontends.python.names import DECLARATION_NAMES, DECLARATION_ONLY, PROGRAM_NAMES, CyclicInterrupt
from plcsim.frontends.python.pipeline import CompiledProgram, compile_program
from plcsim.frontends.python.subset import ALLOWED_BUILTINS, check_subset, parse
from plcsim.frontends.text import read_program_text
from plcsim.tags.memory import parse_address
from plcsim.tags.table import DataBlock, Tag, TagTable
from plcsim.tags.types import ElementaryType, Member, StringType, StructType, value_count

MAX_LABELS_S7_1200 = 32
MAX_VALUES = 1_000_000
"""The most values a program may declare (an S7-1200 has 50..150 KB of work memory: far fewer)."""
COMPILED_KEPT = 4
"""How many compilations (tag tables and options) a program keeps for its next downloads."""


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
        key = (table.entries, table.aliases, aliased, strict_timers, family, input_writes)
        for known, compiled in self._compiled:
            if known == key:
                return replace(compiled, warnings=list(compiled.warnings), inert_timers=set(compiled.inert_timers))
        compiled = compile_program(self, table, aliased, strict_timers, family, input_writes)
        kept = (dict(table.entries), dict(table.aliases), *key[2:])
        self._compiled = [*self._compiled[-(COMPILED_KEPT - 1) :], (kept, compiled)]
        return replace(compiled, warnings=list(compiled.warnings), inert_timers=set(compiled.inert_timers))

    def link(self, target: LinkTarget) -> LoadedProgram:
        """Compile against the CPU's table and run the code once to define the networks (the front end's
        half of a download): the loaded program the runtime runs (see :func:`link_program`)."""
        return link_program(self, target)

    def __repr__(self) -> str:
        return f"<Program {self.filename}: {', '.join(self.tasks) or 'no tasks'}>"


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


def _target_names(stmt: ast.Assign) -> list[str]:
    return [t.id for t in stmt.targets if isinstance(t, ast.Name)]


__all__ = ["Program", "no_ob1_message"]
