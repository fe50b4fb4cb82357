"""Group ``inlined``: the 25 networks of the workload hand-inlined into one Python function, the ceiling.

The anchors (shared/background/anchors/pure_python_bench.py, variant ``inlined``) measure what a
ladder-to-Python compiler could at best emit: state in a ``__slots__`` object, the rungs as straight-line
statements over locals, TON/TOF/CTU/edge bodies written out. Their timers follow pyrung (the enabling scan
already counts), so this module writes the same 25 rungs once more with plcsim's semantics (the S7 timers
of :mod:`benchmarks.equivalence`: start time, ``elapsed >= PT``, ET capped at PT), so that the figure is
the cost of *the same outputs*, checked: over the equivalence run its rows must give the reference's digest.

Figures:

* ``inlined_python_scans_per_s`` -- scans per second of wall time, best of ``--repeats`` runs, 200 k scans
  or 20 s, driven by :func:`benchmarks.harness.drive` with the same schedule as group ``plc`` (inputs
  applied by ``setattr``, as in the anchors), in this process. ``same_outputs`` says whether its rows match
  :class:`benchmarks.equivalence.Reference` scan for scan.
* ``plc_vs_inlined_ratio`` -- plcsim's best scans/s (group ``plc``, same process) divided by this one's.
  Budget (issue 29): >= 0.5.
* ``plc_vs_inlined_opcode_ratio`` -- the Python opcodes a scan of this one executes divided by those of a
  plcsim scan (``sys.settrace`` counting opcodes over the same scans of the schedule, inputs applied as
  above): the same comparison without the machine's load, which on a shared VM moves the rates by 2x.
  It does not see work done in C (plcsim's image copies are ``dict.update`` calls), so it flatters plcsim
  a little; the rate ratio is the budget's figure.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from types import FrameType
from typing import Any

from benchmarks import equivalence, plc, workload
from benchmarks.harness import Figure, Settings, drive, figure, measure, progress

_STATE = (
    *workload.INPUTS,
    *workload.OUTPUTS,
    "Level",
    "now",
    *(f"{t}_{m}" for t in ("t1", "t2", "t3") for m in ("start", "run", "q", "et", "in")),
    "c1_cv",
    "c1_cu",
    "c2_cv",
    "c2_cu",
    "e9",
    "e11",
    "e12",
)


class InlinedWorkload:
    """The workload's 25 networks as one function over locals, with plcsim's timer and counter semantics."""

    __slots__ = _STATE

    def __init__(self) -> None:
        for name in _STATE:
            setattr(self, name, False)
        self.Level = self.now = 0
        self.t1_start = self.t2_start = self.t3_start = self.t1_et = self.t2_et = self.t3_et = 0
        self.c1_cv = self.c2_cv = 0

    def apply(self, changes: dict) -> None:
        for name, value in changes.items():
            setattr(self, name, value)

    def scan(self) -> None:
        s = self
        now = s.now
        I0, I1, I2, I3, I4, I5, I6, I7, I8, I9 = s.I0, s.I1, s.I2, s.I3, s.I4, s.I5, s.I6, s.I7, s.I8, s.I9
        I10, I11, I12, I13, I14, I16, I17, I19 = s.I10, s.I11, s.I12, s.I13, s.I14, s.I16, s.I17, s.I19
        Level = s.Level
        Q0 = (I0 or s.Q0) and not I1
        Q1 = (I2 or s.Q1) and not I3 and not I19
        en = Q0 and I4  # N3: TON T1, 40 ms
        if en:
            if not s.t1_in:
                s.t1_start, s.t1_run, s.t1_q, s.t1_et = now, True, False, 0
            if s.t1_run:
                elapsed = now - s.t1_start
                if elapsed >= 40:
                    s.t1_run, s.t1_q, s.t1_et = False, True, 40
                else:
                    s.t1_et = elapsed
        else:
            s.t1_run, s.t1_q, s.t1_et = False, False, 0
        s.t1_in = en
        Q2 = s.t1_q
        en = I5 and not I3  # N5: TON T2, 75 ms
        if en:
            if not s.t2_in:
                s.t2_start, s.t2_run, s.t2_q, s.t2_et = now, True, False, 0
            if s.t2_run:
                elapsed = now - s.t2_start
                if elapsed >= 75:
                    s.t2_run, s.t2_q, s.t2_et = False, True, 75
                else:
                    s.t2_et = elapsed
        else:
            s.t2_run, s.t2_q, s.t2_et = False, False, 0
        s.t2_in = en
        Q3 = s.t2_q and Q1
        if I6:  # N7: TOF T3, 30 ms
            s.t3_run, s.t3_q, s.t3_et = False, True, 0
        elif s.t3_in:
            s.t3_start, s.t3_run = now, True
        if s.t3_run:
            elapsed = now - s.t3_start
            if elapsed >= 30:
                s.t3_run, s.t3_q, s.t3_et = False, False, 30
            else:
                s.t3_et = elapsed
        s.t3_in = I6
        Q4 = s.t3_q
        if I8:  # N9: CTU C1 on I7, reset I8
            s.c1_cv = 0
        elif I7 and not s.c1_cu:
            s.c1_cv += 1
        s.c1_cu = I7
        c1 = s.c1_cv
        Q5 = c1 >= 5
        edge = I9 and not s.e9  # N11: -|P|- on I9, CTU C2, reset I10
        s.e9 = I9
        cu = edge and Q0
        if I10:
            s.c2_cv = 0
        elif cu and not s.c2_cu:
            s.c2_cv += 1
        s.c2_cu = cu
        Q6 = s.c2_cv >= 6
        Q7 = s.Q7
        if I11 and not s.e11:  # N13
            Q7 = True
        s.e11 = I11
        if I12 and not s.e12:  # N14
            Q7 = False
        s.e12 = I12
        Q8 = s.Q8
        if I13 and not I14:  # N15
            Q8 = True
        if I14:  # N16
            Q8 = False
        Q10 = Level < 20
        Q12 = c1 >= 3 and Level != 50
        Q16 = I16 and (Q8 or Q7) and not Q10
        Q18 = Q6 or Q12
        s.Q0, s.Q1, s.Q2, s.Q3, s.Q4, s.Q5, s.Q6, s.Q7, s.Q8 = Q0, Q1, Q2, Q3, Q4, Q5, Q6, Q7, Q8
        s.Q9 = Level >= 70
        s.Q10 = Q10
        s.Q11 = 30 < Level <= 60
        s.Q12 = Q12
        s.Q13 = (s.I15 and I16) or (I17 and not s.I18)
        s.Q14 = Q0 and Q1 and not Q4
        s.Q15 = Q2 or Q3 or Q5
        s.Q16 = Q16
        s.Q17 = Q16 and I17
        s.Q18 = Q18
        s.Q19 = Q18 and not I19
        s.now = now + workload.SCAN_MS

    def row(self) -> tuple:
        """What :meth:`benchmarks.equivalence.Reference.row` gives: Q0..Q19, the three ETs, the two CVs."""
        outputs = tuple(bool(getattr(self, q)) for q in workload.OUTPUTS)
        return (*outputs, self.t1_et, self.t2_et, self.t3_et, self.c1_cv, self.c2_cv)


def inlined_rows(sched: list) -> list[tuple]:
    plc_ = InlinedWorkload()
    rows = []
    for changes in sched:
        if changes:
            plc_.apply(changes)
        plc_.scan()
        rows.append(plc_.row())
    return rows


def _run_once(n: int, max_s: float, sched: list) -> tuple[int, float]:
    plc_ = InlinedWorkload()
    return drive(plc_.apply, plc_.scan, sched, n, max_s)


def opcodes_per_scan(apply: Callable[[dict], Any], step: Callable[[], Any], sched: list, warm: int) -> float:
    """Python opcodes per scan over ``sched[warm:]`` (the first ``warm`` scans run untraced)."""
    count = 0

    def tracer(frame: FrameType, event: str, arg: Any) -> Any:
        nonlocal count
        frame.f_trace_opcodes = True
        if event == "opcode":
            count += 1
        return tracer

    for k, changes in enumerate(sched):
        if k == warm:
            sys.settrace(tracer)
        if changes:
            apply(changes)
        step()
    sys.settrace(None)
    return count / (len(sched) - warm)


def run(settings: Settings) -> Iterator[Figure]:
    mine, _, _ = plc.throughput(settings)
    check = workload.build_schedule(equivalence.SCANS)
    same = equivalence.digest(inlined_rows(check)) == equivalence.digest(equivalence.reference_rows(check))
    n = settings.size(200_000, 2_000)
    max_s = settings.size(plc.MAX_S, 2.0)
    sched = workload.build_schedule(n)
    progress(f"inlined: {settings.repeats} x {n} scans")
    rates = measure(lambda k, s: _run_once(k, s, sched), n, max_s, settings.repeats)
    context = {"stat": "best", "repeats": settings.repeats, "scans": rates.best_scans, "scan_ms": workload.SCAN_MS}
    yield figure(
        "inlined_python_scans_per_s",
        round(rates.best),
        "scans/s",
        median=round(rates.median),
        same_outputs=same,
        networks=workload.NETWORKS,
        **context,
    )
    yield figure(
        "plc_vs_inlined_ratio",
        round(mine.best / rates.best, 3),
        "x",
        budget=">= 0.5",
        plcsim_scans_per_s=round(mine.best),
        inlined_scans_per_s=round(rates.best),
        stat="best",
    )
    warm = 200
    traced = workload.build_schedule(warm + settings.size(2_000, 200))
    cpu, hand = workload.new_cpu(), InlinedWorkload()
    plc_ops = opcodes_per_scan(cpu.inputs.update, cpu.scan, traced, warm)
    inlined_ops = opcodes_per_scan(hand.apply, hand.scan, traced, warm)
    yield figure(
        "plc_vs_inlined_opcode_ratio",
        round(inlined_ops / plc_ops, 3),
        "x",
        plcsim_opcodes_per_scan=round(plc_ops, 1),
        inlined_opcodes_per_scan=round(inlined_ops, 1),
        scans=len(traced) - warm,
    )
