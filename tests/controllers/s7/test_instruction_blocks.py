"""One description per instance type (:data:`plcsim.controllers.s7.instructions.BLOCKS`): the compiler's typing,
the host access, the recorder and the student reference all read it, so none of them can drift from the others."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from plcsim import CPU, Tag
from plcsim.controllers.s7.instructions import BLOCKS, block_of
from plcsim.core.errors import PlcTypeError, ProgramError, UnknownTagError
from plcsim.frontends.python.reference import instruction_reference
from plcsim.sim.recorder import Recorder, default_signals

ROOT = Path(__file__).resolve().parents[3]

PROGRAM = """
T1 = IEC_TIMER()
C1 = IEC_COUNTER()
E1 = R_TRIG()
E2 = F_TRIG()

def OB1(t):
    t.T1.TON(IN=t.S1, PT="20ms")
    t.C1.CTU(CU=t.S1, R=False, PV=2)
    t.E1.R_TRIG(CLK=t.S1)
    t.E2.F_TRIG(CLK=t.S1)
    t.LED = t.T1.Q
"""


def _cpu() -> CPU:
    return CPU({"S1": Tag("%I0.0"), "LED": Tag("%Q0.0")}, PROGRAM)


def test_the_trace_records_each_instance_by_its_description():
    signals = default_signals(_cpu())
    for name, block in (("T1", "IEC_TIMER"), ("C1", "IEC_COUNTER"), ("E1", "R_TRIG"), ("E2", "F_TRIG")):
        assert [s for s in signals if s.startswith(f"{name}.")] == [f"{name}.{m}" for m in BLOCKS[block].traced]
    assert BLOCKS["IEC_TIMER"].traced == ("Q", "ET") and BLOCKS["IEC_COUNTER"].traced == ("CV", "QU", "QD")


def test_every_member_is_traceable_with_its_type_and_an_unknown_one_names_them_all():
    cpu = _cpu()
    names = [f"{inst}.{m}" for inst, block in (("T1", "IEC_TIMER"), ("C1", "IEC_COUNTER"), ("E1", "R_TRIG"))
             for m in BLOCKS[block].readable]  # fmt: skip
    recorder = Recorder(cpu, names)
    recorder.attach()
    cpu.set_input("S1", True)
    cpu.run("30ms")
    trace = recorder.trace
    assert trace.types["T1.ET"] == "int" and trace.types["T1.Q"] == "bool" and trace.types["C1.CV"] == "int"
    assert trace.kinds["T1.ET"] == "timer" and trace.kinds["C1.QU"] == "counter" and trace.kinds["E1.Q"] == "memory"
    assert trace.column("T1.ET")[-1] == 20 and trace.column("C1.CV")[-1] == 1 and trace.column("E1.Stat_Bit")[-1]
    with pytest.raises(UnknownTagError, match=r"cannot trace 'T1.XY': an instance of IEC_TIMER has Q, ET, PT, IN$"):
        Recorder(cpu, ["T1.XY"])


def test_reading_a_timer_for_the_watch_table_or_the_trace_never_refreshes_it():
    cpu = _cpu()
    cpu.set_input("S1", True)
    cpu.scan()
    cpu.clock.now += 50_000_000  # 50 ms later, no scan: the stored ET is still the scan's
    timer = cpu.t.T1
    assert cpu.read("T1.ET") == 0 and cpu.read("T1.Q") is False
    assert getattr(timer, type(timer).trace_source("ET")) == 0
    assert timer.ET == 20  # the program's read brings it up to date (s7_1200 dialect)


def test_writable_members_come_from_the_description():
    cpu = _cpu()
    cpu.write("T1.PT", "5s")
    cpu.write("C1.PV", 7)
    assert cpu.t.T1.PT == 5000 and cpu.t.C1.PV == 7
    for path in ("T1.ET", "C1.QU", "E1.Q"):
        with pytest.raises(PlcTypeError, match="cannot be written by the program"):
            cpu.write(path, 1)
    with pytest.raises(ProgramError, match=r"line 3: ET of a IEC_TIMER is computed by its box"):
        CPU({"S1": Tag("%I0.0")}, "T1 = IEC_TIMER()\ndef OB1(t):\n    t.T1.ET = 5\n")
    assert {name: sorted(b.writable) for name, b in BLOCKS.items()} == {
        "IEC_TIMER": ["PT"],
        "IEC_COUNTER": ["CV", "PV"],
        "R_TRIG": [],
        "F_TRIG": [],
        "MECHANISM": ["ACTIVE"],
    }


def test_the_student_reference_shows_each_description():
    page = instruction_reference()
    for name, block in BLOCKS.items():
        section = page.split(f"### `{name}()`")[1].split("###")[0]
        members = re.search(r"Members: (.*)\. The trace records (.*) unless told otherwise\.", section)
        assert members is not None, name
        assert re.findall(r"`(\w+)` (?:Bool|Time|Int|the count type)", members.group(1)) == list(block.readable)
        assert re.findall(r"`(\w+)` [^,]*\(writable", members.group(1)) == sorted(
            block.writable, key=list(block.readable).index
        )
        assert members.group(2) == ", ".join(f"`{m}`" for m in block.traced)
        assert sorted(re.findall(r"- `t\.NAME\.(\w+)\(", section)) == sorted(block.boxes)


def test_an_instance_is_described_by_its_class_and_nothing_else_reads_its_private_fields():
    cpu = _cpu()
    assert block_of(cpu.t.T1) is BLOCKS["IEC_TIMER"] and block_of(cpu.t.C1) is BLOCKS["IEC_COUNTER"]
    assert block_of(cpu.t.E2).readable == BLOCKS["F_TRIG"].readable and block_of(cpu.t.S1) is None
    outside = [
        f"{path.relative_to(ROOT)}:{n}"
        for path in sorted((ROOT / "plcsim").rglob("*.py"))
        if path.name != "timers.py"
        for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1)
        if re.search(r"\._(q|et|inert)\b", line)
    ]
    assert outside == []


def test_every_function_instruction_is_described_once_and_in_the_reference():
    from plcsim.controllers.s7.instructions import BOOL_RESULTS, CPU_BOUND, FUNCTIONS, PURE_INSTRUCTIONS
    from plcsim.frontends.python.reference import network_instructions

    assert set(network_instructions()) == set(FUNCTIONS)
    assert sorted(CPU_BOUND) == ["MOVE", "N", "N_COIL", "N_TRIG", "P", "P_COIL", "P_TRIG", "RD_LOC_T"]
    assert sorted(BOOL_RESULTS) == ["IN_RANGE", "N", "N_COIL", "N_TRIG", "OUT_RANGE", "P", "P_COIL", "P_TRIG"]
    assert all(FUNCTIONS[name].run is PURE_INSTRUCTIONS[name] for name in PURE_INSTRUCTIONS)
    assert all(FUNCTIONS[name].run is None for name in CPU_BOUND)
