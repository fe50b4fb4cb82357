"""Linking a compiled program into one CPU: the namespace its code runs in, and the loaded program.

The front end's half of a download. The namespace holds the data types, the instructions, the type
conversions, the bounded operators, the program's constants and the instructions the CPU bound to
itself; the runtime's hooks (:class:`~plcsim.controllers.loaded.RuntimeHooks`, named by the runtime) are
bound here to the names the rewrite writes into the code (:data:`~plcsim.frontends.python.rewrite.TICK`
...), so that the code calls them directly, with nothing in between.
"""

from __future__ import annotations

import builtins
from array import array
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from plcsim.controllers.loaded import LinkTarget, LoadedNetwork, LoadedProgram, LoadedTask, ProgramFacts, RuntimeHooks
from plcsim.controllers.s7.instructions import CPU_BOUND, PURE_INSTRUCTIONS
from plcsim.core.errors import ProgramError
from plcsim.frontends.python.inline import HELPERS
from plcsim.frontends.python.names import TIME, TYPE_NAMES
from plcsim.frontends.python.pipeline import CompiledProgram
from plcsim.frontends.python.rewrite import FB_STORE, REAL_CELL, ROOT_GUARD, STORE, TICK, coerce_name
from plcsim.frontends.python.safe_math import SAFE_FUNCTIONS, bounded_range
from plcsim.frontends.python.subset import ALLOWED_BUILTINS
from plcsim.tags import types as plc_types

if TYPE_CHECKING:
    from plcsim.frontends.python.program import Program


def link_program(program: Program, target: LinkTarget) -> LoadedProgram:
    """Compile against the CPU's table and run the code once to define the networks (the front end's
    half of a download): the loaded program the runtime runs."""
    cfg = target.config
    compiled = program.compile(
        target.table,
        target.aliased,
        strict_timers=cfg.textbook_strict_timers,
        family=cfg.family,
        input_writes=cfg.input_writes,
    )
    namespace = runtime_namespace(compiled, target.instructions, target.hooks)
    exec(compiled.code, namespace)
    analysis = compiled.analysis
    tasks = []
    for spec in program.tasks.values():
        networks = []
        used: set[str] = set()
        for net in spec.networks:
            node = program.functions[net.name]
            networks.append(LoadedNetwork(namespace[net.name], (node.lineno, node.end_lineno or 0)))
            used |= analysis.tags_used(net.name)
        merged = compiled.merged.get(spec.name)
        tasks.append(LoadedTask(spec, networks, namespace[merged] if merged else None, frozenset(used)))
    facts = analysis.functions.values()
    return LoadedProgram(
        program.filename,
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


def safe_builtins() -> dict[str, Any]:
    """The builtins a program may use."""
    allowed = {name: getattr(builtins, name) for name in ALLOWED_BUILTINS if hasattr(builtins, name)}
    allowed["range"] = bounded_range
    return allowed


def runtime_namespace(
    compiled: CompiledProgram, instructions: Mapping[str, Any], hooks: RuntimeHooks
) -> dict[str, Any]:
    """The names a compiled program runs with: types, instructions, conversions, constants, the CPU's
    ``instructions`` and its ``hooks`` under the names the rewrite calls them by.

    Nothing in it lets a network change what another program sees: the types' members are read-only,
    attribute stores go through :data:`~plcsim.frontends.python.rewrite.STORE`, and declaration-only names
    are absent."""
    namespace: dict[str, Any] = {"__builtins__": safe_builtins(), **TYPE_NAMES, "TIME": TIME, **PURE_INSTRUCTIONS}
    for dtype in plc_types.ELEMENTARY.values():
        namespace[coerce_name(dtype)] = dtype.coerce
    namespace[REAL_CELL] = array("f", [0.0])  # this program's own: only its code writes and reads it
    namespace.update(SAFE_FUNCTIONS)
    namespace.update(compiled.program.constants)
    namespace.update(instructions)
    namespace.update(HELPERS)
    namespace[TICK] = hooks.tick
    namespace[ROOT_GUARD] = hooks.tags_of
    namespace[STORE] = hooks.store
    namespace[FB_STORE] = hooks.store_member
    missing = CPU_BOUND - set(namespace)
    if missing:
        raise ProgramError(f"internal: the CPU did not provide {sorted(missing)}")
    return namespace
