"""The benchmark workload: a 25-network "PLC course" program and its input schedule.

The same workload as the anchors in shared/background/anchors (pyrung_bench.py, pure_python_bench.py,
awlsim_bench.py), so plcsim's figures sit next to theirs: 20 BOOL inputs I0..I19, 20 outputs Q0..Q19, one
INT ``Level``; 2 seal-ins, 2 TON, 1 TOF, 2 CTU with reset, 4 rising edges, set/reset coils, 4 compare
networks, AND/OR/branch networks. Input Ik is a square wave with a half-period of ``HALF[k]`` scans;
``Level`` changes every 4 scans. About 85 % of scans change an output or an accumulator, so the
program is never idle.
"""

from __future__ import annotations

from typing import Any

HALF = [97, 131, 53, 179, 61, 113, 37, 3, 47, 5, 71, 19, 29, 23, 41, 7, 11, 13, 17, 211]
INPUTS = [f"I{i}" for i in range(20)]
OUTPUTS = [f"Q{i}" for i in range(20)]
SCAN_MS = 1
NETWORKS = 25

SOURCE = """
T1 = IEC_TIMER()
T2 = IEC_TIMER()
T3 = IEC_TIMER()
C1 = IEC_COUNTER()
C2 = IEC_COUNTER()
E9 = Bool()
E11 = Bool()
E12 = Bool()

def n1(t): t.Q0 = (t.I0 or t.Q0) and not t.I1
def n2(t): t.Q1 = (t.I2 or t.Q1) and not t.I3 and not t.I19
def n3(t): t.T1.TON(IN=t.Q0 and t.I4, PT="40ms")
def n4(t): t.Q2 = t.T1.Q
def n5(t): t.T2.TON(IN=t.I5 and not t.I3, PT="75ms")
def n6(t): t.Q3 = t.T2.Q and t.Q1
def n7(t): t.T3.TOF(IN=t.I6, PT="30ms")
def n8(t): t.Q4 = t.T3.Q
def n9(t): t.C1.CTU(CU=t.I7, R=t.I8, PV=5)
def n10(t): t.Q5 = t.C1.QU
def n11(t):
    edge = P(t.I9, "E9")
    t.C2.CTU(CU=edge and t.Q0, R=t.I10, PV=6)
def n12(t): t.Q6 = t.C2.QU
def n13(t):
    if P(t.I11, "E11"): t.Q7 = True
def n14(t):
    if P(t.I12, "E12"): t.Q7 = False
def n15(t):
    if t.I13 and not t.I14: t.Q8 = True
def n16(t):
    if t.I14: t.Q8 = False
def n17(t): t.Q9 = t.Level >= 70
def n18(t): t.Q10 = t.Level < 20
def n19(t): t.Q11 = t.Level > 30 and t.Level <= 60
def n20(t): t.Q12 = t.C1.CV >= 3 and t.Level != 50
def n21(t): t.Q13 = (t.I15 and t.I16) or (t.I17 and not t.I18)
def n22(t): t.Q14 = t.Q0 and t.Q1 and not t.Q4
def n23(t): t.Q15 = t.Q2 or t.Q3 or t.Q5
def n24(t):
    en = t.I16 and (t.Q8 or t.Q7) and not t.Q10
    t.Q16 = en
    t.Q17 = en and t.I17
def n25(t):
    en = t.Q6 or t.Q12
    t.Q18 = en
    t.Q19 = en and not t.I19

OB1 = [n1, n2, n3, n4, n5, n6, n7, n8, n9, n10, n11, n12, n13, n14, n15, n16, n17, n18, n19, n20,
       n21, n22, n23, n24, n25]
"""


def tags() -> dict[str, Any]:
    """The I/O table: I0..I19 on %I0.0..%I2.3, Q0..Q19 on %Q0.0..%Q2.3, Level on %IW10."""
    from plcsim import Int, Tag

    table: dict[str, Any] = {f"I{i}": Tag(f"%I{i // 8}.{i % 8}") for i in range(20)}
    table.update({f"Q{i}": Tag(f"%Q{i // 8}.{i % 8}") for i in range(20)})
    table["Level"] = Tag("%IW10", Int)
    return table


def new_cpu() -> Any:
    """A CPU in RUN with the workload loaded (1 ms scan, the default configuration)."""
    from plcsim import CPU

    return CPU(tags=tags(), program=SOURCE)


def build_schedule(n: int) -> list[dict[str, Any] | None]:
    """``sched[k]``: the input changes to apply before scan ``k`` (None if nothing changes)."""
    sched: list[dict[str, Any] | None] = [None] * n
    for i, h in enumerate(HALF):
        name = f"I{i}"
        for k in range(h, n, h):  # all inputs start False
            d = sched[k]
            if d is None:
                d = sched[k] = {}
            d[name] = bool((k // h) & 1)
    for k in range(0, n, 4):
        d = sched[k]
        if d is None:
            d = sched[k] = {}
        d["Level"] = (k // 4 * 37) % 100
    return sched
