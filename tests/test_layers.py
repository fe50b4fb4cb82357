"""The house stays readable: plcsim's packages import only the packages below them, and no module of
plcsim takes part in an import circle, counting imports deferred into a function (an import under
``if TYPE_CHECKING:`` is for the type checker alone and does not count). Each failure names the import.

The order, bottom to top, is the one ``docs/architecture.md`` draws; the seams inside a package that the
layer order cannot see (the trace table knows none of its exporters; the S7 CPU names no instruction)
are tested here too.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import pytest

from plcsim import CPU, Tag
from plcsim.controllers.loaded import LinkTarget, LoadedProgram
from plcsim.controllers.s7 import instructions
from plcsim.controllers.s7.instructions import FUNCTIONS, Function
from plcsim.tags import TagTable
from plcsim.trace import Trace, TraceTable

PLCSIM = Path(__file__).resolve().parents[1] / "plcsim"

LAYERS = [
    "core",
    "tags",
    "plant",
    "trace",
    "scenario",
    "controllers",
    "frontends",
    "ladder",
    "sim",
    "check",
    "exercise",
    "grading",
    "mutate",
    "apps",
]
"""plcsim's packages, bottom to top: each imports only those before it in this list (and itself)."""

DOORS = {"plcsim", "plcsim.__main__"}
"""The modules at the top of ``plcsim/``: they import whatever they re-export or start, and nothing of
plcsim imports them."""


@dataclass(frozen=True)
class Import:
    """One import statement of a plcsim module, resolved to the plcsim module it loads."""

    source: str
    target: str
    line: int

    def __str__(self) -> str:
        path = module_path(self.source).relative_to(PLCSIM.parent)
        return f"{path}:{self.line}: {self.source} imports {self.target}"


def module_path(name: str) -> Path:
    base = PLCSIM.parent.joinpath(*name.split("."))
    return base / "__init__.py" if base.is_dir() else base.with_suffix(".py")


def modules() -> list[str]:
    names = []
    for path in sorted(PLCSIM.rglob("*.py")):
        parts = list(path.relative_to(PLCSIM.parent).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        names.append(".".join(parts))
    return names


MODULES = set(modules())


def _resolve(module: str, imported: str, names: list[str]) -> Iterator[str]:
    """The plcsim modules ``from imported import names`` loads: a name that is a submodule counts as one."""
    if imported not in MODULES:
        return
    for name in names:
        if f"{imported}.{name}" in MODULES:
            yield f"{imported}.{name}"
    if any(f"{imported}.{name}" not in MODULES for name in names):
        yield imported


def imports_of(module: str) -> Iterator[Import]:
    """Every import of ``module`` that loads a plcsim module, at its top or inside a function."""
    tree = ast.parse(module_path(module).read_text(encoding="utf-8"))
    is_package = module_path(module).name == "__init__.py"

    def visit(node: ast.AST) -> Iterator[Import]:
        for child in ast.iter_child_nodes(node):
            if isinstance(child, ast.If) and "TYPE_CHECKING" in ast.unparse(child.test):
                yield from (i for stmt in child.orelse for i in visit_one(stmt))
                continue
            yield from visit_one(child)

    def visit_one(node: ast.AST) -> Iterator[Import]:
        if isinstance(node, ast.Import):
            for alias in node.names:
                if alias.name in MODULES:
                    yield Import(module, alias.name, node.lineno)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                package = module.split(".") if is_package else module.split(".")[:-1]
                package = package[: len(package) - (node.level - 1)]
                base = ".".join(package + ([base] if base else []))
            for target in _resolve(module, base, [a.name for a in node.names]):
                yield Import(module, target, node.lineno)
        else:
            yield from visit(node)

    yield from visit(tree)


IMPORTS = [i for m in sorted(MODULES) for i in imports_of(m) if i.target != i.source]


def package_of(module: str) -> str | None:
    parts = module.split(".")
    return None if module in DOORS else parts[1]


def test_every_package_has_a_place_in_the_order():
    packages = {package_of(m) for m in MODULES} - {None}
    assert packages <= set(LAYERS), f"packages missing from LAYERS: {sorted(packages - set(LAYERS))}"
    assert set(LAYERS) <= packages, f"LAYERS names no package: {sorted(set(LAYERS) - packages)}"


def test_the_top_of_plcsim_is_a_handful_of_doors():
    top = sorted(p.name for p in PLCSIM.glob("*.py"))
    assert top == ["__init__.py", "__main__.py"]


def test_no_import_runs_up_the_layers():
    upward = [
        str(i)
        for i in IMPORTS
        if package_of(i.target) is None
        or (
            package_of(i.source) is not None and LAYERS.index(package_of(i.target)) > LAYERS.index(package_of(i.source))
        )
    ]
    assert upward == [], "imports that run up the layers:\n" + "\n".join(upward)


def _circles() -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    edges: dict[str, set[str]] = {m: set() for m in MODULES}
    for i in IMPORTS:
        edges[i.source].add(i.target)
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def connect(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(edges[v]):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(MODULES):
        if v not in index:
            connect(v)
    return found


def test_no_module_takes_part_in_an_import_circle():
    circles = _circles()
    described = []
    for circle in circles:
        members = set(circle)
        described.append("\n".join(str(i) for i in IMPORTS if i.source in members and i.target in members))
    assert circles == [], "import circles:\n\n" + "\n\n".join(described)


def test_the_layer_test_sees_deferred_imports_and_skips_type_checking_ones():
    tree = "\n".join(str(i) for i in imports_of("plcsim.trace.facade"))
    assert "plcsim.trace.plot" in tree and "plcsim.trace.rerun" in tree  # deferred into Trace.plot/to_rrd


# -- seams inside a package ------------------------------------------------------------------------------

EXPORTERS = {"plcsim.trace.plot", "plcsim.trace.rerun"}


def targets(module: str) -> set[str]:
    return {i.target for i in imports_of(module)}


def test_the_trace_table_imports_neither_its_exporters_nor_the_facade():
    assert targets("plcsim.trace.table") & (EXPORTERS | {"plcsim.trace", "plcsim.trace.facade"}) == set()


@pytest.mark.parametrize("exporter", sorted(EXPORTERS))
def test_an_exporter_imports_the_table_and_never_the_facade(exporter: str):
    uses = targets(exporter)
    assert "plcsim.trace.table" in uses
    assert uses & {"plcsim.trace", "plcsim.trace.facade"} == set()


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
    tree = ast.parse(module_path("plcsim.controllers.s7.cpu").read_text(encoding="utf-8"))
    names = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
    names |= {a.name for node in ast.walk(tree) if isinstance(node, ast.ImportFrom) for a in node.names}
    strings = {node.value for node in ast.walk(tree) if isinstance(node, ast.Constant) and isinstance(node.value, str)}
    assert names & BOUND_BY_NAME == set()
    assert strings & {f.name for f in FUNCTIONS.values() if f.needs_cpu} == set()


TECOMAT_CODE = {f"plcsim.controllers.tecomat.{m}" for m in ("instructions", "blocks", "tables", "fused", "linker")}


def test_the_tecomat_machine_imports_no_instruction_and_the_cpu_links():
    assert targets("plcsim.controllers.tecomat.machine") & TECOMAT_CODE == set()
    assert "plcsim.controllers.tecomat.linker" in targets("plcsim.controllers.tecomat.cpu")


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
