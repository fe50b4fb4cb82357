"""Golden tests: IEC counters CTU, CTD, CTUD (spec §4.6, §2.3, §3.7.1, §4.2.16).

Rules these tests pin:

* CU/CD count on rising edges only (one count per edge, however long the input stays TRUE).
* QU = CV >= PV, QD = CV <= 0; QD is TRUE at the start (CV = 0).
* R resets CV to 0 and dominates LD, which loads PV (level-sensitive); both dominate counting.
* Counting past the type's limits wraps both ways (the textbook), so QU drops after an up-overflow;
  ``counter_overflow="saturate"`` keeps CV at the limit (IEC/S7-300).
* The instance is retentive by default (Fig. 3.233): CV survives STOP->RUN and a power cycle.
"""

from __future__ import annotations

import pytest
from plcharness import Probe, drive, held

from plcsim import CPU, Tag

TAGS = {"CU": Tag("%I0.0"), "CD": Tag("%I0.1"), "R": Tag("%I0.2"), "LD": Tag("%I0.3"), "LED": Tag("%Q0.0")}

CTUD = """
C1 = IEC_COUNTER(COUNT_TYPE)
def OB1(t):
    t.LED = t.C1.CTUD(CU=t.CU, CD=t.CD, R=t.R, LD=t.LD, PV=PRESET)
"""


def ctud(pv: int = 4, count_type: str = "Int", **options) -> CPU:
    program = CTUD.replace("COUNT_TYPE", count_type).replace("PRESET", str(pv))
    return CPU(tags=TAGS, program=program, **options)


def pulse(cpu: CPU, name: str, scans_on: int = 3, scans_off: int = 2) -> None:
    cpu.set_input(name, True)
    cpu.scan(scans_on)
    cpu.set_input(name, False)
    cpu.scan(scans_off)


def state(cpu: CPU) -> tuple[int, bool, bool]:
    return cpu.read("C1.CV"), cpu.read("C1.QU"), cpu.read("C1.QD")


def test_ctud_start_values_qd_true():
    cpu = ctud(start=False)
    assert state(cpu) == (0, False, True)
    cpu.start()
    cpu.scan()
    assert state(cpu) == (0, False, True)
    assert cpu.outputs["LED"] is False


def test_ctud_counts_edges_not_scans_and_qu_is_cv_ge_pv():
    cpu = ctud(pv=4)
    seen = []
    for _ in range(5):
        pulse(cpu, "CU", scans_on=7)
        seen.append(state(cpu))
    assert seen == [(1, False, False), (2, False, False), (3, False, False), (4, True, False), (5, True, False)]
    assert cpu.outputs["LED"] is True


def test_ctud_count_down_through_zero_qd_is_cv_le_0():
    cpu = ctud(pv=10)
    cpu.set_input("LD", True)
    cpu.scan()
    assert state(cpu) == (10, True, False)  # LD loads PV: QU because CV = PV
    cpu.set_input("LD", False)
    seen = []
    for _ in range(11):
        pulse(cpu, "CD")
        seen.append(state(cpu)[0])
    assert seen == [9, 8, 7, 6, 5, 4, 3, 2, 1, 0, -1]
    assert state(cpu) == (-1, False, True)  # QD stays TRUE below 0


def test_ctud_r_dominates_ld_and_counting():
    cpu = ctud(pv=4)
    pulse(cpu, "CU")
    pulse(cpu, "CU")
    cpu.set_input("R", True)
    cpu.set_input("LD", True)
    cpu.set_input("CU", True)
    cpu.scan(3)
    assert state(cpu) == (0, False, True)
    cpu.set_input("R", False)
    cpu.scan()
    assert state(cpu) == (4, True, False)  # LD alone: CV = PV
    cpu.set_input("LD", False)
    cpu.scan(3)
    assert state(cpu)[0] == 4  # CU stayed TRUE throughout: no new edge
    cpu.set_input("CU", False)
    cpu.scan()
    cpu.set_input("CU", True)
    cpu.scan()
    assert state(cpu)[0] == 5


def test_ctud_cu_and_cd_edges_in_one_call_cancel():
    cpu = ctud(pv=4)
    pulse(cpu, "CU")
    cpu.set_input("CU", True)
    cpu.set_input("CD", True)
    cpu.scan()
    assert state(cpu)[0] == 1


@pytest.mark.parametrize(
    ("count_type", "top", "bottom"),
    [("Int", 32_767, -32_768), ("DInt", 2_147_483_647, -2_147_483_648), ("SInt", 127, -128), ("UInt", 65_535, 0)],
)
def test_cv_wraps_at_the_type_limits_both_ways(count_type, top, bottom):
    cpu = ctud(pv=4, count_type=count_type)
    cpu.t.C1.CV = top - 1
    pulse(cpu, "CU")
    assert state(cpu)[0] == top
    pulse(cpu, "CU")
    assert state(cpu)[:2] == (bottom, False)  # past the maximum comes the minimum; QU drops
    pulse(cpu, "CD")
    assert state(cpu)[0] == top  # and below the minimum the maximum
    pulse(cpu, "CD")
    assert state(cpu)[0] == top - 1


@pytest.mark.parametrize(("count_type", "top", "bottom"), [("Int", 32_767, -32_768), ("SInt", 127, -128)])
def test_saturate_mode_keeps_cv_at_the_limits(count_type, top, bottom):
    cpu = ctud(pv=4, count_type=count_type, counter_overflow="saturate")
    cpu.t.C1.CV = top - 1
    for _ in range(3):
        pulse(cpu, "CU")
    assert state(cpu)[:2] == (top, True)
    cpu.t.C1.CV = bottom + 1
    for _ in range(3):
        pulse(cpu, "CD")
    assert state(cpu)[0] == bottom


P_4_2_16 = """
TON_1 = IEC_TIMER()
C1 = IEC_COUNTER()
def OB1(t):
    t.TON_1.TON(IN=t.CU, PT="12s")
    cu = t.TON_1.ET >= TIME("2s") or t.TON_1.ET >= TIME("8s") or t.TON_1.ET >= TIME("12s")
    t.LED = t.C1.CTU(CU=cu, PV=4)
"""


def test_4_2_16_one_count_per_press_of_at_least_2s():
    cpu = CPU(tags=TAGS, program=P_4_2_16, cycle="100ms")
    probe = Probe(cpu, "C1.CV", "LED")
    # presses: 1 s and 2 s exactly (too short: the last scan that sees the button has ET = 1.9 s),
    # 13 s (the 8 s and 12 s comparisons add nothing), then 2.1 s, 3 s and 2.5 s
    drive(cpu, held("CU", (1, 2), (3, 16), (17, 19), (20, 22.1), (25, 28), (30, 32.5)), 35)
    assert probe.changes("C1.CV") == [(0.0, 0), (5.0, 1), (22.0, 2), (27.0, 3), (32.0, 4)]
    assert probe.changes("LED") == [(0.0, False), (32.0, True)]


def test_4_2_16_after_overflow_the_led_is_off_from_the_most_negative_int_up_to_3():
    program = "C1 = IEC_COUNTER()\ndef OB1(t):\n    t.LED = t.C1.CTU(CU=t.CU, PV=4)\n"
    cpu = CPU(tags=TAGS, program=program)
    cpu.t.C1.CV = 32_766
    led_by_cv: dict[int, set[bool]] = {}

    def hook(c):
        led_by_cv.setdefault(c.t.C1.CV, set()).add(c.t.LED)

    cpu.on_scan_end = hook
    cu = False
    while cpu.t.C1.CV != 5:  # 32 767 -> -32 768 -> ... -> 5: 32 775 counts, one every two scans
        cu = not cu
        cpu.set_input("CU", cu)
        cpu.scan()
    assert led_by_cv[32_767] == {True}
    assert all(led_by_cv[cv] == {False} for cv in range(-32_768, 4))
    assert led_by_cv[4] == {True} and led_by_cv[5] == {True}
    assert len(led_by_cv) == 2 + 32_768 + 4 + 1  # 32 766 .. 32 767, -32 768 .. 3, 4, 5: every value seen


CTU_CTD = """
CU_C = IEC_COUNTER()
CD_C = IEC_COUNTER()
def OB1(t):
    t.QU_OUT = t.CU_C.CTU(CU=t.CU, R=t.R, PV=3)
    t.QD_OUT = t.CD_C.CTD(CD=t.CD, LD=t.LD, PV=3)
"""


def test_ctu_q_is_qu_and_ctd_q_is_qd():
    cpu = CPU(tags={**TAGS, "QU_OUT": Tag("%Q0.1"), "QD_OUT": Tag("%Q0.2")}, program=CTU_CTD)
    cpu.scan()
    assert (cpu.read("CU_C.Q"), cpu.read("CD_C.Q"), cpu.outputs["QD_OUT"]) == (False, True, True)
    for _ in range(3):
        pulse(cpu, "CU")
    assert (cpu.read("CU_C.CV"), cpu.read("CU_C.QU"), cpu.read("CU_C.Q"), cpu.outputs["QU_OUT"]) == (
        3,
        True,
        True,
        True,
    )
    cpu.set_input("R", True)
    cpu.scan()
    assert (cpu.read("CU_C.CV"), cpu.outputs["QU_OUT"]) == (0, False)
    cpu.set_input("LD", True)
    cpu.scan()
    cpu.set_input("LD", False)
    assert (cpu.read("CD_C.CV"), cpu.read("CD_C.Q")) == (3, False)
    seen = []
    for _ in range(4):
        pulse(cpu, "CD")
        seen.append((cpu.read("CD_C.CV"), cpu.outputs["QD_OUT"]))
    assert seen == [(2, False), (1, False), (0, True), (-1, True)]


@pytest.mark.parametrize("how", ["stop-run", "power-cycle"])
def test_counter_instance_is_retentive(how):
    program = """
C1 = IEC_COUNTER()
C2 = IEC_COUNTER(retain=False)
def OB1(t):
    t.C1.CTU(CU=t.CU, PV=4)
    t.C2.CTU(CU=t.CU, PV=4)
"""
    cpu = CPU(tags=TAGS, program=program)
    for _ in range(3):
        pulse(cpu, "CU")
    assert (cpu.read("C1.CV"), cpu.read("C2.CV")) == (3, 3)
    if how == "stop-run":
        cpu.stop()
        cpu.start()
    else:
        cpu.power_cycle()
    assert (cpu.read("C1.CV"), cpu.read("C1.QD"), cpu.read("C2.CV"), cpu.read("C2.QD")) == (3, False, 0, True)
    pulse(cpu, "CU")
    assert (cpu.read("C1.CV"), cpu.read("C2.CV")) == (4, 1)
