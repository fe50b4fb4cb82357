"""Group ``pyrung``: the same ladder logic on pyrung (PyPI), run in this process next to plcsim.

design.md asks for plcsim "compared side by side with pyrung on the same ladder logic". The 25 rungs
below are copied from shared/background/anchors/pyrung_bench.py; the input schedule and the driver loop
(inside the timing) are plcsim's (:mod:`benchmarks.workload`, :func:`benchmarks.harness.drive`).

Figures (scans/s, best of ``--repeats`` runs, median as context):

* ``pyrung_scans_per_s`` -- the public default ``PLC(logic, dt=0.001)``: interpreted, with unlimited
  history. 0.65-1 ms per scan, so a run is bounded to 3 k scans or 4 s; scans/s stays comparable.
  Its cost per scan was flat over 12 k scans (memory grows, time does not), so short runs are
  representative.
* ``pyrung_compiled_scans_per_s`` -- ``pyrung.core.CompiledPLC(logic, dt=0.001)``, the code-generated
  kernel without history or debugger; 20 k scans or 4 s per run.
* ``pyrung_kernel_scans_per_s`` -- pyrung's generated kernel alone,
  ``pyrung.circuitpy.codegen.render_kernel.compile_kernel(logic).step_fn``, driven as the anchors'
  ``run_raw_kernel`` drives it (tags, blocks, memory and edge memory as plain dicts; the edge tags copied
  after each step): the fastest pyrung can run this logic; 200 k scans or 20 s per run.
* ``plcsim_vs_pyrung_ratio``, ``plcsim_vs_pyrung_compiled_ratio``, ``plcsim_vs_pyrung_kernel_ratio`` --
  plcsim's best scans/s (group ``plc``, measured in this same process) divided by pyrung's best: how many
  times faster plcsim is. Budget (issue 29) for the kernel ratio: >= 3.

Same logic, not same outputs: pyrung's timers count the enabling scan, so its timer-driven outputs run
one scan ahead of plcsim's (see :mod:`benchmarks.equivalence`). pyrung is optional (``plcsim[bench]``);
without it every figure is printed with ``"value": null`` and a ``skipped`` reason.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from benchmarks import plc, workload
from benchmarks.harness import Figure, Rates, Settings, drive, figure, measure, progress

DT = workload.SCAN_MS / 1000
SKIPPED = "pyrung not installed (pip install plcsim[bench])"
FIGURES = [
    ("pyrung_scans_per_s", "scans/s"),
    ("pyrung_compiled_scans_per_s", "scans/s"),
    ("plcsim_vs_pyrung_ratio", "x"),
    ("plcsim_vs_pyrung_compiled_ratio", "x"),
    ("pyrung_kernel_scans_per_s", "scans/s"),
    ("plcsim_vs_pyrung_kernel_ratio", "x"),
]
BUDGETS = {"pyrung_kernel": ">= 3"}


def build_logic() -> Any:
    """The anchors' 25 rungs as a pyrung Program (imports pyrung)."""
    from pyrung import (
        And,
        Bool,
        Counter,
        Int,
        Or,
        Program,
        Timer,
        branch,
        count_up,
        latch,
        off_delay,
        on_delay,
        out,
        reset,
        rise,
        rung,
    )

    IN = [Bool(f"I{i}") for i in range(20)]
    Q = [Bool(f"Q{i}") for i in range(20)]
    Level = Int("Level")
    T1, T2, T3 = Timer.clone("T1"), Timer.clone("T2"), Timer.clone("T3")
    C1, C2 = Counter.clone("C1"), Counter.clone("C2")

    with Program() as logic:
        with rung(Or(IN[0], Q[0]), ~IN[1]):  # N1 seal-in
            out(Q[0])
        with rung(Or(IN[2], Q[1]), ~IN[3], ~IN[19]):  # N2 seal-in with interlock
            out(Q[1])
        with rung(Q[0], IN[4]):  # N3 TON 40 ms
            on_delay(T1, 40)
        with rung(T1.Done):  # N4
            out(Q[2])
        with rung(IN[5], ~IN[3]):  # N5 TON 75 ms
            on_delay(T2, 75)
        with rung(T2.Done, Q[1]):  # N6
            out(Q[3])
        with rung(IN[6]):  # N7 TOF 30 ms
            off_delay(T3, 30)
        with rung(T3.Done):  # N8
            out(Q[4])
        with rung(rise(IN[7])):  # N9 CTU on rising edge, reset I8
            count_up(C1, 5).reset(IN[8])
        with rung(C1.Done):  # N10
            out(Q[5])
        with rung(rise(IN[9]), Q[0]):  # N11 CTU on rising edge while Q0
            count_up(C2, 6).reset(IN[10])
        with rung(C2.Done):  # N12
            out(Q[6])
        with rung(rise(IN[11])):  # N13 edge -> set
            latch(Q[7])
        with rung(rise(IN[12])):  # N14 edge -> reset
            reset(Q[7])
        with rung(IN[13], ~IN[14]):  # N15 set coil
            latch(Q[8])
        with rung(IN[14]):  # N16 reset coil
            reset(Q[8])
        with rung(Level >= 70):  # N17 compares
            out(Q[9])
        with rung(Level < 20):  # N18
            out(Q[10])
        with rung(Level > 30, Level <= 60):  # N19 window
            out(Q[11])
        with rung(C1.Acc >= 3, Level != 50):  # N20
            out(Q[12])
        with rung(Or(And(IN[15], IN[16]), And(IN[17], ~IN[18]))):  # N21
            out(Q[13])
        with rung(Q[0], Q[1], ~Q[4]):  # N22
            out(Q[14])
        with rung(Or(Q[2], Q[3], Q[5])):  # N23
            out(Q[15])
        with rung(IN[16], Or(Q[8], Q[7]), ~Q[10]):  # N24
            out(Q[16])
            with branch(IN[17]):
                out(Q[17])
        with rung(Or(Q[6], Q[12])):  # N25
            out(Q[18])
            with branch(~IN[19]):
                out(Q[19])
    assert len(logic.rungs) == workload.NETWORKS
    return logic


def _runners(logic: Any, version: str | None) -> list[tuple[str, Any, int, int, int, str | None]]:
    """(name, factory, scans, quick scans, clock-check chunk, skip reason) of each pyrung runner."""
    from pyrung import PLC

    runners: list[tuple[str, Any, int, int, int, str | None]] = [
        ("pyrung", lambda: PLC(logic, dt=DT), 3_000, 100, 100, None)
    ]
    try:
        from pyrung.core import CompiledPLC
    except ImportError as exc:
        reason = f"pyrung.core.CompiledPLC unavailable in pyrung {version}: {exc}"
        runners.append(("pyrung_compiled", None, 0, 0, 0, reason))
    else:
        runners.append(("pyrung_compiled", lambda: CompiledPLC(logic, dt=DT), 20_000, 300, 500, None))
    try:
        from pyrung.circuitpy.codegen.render_kernel import compile_kernel
    except ImportError as exc:
        reason = f"pyrung.circuitpy.codegen.render_kernel unavailable in pyrung {version}: {exc}"
        runners.append(("pyrung_kernel", None, 0, 0, 0, reason))
    else:
        compiled = compile_kernel(logic)
        runners.append(("pyrung_kernel", lambda: KernelRunner(compiled), 200_000, 2_000, 500, None))
    return runners


class KernelRunner:
    """pyrung's generated step function on plain dicts, with ``patch`` and ``step`` as the anchors'
    ``run_raw_kernel`` drives it: the edge tags are copied into ``prev`` after each step (the kernel leaves
    that to its caller)."""

    def __init__(self, compiled: Any):
        kernel = compiled.create_kernel()
        self.tags, self.blocks, self.memory, self.prev = kernel.tags, kernel.blocks, kernel.memory, kernel.prev
        self.step_fn, self.edge = compiled.step_fn, tuple(compiled.edge_tags)
        self.patch = self.tags.update

    def step(self) -> None:
        tags, prev = self.tags, self.prev
        self.step_fn(tags, self.blocks, self.memory, prev, DT)
        for name in self.edge:
            prev[name] = tags[name]


def _rates(settings: Settings, factory: Any, n: int, chunk: int) -> tuple[Rates, float]:
    max_s = settings.size(plc.MAX_S if n >= 100_000 else 4.0, 1.0)
    sched = workload.build_schedule(n)

    def run_once(k: int, s: float) -> tuple[int, float]:
        runner = factory()
        return drive(runner.patch, runner.step, sched, k, s, chunk)

    return measure(run_once, n, max_s, settings.repeats, warmup=min(n, 200)), max_s


def run(settings: Settings) -> Iterator[Figure]:
    try:
        import pyrung  # noqa: F401
    except ImportError:
        for name, unit in FIGURES:
            yield figure(name, None, unit, skipped=SKIPPED)
        return
    version = _version()
    mine, _, _ = plc.throughput(settings)
    logic = build_logic()
    for name, factory, full_n, quick_n, chunk, skipped in _runners(logic, version):
        if factory is None:
            yield figure(f"{name}_scans_per_s", None, "scans/s", skipped=skipped)
            yield figure(f"plcsim_vs_{name}_ratio", None, "x", skipped=skipped)
            continue
        n = settings.size(full_n, quick_n)
        progress(f"{name}: {settings.repeats} x {n} scans")
        rates, max_s = _rates(settings, factory, n, chunk)
        yield figure(
            f"{name}_scans_per_s",
            round(rates.best),
            "scans/s",
            median=round(rates.median),
            stat="best",
            repeats=settings.repeats,
            scans=rates.best_scans,
            scan_budget=n,
            max_s=max_s,
            scan_ms=workload.SCAN_MS,
            networks=workload.NETWORKS,
            pyrung_version=version,
        )
        yield figure(
            f"plcsim_vs_{name}_ratio",
            round(mine.best / rates.best, 2),
            "x",
            stat="best",
            **({"budget": BUDGETS[name]} if name in BUDGETS else {}),
            plcsim_scans_per_s=round(mine.best),
            pyrung_scans_per_s=round(rates.best),
            pyrung_version=version,
        )


def _version() -> str | None:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("pyrung")
    except PackageNotFoundError:
        return None
