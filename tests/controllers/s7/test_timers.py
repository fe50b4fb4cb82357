"""Golden tests: IEC timers TON, TOF, TP, TONR and RT, as the textbook's timing diagrams give them (spec §4.5).

Timing rules these tests pin:

* Every network of one OB1 execution sees the execution's start time t0; an input set at time T is
  seen by the scan that starts at T. With a 100 ms cycle and events on whole 100 ms, every edge of
  the textbook diagrams falls on a scan start, so a timer started in the scan at T1 shows Q in the
  scan at T1 + PT exactly (exercises.md §0.4: observed delay in [PT, PT + T_scan), here exactly PT).
* Values are read as a watch table shows them (``cpu.read``, never refreshing a timer).
* The output image is written to the output modules at the end of the scan, t0 + cycle.
* ``RT`` clears the instance at once; the rung's coils after it still got TRUE, and a TON with
  IN = TRUE restarts in the next scan (spec §3.6.5, §5.5 item 4).
* The "unused timer" rule (§3.6.1, Fig. 3.197): a timer whose Q and ET are read nowhere does not
  start when ``textbook_strict_timers=True`` (the default), with a load warning; with False it runs.
"""

from __future__ import annotations

import pytest
from plcharness import Probe, drive, held

from plcsim import CPU, Tag

DIALECTS = pytest.mark.parametrize("dialect", ["s7_1200", "iec"])
BOX_TAGS = {"IN": Tag("%I0.0"), "R": Tag("%I0.1"), "Q": Tag("%Q0.0")}
PANEL = {"TLACIDLO": Tag("%I0.0"), "PREPINAC": Tag("%I0.2"), "LED": Tag("%Q0.0")}


def box_program(box: str, pt: str, extra: str = "") -> str:
    return f"T = IEC_TIMER()\ndef OB1(t):\n    t.Q = t.T.{box}(IN=t.IN, PT={pt!r}{extra})\n"


def run_box(box, pt, events, until, dialect, extra=""):
    cpu = CPU(tags=BOX_TAGS, program=box_program(box, pt, extra), cycle="100ms", timer_dialect=dialect)
    probe = Probe(cpu, "Q", "T.ET")
    drive(cpu, events, until)
    assert cpu.mode == "RUN" and cpu.warnings == []
    return probe


# --------------------------------------------------------------------------------------------
# TON (§4.5.2): PT = 2 s
# --------------------------------------------------------------------------------------------


@DIALECTS
def test_ton_diagram_pt_2s(dialect):
    probe = run_box("TON", "2s", held("IN", (1, 6), (10, 11), (14, 18)), 20, dialect)
    # IN 1-6 s: Q 3-6 s; IN 10-11 s: no Q; IN 14-18 s: Q 16-18 s
    assert probe.changes("Q") == [(0.0, False), (3.0, True), (6.0, False), (16.0, True), (18.0, False)]


@DIALECTS
def test_ton_et_counts_to_exactly_pt_and_resets_with_in(dialect):
    probe = run_box("TON", "2s", held("IN", (1, 6), (10, 11)), 12, dialect)
    assert probe.at("T.ET", 1.0) == 0
    assert probe.at("T.ET", 2.5) == 1500
    assert probe.at("T.ET", 3.0) == 2000  # ET stops at exactly PT
    assert probe.at("T.ET", 5.9) == 2000  # and stays there while IN stays TRUE
    assert probe.at("T.ET", 6.0) == 0  # IN FALSE resets Q and ET
    assert probe.at("T.ET", 10.9) == 900
    assert probe.at("T.ET", 11.0) == 0  # released before PT: reset, Q never came


def test_ton_physical_output_follows_at_the_end_of_the_scan():
    cpu = CPU(tags=BOX_TAGS, program=box_program("TON", "2s"), cycle="100ms")
    probe = Probe(cpu, "Q", outputs=True)
    drive(cpu, held("IN", (1, 6)), 8)
    assert probe.changes("Q") == [(0.1, False), (3.1, True), (6.1, False)]


# --------------------------------------------------------------------------------------------
# TOF (§4.5.3): PT = 2 s
# --------------------------------------------------------------------------------------------


@DIALECTS
def test_tof_diagram_pt_2s(dialect):
    probe = run_box("TOF", "2s", [*held("IN", (1, 6), (10, 11)), (12, "IN", True)], 20, dialect)
    # initial Q FALSE; IN 1-6 s: Q 1-8 s; IN 10-11 s then TRUE again at 12 s: Q stays 1 from 10 s on
    assert probe.changes("Q") == [(0.0, False), (1.0, True), (8.0, False), (10.0, True)]


@DIALECTS
def test_tof_starts_false_and_et_stays_at_pt_after_timeout(dialect):
    probe = run_box("TOF", "2s", [*held("IN", (1, 6), (10, 11)), (12, "IN", True)], 20, dialect)
    assert (probe.at("Q", 0.0), probe.at("T.ET", 0.0)) == (False, 0)  # "IN has not yet been TRUE"
    assert (probe.at("Q", 3.0), probe.at("T.ET", 3.0)) == (True, 0)  # IN TRUE: the reset state
    assert probe.at("T.ET", 7.0) == 1000
    assert (probe.at("Q", 8.0), probe.at("T.ET", 8.0)) == (False, 2000)
    assert (probe.at("Q", 9.9), probe.at("T.ET", 9.9)) == (False, 2000)  # ET stays PT: differs from the start
    assert probe.at("T.ET", 11.5) == 500  # falling edge at 11 s times again
    assert (probe.at("Q", 12.0), probe.at("T.ET", 12.0)) == (True, 0)  # IN again within PT: ET 0, Q stays


# --------------------------------------------------------------------------------------------
# TP (§4.5.4): PT = 4 s
# --------------------------------------------------------------------------------------------


@DIALECTS
def test_tp_diagram_pt_4s_edges_during_the_pulse_are_ignored(dialect):
    events = held("IN", (1, 1.2), (2, 2.2), (3, 3.2), (10, 10.2))
    probe = run_box("TP", "4s", events, 16, dialect)
    assert probe.changes("Q") == [(0.0, False), (1.0, True), (5.0, False), (10.0, True), (14.0, False)]


@DIALECTS
def test_tp_pulse_length_does_not_depend_on_in_and_et_after_the_pulse(dialect):
    # Documented model (timers.py, TP): after the pulse ET stays at PT while IN stays TRUE and returns
    # to 0 once IN is FALSE ([X] Siemens; the textbook's Fig. 3.218 shows only ET = PT).
    probe = run_box("TP", "4s", held("IN", (1, 7)), 9, dialect)
    assert probe.changes("Q") == [(0.0, False), (1.0, True), (5.0, False)]
    assert probe.at("T.ET", 3.0) == 2000
    assert probe.at("T.ET", 6.0) == 4000
    assert probe.at("T.ET", 7.0) == 0


@DIALECTS
def test_tp_retrigger_needs_in_false_for_one_scan(dialect):
    # IN held across the end of the pulse: no new pulse until IN has been FALSE and TRUE again
    probe = run_box("TP", "1s", held("IN", (1, 3), (3.1, 3.2)), 5, dialect)
    assert probe.changes("Q") == [(0.0, False), (1.0, True), (2.0, False), (3.1, True), (4.1, False)]


# --------------------------------------------------------------------------------------------
# TONR (§4.5.5): PT = 4 s
# --------------------------------------------------------------------------------------------


@DIALECTS
def test_tonr_diagram_pt_4s(dialect):
    events = held("IN", (1, 3), (6, 7.5), (10, 11), (16, 18)) + held("R", (14, 14.5))
    probe = run_box("TONR", "4s", events, 20, dialect, extra=", R=t.R")
    assert probe.at("T.ET", 3.0) == 2000  # IN 1-3 s: ET 2 s
    assert probe.at("T.ET", 5.0) == 2000  # IN FALSE keeps ET
    assert probe.at("T.ET", 7.5) == 3500  # IN 6-7.5 s continues: ET 3.5 s
    assert probe.at("T.ET", 10.4) == 3900
    assert probe.at("T.ET", 10.5) == 4000  # IN 10-11 s: ET reaches PT at 10.5 s
    assert probe.at("T.ET", 13.9) == 4000  # Q and ET stay when IN drops
    assert (probe.at("Q", 14.0), probe.at("T.ET", 14.0)) == (False, 0)  # R 14-14.5 s resets
    assert probe.at("T.ET", 17.0) == 1000  # IN 16-18 s restarts from 0
    assert probe.at("T.ET", 18.0) == 2000
    assert probe.changes("Q") == [(0.0, False), (10.5, True), (14.0, False)]


@DIALECTS
def test_tonr_reset_dominates_in(dialect):
    probe = run_box("TONR", "1s", held("IN", (1, 4)) + held("R", (1, 2)), 4, dialect, extra=", R=t.R")
    assert all(et == 0 for when, et in probe.samples["T.ET"] if when < 2_000_000_000)
    assert probe.changes("Q") == [(0.0, False)]  # IN stays TRUE when R falls at 2 s: see the next test


@DIALECTS
def test_tonr_r_falling_while_in_is_true_does_not_start(dialect):
    # "If both inputs are TRUE and R changes to FALSE, the timer does not start, because starting requires
    # a change of IN from FALSE to TRUE."
    events = held("IN", (1, 3), (4, 6)) + held("R", (0.5, 2))
    probe = run_box("TONR", "1s", events, 6, dialect, extra=", R=t.R")
    assert probe.at("T.ET", 2.9) == 0
    assert probe.at("T.ET", 4.5) == 500  # a fresh rising edge of IN starts it
    assert probe.changes("Q") == [(0.0, False), (5.0, True)]


# --------------------------------------------------------------------------------------------
# RT (§3.6.5, §4.5.6, §5.5 item 4)
# --------------------------------------------------------------------------------------------

RT_PROGRAM = """
T = IEC_TIMER()
AFTER = Tag("%M10.0")
LATER = Tag("%M10.1")
DATA = DB(INT_1=Int(0))
def rung(t):
    q = t.T.TON(IN=t.IN, PT="13s")
    if q:
        RT(t.T)
        t.DATA.INT_1 += 1
    t.AFTER = q            # a coil after RT on the same rung still gets TRUE
def next_rung(t):
    t.LATER = t.T.Q        # the instance itself is already reset
OB1 = [rung, next_rung]
"""


@pytest.mark.parametrize(("cycle", "expected"), [("100ms", [13.0, 26.1, 39.2]), ("1ms", [13.0, 26.001, 39.002])])
def test_rt_counts_completed_timings_restarting_one_scan_later(cycle, expected):
    cpu = CPU(tags=BOX_TAGS, program=RT_PROGRAM, cycle=cycle)
    probe = Probe(cpu, "AFTER", "LATER", "DATA.INT_1", "T.ET")
    drive(cpu, held("IN", (0, 40)), 40)
    assert [r / 1e9 for r in probe.rises("AFTER")] == expected  # period PT + 1 scan
    assert probe.true_runs("AFTER") == [1, 1, 1]
    assert probe.rises("LATER") == []
    assert cpu.read("DATA.INT_1") == 3


def test_rt_shows_in_the_rlo_only_in_the_next_cycle():
    cpu = CPU(tags=BOX_TAGS, program=RT_PROGRAM, cycle="100ms")
    probe = Probe(cpu, "AFTER", "T.ET")
    drive(cpu, held("IN", (0, 14)), 13.5)
    assert probe.at("AFTER", 13.0) is True
    assert probe.at("T.ET", 13.0) == 0  # reset in the expiry scan
    assert probe.at("AFTER", 13.1) is False
    assert probe.at("T.ET", 13.1) == 0  # restarted in this scan: ET counts from here
    assert probe.at("T.ET", 13.2) == 100


# --------------------------------------------------------------------------------------------
# The unused-timer rule (§3.6.1, Fig. 3.197) and the two dialects
# --------------------------------------------------------------------------------------------

UNUSED = "TON_1 = IEC_TIMER()\ndef OB1(t):\n    t.TON_1.TON(IN=t.TLACIDLO, PT='1s')\n"


def test_unused_timer_never_starts_under_the_strict_rule():
    cpu = CPU(tags=PANEL, program=UNUSED, cycle="100ms")
    assert len(cpu.warnings) == 1
    assert "TON_1" in cpu.warnings[0] and "§3.6.1" in cpu.warnings[0] and "does not start" in cpu.warnings[0]
    drive(cpu, held("TLACIDLO", (0, 3)), 2)
    assert (cpu.read("TON_1.Q"), cpu.read("TON_1.ET"), cpu.read("TON_1.PT"), cpu.read("TON_1.IN")) == (
        False,
        0,
        0,
        False,
    )


@DIALECTS
def test_unused_timer_runs_when_the_strict_rule_is_off(dialect):
    cpu = CPU(tags=PANEL, program=UNUSED, cycle="100ms", textbook_strict_timers=False, timer_dialect=dialect)
    assert len(cpu.warnings) == 1 and "runs it anyway" in cpu.warnings[0]
    drive(cpu, held("TLACIDLO", (0, 3)), 2)
    assert (cpu.read("TON_1.Q"), cpu.read("TON_1.ET")) == (True, 1000)


@pytest.mark.parametrize(
    "use",
    [
        pytest.param("    t.LED = t.TON_1.Q\n", id="Q-read-elsewhere-4.2.9"),
        pytest.param("    t.LED = t.TON_1.ET > 500\n", id="ET-read"),
    ],
)
def test_a_timer_read_anywhere_is_used(use):
    cpu = CPU(tags=PANEL, program=UNUSED + use, cycle="100ms")
    assert cpu.warnings == []
    drive(cpu, held("TLACIDLO", (0, 3)), 2)
    assert cpu.outputs["LED"] is True


REFRESH = """
T = IEC_TIMER()
SEEN_BEFORE = Tag("%M10.0")
def OB1(t):
    t.SEEN_BEFORE = t.T.Q      # read before the box runs in this scan
    t.LED = t.T.TON(IN=t.TLACIDLO, PT="1s")
"""


@pytest.mark.parametrize(("dialect", "lag_s"), [("s7_1200", 0.0), ("iec", 0.1)])
def test_reading_q_refreshes_the_timer_only_in_the_s7_1200_dialect(dialect, lag_s):
    cpu = CPU(tags=PANEL, program=REFRESH, cycle="100ms", timer_dialect=dialect)
    probe = Probe(cpu, "SEEN_BEFORE", "LED")
    drive(cpu, held("TLACIDLO", (0, 3)), 2)
    assert [r / 1e9 for r in probe.rises("LED")] == [1.0]
    # s7_1200: the read refreshes the instance, so Q is seen in the expiry scan before the box runs;
    # iec: the instance changes only at the box, so the earlier read sees it one scan later
    assert [r / 1e9 for r in probe.rises("SEEN_BEFORE")] == [pytest.approx(1.0 + lag_s)]


# --------------------------------------------------------------------------------------------
# §4.2 program analysis with timers (spec §6.2)
# --------------------------------------------------------------------------------------------

P_4_2_8 = "TON_1 = IEC_TIMER()\ndef OB1(t):\n    t.LED = t.TON_1.TON(IN=t.TLACIDLO, PT='5s')\n"
P_4_2_9 = """
TON_1 = IEC_TIMER()
def n1(t):
    t.TON_1.TON(IN=t.TLACIDLO, PT="5s")
def n2(t):
    t.LED = t.TON_1.Q
OB1 = [n1, n2]
"""


@pytest.mark.parametrize("program", [pytest.param(P_4_2_8, id="4.2.8"), pytest.param(P_4_2_9, id="4.2.9")])
def test_4_2_8_and_4_2_9_hold_5s_for_the_led(program):
    cpu = CPU(tags=PANEL, program=program, cycle="100ms")
    probe = Probe(cpu, "LED")
    drive(cpu, held("TLACIDLO", (1, 4), (10, 17)), 20)  # released before 5 s: nothing; held 7 s: on 15-17 s
    assert probe.changes("LED") == [(0.0, False), (15.0, True), (17.0, False)]


P_4_2_10 = """
TOF_1 = IEC_TIMER()
def OB1(t):
    t.TOF_1.TOF(IN=t.TLACIDLO, PT="5s")
    t.LED = not t.TOF_1.Q
"""


def test_4_2_10_tof_led_on_at_start_back_on_5s_after_release():
    cpu = CPU(tags=PANEL, program=P_4_2_10, cycle="100ms")
    probe = Probe(cpu, "LED")
    # press 1-2 s, press again 3-4 s (within the 5 s: timing restarts), press 10-11 s
    drive(cpu, held("TLACIDLO", (1, 2), (3, 4), (10, 11)), 20)
    assert probe.changes("LED") == [(0.0, True), (1.0, False), (9.0, True), (10.0, False), (16.0, True)]


P_4_2_13 = """
TON_1 = IEC_TIMER()
def OB1(t):
    t.TON_1.TON(IN=t.TLACIDLO, PT="PTVALUE")
    t.LED = t.TON_1.ET >= TIME("4s")
"""


@pytest.mark.parametrize("pt", ["4s", "10s"])
def test_4_2_13_led_on_after_4s_until_release(pt):
    cpu = CPU(tags=PANEL, program=P_4_2_13.replace("PTVALUE", pt), cycle="100ms")
    probe = Probe(cpu, "LED")
    drive(cpu, held("TLACIDLO", (1, 3), (5, 12)), 14)
    assert probe.changes("LED") == [(0.0, False), (9.0, True), (12.0, False)]


P_4_2_14 = """
TON_1 = IEC_TIMER()
def OB1(t):
    t.TON_1.TON(IN=t.TLACIDLO, PT="8s")
    if t.TON_1.ET <= TIME("2s"):
        t.LED = True
    if t.TON_1.ET >= TIME("6s"):
        t.LED = False
"""


@pytest.mark.parametrize(
    ("press", "expected"),
    [
        pytest.param((2, 9), [(0.0, True), (8.0, False), (9.0, True)], id="press-2-9"),
        pytest.param((12, 15), [(0.0, True)], id="press-12-15-stays-on"),
        pytest.param((20, 30), [(0.0, True), (26.0, False), (30.0, True)], id="press-20-30"),
    ],
)
def test_4_2_14_scenarios(press, expected):
    cpu = CPU(tags=PANEL, program=P_4_2_14, cycle="100ms")
    probe = Probe(cpu, "LED")
    drive(cpu, held("TLACIDLO", press), 35)
    assert probe.changes("LED") == expected


P_4_2_15 = """
TON_1 = IEC_TIMER()
def OB1(t):
    t.TON_1.TON(IN=t.TLACIDLO, PT="6s")
    if t.TON_1.ET < TIME("6s"):
        t.LED = True
    if t.TON_1.ET >= TIME("2s"):
        t.LED = False
"""


def test_4_2_15_on_for_2s_then_reset_wins():
    cpu = CPU(tags=PANEL, program=P_4_2_15, cycle="100ms")
    probe = Probe(cpu, "LED")
    drive(cpu, held("TLACIDLO", (1, 10)), 12)
    assert probe.changes("LED") == [(0.0, True), (3.0, False), (10.0, True)]
    assert cpu.read("TON_1.ET") == 0


P_4_2_17 = """
TON_1 = IEC_TIMER()
TOF_1 = IEC_TIMER()
def OB1(t):
    t.LED = t.TOF_1.TOF(IN=t.TON_1.TON(IN=t.PREPINAC, PT="3s"), PT="5s")
"""


@pytest.mark.parametrize(
    ("switch", "expected"),
    [
        pytest.param((1, 9), [(0.0, False), (4.0, True), (14.0, False)], id="on-1-9"),
        pytest.param((17, 18), [(0.0, False)], id="on-17-18-never"),
        pytest.param((22, 29), [(0.0, False), (25.0, True), (34.0, False)], id="on-22-29"),
    ],
)
def test_4_2_17_scenarios(switch, expected):
    cpu = CPU(tags=PANEL, program=P_4_2_17, cycle="100ms")
    probe = Probe(cpu, "LED")
    drive(cpu, held("PREPINAC", switch), 36)
    assert probe.changes("LED") == expected


P_SET_RESET_ON_ET = """
TON_1 = IEC_TIMER()
def OB1(t):
    t.TON_1.TON(IN=t.TLACIDLO, PT="10s")
    if t.TON_1.ET >= TIME("2s"):
        t.LED = True
    if t.TON_1.ET >= TIME("5s"):
        t.LED = False
"""


def test_4_5_2_et_comparisons_set_at_2s_reset_at_5s_and_keep_on_release():
    cpu = CPU(tags=PANEL, program=P_SET_RESET_ON_ET, cycle="100ms")
    probe = Probe(cpu, "LED")
    drive(cpu, held("TLACIDLO", (1, 4), (10, 20)), 22)
    # released at 4 s (after the SET, before the RESET): the LED keeps TRUE; the second press resets it at 15 s
    assert probe.changes("LED") == [(0.0, False), (3.0, True), (15.0, False)]


# --------------------------------------------------------------------------------------------
# A negative preset: the S7-1200 System Manual (11/2011, A5E02486680-05, §7.2, note to Table 7-20)
# --------------------------------------------------------------------------------------------


def test_the_manuals_words_on_a_negative_preset_are_the_ones_the_timers_cite():
    from plcsim.controllers.s7.instructions.timers import NEGATIVE_PRESET

    assert "Negative PT (preset time) values are set to zero when the timer instruction is executed" in NEGATIVE_PRESET
    assert NEGATIVE_PRESET.endswith("ET (elapsed time) is always a positive value.")


@DIALECTS
@pytest.mark.parametrize("box", ["TON", "TOF", "TP", "TONR"])
def test_a_negative_preset_is_zero_when_the_box_runs_and_et_is_never_negative(dialect, box):
    """PT = -500 ms times exactly as PT = T#0ms, scan by scan (TON is done in the scan IN rises, TOF's Q falls with
    IN); the instance's PT reads 0 once the box has run, and ET is 0 throughout, never -500 ms."""
    runs = {}
    for pt in (-500, 0):
        cpu = CPU(tags=BOX_TAGS, program=box_program(box, pt), cycle="100ms", timer_dialect=dialect)
        probe = Probe(cpu, "Q", "T.ET", "T.PT")
        drive(cpu, held("IN", (1, 2)), 3)
        assert cpu.mode == "RUN"
        runs[pt] = probe
    assert runs[-500].changes("Q") == runs[0].changes("Q")
    assert runs[-500].changes("T.ET") == runs[0].changes("T.ET") == [(0.0, 0)]
    assert runs[-500].changes("T.PT") == [(0.0, 0)]
    if box == "TON":
        assert runs[-500].changes("Q") == [(0.0, False), (1.0, True), (2.0, False)]


def test_a_negative_preset_written_meanwhile_never_makes_et_negative():
    """A PT written while the timer runs (an HMI's, or the -(PT)- coil's) reaches ET through a read's refresh before
    the box runs again: ET is 0 then, not the negative preset; the next execution of the box sets PT to zero."""
    program = (
        "T = IEC_TIMER()\n"
        "def OB1(t):\n"
        "    if t.R:\n"
        "        PT(t.T, -500)\n"
        "    t.Q = t.T.ET > T#0ms\n"
        "    t.T.TON(IN=t.IN, PT=t.T.PT)\n"
    ).replace("T#0ms", "TIME('0ms')")
    cpu = CPU(tags=BOX_TAGS, program=program, cycle="100ms", textbook_strict_timers=False)
    cpu.write("T.PT", 2000)
    probe = Probe(cpu, "Q", "T.ET", "T.PT")
    drive(cpu, [*held("IN", (1, 5)), *held("R", (1.5, 1.6))], 5)
    assert probe.at("T.ET", 1.4) == 400
    assert min(v for _t, v in probe.changes("T.ET")) == 0
    assert probe.at("T.PT", 2.0) == 0
