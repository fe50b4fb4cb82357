"""Issue 11: the seams stay where they were cut. The trace table knows none of its exporters (they import
it, :mod:`plcsim.trace` puts them on it as methods); the S7 CPU names no instruction (it binds every
description that needs a CPU alike, so a new one reaches a program without an edit to the CPU)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from plcsim import CPU, Tag, instructions
from plcsim.instructions import FUNCTIONS, Function
from plcsim.loaded import LinkTarget, LoadedProgram
from plcsim.tags import TagTable
from plcsim.trace import Trace, TraceTable

PLCSIM = Path(__file__).resolve().parents[1] / "plcsim"
EXPORTERS = {"plcsim.trace_plot", "plcsim.trace_rerun"}


def imported(module: str) -> set[str]:
    """Every plcsim module ``module`` imports, at its top or inside a function."""
    tree = ast.parse((PLCSIM / f"{module}.py").read_text(encoding="utf-8"))
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            found.add(node.module)
            found.update(f"{node.module}.{a.name}" for a in node.names)
        elif isinstance(node, ast.Import):
            found.update(a.name for a in node.names)
    return {name for name in found if name.startswith("plcsim")}


def test_the_trace_table_imports_neither_its_exporters_nor_the_facade():
    assert imported("trace_table") & (EXPORTERS | {"plcsim.trace"}) == set()


@pytest.mark.parametrize("exporter", sorted(EXPORTERS))
def test_an_exporter_imports_the_table_and_never_the_facade(exporter: str):
    uses = imported(exporter.removeprefix("plcsim."))
    assert "plcsim.trace_table" in uses
    assert not {name for name in uses if name == "plcsim.trace" or name.startswith("plcsim.trace.")}


def test_the_facade_s_methods_export_what_the_table_holds(tmp_path: Path):
    trace = Trace(["LED"], kinds={"LED": "output"}, types={"LED": "bool"})
    for k in range(4):
        trace.add_row(k * 1_000_000, (k + 1) * 1_000_000, 1, (k % 2 == 1,))
    assert isinstance(trace, TraceTable) and type(trace.of_task("OB1")) is Trace
    loaded = Trace.load(trace.save(tmp_path / "run.npz"))
    assert type(loaded) is Trace and loaded.digest() == trace.digest()
    diagram = trace.plot(["LED"])
    assert diagram._repr_png_().startswith(b"\x89PNG")


BOUND_BY_NAME = {"make_move", "make_rd_loc_t", "make_edge_instructions", "bit_resolver"}


def test_the_s7_cpu_names_no_instruction():
    tree = ast.parse((PLCSIM / "cpu.py").read_text(encoding="utf-8"))
    names = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
    names |= {a.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) for a in node.names}
    strings = {node.value for node in ast.walk(tree) if isinstance(node, ast.Constant) and isinstance(node.value, str)}
    assert names & BOUND_BY_NAME == set()
    assert strings & {f.name for f in FUNCTIONS.values() if f.needs_cpu} == set()


class Capture:
    """A front end that links nothing and keeps what the CPU offered it."""

    filename = "capture.il"

    def declare_into(self, table: TagTable) -> TagTable:
        return table.copy()

    def absolute_addresses(self) -> list[str]:
        return []

    def link(self, target: LinkTarget) -> LoadedProgram:
        self.target = target
        return LoadedProgram(self.filename, [])


def test_a_new_instruction_that_needs_the_cpu_is_bound_from_its_description_alone(monkeypatch):
    echo = Function("ECHO", bind=lambda host: lambda: host.resolve_path("LED"))
    monkeypatch.setitem(FUNCTIONS, "ECHO", echo)
    program = Capture()
    cpu = CPU(tags={"LED": Tag("%Q0.0")}, program=program)
    bound = program.target.instructions
    assert set(bound) >= {"ECHO", "P", "N", "MOVE", "RD_LOC_T"}
    assert bound["ECHO"]() == (cpu.t, "LED")
    assert set(instructions.bind_instructions(cpu)) == {f.name for f in FUNCTIONS.values() if f.needs_cpu}
