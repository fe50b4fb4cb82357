"""Group ``equivalence``: does plcsim run the workload the way the course's S7-1200 would?

Figure ``plc_equivalence`` (a check, not a timing): over 20 k scans of the workload, plcsim and
:class:`Reference`, a hand-written pure-Python version of the same 25 networks, produce the same per-scan
rows ``Q0..Q19, T1.ET, T2.ET, T3.ET, C1.CV, C2.CV``; the value is True when the two sha256 digests of
all rows agree. The reference states plcsim's semantics independently of its code:

* TON: the scan in which IN rises starts the timer (elapsed 0); Q is TRUE once ``elapsed ms >= PT``,
  so at a 1 ms scan a 40 ms TON is done in the scan 40 scans after the start scan, the 41st scan that
  sees IN. ET counts whole ms since the start, stops at PT; IN = FALSE resets Q and ET.
* TOF: IN = TRUE gives Q = TRUE, ET = 0; the scan in which IN falls starts the timer, and Q falls once
  ``elapsed ms >= PT``; ET then stays at PT. Q is FALSE at start-up.
* CTU counts rising edges of CU (its own edge memory, updated in every call); R is level-triggered,
  dominates, and sets CV = 0; QU = CV >= PV.
* -|P|- compares with its memory bit and updates it at once.

plcsim vs pyrung: pyrung (``benchmarks.pyrung_peer``) adds ``dt`` to a timer's accumulator in every scan
the rung is enabled, *including* the first, so its 40 ms TON is done on the 40th enabled scan, one scan
before plcsim's; its TOF likewise (shared/background/anchors/README.md). Outputs driven by timers
therefore differ by one scan, and the anchors' digest (``d2c251a0f08e4a33``, pyrung and the anchors'
pure-Python variants) is not this one. The pyrung figures compare the *same logic*, not the same outputs.
"""

from __future__ import annotations

import hashlib
import itertools
from collections.abc import Iterator

from benchmarks import workload
from benchmarks.harness import Figure, Settings, figure, progress

SCANS = 20_000
ROW_EXTRAS = ["T1.ET", "T2.ET", "T3.ET", "C1.CV", "C2.CV"]


class _Ton:
    __slots__ = ("pt", "start", "running", "q", "et", "last_in")

    def __init__(self, pt: int):
        self.pt, self.start, self.running, self.q, self.et, self.last_in = pt, 0, False, False, 0, False

    def __call__(self, enable: bool, k: int) -> bool:
        if not enable:
            self.running, self.q, self.et = False, False, 0
        else:
            if not self.last_in:
                self.start, self.running, self.q, self.et = k, True, False, 0
            if self.running:
                elapsed = (k - self.start) * workload.SCAN_MS
                if elapsed >= self.pt:
                    self.running, self.q, self.et = False, True, self.pt
                else:
                    self.et = elapsed
        self.last_in = enable
        return self.q


class _Tof(_Ton):
    __slots__ = ()

    def __call__(self, enable: bool, k: int) -> bool:
        if enable:
            self.running, self.q, self.et = False, True, 0
        elif self.last_in:
            self.start, self.running = k, True
        if self.running:
            elapsed = (k - self.start) * workload.SCAN_MS
            if elapsed >= self.pt:
                self.running, self.q, self.et = False, False, self.pt
            else:
                self.et = elapsed
        self.last_in = enable
        return self.q


class _Ctu:
    __slots__ = ("pv", "cv", "last_cu")

    def __init__(self, pv: int):
        self.pv, self.cv, self.last_cu = pv, 0, False

    def __call__(self, cu: bool, r: bool) -> bool:
        if r:
            self.cv = 0
        elif cu and not self.last_cu:
            self.cv += 1
        self.last_cu = cu
        return self.cv >= self.pv


class Reference:
    """The 25 networks in plain Python with plcsim's semantics (see the module docstring)."""

    def __init__(self) -> None:
        self.v: dict[str, bool | int] = dict.fromkeys(workload.INPUTS + workload.OUTPUTS, False)
        self.v["Level"] = 0
        self.t1, self.t2, self.t3 = _Ton(40), _Ton(75), _Tof(30)
        self.c1, self.c2 = _Ctu(5), _Ctu(6)
        self.e9 = self.e11 = self.e12 = False
        self.k = 0

    def scan(self) -> None:
        v, k = self.v, self.k
        v["Q0"] = (v["I0"] or v["Q0"]) and not v["I1"]
        v["Q1"] = (v["I2"] or v["Q1"]) and not v["I3"] and not v["I19"]
        v["Q2"] = self.t1(v["Q0"] and v["I4"], k)
        v["Q3"] = self.t2(v["I5"] and not v["I3"], k) and v["Q1"]
        v["Q4"] = self.t3(v["I6"], k)
        v["Q5"] = self.c1(v["I7"], v["I8"])
        edge, self.e9 = v["I9"] and not self.e9, v["I9"]
        v["Q6"] = self.c2(edge and v["Q0"], v["I10"])
        if v["I11"] and not self.e11:
            v["Q7"] = True
        self.e11 = v["I11"]
        if v["I12"] and not self.e12:
            v["Q7"] = False
        self.e12 = v["I12"]
        if v["I13"] and not v["I14"]:
            v["Q8"] = True
        if v["I14"]:
            v["Q8"] = False
        level = v["Level"]
        v["Q9"] = level >= 70
        v["Q10"] = level < 20
        v["Q11"] = 30 < level <= 60
        v["Q12"] = self.c1.cv >= 3 and level != 50
        v["Q13"] = (v["I15"] and v["I16"]) or (v["I17"] and not v["I18"])
        v["Q14"] = v["Q0"] and v["Q1"] and not v["Q4"]
        v["Q15"] = v["Q2"] or v["Q3"] or v["Q5"]
        v["Q16"] = v["I16"] and (v["Q8"] or v["Q7"]) and not v["Q10"]
        v["Q17"] = v["Q16"] and v["I17"]
        v["Q18"] = v["Q6"] or v["Q12"]
        v["Q19"] = v["Q18"] and not v["I19"]
        self.k = k + 1

    def row(self) -> tuple:
        outputs = tuple(bool(self.v[q]) for q in workload.OUTPUTS)
        return (*outputs, self.t1.et, self.t2.et, self.t3.et, self.c1.cv, self.c2.cv)


def reference_rows(sched: list) -> list[tuple]:
    ref = Reference()
    rows = []
    for ch in sched:
        if ch:
            ref.v.update(ch)
        ref.scan()
        rows.append(ref.row())
    return rows


def plcsim_rows(sched: list) -> list[tuple]:
    cpu = workload.new_cpu()
    outputs, read = cpu.outputs, cpu.read
    rows = []
    for ch in sched:
        if ch:
            cpu.inputs.update(ch)
        cpu.scan()
        rows.append(tuple(outputs[q] for q in workload.OUTPUTS) + tuple(read(x) for x in ROW_EXTRAS))
    return rows


def digest(rows: list[tuple]) -> str:
    return hashlib.sha256(repr(rows).encode()).hexdigest()[:16]


def run(settings: Settings) -> Iterator[Figure]:
    sched = workload.build_schedule(SCANS)
    progress(f"equivalence: {SCANS} scans, plcsim vs reference")
    mine, ref = plcsim_rows(sched), reference_rows(sched)
    mismatched = [k for k, (a, b) in enumerate(zip(mine, ref)) if a != b]
    yield figure(
        "plc_equivalence",
        not mismatched and len(mine) == len(ref),
        "bool",
        scans=SCANS,
        plcsim_digest=digest(mine),
        reference_digest=digest(ref),
        mismatched_scans=len(mismatched),
        first_mismatch=mismatched[0] if mismatched else None,
        scans_with_change=sum(1 for a, b in itertools.pairwise(ref) if a != b),
    )
