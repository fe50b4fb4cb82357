"""Issue 11: the contract every registered front end and CPU profile passes, as ``check_plant`` is for
rigs. Each front end's contract program (the self-holding motor of ``CONTRACT_TASK``, in its own language)
runs on the controller its profile names, against the PANEL rig, and gives the Python program's trace
digest bit for bit; each profile's address grammar reads its own examples and its triggers number each
task once. A front end or profile another package registers is tested here without an edit.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from plants import Panel
from plcsim import Simulation, Tag, frontends
from plcsim.apps.cli import main
from plcsim.controllers import profiles
from plcsim.controllers.choice import controller_for
from plcsim.controllers.profiles import Profile
from plcsim.controllers.s7.profile import task_kind
from plcsim.frontends import CONTRACT_TAGS, FrontEnd
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import press
from plcsim.sim.wiring import NO

FRONT_ENDS = frontends.front_ends()
PROFILES = profiles.all_profiles()


def contract_run(front: FrontEnd, folder: Path) -> Simulation:
    """The contract program of ``front`` read from a file, on its controller, pressed as the test says."""
    assert front.contract, f"the front end of {front.suffix} gives no contract program (FrontEnd.contract)"
    path = folder / f"contract{front.suffix}"
    path.write_text(front.contract, encoding="utf-8")
    cpu = controller_for(frontends.read_program(path), {name: Tag(a) for name, a in CONTRACT_TAGS.items()})
    scenario = Scenario(
        "start, stop, a short start",
        *press("START", t="20ms", hold="30ms"),
        *press("STOP", t="100ms", hold="20ms"),
        *press("START", t="150ms", hold="3ms"),
        *press("STOP", t="200ms", hold="2ms"),
        *press("START", t="201ms", hold="10ms"),
        duration="300ms",
    )
    plant = Panel(buttons=("START", "STOP"), switches=(), lamps=("MOTOR",))
    sim = Simulation(cpu, plant, [NO(name) for name in CONTRACT_TAGS], scenario)
    sim.run()
    return sim


@pytest.fixture(scope="module")
def python_run(tmp_path_factory) -> Simulation:
    return contract_run(frontends.frontend_for(".py"), tmp_path_factory.mktemp("python"))


@pytest.mark.parametrize("front", FRONT_ENDS, ids=[f.suffix for f in FRONT_ENDS])
def test_a_front_end_s_contract_program_gives_the_python_trace_bit_for_bit(front, python_run, tmp_path):
    run = contract_run(front, tmp_path)
    ms = [(a // 1_000_000, b // 1_000_000 if b else None) for a, b in run.trace.intervals("MOTOR")]
    # seen by the scan starting at each press (1 ms scans), written at its end; the scan at 201 ms sees
    # START and STOP both pressed and keeps the motor off (STOP dominates); from 202 ms START alone holds it
    assert ms == [(21, 101), (151, 201), (203, None)]
    assert run.trace.names[:3] == ["START", "STOP", "MOTOR"]
    assert run.trace.digest() == python_run.trace.digest()


@pytest.mark.parametrize("front", FRONT_ENDS, ids=[f.suffix for f in FRONT_ENDS])
def test_a_front_end_runs_on_the_controller_of_the_profile_it_names(front, tmp_path):
    profile = profiles.profile(front.profile)
    run = contract_run(front, tmp_path)
    controller = type(run.cpu)
    assert f"{controller.__module__}:{controller.__qualname__}" == profile.controller


@pytest.mark.parametrize("profile", PROFILES, ids=[p.name for p in PROFILES])
def test_a_profile_s_address_grammar_reads_its_examples_and_refuses_nonsense(profile: Profile):
    for area in profile.areas:
        for text in area.examples:
            assert profile.parse_address(text) is not None, text
    with pytest.raises(ValueError):
        profile.parse_address("Z9.9")


@pytest.mark.parametrize("profile", PROFILES, ids=[p.name for p in PROFILES])
def test_a_profile_s_triggers_number_each_task_once(profile: Profile):
    numbers = [n for t in profile.triggers for n in range(t.first, t.last + 1)]
    assert len(numbers) == len(set(numbers)) and all(t.first <= t.last for t in profile.triggers)
    assert profile.restarts and profile.system_bits and profile.instructions()
    assert profile.byte_order in ("big", "little")


def test_the_s7_profile_is_what_the_python_front_end_reads_task_names_by():
    s7 = profiles.profile("s7-1200")
    assert [(t.first, t.last, t.kind) for t in s7.triggers] == [
        (1, 1, "cyclic"),
        (30, 38, "interrupt"),
        (100, 100, "startup"),
    ]
    assert task_kind("OB35") == ("interrupt", 8) and task_kind("OB100") == ("startup", 1)
    assert s7.trigger_of(2) is None
    assert {"P", "MOVE", "RD_LOC_T", "TON", "CTUD", "R_TRIG"} <= s7.instructions()
    assert s7.parse_address("%MW10").bits == 16 and s7.byte_order == "big"


def test_the_tecomat_profile_describes_what_its_controller_runs():
    tecomat = profiles.profile("TECOMAT-NS950")
    assert tecomat.parse_address("RW4").width == "word" and tecomat.byte_order == "little"
    assert [tecomat.trigger_of(n).tasks for n in (0, 3, 41, 63, 64)] == ["P0", "P1..P4", "P41..P48", "P62, P63", "P64"]
    assert {"LD", "WR", "TON", "EOC", "CAL"} <= tecomat.instructions() and "MUL" not in tecomat.instructions()


def test_the_plc836_profile_runs_on_the_s7_runtime_with_the_chapter_s_instructions():
    plc836 = profiles.profile("PLC836")
    assert plc836.controller == profiles.profile("s7-1200").controller
    assert plc836.parse_address("BYTE.(CITAC+13)") == ("BYTE", "CITAC", 13)
    assert {"MECH_BEGIN", "EX0", "TEX1", "TIM", "BEX", "LDR", "FL", "STO"} <= plc836.instructions()
    assert [t.kind for t in plc836.triggers] == ["cyclic"]


def test_an_unknown_profile_is_named_with_the_known_ones():
    with pytest.raises(Exception, match=r"no CPU profile 's7-1500'.*profiles: plc836, s7-1200, tecomat-ns950"):
        profiles.profile("s7-1500")


def test_plcsim_list_profiles_shows_each_profile_with_its_front_ends(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "250")
    assert main(["list", "--profiles"]) == 0
    out = capsys.readouterr().out
    s7 = next(line for line in out.splitlines() if "s7-1200" in line)
    tecomat = next(line for line in out.splitlines() if "tecomat-ns950" in line)
    assert "Siemens S7-1200" in s7 and ".py (the Python subset)" in s7 and "big-endian" in out
    assert "Tecomat NS950" in tecomat and ".il (Tecomat NS950 instruction list)" in tecomat and "cold, warm" in tecomat
    plc836 = next(line for line in out.splitlines() if line.lstrip("│ ").startswith("plc836"))
    assert ".mech (PLC836 mechanisms)" in plc836
