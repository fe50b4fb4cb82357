"""The Tecomat controller against the rigs: ``.il`` programs chosen by their suffix, run and graded by the
same simulation, wiring, recorder and checks as S7 programs, in process and through the grader's sandbox."""

from __future__ import annotations

from pathlib import Path

import pytest

import exercises
from plants import Panel
from plcsim import CPU, Program, Simulation, Tag
from plcsim.controllers.choice import controller_for
from plcsim.controllers.tecomat.assembly import AssemblyError
from plcsim.core.errors import ConfigurationError, ProgramError
from plcsim.frontends import read_program
from plcsim.frontends.il import IlProgram, program_text
from plcsim.grading.grader import grade
from plcsim.grading.report import Report
from plcsim.grading.run import run_scenarios
from plcsim.grading.scoring import evaluate
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import press
from plcsim.sim.wiring import NO

SOLUTIONS = Path(__file__).resolve().parents[3] / "examples" / "tecomat" / "exercises"


def graded(number: str, name: str, seed: int = 1) -> Report:
    exercise = exercises.get(number)
    major, minor, n = number.split(".")
    program = read_program(SOLUTIONS / f"{major}_{minor}_{int(n):02d}_{name}.il")
    runs, analysis = run_scenarios(exercise, program, seed=seed)
    return evaluate(exercise, runs, analysis, Report(exercise.number, exercise.title, name, seed=seed))


def failed(report: Report) -> set[str]:
    return {c.check for c in report.checks if not c.passed}


def test_il_files_are_read_by_the_tecomat_front_end_and_refused_by_the_s7_cpu(tmp_path: Path):
    path = tmp_path / "led.il"
    path.write_text("LD TLACIDLO\nWR LED\n", encoding="utf-8")
    program = read_program(path)
    assert isinstance(program, IlProgram)
    with pytest.raises(ProgramError, match=r"led\.il is a Tecomat instruction-list program: it runs on the Tecomat"):
        CPU(tags={"TLACIDLO": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program=program)
    with pytest.raises(AssemblyError, match=r"led\.il, line 2, column 4: no name 'LDE'; did you mean 'LED'"):
        controller_for(IlProgram("LD TLACIDLO\nWR LDE\n", str(path)), {"TLACIDLO": Tag("%I0.0"), "LED": Tag("%Q0.0")})


@pytest.mark.parametrize("seed", [1, 2])
@pytest.mark.parametrize("number", ["4.3.1", "4.3.2", "4.3.4"])
def test_the_il_references_pass_the_exercises_checks(number, seed):
    report = graded(number, "reference", seed)
    assert report.error is None and not failed(report) and report.score == report.max_score > 0


@pytest.mark.parametrize(
    "number, name, fails",
    [
        ("4.3.2", "wrong-no-contact", {"LED is lit exactly while the NC input is FALSE (pressed)"}),
        ("4.3.4", "wrong-start-dominant", {"the OFF button switches the LED off, also when both are pressed"}),
        ("4.3.4", "wrong-set-reset", {"no SET instruction", "no RESET instruction"}),
    ],
)
def test_the_wrong_il_programs_fail_on_the_check_that_explains_their_flaw(number, name, fails):
    report = graded(number, name)
    assert fails <= failed(report) and report.score < report.max_score


def test_grading_an_il_file_through_the_sandbox():
    report = grade(exercises.get("4.3.4"), SOLUTIONS / "4_3_04_wrong-set-reset.il", seed=1)
    assert report.error is None
    assert failed(report) == {"no SET instruction", "no RESET instruction"}
    assert any("SET coils: LED (line 3)" in c.message for c in report.checks if not c.passed)


TAGS = {"TL": Tag("%I0.0"), "TL2": Tag("%I0.1"), "LED": Tag("%Q0.0")}


def panel_run(program) -> Simulation:
    scenario = Scenario(
        "presses",
        *press("TL", t="20ms", hold="30ms"),
        *press("TL2", t="100ms", hold="120ms"),
        *press("TL", t="150ms", hold="100ms"),
        duration="400ms",
    )
    plant = Panel(buttons=("TL", "TL2"), switches=(), lamps=("LED",))
    sim = Simulation(controller_for(program, TAGS), plant, [NO("TL"), NO("TL2"), NO("LED")], scenario)
    sim.run()
    return sim


def test_contract_one_program_on_the_s7_and_on_the_tecomat_gives_the_same_trace():
    s7 = panel_run(Program.from_source("def OB1(t):\n    t.LED = t.TL and not t.TL2\n"))
    il = panel_run(program_text("LD TL\nANC TL2\nWR LED\n", "lamp.il"))
    assert s7.trace.names == il.trace.names == ["TL", "TL2", "LED"]
    assert il.trace.digest() == s7.trace.digest()
    assert [(a // 1_000_000, b // 1_000_000) for a, b in il.trace.intervals("LED")] == [(21, 51), (221, 251)]


def test_a_program_error_stops_the_controller_and_the_trace_says_where():
    sim = panel_run(program_text("P 0\nLD TL\nJMC on\nRET\non:\nLD TL2\nWR LED\nE 0\n", "bad.il"))
    assert sim.cpu.mode == "STOP" and sim.cpu.error.line == 4
    event = next(e for e in sim.trace.events if e.kind == "error in the program")
    assert event.t_ns == 20_000_000 and event.detail.startswith("bad.il, line 4: RET outside a subroutine")
    assert sim.trace.column("LED").max() == 0 and sim.trace.tasks[-1] == 0  # STOP rows after the fault


def test_io_names_spelt_like_addresses_shadow_them_and_the_address_stays_reachable():
    tags = {"S1": Tag("%I0.3"), "D1": Tag("%Q0.1")}
    cpu = controller_for(program_text("LD S1\nWR D1\nLD 1\nFLG\nLD S 1\nWR R0\n"), tags)
    cpu.set_input("S1", True)
    cpu.scan()
    assert cpu.outputs["D1"] is True and cpu.peek("Y0.1") == 1 and cpu.peek("R0") == 0x41
    assert any("the I/O name S1 is X0.3 in this program" in w for w in cpu.warnings)


def test_markers_of_the_io_table_live_in_r_and_an_hmi_write_reaches_them():
    tags = {"AUTO": Tag("%M10.1"), "LED": Tag("%Q0.0")}
    cpu = controller_for(program_text("LD AUTO\nWR LED\n"), tags)
    cpu.write("AUTO", 1)
    cpu.scan()
    assert cpu.peek("R10") == 0b10 and cpu.outputs["LED"] is True
    with pytest.raises(ConfigurationError, match="cannot write R9000: R9000 is outside the user registers"):
        cpu.write("R9000", 1)


def test_an_hmi_write_to_the_input_image_lasts_until_the_next_turnaround_samples_the_terminals():
    """The turnaround samples X from the terminals every cycle (tecomat.md: a write to X is overwritten at the next
    turnaround), so a write into X holds for the rest of the cycle alone, even when no input changed."""
    tags = {"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "LED": Tag("%Q0.0")}
    cpu = controller_for(program_text("LD S1\nWR LED\n"), tags)
    cpu.scan()
    cpu.write("S1", 1)
    assert cpu.peek("S1") == 1
    cpu.scan()
    assert cpu.peek("S1") == 0 and cpu.outputs["LED"] is False
    cpu.scan()
    assert cpu.outputs["LED"] is False


def test_the_manual_s_pulse_filter_on_the_panel_rig_wired_by_its_own_names():
    program = read_program(Path(__file__).resolve().parents[3] / "examples" / "tecomat" / "ex18_pulse_filter.il")
    plant = Panel(buttons=("signal",), switches=(), lamps=("vystup",))
    scenario = Scenario(
        "pulses", *press("signal", t="100ms", hold="200ms"), *press("signal", t="1s", hold="1s"), duration="2.5s"
    )
    sim = Simulation(controller_for(program), plant, [NO("signal"), NO("vystup")], scenario)
    sim.run()
    assert sim.trace.names == ["signal", "vystup", "casovac"]
    ms = [(a // 1_000_000, b // 1_000_000) for a, b in sim.trace.intervals("vystup")]
    assert ms == [(1251, 2001)]  # the 200 ms pulse is suppressed; the 1 s one passes, 250 ms late


def test_the_0_1_loader_writes_levels_into_their_terminals_as_the_sampler_does():
    """``symbols.loader`` (0.1's name, kept for the old import path) stores bits by mask and a byte whole."""
    from plcsim.controllers.tecomat.memory import Scratchpad, parse_address
    from plcsim.controllers.tecomat.symbols import loader

    pad = Scratchpad({"X": bytearray([0b1000_0000, 0, 0])})
    loader(pad, "X", [parse_address(a) for a in ("X0.0", "X0.3", "X1")])((True, 1, 0x5A))
    assert list(pad.areas["X"]) == [0b1000_1001, 0x5A, 0]
