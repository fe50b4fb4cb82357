"""The MECHANISM instance type (PLC836 step mechanisms in the Python form): what the chapter implies
beyond its examples (spec §6.2) and the one-step-per-scan setting (IEC 61131-3 SFC)."""

from __future__ import annotations

import pytest

from plcsim import CPU, Tag
from plcsim.core.errors import ConfigurationError

TAGS = {name: Tag(f"%I0.{k}") for k, name in enumerate("ABC")} | {f"Y{k}": Tag(f"%Q0.{k - 1}") for k in (1, 2, 3)}
CHAIN = """
SEQ = MECHANISM()

def seq(t):
    if t.SEQ.begin():
        if t.SEQ.step(1):
            t.Y1 = True
            t.SEQ.wait_until(t.A)
        if t.SEQ.step(2):
            t.Y2 = True
            t.SEQ.wait_until(t.B)
        if t.SEQ.step(3):
            t.Y3 = True
            t.SEQ.wait_until(t.C)
        t.SEQ.end()

OB1 = [seq]
"""


def started(program: str = CHAIN, **options) -> CPU:
    cpu = CPU(tags=TAGS, program=program, **options)
    for name in ("A", "B", "C"):
        cpu.set_input(name, True)
    cpu.write("SEQ.ACTIVE", True)
    return cpu


def test_a_sequence_whose_conditions_all_hold_finishes_in_the_scan_that_starts_it():
    cpu = started()
    cpu.scan()
    assert (cpu.t.Y1, cpu.t.Y2, cpu.t.Y3) == (True, True, True)
    assert cpu.read("SEQ.ACTIVE") is False and cpu.read("SEQ.STEP") == 0


def test_one_step_per_scan_takes_a_scan_for_each_step_and_one_for_the_end():
    cpu = started(mechanism_mode="iec")
    seen = []
    for _ in range(4):
        cpu.scan()
        seen.append((cpu.t.Y1, cpu.t.Y2, cpu.t.Y3, cpu.read("SEQ.STEP"), cpu.read("SEQ.ACTIVE")))
    assert seen == [
        (True, False, False, 2, True),
        (True, True, False, 3, True),
        (True, True, True, 4, True),
        (True, True, True, 0, False),
    ]


def test_an_unknown_mode_is_refused_with_the_choices():
    with pytest.raises(ConfigurationError, match="mechanism_mode 'sfc': use 'plc836' or 'iec'"):
        CPU(tags=TAGS, program=CHAIN, mechanism_mode="sfc")


def test_mech_init_from_an_opposing_mechanism_aborts_it_and_leaves_its_outputs():
    program = CHAIN.replace(
        "OB1 = [seq]",
        "def stop(t):\n    if t.C:\n        t.SEQ.init()\n        t.Y2 = False\n\nOB1 = [seq, stop]",
    )
    cpu = CPU(tags=TAGS, program=program)
    cpu.write("SEQ.ACTIVE", True)
    cpu.set_input("A", True)
    cpu.scan()
    assert cpu.read("SEQ.STEP") == 2 and cpu.t.Y1 and cpu.t.Y2
    cpu.set_input("C", True)
    cpu.scan()
    assert cpu.read("SEQ.ACTIVE") is False and cpu.read("SEQ.STEP") == 0
    assert cpu.t.Y1 is True and cpu.t.Y2 is False  # MECH_INIT undoes nothing; the stop drives Y2 itself
    cpu.set_input("C", False)
    cpu.write("SEQ.ACTIVE", True)
    cpu.scan()
    assert cpu.read("SEQ.STEP") == 2  # a new run starts from the top (step 1 passed again at once)


def test_clearing_the_bit_freezes_the_run_and_setting_it_resumes_mid_way():
    cpu = CPU(tags=TAGS, program=CHAIN)
    cpu.write("SEQ.ACTIVE", True)
    cpu.set_input("A", True)
    cpu.scan()
    cpu.write("SEQ.ACTIVE", False)  # spec §6.2 i: not MECH_INIT
    cpu.scan(3)
    assert cpu.read("SEQ.STEP") == 2
    cpu.write("SEQ.ACTIVE", True)
    cpu.set_input("B", True)
    cpu.scan()
    assert cpu.read("SEQ.STEP") == 3 and cpu.t.Y3 is True


def test_where_the_starting_code_sits_decides_whether_the_run_starts_in_the_same_scan():
    before = CHAIN.replace("OB1 = [seq]", "def go(t):\n    if t.A:\n        t.SEQ.start()\n\nOB1 = [go, seq]")
    after = CHAIN.replace("OB1 = [seq]", "def go(t):\n    if t.A:\n        t.SEQ.start()\n\nOB1 = [seq, go]")
    steps = {}
    for name, program in (("before", before), ("after", after)):
        cpu = CPU(tags=TAGS, program=program)
        cpu.set_input("A", True)
        cpu.scan()
        steps[name] = cpu.read("SEQ.STEP")
    assert steps == {"before": 2, "after": 0}


def test_a_wait_outside_its_step_stops_the_cpu_naming_the_fix():
    program = (
        "M = MECHANISM()\n\ndef m(t):\n    if t.M.begin():\n        t.M.wait_until(t.A)\n        t.M.end()\n\nOB1 = [m]"
    )
    cpu = CPU(tags=TAGS, program=program)
    cpu.write("M.ACTIVE", True)
    cpu.scan()
    assert cpu.mode == "STOP"
    assert "write it under `if t.M.step(n):`" in cpu.error.message and cpu.error.line == 5


def test_a_timeout_needs_an_error_label():
    program = CHAIN.replace("t.SEQ.wait_until(t.A)", 't.SEQ.wait_until(t.A, timeout="1s")')
    cpu = CPU(tags=TAGS, program=program)
    cpu.write("SEQ.ACTIVE", True)
    cpu.scan()
    assert cpu.mode == "STOP" and "a timeout needs error='LABEL'" in cpu.error.message


def test_the_trace_records_the_bit_the_step_its_time_and_the_error():
    from plcsim.sim.recorder import Recorder

    cpu = CPU(tags=TAGS, program=CHAIN)
    recorder = Recorder(cpu)
    assert [n for n in recorder.trace.names if n.startswith("SEQ")] == ["SEQ.ACTIVE", "SEQ.STEP", "SEQ.ET", "SEQ.ERR"]
    assert recorder.trace.types["SEQ.ET"] == "int" and recorder.trace.types["SEQ.ACTIVE"] == "bool"
