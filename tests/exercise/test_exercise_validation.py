"""Instructors' mistakes are the exercise's errors, found when it is loaded (plcsim.exercise.validation), not a
student's failed grade: unknown stations, signals, tags and plant events, negative times, checks on
scenarios that do not exist, actions that can never work at run time, and a broken exercise module
beside good ones. Every error names the file and line the instructor wrote and the fix.
"""

from __future__ import annotations

import dataclasses
import re
import sys
from pathlib import Path

import pytest

import exercises
import plcsim.exercise.catalog
from exercises import all_exercises, broken_exercises, load_package
from plants import Conv1, Panel
from plcsim import CPU, Simulation, Tag
from plcsim.apps.cli import main
from plcsim.check import action, count, event, eventually, falls, final, never, rises
from plcsim.core.errors import ConfigurationError, ExerciseError
from plcsim.exercise.model import IO, Exercise, only
from plcsim.exercise.validation import validate
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import ScenarioError, after_event, held, place, press, remove, shift_sensor, stuck, write
from plcsim.sim.wiring import NO

HERE = re.escape(__file__)
CONV1_EVENTS = (  # an open end: no end stop, no "end stop hit"
    "interlock violated, motor jammed, part entered, part fell off, part jammed, "
    "part knocked off, part left, part placed, part released, part removed"
)
IO_TABLE = [
    IO("S1", "sensor at the belt start", "Bool", "%I0.0", "NO"),
    IO("S2", "sensor at the belt end", "Bool", "%I0.1", "NO"),
    IO("D1", "conveyor forward", "Bool", "%Q0.0"),
    IO("POCET", "objects carried", "Int"),
]
IDLE = Scenario("idle", duration="2s")


def here() -> int:
    """The caller's line number."""
    return sys._getframe(1).f_lineno


def conveyor(scenarios=(IDLE,), checks=(), rig=Conv1) -> Exercise:
    """A small exercise on CONV1 (the validation runs as it is built)."""
    return Exercise(
        number="9.9.1",
        slug="validation",
        title="validation",
        task="carry objects from S1 to S2",
        io=IO_TABLE,
        rig=rig,
        scenarios=list(scenarios),
        checks=list(checks) or [never("D1").named("the belt stays off")],
        solutions=[],
    )


EXERCISE_LINE = conveyor.__code__.co_firstlineno + 2  # exercise-wide mistakes are reported at its Exercise(...)


def refused(make) -> str:
    with pytest.raises(ExerciseError) as info:
        make()
    return str(info.value)


# -- every shipped exercise is valid ---------------------------------------------------------------


def test_all_shipped_exercises_validate_cleanly():
    assert broken_exercises() == ()
    numbers = [e.number for e in all_exercises()]
    modules = sorted(Path(exercises.__file__).parent.glob("ex_*.py"))
    # 4.3.x with 4.3.12, 4.3.16-18; 6.3.1-6.3.5; the PLC836 mechanisms' P-01, P-02; the Tecomat's T-01..T-06
    assert len(numbers) == len(modules) == 35
    assert numbers[:5] == ["4.3.1", "4.3.2", "4.3.3", "4.3.4", "4.3.5"] and numbers[-9] == "6.3.5"
    assert numbers[-8:-6] == ["P-01", "P-02"]
    assert numbers[-6:] == ["T-01", "T-02", "T-03", "T-04", "T-05", "T-06"]  # after the textbook's numbers
    for ex in all_exercises():
        validate(ex)  # again, explicitly: no ExerciseError
        if ex.number.startswith(("T-", "P-")):
            stem = ex.number.lower().replace("-", "_")
        else:
            major, minor, item = ex.number.split(".")
            stem = f"{major}_{minor}_{int(item):02d}"
        assert re.search(rf"/exercises/ex_{stem}\.py:\d+$", ex.defined_at), ex.defined_at


def test_the_errors_are_the_instructors_kind():
    assert issubclass(ExerciseError, ConfigurationError)
    assert issubclass(ScenarioError, ExerciseError)


# -- scenarios: names --------------------------------------------------------------------------------


def test_unknown_station():
    line = here() + 1
    message = refused(lambda: conveyor([Scenario("bad", place("p1", at="S3", t="1s"))]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: scenario 'bad': place 'p1' at S3 at 1 s: no station 'S3'; "
        "valid: S1, S2, belt"
    )


def test_unknown_signal_for_a_fault_with_the_nearest_name():
    line = here() + 1
    message = refused(lambda: conveyor([Scenario("bad", stuck("S22", True, t="1s"))]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: scenario 'bad': stick S22 at True at 1 s: no wired signal 'S22'; "
        "did you mean 'S2'?; valid: S1, S2, D1"
    )


def test_a_trigger_must_wait_for_a_plant_sensor():
    # the runner polls the plant's sensors only: waiting for the motor D1 would never fire
    scenario = Scenario("bad", place("p1", at="S1", t="1s"), remove("p1", when=held("D1", "1s")))
    line = here() - 1
    message = refused(lambda: conveyor([scenario]))
    assert message.startswith(f"{__file__}:{line}: exercise 9.9.1: scenario 'bad': remove 'p1' when D1 ")
    assert message.endswith("no signal to wait for 'D1'; valid: S1, S2")


def test_an_unknown_button_and_an_hmi_tag_typo():
    line = here() + 1
    message = refused(lambda: conveyor([Scenario("bad", press("START", t="1s"), write("POCT", 1, t="1s"))]))
    assert message.splitlines() == [
        f"{__file__}:{EXERCISE_LINE}: exercise 9.9.1 has 2 mistakes:",
        f"  {__file__}:{line}: exercise 9.9.1: scenario 'bad': press START at 1 s: no button or switch 'START'; "
        "valid: none",
        f"  {__file__}:{line}: exercise 9.9.1: scenario 'bad': write POCT = 1 at 1 s: no tag 'POCT'; "
        "did you mean 'POCET'?; valid: S1, S2, D1, POCET",
    ]


def test_an_hmi_write_its_tag_refuses():
    line = here() + 1
    message = refused(lambda: conveyor([Scenario("bad", write("POCET", "three", t="1s"))]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: scenario 'bad': write POCET = 'three' at 1 s: "
        "POCET is Int; cannot store str 'three'"
    )


def test_an_event_the_plant_cannot_emit_in_a_trigger():
    line = here() + 2
    scenario = Scenario(
        "bad", place("p1", at="S1", t="1s"), remove("p1", when=after_event("part droped", "p1")), duration="5s"
    )
    message = refused(lambda: conveyor([scenario]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: scenario 'bad': remove 'p1' after 'part droped' of p1: "
        "no plant event to wait for 'part droped'; did you mean 'part removed' or 'part placed' or 'part entered'?; "
        f"valid: {CONV1_EVENTS}"
    )


def test_a_trigger_on_an_event_about_a_name_nobody_has():
    line = here() + 2
    scenario = Scenario(
        "bad", place("p1", at="S1", t="1s"), remove("p1", when=after_event("part removed", "p11")), duration="5s"
    )
    message = refused(lambda: conveyor([scenario]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: scenario 'bad': remove 'p1' after 'part removed' of p11: "
        "no event subject (a part or plant name) 'p11'; did you mean 'p1'?; valid: p1, D1, S1, S2, belt"
    )


def test_two_scenarios_with_one_name():
    message = refused(lambda: conveyor([Scenario("run", duration="1s"), Scenario("run", duration="2s")]))
    assert message == (
        f"{__file__}:{EXERCISE_LINE}: exercise 9.9.1: two scenarios are named 'run'; give each a name of its own"
    )


# -- scenarios: times ----------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("make", "expected"),
    [
        (lambda: place("p1", at="S1", t="-1s"), r"place p1: time '-1s' is negative; times count from the start"),
        (lambda: place("p1", at="S1", t="-2s..1s"), r"place p1: time '-2s..1s' is negative"),
        (lambda: place("p1", at="S1", t="1s", delay="-100ms"), r"place p1: delay: time '-100ms' is negative"),
        (lambda: press("TL", t="1s", hold="-1s"), r"press TL: hold: time '-1s' is negative"),
        (lambda: held("S1", "-1s"), r"held\('S1'\): time '-1s' is negative"),
        (lambda: Scenario("zero", duration="0s"), r"scenario 'zero': duration '0s' is not positive; a run needs"),
        (lambda: Scenario("minus", duration="-5s"), r"scenario 'minus': duration '-5s' is not positive"),
        (
            lambda: Scenario("late", place("p1", at="S1", t="9s..11s"), duration="10s"),
            r"scenario 'late': place 'p1' at S1 at 9 s..11 s: the run ends at 10 s, so this action may never happen",
        ),
    ],
    ids=["negative", "negative-range", "delay", "hold", "trigger", "zero-run", "negative-run", "after-the-end"],
)
def test_bad_times_are_refused_where_they_were_written(make, expected):
    with pytest.raises(ScenarioError) as info:
        make()
    # the place is the line that built it (the lambda in the parameter list above)
    assert re.match(rf"{HERE}:\d+: {expected}", str(info.value)), str(info.value)


def test_a_time_at_zero_is_fine():
    scenario = Scenario("start", place("p1", at="S1", t="0s"), duration="1s")
    assert scenario.actions[0].t.lo_ns == 0 and scenario.duration_ns == 1_000_000_000


# -- the rig, the I/O table, the wiring, the options ------------------------------------------------


def small(io=IO_TABLE, rig=Conv1, **options) -> Exercise:
    return Exercise(
        number="9.9.1",
        slug="small",
        title="small",
        task="...",
        io=io,
        rig=rig,
        scenarios=[IDLE],
        checks=[never("D1")],
        solutions=[],
        **options,
    )


SMALL_LINE = small.__code__.co_firstlineno + 1


@pytest.mark.parametrize(
    ("make", "expected"),
    [
        (
            lambda: small(io=[*IO_TABLE, IO("S3", "a third sensor", "Bool", "%I0.2", "NO")]),
            "wiring: CONV1 has no signal 'S3'; its signals: S1, S2, D1",
        ),
        (
            lambda: small(io=[*IO_TABLE[:2], IO("D1", "conveyor forward", "Boool", "%Q0.0")]),
            "the I/O table, data blocks or CPU options are wrong: unknown data type 'Boool'; did you mean 'Bool'?",
        ),
        (
            lambda: small(scenario_cpu={"idel": {}}),
            "scenario_cpu names scenario 'idel'; did you mean 'idle'?; scenarios: idle",
        ),
        (
            lambda: small(rig=lambda: Conv1(end="nowhere")),
            "the rig could not be built: ValueError: CONV1: end must be 'open' or 'stop', not 'nowhere'",
        ),
        (lambda: small(dt="0ms"), "dt='0ms' must be a positive step such as '1ms'"),
    ],
    ids=["wired-to-nothing", "unknown-type", "scenario-options", "rig", "dt"],
)
def test_exercise_wide_mistakes_are_reported_at_the_exercise(make, expected):
    assert refused(make) == f"{__file__}:{SMALL_LINE}: exercise 9.9.1: {expected}"


# -- checks ----------------------------------------------------------------------------------------------


def test_a_check_naming_a_missing_tag():
    line = here() + 1
    message = refused(lambda: conveyor(checks=[never("d1").named("the belt stays off")]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: check 'the belt stays off' reads 'd1', which the exercise does not have; "
        "did you mean 'D1'?; a check can read: S1, S2, D1, POCET"
    )


def test_a_check_naming_a_missing_tag_in_a_quantity_and_a_plot():
    line = here() + 1
    checks = [final("POCT").equals(1), rises("D1").within("1 scan").after(rises("S1")).plotting("S3")]
    message = refused(lambda: conveyor(checks=checks))
    assert message.splitlines()[1:] == [
        f"  {__file__}:{line}: exercise 9.9.1: check 'POCT at the end = 1' reads 'POCT', which the exercise does "
        "not have; did you mean 'POCET'?; a check can read: S1, S2, D1, POCET",
        f"  {__file__}:{line}: exercise 9.9.1: check 'D1 rises within 1 scan after S1 rises' reads 'S3', which "
        "the exercise does not have; a check can read: S1, S2, D1, POCET",
    ]


def test_an_event_the_plant_cannot_emit_in_a_check():
    line = here() + 1
    message = refused(lambda: conveyor(checks=[never(event("part fell of")).named("nothing falls")]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: check 'nothing falls' waits for the plant event 'part fell of', "
        "which CONV1 never emits; did you mean 'part fell off' or 'part left' or 'part knocked off'?; "
        f"its events: {CONV1_EVENTS}"
    )


def test_a_check_on_an_event_about_a_name_nobody_has():
    line = here() + 2
    scenario = Scenario("one", place("p1", at="S1", t="1s"), duration="2s")
    checks = [count(event("part entered", "S22")).equals(1).named("p1 reaches S2"), count(event("part left", "p1"))]
    message = refused(lambda: conveyor([scenario], checks))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: check 'p1 reaches S2' waits for 'part entered' of 'S22', which is "
        "neither a part of its scenarios nor a name in CONV1; did you mean 'S2'?; valid: p1, D1, S1, S2, belt"
    )  # the second check, about the part p1, is fine


def test_a_panel_never_reports_parts():
    line = here() + 1
    checks = [never(event("part fell off")).named("nothing falls")]
    message = refused(lambda: conveyor(checks=checks, rig=lambda: Panel(buttons=("S1", "S2"), lamps=("D1",))))
    assert message.startswith(f"{__file__}:{line}: exercise 9.9.1: check 'nothing falls' waits for the plant event")
    assert message.endswith("which PANEL never emits; its events: button pressed, button released")


def test_a_check_on_an_action_no_scenario_does():
    line = here() + 1
    message = refused(lambda: conveyor(checks=[count(action("press", "ACK")).equals(1).named("one ack")]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: check 'one ack' looks for the action 'press ACK', "
        "but none of its scenarios does press"
    )
    line = here() + 1
    message = refused(lambda: conveyor(checks=[count(action("jump")).equals(1).named("jumps")]))
    assert message.startswith(
        f"{__file__}:{line}: exercise 9.9.1: check 'jumps' counts the scenario action 'jump', which is not an action"
    )


def test_a_check_on_a_scenario_that_does_not_exist():
    line = here() + 1
    message = refused(lambda: conveyor(checks=[only(never("D1").named("off"), "idel")]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: check 'off' applies to scenario 'idel', which does not exist; "
        "did you mean 'idle'?; scenarios: idle"
    )


def test_a_duration_bound_that_cannot_be_read():
    line = here() + 1
    message = refused(lambda: conveyor(checks=[count(rises("D1")).between("1 sec", 2).named("runs")]))
    assert message == (
        f"{__file__}:{line}: exercise 9.9.1: check 'runs': bound '1 sec': duration '1 sec': unknown unit 'sec'; "
        "use s, ms, us, min, h or scans"
    )


@pytest.mark.parametrize(
    ("make", "expected"),
    [
        (
            lambda: falls("D1").within("-1s").after(rises("S1")),
            "check 'D1 falls within -1s after S1 rises': the duration '-1s' is negative; durations count forwards",
        ),
        (
            lambda: falls("D1").between("2s", "1s").after(rises("S1")),
            "check 'D1 falls between 2s and 1s after S1 rises': the window from 2s to 1s runs backwards",
        ),
        (lambda: never("D1").during("2s", "1s"), "check 'never D1': the window from 2s to 1s runs backwards"),
        (
            lambda: eventually("D1").before("-1 scan"),
            "check 'eventually D1 before -1 scan': the duration '-1 scan' is negative; durations count forwards",
        ),
        (
            lambda: count(rises("D1")).between(3, 1),
            "check 'number of times D1 rises between 3 and 1': the bounds 3 and 1 run backwards; no value lies between",
        ),
    ],
    ids=["negative-reaction", "backwards-window", "backwards-during", "negative-deadline", "backwards-bounds"],
)
def test_a_check_whose_durations_cannot_hold(make, expected):
    message = refused(lambda: conveyor(checks=[make()]))
    assert re.fullmatch(rf"{HERE}:\d+: exercise 9\.9\.1: {re.escape(expected)}", message), message


def test_a_duration_with_a_scan_subtracted_is_fine():
    conveyor(checks=[falls("D1").within("0.5s - 1 scan").after(rises("S1"))])  # no error


def test_every_mistake_is_listed_once():
    line = here() + 2
    message = refused(
        lambda: conveyor([Scenario("bad", place("p1", at="S3", t="1s"))], [never("D2"), never(event("part fell of"))])
    )
    lines = message.splitlines()
    assert lines[0] == f"{__file__}:{EXERCISE_LINE}: exercise 9.9.1 has 3 mistakes:"
    assert [re.match(rf"  {HERE}:(\d+): ", x).group(1) for x in lines[1:]] == [str(line)] * 3
    assert ["no station 'S3'" in lines[1], "reads 'D2'" in lines[2], "'part fell of'" in lines[3]] == [True] * 3


def test_a_check_written_in_a_helper_module_names_both_files(tmp_path, monkeypatch):
    helper = tmp_path / "validation_helper_checks.py"
    helper.write_text(
        "from plcsim.check import never\n\n\ndef belt_checks():\n    return [never('D9')]\n", encoding="utf-8"
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    from validation_helper_checks import belt_checks

    message = refused(lambda: conveyor(checks=belt_checks()))
    assert re.fullmatch(
        rf"{re.escape(str(helper))}:5: exercise 9.9.1 \(defined at {HERE}:\d+\): check 'never D9' reads 'D9'.*",
        message,
    ), message


# -- at run time: the instructor's mistakes raise, the student's trace is untouched ------------------------


def panel_sim(scenario: Scenario) -> Simulation:
    cpu = CPU({"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}, "def OB1(t):\n    t.LED = t.TL\n")
    return Simulation(cpu, Panel(buttons=("TL",), switches=(), lamps=("LED",)), [NO("TL"), NO("LED")], scenario)


def test_an_action_the_plant_cannot_do_is_an_exercise_error_before_the_run():
    line = here() + 1
    scenario = Scenario("shift", shift_sensor("TL", 5.0, t="1s"), duration="2s")
    with pytest.raises(ExerciseError) as info:  # the panel declares no 'sensor shift': refused before any run
        panel_sim(scenario)
    assert str(info.value) == (
        f"{__file__}:{line}: scenario 'shift': shift sensor TL by 5.0 mm at 1 s: the rig cannot do this "
        "(it does not declare the capability 'sensor shift')"
    )


def test_a_write_its_tag_refuses_at_run_time_is_an_exercise_error():
    line = here() + 1
    sim = panel_sim(Scenario("write", write("LED", 7, t="1s"), duration="2s"))
    with pytest.raises(ExerciseError, match=rf"^{HERE}:{line}: write LED = 7 at 1 s: LED is Bool; cannot store int 7"):
        sim.run()
    assert sim.trace.events_of("action failed") == []


def test_what_the_run_made_impossible_is_still_recorded():
    cpu = CPU({"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0")}, "def OB1(t):\n    t.D1 = True\n")
    scenario = Scenario("fall", place("p1", at="S2", t="100ms", noise=False), remove("p1", t="3s"), duration="4s")
    sim = Simulation(cpu, Conv1(), [NO("S1"), NO("S2"), NO("D1")], scenario)
    sim.run()  # the program ran the part off the belt: its removal fails, the run goes on
    failed = sim.trace.events_of("action failed", source="scenario")
    assert [(e.t_ns, e.subject) for e in failed] == [(3_000_000_000, "p1")]
    assert "p1 is no longer in the plant" in failed[0].detail


def test_a_bug_of_ours_in_an_action_is_not_recorded_as_the_students(monkeypatch):
    cpu = CPU({"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0")}, "def OB1(t):\n    pass\n")
    plant = Conv1()
    scenario = Scenario("remove", place("p1", at="S1", t="100ms"), remove("p1", t="1s"), duration="2s")
    sim = Simulation(cpu, plant, [NO("S1"), NO("S2"), NO("D1")], scenario)

    def broken_remove(target: str) -> None:
        raise ZeroDivisionError("a bug in the plant")

    monkeypatch.setattr(plant, "remove", broken_remove)
    with pytest.raises(ZeroDivisionError):
        sim.run()
    assert sim.trace.events_of("action failed") == []


# -- the registry: one broken module does not block the others ---------------------------------------------

GOOD = """\
from plants import Conv1
from plcsim.check import never
from plcsim.exercise.model import IO, Exercise
from plcsim.scenario import Scenario, place

EXERCISE = Exercise(
    number="9.9.{n}",
    slug="good-{n}",
    title="good",
    task="the belt stays off",
    io=[IO("S1", "s", "Bool", "%I0.0", "NO"), IO("S2", "s", "Bool", "%I0.1", "NO"), IO("D1", "m", "Bool", "%Q0.0")],
    rig=Conv1,
    scenarios=[Scenario("idle", {actions}duration="1s")],
    checks=[never("D1").named("the belt stays off")],
    solutions=[],
)
"""
BROKEN = {
    "ex_9_9_03": (GOOD.replace("{n}", "3").replace("{actions}", 'place("p1", at="S3", t="0.5s"), '), None),
    "ex_9_9_04": ("from plcsim.exercise.model import Exercise\n\nEXERCISE = Exercise(\n    number=\n", 3),
    "ex_9_9_05": ("from plcsim.exercise.model import Exercise\n\n\nEXERCISE = Exercize(number='9.9.5')\n", 4),
    "ex_9_9_06": ("NUMBER = '9.9.6'\n", None),
}


@pytest.fixture
def package(tmp_path, monkeypatch):
    """A package of exercise modules beside ``exercises``: two good ones and four broken ones."""
    name = f"validation_pkg_{tmp_path.name.replace('-', '_')}"
    root = tmp_path / name
    root.mkdir()
    (root / "__init__.py").write_text("", encoding="utf-8")
    for n in (1, 2):
        (root / f"ex_9_9_0{n}.py").write_text(GOOD.replace("{n}", str(n)).replace("{actions}", ""), encoding="utf-8")
    for module, (text, _line) in BROKEN.items():
        (root / f"{module}.py").write_text(text, encoding="utf-8")
    again = GOOD.replace("{n}", "1").replace("{actions}", "")  # 9.9.1 again
    (root / "ex_9_9_07.py").write_text(again, encoding="utf-8")
    monkeypatch.syspath_prepend(str(tmp_path))
    return name, root


def test_a_broken_module_beside_good_ones(package):
    name, root = package
    loaded, broken = load_package(name)
    assert [e.number for e in loaded] == ["9.9.1", "9.9.2"]
    by_module = {b.module.rpartition(".")[2]: b for b in broken}
    assert sorted(by_module) == ["ex_9_9_03", "ex_9_9_04", "ex_9_9_05", "ex_9_9_06", "ex_9_9_07"]
    assert str(by_module["ex_9_9_03"]) == (
        f"{root / 'ex_9_9_03.py'}:13: exercise 9.9.3: scenario 'idle': place 'p1' at S3 at 500 ms: no station 'S3'; "
        "valid: S1, S2, belt"
    )
    assert str(by_module["ex_9_9_04"]) == f"{root / 'ex_9_9_04.py'}:3: SyntaxError: '(' was never closed"
    assert str(by_module["ex_9_9_05"]) == f"{root / 'ex_9_9_05.py'}:4: NameError: name 'Exercize' is not defined"
    assert str(by_module["ex_9_9_06"]) == f"{root / 'ex_9_9_06.py'}:1: the module defines no EXERCISE = Exercise(...)"
    taken = f"'9.9.1' is already taken by {root / 'ex_9_9_01.py'}"
    assert str(by_module["ex_9_9_07"]) == f"{root / 'ex_9_9_07.py'}:6: {taken}"
    assert by_module["ex_9_9_04"].number == "9.9.4"


def test_the_cli_lists_the_good_and_names_the_broken_without_a_traceback(package, monkeypatch, capsys):
    name, root = package
    loaded, broken = load_package(name)
    monkeypatch.setattr(plcsim.exercise.catalog, "_catalog", lambda: (tuple(loaded), tuple(broken)))
    assert main(["list"]) == 2
    out, err = capsys.readouterr()
    assert "9.9.1" in out and "9.9.2" in out and "good-2" in out
    assert "Traceback" not in out + err
    assert f"{root / 'ex_9_9_05.py'}:4: NameError: name 'Exercize' is not defined" in err.replace("\n", "")
    where = re.escape(str(root / "ex_9_9_04"))
    with pytest.raises(ExerciseError, match=rf"^exercise 9\.9\.4 cannot be loaded: {where}"):
        exercises.get("9.9.4")
    assert exercises.get("good-2").number == "9.9.2"
    assert main(["show", "9.9.5"]) == 2
    out, err = capsys.readouterr()
    assert "cannot be loaded" in err and "ex_9_9_05.py:4" in err.replace("\n", "") and "Traceback" not in err


def test_an_unknown_exercise_mentions_the_modules_that_did_not_load(package, monkeypatch):
    name, _root = package
    loaded, broken = load_package(name)
    monkeypatch.setattr(plcsim.exercise.catalog, "_catalog", lambda: (tuple(loaded), tuple(broken)))
    with pytest.raises(ConfigurationError) as info:
        exercises.get("9.9.9")
    message = str(info.value)
    assert message.startswith("no exercise '9.9.9'")
    assert message.count("\n(not loaded: ") == 5


def test_the_shipped_registry_loads_through_load_package():
    loaded, broken = load_package("exercises")
    assert broken == [] and [e.number for e in loaded] == [e.number for e in all_exercises()]


def test_an_hmi_control_must_be_a_tag_of_the_exercise_and_a_switch_or_a_button():
    good = conveyor()
    message = refused(lambda: dataclasses.replace(good, hmi={"ACK": "switch", "D1": "lamp"}))
    assert "hmi names 'ACK', which the exercise does not have" in message
    assert "hmi['D1'] is 'lamp'; a control is 'switch' or 'button'" in message


# -- a check grades only what the task states ------------------------------------------------------


def test_a_check_grading_words_the_task_does_not_state_is_refused_at_its_line():
    line = here() + 1
    check = never("D1").named("the belt stays off").grades("the belt never runs")
    message = refused(lambda: conveyor(checks=[check]))
    assert re.search(rf"{HERE}:{line}: exercise 9.9.1: check 'the belt stays off' grades 'the belt never", message)
    assert "which the task text does not state: quote the task's own words" in message


def test_a_requirement_is_found_in_the_task_whatever_its_case_and_spacing():
    check = never("D1").named("the belt stays off").grades("Carry  objects\nfrom S1")
    exercise = conveyor(checks=[check])
    assert [(words, [c.name for c in checks]) for words, checks in exercise.requirement_list()] == [
        ("Carry  objects\nfrom S1", ["the belt stays off"])
    ]


def test_requirements_by_check_name_must_name_a_check_and_quote_the_task():
    def make(requirements):
        return Exercise(
            number="9.9.1",
            slug="validation",
            title="validation",
            task="carry objects from S1 to S2",
            io=IO_TABLE,
            rig=Conv1,
            scenarios=[IDLE],
            checks=[never("D1").named("the belt stays off")],
            solutions=[],
            requirements=requirements,
        )

    assert make({"the belt stays off": "to S2"}).checks[0].requirement == "to S2"
    assert "requirements names 'the belt stays of', which is not a check; did you mean 'the belt stays off'" in (
        refused(lambda: make({"the belt stays of": "to S2"}))
    )
    wrong = refused(lambda: make({"the belt stays off": "to S3"}))
    assert "grades 'to S3', which the task text does not state" in wrong
