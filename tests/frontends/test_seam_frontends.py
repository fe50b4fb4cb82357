"""Issue 11, the proof of the front-end seam: a deliberately tiny instruction-list front end, written here
in the tests with no edit to the runtime, runs on the S7 profile against the PANEL rig, is graded by an
exercise's existing checks, and gives the same trace bit for bit as the same program in Python.

The language (one instruction a line; ``;`` starts a comment; ``NETWORK`` starts the next network):
``LD a`` / ``LDN a`` load a Bool (negated), ``AND``/``ANDN``/``OR``/``ORN a`` combine it with the result
of logic operation (RLO), ``NOT`` negates the RLO, ``ST a`` stores it, ``TON T, 50ms`` runs the on-delay
timer T (declared by its first use) with the RLO as IN and makes its Q the RLO.
"""

from __future__ import annotations

import operator
from pathlib import Path

import pytest

import exercises
from plants import Panel
from plcsim import CPU, Program, Simulation, Tag, frontends
from plcsim.controllers.loaded import (
    LinkTarget,
    LoadedNetwork,
    LoadedProgram,
    LoadedTask,
    NetworkSpec,
    ProgramFacts,
    TaskSpec,
)
from plcsim.controllers.s7.instructions import FB_TYPES
from plcsim.core.errors import ConfigurationError, ProgramError, UnknownTagError
from plcsim.frontends import read_program, register, suffixes, unregister
from plcsim.grading.report import Report
from plcsim.grading.run import run_scenarios
from plcsim.grading.scoring import evaluate
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import press
from plcsim.sim.wiring import NO
from plcsim.tags.table import TagTable

COMBINE = {"AND": operator.and_, "OR": operator.or_}


class TinyIL:
    """A source program in the tiny IL: parsed when read, linked against the CPU's tags on load."""

    def __init__(self, text: str, filename: str = "<il>"):
        self.filename = filename
        self.networks: list[list[tuple[int, str, str]]] = [[]]
        for lineno, raw in enumerate(text.splitlines(), 1):
            words = raw.split(";", 1)[0].replace(",", " ").split()
            if not words:
                continue
            op, args = words[0].upper(), words[1:]
            if op == "NETWORK":
                self.networks.append([])
                continue
            arity = {"NOT": 0, "TON": 2}.get(op, 1)
            if op not in ("LD", "LDN", "AND", "ANDN", "OR", "ORN", "ST", "NOT", "TON") or len(args) != arity:
                raise ProgramError(
                    f"{filename}, line {lineno}: {raw.strip()!r} is not an instruction; write "
                    f"LD/LDN/AND/ANDN/OR/ORN/ST TAG, NOT, or TON TIMER, 50ms"
                )
            self.networks[-1].append((lineno, op, " ".join(args)))
        self.networks = [n for n in self.networks if n]
        self.timers = sorted({arg.split()[0] for net in self.networks for _, op, arg in net if op == "TON"})

    def declare_into(self, table: TagTable) -> TagTable:
        merged = table.copy()
        for name in self.timers:
            if name not in merged:
                merged.add(name, FB_TYPES["IEC_TIMER"](), source=self.filename)
        return merged

    def absolute_addresses(self) -> list[str]:
        return []

    def link(self, target: LinkTarget) -> LoadedProgram:
        store = target.hooks.store
        known = set(target.table.entries)
        reads: set[str] = set()
        writes: set[str] = set()
        networks, specs = [], []
        for k, ops in enumerate(self.networks):
            for lineno, op, arg in ops:
                name = arg.split()[0] if arg else ""
                if name and name not in known:
                    raise UnknownTagError(
                        f"{self.filename}, line {lineno}: no tag {name!r}; declare it or fix the name"
                    )
                (writes if op == "ST" else reads).add(name) if name and op != "TON" else None
            networks.append(LoadedNetwork(_network(ops, store), (ops[0][0], ops[-1][0])))
            specs.append(NetworkSpec(f"network_{k + 1}", f"network {k + 1}", None, ops[0][0]))
        spec = TaskSpec("OB1", "cyclic", specs, number=1)
        facts = ProgramFacts(frozenset(reads), frozenset(writes), frozenset({"TON"} if self.timers else set()))
        return LoadedProgram(
            self.filename, [LoadedTask(spec, networks, None, facts.tags_read | facts.tags_written)], facts
        )


def _network(ops: list[tuple[int, str, str]], store) -> object:
    def run(t) -> None:
        d = t.__dict__
        rlo = False
        for _, op, arg in ops:
            if op in ("LD", "LDN"):
                rlo = bool(d[arg]) != (op == "LDN")
            elif op == "NOT":
                rlo = not rlo
            elif op == "ST":
                store(t, arg, rlo)
            elif op == "TON":
                timer, preset = arg.split()
                rlo = d[timer].TON(IN=rlo, PT=preset)
            else:
                rlo = COMBINE[op.rstrip("N")](rlo, bool(d[arg]) != op.endswith("N"))

    return run


@pytest.fixture
def il_suffix():
    before = frontends.frontend_for(".il")  # the Tecomat front end, put back afterwards
    register(".il", lambda path: TinyIL(path.read_text(encoding="utf-8"), str(path)))
    yield ".il"
    if before is None:
        unregister(".il")
    else:
        register(".il", before.read, profile=before.profile, language=before.language, contract=before.contract)


def test_the_front_end_is_chosen_by_the_file_suffix(tmp_path: Path, il_suffix):
    (tmp_path / "led.il").write_text("LD TLACIDLO\nST LED\n", encoding="utf-8")
    (tmp_path / "led.py").write_text("def OB1(t):\n    t.LED = t.TLACIDLO\n", encoding="utf-8")
    assert isinstance(read_program(tmp_path / "led.il"), TinyIL)
    assert isinstance(read_program(tmp_path / "led.py"), Program)
    with pytest.raises(ProgramError, match=r"led\.st: no front end reads \.st; use \.il, \.mech, \.py"):
        read_program(tmp_path / "led.st")
    assert ".il" in suffixes()


def test_a_second_front_end_is_graded_by_an_exercise_s_existing_checks(tmp_path: Path):
    exercise = exercises.get("4.3.1")
    runs, analysis = run_scenarios(exercise, TinyIL("LD TLACIDLO\nST LED\n", "led.il"), seed=3)
    report = evaluate(exercise, runs, analysis, Report(exercise.number, exercise.title, "led.il", seed=3))
    assert report.error is None and report.score == report.max_score > 0
    wrong = TinyIL("LDN TLACIDLO\nST LED\n", "inverted.il")
    runs, analysis = run_scenarios(exercise, wrong, seed=3)
    report = evaluate(exercise, runs, analysis, Report(exercise.number, exercise.title, "inverted.il", seed=3))
    failed = {c.check for c in report.checks if not c.passed}
    assert {"LED equals the button in every scan", "LED lights within 2 scans"} <= failed
    assert report.score < report.max_score


def test_its_errors_name_the_student_s_file_and_line():
    with pytest.raises(ProgramError, match=r"bad\.il, line 2: 'JMP x' is not an instruction"):
        TinyIL("LD TLACIDLO\nJMP x\n", "bad.il")
    with pytest.raises(UnknownTagError, match=r"typo\.il, line 2: no tag 'LDE'"):
        CPU(tags={"TLACIDLO": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program=TinyIL("LD TLACIDLO\nST LDE\n", "typo.il"))


TAGS = {"TL": Tag("%I0.0"), "TL2": Tag("%I0.1"), "LED": Tag("%Q0.0"), "SLOW": Tag("%Q0.1")}
IL = """
LD TL        ; LED := (TL OR TL2) AND NOT SLOW
OR TL2
ANDN SLOW
ST LED
NETWORK      ; SLOW := TON(TL AND NOT TL2, 50ms)
LD TL
ANDN TL2
TON T1, 50ms
ST SLOW
"""
PYTHON = """
T1 = IEC_TIMER()

def lamp(t):
    t.LED = (t.TL or t.TL2) and not t.SLOW

def slow(t):
    t.SLOW = t.T1.TON(IN=t.TL and not t.TL2, PT="50ms")

OB1 = [lamp, slow]
"""


def panel_run(program) -> Simulation:
    scenario = Scenario(
        "presses",
        *press("TL", t="20ms", hold="30ms"),
        *press("TL", t="100ms", hold="120ms"),
        *press("TL2", t="200ms", hold="40ms"),
        *press("TL2", t="300ms", hold="5ms"),
        duration="400ms",
    )
    plant = Panel(buttons=("TL", "TL2"), switches=(), lamps=("LED", "SLOW"))
    sim = Simulation(CPU(tags=TAGS, program=program), plant, [NO("TL"), NO("TL2"), NO("LED"), NO("SLOW")], scenario)
    sim.run()
    return sim


def test_contract_the_same_program_in_two_front_ends_gives_the_same_trace_bit_for_bit():
    python, il = panel_run(Program.from_source(PYTHON)), panel_run(TinyIL(IL, "lamp.il"))
    assert python.trace.names == il.trace.names == ["TL", "TL2", "LED", "SLOW", "T1.Q", "T1.ET"]
    assert il.trace.digest() == python.trace.digest()
    ms = lambda name: [(a // 1_000_000, b // 1_000_000) for a, b in il.trace.intervals(name)]  # noqa: E731
    # TL alone from 100 ms: T1 is due in the scan at 150 ms (SLOW from its end); TL2 at 200 ms resets it
    assert ms("SLOW") == [(151, 201)]
    # the lamp network runs first, so it sees SLOW one scan late: off at 152 ms, on again at 202 ms
    assert ms("LED") == [(21, 51), (101, 152), (202, 241), (301, 306)]
    assert il.cpu.loaded.facts.tags_written == {"LED", "SLOW"} and il.cpu.loaded.facts.instructions == {"TON"}


def test_a_front_end_that_numbers_two_tasks_alike_is_refused_as_its_own_bug():
    program = TinyIL("LD TLACIDLO\nST LED\n", "twice.il")
    link = program.link

    def twice(target):
        loaded = link(target)
        task = loaded.tasks[0]
        again = TaskSpec("P2", "interrupt", task.spec.networks, 10**7, number=1)
        loaded.tasks.append(LoadedTask(again, task.networks, None, task.tags_used))
        return loaded

    program.link = twice
    with pytest.raises(ConfigurationError, match=r"twice\.il: the front end gave task P2 the same number 1 as OB1"):
        CPU(tags={"TLACIDLO": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program=program)


def test_a_fault_in_a_network_of_another_front_end_names_the_network_s_line_in_its_file():
    cpu = CPU(tags=TAGS, program=TinyIL("LD TL\nST LED\nNETWORK\nLD TL\nTON T1, soon\nST SLOW\n", "late.il"))
    cpu.set_input("TL", True)
    cpu.scan()
    assert cpu.mode == "STOP"
    assert cpu.error.line == 4 and cpu.error.message.startswith(
        "OB1 network 2 (network_2), line 4: cannot read duration 'soon'"
    )
