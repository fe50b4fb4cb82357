"""Golden tests: edge instructions -|P|-, -|N|-, P_TRIG/N_TRIG, -(P)-/-(N)-, R_TRIG/F_TRIG (spec §4.1, §6.2).

Rules these tests pin:

* ``P(op, "SB")`` is TRUE in the one execution in which ``op`` went FALSE -> TRUE; it writes the edge
  memory bit at once, so a later read of SB in the same scan sees the new value (§4.2.4).
* Every instruction runs every scan, so "how many toggles" questions count scans, not toggles, for
  plain contacts (§4.2.1/4.2.2), and toggles for edges (§4.2.3/4.2.5).
* A P and an N sharing one memory bit: the second one never fires.
* Non-retentive %M is cleared at STOP->RUN, so an input TRUE at startup gives a rising edge in the
  first scan (§4.3.22).
* An R_TRIG instance keeps its own Stat_Bit; calling one instance twice per scan breaks it.
"""

from __future__ import annotations

import pytest
from plcharness import Probe

from plcsim import CPU, Tag

PANEL = {"TLACIDLO": Tag("%I0.0"), "PREPINAC": Tag("%I0.2"), "LED": Tag("%Q0.0")}
DECLS = """
POM = Tag("%M10.0")
SB = Tag("%M10.1")
CISLO = Tag("%MW12", Int)
"""


def toggles_to_reach_10(program: str, scans_per_half: int, limit: int = 20) -> tuple[int | None, int]:
    """Toggle PREPINAC FALSE -> TRUE -> FALSE until CISLO >= 10; return (toggles, CISLO)."""
    cpu = CPU(tags=PANEL, program=DECLS + program)
    for toggle in range(1, limit + 1):
        cpu.set_input("PREPINAC", True)
        cpu.scan(scans_per_half)
        if cpu.read("CISLO") >= 10:
            return toggle, cpu.read("CISLO")
        cpu.set_input("PREPINAC", False)
        cpu.scan(scans_per_half)
    assert cpu.mode == "RUN"
    return None, cpu.read("CISLO")


P_4_2_1 = "def OB1(t):\n    if t.PREPINAC:\n        t.CISLO += 2\n"
P_4_2_2 = "def n1(t):\n    t.POM = t.PREPINAC\ndef n2(t):\n    if t.POM:\n        t.CISLO += 2\nOB1 = [n1, n2]\n"
P_4_2_3 = (
    'def n1(t):\n    t.POM = P(t.PREPINAC, "SB")\ndef n2(t):\n    if t.POM:\n        t.CISLO += 2\nOB1 = [n1, n2]\n'
)
P_4_2_4 = """
def n1(t):
    t.POM = P(t.PREPINAC, "SB")
def n2(t):
    pom = t.POM
    not_sb = not t.SB
    if pom and not_sb:
        t.CISLO += 2
OB1 = [n1, n2]
"""
P_4_2_5 = """
def OB1(t):
    edge = P(t.PREPINAC, "SB")
    t.POM = edge               # upper branch: = POM
    if edge and t.POM:         # lower branch: POM -> ADD, fed by the same edge
        t.CISLO += 2
"""


@pytest.mark.parametrize(
    ("program", "scans", "toggles", "cislo"),
    [
        pytest.param(P_4_2_1, 5, 1, 10, id="4.2.1-one-toggle-5-scans"),
        pytest.param(P_4_2_2, 5, 1, 10, id="4.2.2-one-toggle-5-scans"),
        pytest.param(P_4_2_1, 50, 1, 100, id="4.2.1-cycles-not-toggles"),
        pytest.param(P_4_2_3, 3, 5, 10, id="4.2.3-five-toggles"),
        pytest.param(P_4_2_4, 3, None, 0, id="4.2.4-never"),
        pytest.param(P_4_2_5, 3, 5, 10, id="4.2.5-five-toggles"),
    ],
)
def test_toggles_needed_for_cislo_10(program, scans, toggles, cislo):
    assert toggles_to_reach_10(program, scans) == (toggles, cislo)


def test_4_2_4_edge_memory_is_written_at_the_instruction():
    cpu = CPU(tags=PANEL, program=DECLS + P_4_2_4)
    cpu.set_input("PREPINAC", True)
    cpu.scan()
    assert (cpu.read("POM"), cpu.read("SB"), cpu.read("CISLO")) == (True, True, 0)


P_4_2_6 = """
def n1(t):
    if t.PREPINAC:
        t.POM = True
def n2(t):
    t.POM = t.TLACIDLO
def n3(t):
    if t.POM:
        t.CISLO += 2
OB1 = [n1, n2, n3]
"""


def test_4_2_6_assignment_overwrites_the_set_prepinac_has_no_effect():
    cpu = CPU(tags=PANEL, program=DECLS + P_4_2_6)
    cpu.set_input("PREPINAC", True)
    cpu.scan(20)
    assert cpu.read("CISLO") == 0
    cpu.set_input("TLACIDLO", True)
    cpu.scan(5)
    assert cpu.read("CISLO") == 10


P_4_2_7 = """
def n1(t):
    t.POM = t.TLACIDLO or t.POM
def n2(t):
    if not t.POM:
        t.CISLO += 2
OB1 = [n1, n2]
"""


def test_4_2_7_adds_every_scan_wrapping_until_the_first_press_then_never():
    cpu = CPU(tags=PANEL, program=DECLS + P_4_2_7)
    cpu.scan(16_383)
    assert cpu.read("CISLO") == 32_766
    cpu.scan()
    assert cpu.read("CISLO") == -32_768  # INT wraps and keeps counting up
    cpu.scan(4)
    assert cpu.read("CISLO") == -32_760
    cpu.set_input("TLACIDLO", True)
    cpu.scan()  # POM seals in and ADD stops in that very scan
    assert (cpu.read("POM"), cpu.read("CISLO")) == (True, -32_760)
    cpu.set_input("TLACIDLO", False)
    cpu.scan(100)
    assert (cpu.read("POM"), cpu.read("CISLO")) == (True, -32_760)


P_4_2_11 = """
def n1(t):
    if t.TLACIDLO and not t.LED:
        t.LED = True
def n2(t):
    if t.TLACIDLO and t.LED:
        t.LED = False
OB1 = [n1, n2]
"""
P_4_2_12 = """
SB = Tag("%M10.1")
def OB1(t):
    edge = P(t.TLACIDLO, "SB")
    if edge and not t.LED:
        t.LED = True
    if edge and t.LED:
        t.LED = False
"""


@pytest.mark.parametrize("program", [pytest.param(P_4_2_11, id="4.2.11"), pytest.param(P_4_2_12, id="4.2.12")])
def test_led_never_turns_on_from_the_button(program):
    cpu = CPU(tags=PANEL, program=program)
    probe = Probe(cpu, "LED", outputs=True)
    for _ in range(5):
        cpu.set_input("TLACIDLO", True)
        cpu.scan(3)
        cpu.set_input("TLACIDLO", False)
        cpu.scan(3)
    assert probe.changes("LED") == [(0.001, False)]


def test_4_2_11_led_set_from_the_watch_table_stays_until_the_button():
    cpu = CPU(tags=PANEL, program=P_4_2_11)
    cpu.scan()
    cpu.write("LED", True)
    cpu.scan(10)
    assert cpu.outputs["LED"] is True
    cpu.set_input("TLACIDLO", True)
    cpu.scan()
    assert cpu.outputs["LED"] is False


SHARED_BIT = """
SB = Tag("%M10.1")
RISE = Tag("%M10.2")
FALL = Tag("%M10.3")
def OB1(t):
    t.RISE = P(t.TLACIDLO, "SB")
    t.FALL = N(t.TLACIDLO, "SB")
"""
OWN_BITS = """
SB = Tag("%M10.1")
SB2 = Tag("%M10.4")
RISE = Tag("%M10.2")
FALL = Tag("%M10.3")
def OB1(t):
    t.RISE = P(t.TLACIDLO, "SB")
    t.FALL = N(t.TLACIDLO, "SB2")
"""


@pytest.mark.parametrize(
    ("program", "falls"),
    [pytest.param(SHARED_BIT, 0, id="shared-bit-N-never"), pytest.param(OWN_BITS, 3, id="own-bits")],
)
def test_p_and_n_sharing_one_memory_bit(program, falls):
    cpu = CPU(tags=PANEL, program=program)
    probe = Probe(cpu, "RISE", "FALL")
    for _ in range(3):
        cpu.set_input("TLACIDLO", True)
        cpu.scan(3)
        cpu.set_input("TLACIDLO", False)
        cpu.scan(3)
    assert probe.true_runs("RISE") == [1, 1, 1]
    assert len(probe.rises("FALL")) == falls


def test_n_fires_once_on_the_falling_edge():
    program = 'SB = Tag("%M10.1")\nFALL = Tag("%M10.3")\ndef OB1(t):\n    t.FALL = N(t.TLACIDLO, "SB")\n'
    cpu = CPU(tags=PANEL, program=program)
    probe = Probe(cpu, "FALL")
    cpu.scan(2)
    cpu.set_input("TLACIDLO", True)
    cpu.scan(3)
    cpu.set_input("TLACIDLO", False)
    cpu.scan(3)
    assert [r / 1e6 for r in probe.rises("FALL")] == [5.0]
    assert probe.true_runs("FALL") == [1]


FIRST_SCAN_EDGE = """
SB = Tag("%M10.1")
N_EDGES = DB(COUNT=Int(0, retain=True))
def OB1(t):
    if P(t.TLACIDLO, "SB"):
        t.N_EDGES.COUNT += 1
"""


@pytest.mark.parametrize("declared_in", ["program", "tag-table"])
@pytest.mark.parametrize(("retentive_markers", "after_restart"), [(0, 2), (11, 1)])
def test_rising_edge_in_the_first_scan_after_stop_run(retentive_markers, after_restart, declared_in):
    program, tags = FIRST_SCAN_EDGE, PANEL
    if declared_in == "tag-table":  # the edge bit is in the exercise's tag table, not in the program
        program, tags = program.replace('SB = Tag("%M10.1")', ""), {**PANEL, "SB": Tag("%M10.1")}
    cpu = CPU(tags=tags, program=program, retentive_markers=retentive_markers)
    cpu.set_input("TLACIDLO", True)
    cpu.scan(5)
    assert cpu.read("N_EDGES.COUNT") == 1
    cpu.stop()
    cpu.start()  # SB (%M10.1) is cleared unless MB0..MB10 are retentive
    cpu.scan()
    assert cpu.read("N_EDGES.COUNT") == after_restart


P_TRIG_PROGRAM = """
MEM = Tag("%M10.1")
MEM_N = Tag("%M10.2")
UP = Tag("%M10.3")
DOWN = Tag("%M10.4")
def OB1(t):
    rlo = t.TLACIDLO and t.PREPINAC         # P_TRIG watches the RLO, not one operand
    t.UP = P_TRIG(rlo, "MEM")
    t.DOWN = N_TRIG(rlo, "MEM_N")
"""


def test_p_trig_and_n_trig_watch_the_rlo():
    cpu = CPU(tags=PANEL, program=P_TRIG_PROGRAM)
    probe = Probe(cpu, "UP", "DOWN")
    cpu.set_input("TLACIDLO", True)
    cpu.scan(2)
    cpu.set_input("PREPINAC", True)  # the AND rises in scan 2
    cpu.scan(2)
    cpu.set_input("TLACIDLO", False)  # and falls in scan 4
    cpu.scan(2)
    assert [r // 1_000_000 for r in probe.rises("UP")] == [2]
    assert [r // 1_000_000 for r in probe.rises("DOWN")] == [4]
    assert probe.true_runs("UP") == [1] and probe.true_runs("DOWN") == [1]


COILS = """
MEM_P = Tag("%M10.1")
MEM_N = Tag("%M10.2")
PULSE_UP = Tag("%M10.3")
PULSE_DOWN = Tag("%M10.4")
def OB1(t):
    rlo = P_COIL(t.TLACIDLO, "PULSE_UP", "MEM_P")
    N_COIL(rlo, "PULSE_DOWN", "MEM_N")
    t.LED = rlo                    # the RLO passes through the coils
"""


def test_p_coil_and_n_coil_write_their_operand_for_one_scan():
    cpu = CPU(tags=PANEL, program=COILS)
    probe = Probe(cpu, "PULSE_UP", "PULSE_DOWN", "LED")
    cpu.scan(2)
    cpu.set_input("TLACIDLO", True)
    cpu.scan(4)
    cpu.set_input("TLACIDLO", False)
    cpu.scan(4)
    assert [r // 1_000_000 for r in probe.rises("PULSE_UP")] == [2]
    assert [r // 1_000_000 for r in probe.rises("PULSE_DOWN")] == [6]
    assert probe.true_runs("PULSE_UP") == [1] and probe.true_runs("PULSE_DOWN") == [1]
    assert probe.true_runs("LED") == [4]


R_TRIG_PROGRAM = """
EDGE = R_TRIG()
FALL = F_TRIG()
POMOCNY_STAV = Tag("%M10.0")
DOWN = Tag("%M10.5")
def n1(t):
    if t.PREPINAC:                                         # EN = MANUALNY_REZIM
        t.POMOCNY_STAV = t.EDGE.R_TRIG(CLK=t.TLACIDLO)
def n2(t):
    t.DOWN = t.FALL.F_TRIG(CLK=t.TLACIDLO)
OB1 = [n1, n2]
"""


def test_r_trig_and_f_trig_instances():
    cpu = CPU(tags=PANEL, program=R_TRIG_PROGRAM)
    probe = Probe(cpu, "POMOCNY_STAV", "DOWN", "EDGE.Stat_Bit")
    cpu.set_input("PREPINAC", True)
    cpu.scan(2)
    cpu.set_input("TLACIDLO", True)
    cpu.scan(3)
    cpu.set_input("TLACIDLO", False)
    cpu.scan(3)
    assert [r // 1_000_000 for r in probe.rises("POMOCNY_STAV")] == [2]
    assert probe.true_runs("POMOCNY_STAV") == [1]
    assert [r // 1_000_000 for r in probe.rises("DOWN")] == [5]
    assert (cpu.read("EDGE.Q"), cpu.read("EDGE.CLK"), cpu.read("EDGE.Stat_Bit")) == (False, False, False)


def test_r_trig_not_called_when_en_is_false_keeps_its_state():
    cpu = CPU(tags=PANEL, program=R_TRIG_PROGRAM)
    cpu.set_input("TLACIDLO", True)  # mode off: the button's edge goes unseen by the FB
    cpu.scan(3)
    assert (cpu.read("POMOCNY_STAV"), cpu.read("EDGE.Stat_Bit")) == (False, False)
    cpu.set_input("PREPINAC", True)  # mode on with the button still held: the FB sees the rise now
    cpu.scan()
    assert cpu.read("POMOCNY_STAV") is True


SHARED_INSTANCE = """
EDGE = R_TRIG()
UP_A = Tag("%M10.0")
UP_B = Tag("%M10.1")
def OB1(t):
    t.UP_A = t.EDGE.R_TRIG(CLK=t.TLACIDLO)
    t.UP_B = t.EDGE.R_TRIG(CLK=t.PREPINAC)
"""


def test_one_r_trig_instance_shared_by_two_calls_fires_every_scan():
    cpu = CPU(tags=PANEL, program=SHARED_INSTANCE)
    probe = Probe(cpu, "UP_A", "UP_B")
    cpu.set_input("TLACIDLO", True)  # held for 5 scans, PREPINAC stays FALSE
    cpu.scan(5)
    # the second call overwrites Stat_Bit with PREPINAC = FALSE, so the first "sees" a rise every scan
    assert probe.true_runs("UP_A") == [5]
    assert probe.rises("UP_B") == []
