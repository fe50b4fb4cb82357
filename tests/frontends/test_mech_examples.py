"""Every example of the PLC836 mechanisms chapter (seed 003, chapter 4; inventory M-01..M-08), in the
chapter's text (``.mech``) and in the Python form, with what the chapter says or implies (spec §5, §6).

Each runs on a 1 ms scan; inputs change at exact times (:mod:`plcharness`). Where the chapter leaves an
example incomplete the file says which lines are ours (M-02's contact names, M-03's elided code, the
CW mechanism and the preparatory-functions host of M-04/M-05, M-06's D02).
"""

from __future__ import annotations

import pytest
from mech_examples import BOTH_FORMS, cpu
from plcharness import drive, held, ns

from plcsim.sim.recorder import Recorder

FORMS = (".mech", ".py")


def run(example: str, suffix: str, events: list, until: float, **options):
    """Run an example with a recorder attached; return the CPU and its trace."""
    c = cpu(example, suffix, **options)
    recorder = Recorder(c)
    recorder.attach()
    drive(c, events, until)
    return c, recorder.trace


def ms(trace, name: str, value: bool = True) -> list[tuple[int, int | None]]:
    return [(a // 1_000_000, None if b is None else b // 1_000_000) for a, b in trace.intervals(name, value)]


@pytest.mark.parametrize("suffix", FORMS)
def test_m01_the_classic_latch_is_set_by_either_input_holds_itself_and_reset_dominates(suffix):
    events = [*held("NASTAV1", (0.010, 0.012)), *held("NASTAV2", (0.030, 0.031))]
    events += [*held("NULUJ", (0.020, 0.022), (0.040, 0.050)), *held("NASTAV1", (0.045, 0.060))]
    _c, trace = run("m01_latch", suffix, events, 0.070)
    # set by NASTAV1 at 10 ms, held after it falls, reset at 20 ms; set by NASTAV2 at 30 ms; NULUJ wins at 45 ms
    # (an output is recorded as the output module gets it: at the end of the 1 ms scan)
    assert ms(trace, "BUNKA") == [(11, 21), (31, 41), (51, None)]


@pytest.mark.parametrize("suffix", FORMS)
def test_m02_actions_chained_states_and_the_bit_that_clears_itself(suffix):
    c = cpu("m02_nazev", suffix)
    c.write("NAZEV.ACTIVE", True)
    c.scan()
    assert c.t.HYDRAULIKA is True and c.read("NAZEV.ACTIVE") is True and c.read("NAZEV.STEP") == 1
    # the window of the first state runs again every scan: clear HYDRAULIKA and it is set again
    c.write("HYDRAULIKA", False)
    c.scan()
    assert c.t.HYDRAULIKA is True and c.read("NAZEV.ACTIVE") is True
    c.write("POHON", True)
    c.set_input("KONTAKT1", True)
    c.set_input("KONTAKT2", True)
    c.scan()
    # K1*K2 = 1 and K3 = 0: action 2 and the end in the same scan
    assert c.t.POHON is False and c.read("NAZEV.ACTIVE") is False and c.read("NAZEV.STEP") == 0
    assert c.t.HYDRAULIKA is True  # actions persist after the end
    assert c.read("NAZEV.LINE") == 0


@pytest.mark.parametrize("suffix", FORMS)
def test_m02_waits_while_k3_and_names_the_state_in_line(suffix):
    c = cpu("m02_nazev", suffix)
    for name in ("KONTAKT1", "KONTAKT2", "KONTAKT3"):
        c.set_input(name, True)
    c.write("NAZEV.ACTIVE", True)
    c.scan(5)
    assert c.read("NAZEV.ACTIVE") is True and c.read("NAZEV.STEP") == 2
    # NAZEV_LINE: the EX1's line in the file (14), the step number in Python
    assert c.read("NAZEV.LINE") == (14 if suffix == ".mech" else 2)
    c.set_input("KONTAKT3", False)
    c.scan()
    assert c.read("NAZEV.ACTIVE") is False


@pytest.mark.parametrize("suffix", FORMS)
def test_m03_the_window_action_is_rewritten_every_scan_and_the_timeout_jumps_to_err(suffix):
    c = cpu("m03_window", suffix)
    c.set_input("VST1", True)
    c.set_input("VST2", True)
    c.write("MCH.ACTIVE", True)
    c.scan()
    assert c.t.VYST1 is True and c.read("MCH.STEP") == 2  # EX0 passed in the same scan, TEX1 blocks
    for _ in range(3):
        c.write("VYST1", False)
        c.scan()
        assert c.t.VYST1 is True  # FL 1,VYST1 lies in the re-executed window
    c.run_until(ns(2.0))
    assert c.read("MCH.ACTIVE") is True and c.t.ALARM is False
    c.run_until(ns(2.002))  # CAS_ERR = 100 counts = 2 s after the state was entered (at 0 ms)
    assert c.read("MCH.ACTIVE") is False and c.t.ALARM is True and c.t.VYST1 is True


@pytest.mark.parametrize("suffix", FORMS)
def test_m03_a_condition_that_falls_in_time_passes_and_the_mechanism_ends(suffix):
    c = cpu("m03_window", suffix)
    c.write("MCH.ACTIVE", True)
    drive(c, [*held("VST1", (0.001, 1.0)), *held("VST2", (0.001, 0.5))], 1.2)
    assert c.read("MCH.ACTIVE") is False and c.t.ALARM is False and c.t.VYST1 is False


def _feedback(times: dict[str, tuple[float, float]]) -> list:
    return [e for name, span in times.items() for e in held(name, span)]


@pytest.mark.parametrize("suffix", FORMS)
def test_m04_prep_starts_cw_and_resumes_only_after_cw_has_ended(suffix):
    events = [*held("START", (0.010, 0.020)), *held("KSMP", (0.300, 5.0))]
    _c, trace = run("m04_prep_cw", suffix, events, 1.0)
    assert ms(trace, "SMP") == [(11, None)]
    assert ms(trace, "CW.ACTIVE") == [(10, 300)]  # CW ends in the scan that sees KSMP
    assert ms(trace, "PREP.ACTIVE") == [(10, 301)]  # PREP: one scan later (the EX1 reads CW after CW's network ran)


def test_m04_without_the_ex_the_wait_never_ends_and_cw_restarts_every_scan(tmp_path):
    from mech_examples import TAGS, path

    from plcsim import CPU
    from plcsim.frontends.mech import MechProgram

    text = (
        path("m04_prep_cw", ".mech")
        .read_text(encoding="utf-8")
        .replace("FL 1,CW ;Nastaveni aktivacni promenne.\nEX\n", "FL 1,CW\n")
    )
    c = CPU(tags=TAGS["m04_prep_cw"], program=MechProgram(text, "no_ex.mech"))
    recorder = Recorder(c)
    recorder.attach()
    events = [*held("START", (0.010, 0.020)), *held("KSMP", (0.300, 5.0))]
    # CW is set again in every scan of PREP's window: from 300 ms on it starts (and ends) in every scan,
    # so its last run (its time analysis) began in the last scan
    for until in (0.5, 1.0):
        drive(c, events, until)
        assert c.t.CW.history[0][1] == ns(until - 0.001)
    assert recorder.trace.value_at("PREP.ACTIVE", ns(0.999)) is True and c.read("PREP.STEP") == 1  # never ends


@pytest.mark.parametrize("suffix", FORMS)
def test_m05_cw_finishing_in_3_s_is_no_error(suffix):
    c, trace = run("m05_prep_cw_timeout", suffix, [*held("START", (0.010, 0.020)), *held("KSMP", (3.0, 20.0))], 12.0)
    assert ms(trace, "PREP.ACTIVE") == [(10, 3001)] and c.t.BZH11 == 0


@pytest.mark.parametrize("suffix", FORMS)
def test_m05_cw_never_finishing_is_error_4_12_after_10_s_and_cw_stays_active(suffix):
    c, trace = run("m05_prep_cw_timeout", suffix, [*held("START", (0.010, 0.020))], 12.0)
    # PREP enters its TEX1 state at 11 ms (after the EX): 500 counts = 10 s later it jumps to ERR1
    assert ms(trace, "PREP.ACTIVE") == [(10, 10011)]
    assert trace.value_at("BZH11", ns(10.010)) == 0 and c.t.BZH11 == 0x12  # "4.12"
    assert c.read("CW.ACTIVE") is True  # the handler does not deactivate CW (spec §5.5 [E])


def _reversal(ksmp_falls: float | None, ksmn_closes: float | None) -> list:
    events = [*held("START", (0.010, 0.020)), (0.0, "KSMP", True)]
    if ksmp_falls is not None:
        events.append((ksmp_falls, "KSMP", False))
    if ksmn_closes is not None:
        events.append((ksmn_closes, "KSMN", True))
    return events


@pytest.mark.parametrize("suffix", FORMS)
@pytest.mark.parametrize("example", ["m06_cwccw", "m07_cwccw_tex"])
def test_m06_m07_the_reversal_in_order(example, suffix):
    c, trace = run(example, suffix, _reversal(0.050, 0.400), 1.0)
    # SMP off at activation; KSMP falls at 50 ms; 0.2 s later SMN on; KSMN at 400 ms ends the mechanism
    assert ms(trace, "SMP") == []
    assert ms(trace, "SMN") == [(251, None)]
    assert ms(trace, "CWCCW.ACTIVE") == [(10, 400)]
    assert c.t.BZH11 == 0 and c.read("CWCCW.ERR") == 0
    steps = [(t // 1_000_000, int(v)) for t, v in zip(trace.times, trace.column("CWCCW.STEP"), strict=True)]
    changes = [s for k, s in enumerate(steps) if k == 0 or s[1] != steps[k - 1][1]]
    assert changes == [(0, 0), (10, 1), (50, 2), (250, 3), (400, 0)]


@pytest.mark.parametrize("suffix", FORMS)
def test_m06_a_stuck_contact_waits_for_ever_at_the_ex1(suffix):
    c, _trace = run("m06_cwccw", suffix, _reversal(None, None), 30.0)
    assert c.read("CWCCW.ACTIVE") is True and c.read("CWCCW.STEP") == 1
    assert c.read("CWCCW.LINE") == (12 if suffix == ".mech" else 1) and c.t.SMN is False
    assert c.read("CWCCW.ET") == 29_989  # how long it has waited there: entered at 10 ms, last scan at 29.999 s


@pytest.mark.parametrize("suffix", FORMS)
def test_m07_ksmp_stuck_is_error_4_04_after_1_s(suffix):
    c, trace = run("m07_cwccw_tex", suffix, _reversal(None, None), 2.0)
    assert ms(trace, "CWCCW.ACTIVE") == [(10, 1010)]  # 50 counts after the TEX1 state was entered
    assert c.t.BZH11 == 4 and c.t.SMN is False and trace.value_at("CWCCW.ERR", ns(1.010)) == 4


@pytest.mark.parametrize("suffix", FORMS)
def test_m07_ksmn_never_closing_is_error_4_05_one_second_after_smn(suffix):
    c, trace = run("m07_cwccw_tex", suffix, _reversal(0.050, None), 2.0)
    assert ms(trace, "SMN") == [(251, 1251)]  # on after 0.2 s, off by the handler 1 s later
    assert ms(trace, "CWCCW.ACTIVE") == [(10, 1250)]
    assert c.t.BZH11 == 5 and c.read("CWCCW.ERR") == 5


def test_m08_typed_operands_read_the_reconfigurable_times_and_tex1_leaves_23h_in_dr():
    events = [*held("START", (0.010, 0.020)), *held("VST1", (0.5, 5.0)), *held("VST2", (0.0, 5.0))]
    c, trace = run("m08_typed", ".mech", events, 2.0)
    # TEX0 passes when VST1 rises at 0.5 s; TEX1 waits while VST2 = 1 for BYTE (REKONFIG+21) = 25 counts = 0.5 s
    assert ms(trace, "M8.ACTIVE") == [(10, 1000)]
    assert c.t.CODE == 0x23


def test_m08_tex0_times_out_after_the_word_time_at_rekonfig_14():
    _c, trace = run("m08_typed", ".mech", [*held("START", (0.010, 0.020))], 2.0)
    assert ms(trace, "M8.ACTIVE") == [(10, 1010)]  # WORD (REKONFIG+14) = 50 counts = 1 s


@pytest.mark.parametrize("example", BOTH_FORMS)
def test_contract_the_same_example_in_both_forms_records_the_same_trace_bit_for_bit(example):
    events = [*held("START", (0.010, 0.020)), (0.0, "KSMP", True), (0.05, "KSMP", False), (0.4, "KSMN", True)]
    events += [*held("NASTAV1", (0.010, 0.012)), *held("NULUJ", (0.020, 0.022)), *held("KONTAKT3", (0.1, 0.2))]
    events += [*held("KONTAKT1", (0.05, 0.3)), *held("KONTAKT2", (0.05, 0.3)), *held("VST1", (0.03, 0.9))]
    from mech_examples import TAGS

    events = [e for e in events if e[1] in TAGS[example]]
    traces = []
    for suffix in FORMS:
        c = cpu(example, suffix)
        recorder = Recorder(c)
        recorder.attach()
        if example == "m03_window":
            c.write("MCH.ACTIVE", True)
        drive(c, events, 12.0)
        traces.append(recorder.trace)
    mech, python = traces
    assert mech.names == python.names
    assert mech.digest() == python.digest()


@pytest.mark.parametrize("example", ["m07_cwccw_tex", "m05_prep_cw_timeout", "m02_nazev"])
def test_contract_holds_in_the_one_step_per_scan_mode_too(example):
    from mech_examples import TAGS

    events = [*held("START", (0.010, 0.020)), (0.0, "KSMP", True), (0.05, "KSMP", False), (0.4, "KSMN", True)]
    events += [*held("KONTAKT1", (0.05, 0.3)), *held("KONTAKT2", (0.05, 0.3))]
    events = [e for e in events if e[1] in TAGS[example]]
    digests = []
    for suffix in FORMS:
        c = cpu(example, suffix, mechanism_mode="iec")
        recorder = Recorder(c)
        recorder.attach()
        drive(c, events, 12.0)
        digests.append(recorder.trace.digest())
    assert digests[0] == digests[1]


SHARED = """
MECH_BEGIN A
LDR X
TEX0 C,50,A_ERR
JUM A_END
A_ERR: FL 1,ALARM
A_END:
MECH_END A
MECH_BEGIN B
LOOP: TIM {counter},10
JUM LOOP
MECH_END B
"""


@pytest.mark.parametrize(("counter", "alarm"), [("C", False), ("-", True), ("D", True)])
def test_a_counter_named_by_two_states_is_restarted_by_each_so_a_loop_can_starve_a_timeout(counter, alarm):
    from plcsim import CPU, Tag
    from plcsim.frontends.mech import MechProgram

    c = CPU(tags={"X": Tag("%I0.0")}, program=MechProgram(SHARED.format(counter=counter), "shared.mech"))
    c.write("A.ACTIVE", True)
    c.write("B.ACTIVE", True)
    c.run_until(ns(3.0))
    # B's TIM restarts a counter it shares with A's TEX0 every 0.2 s: A's 1 s never runs out
    assert c.t.ALARM is alarm and c.read("A.ACTIVE") is not alarm


def test_goto_continues_in_another_step_from_the_next_scan():
    from plcsim import CPU, Tag

    program = """
M = MECHANISM()
N = Int()

def m(t):
    if t.M.begin():
        if t.M.step(1):
            t.N = t.N + 1
            t.M.wait_until(t.X, timeout="10ms", error="AGAIN")
        if t.M.error("AGAIN"):
            t.M.goto(1)
        t.M.end()

OB1 = [m]
"""
    c = CPU(tags={"X": Tag("%I0.0")}, program=program)
    c.write("M.ACTIVE", True)
    c.scan(25)
    # step 1's window runs in every scan; its time restarts at each goto: timeouts in the scans at 10 ms
    # and 21 ms (entered again at 11 ms), so in the last scan (24 ms) it has waited 2 ms
    assert c.read("M.ACTIVE") is True and c.read("M.STEP") == 1 and c.t.N == 25 and c.read("M.ET") == 2


OPPOSING = """
LDR STOP
LO SPSTOP
WR SPSTOP
MECH_BEGIN SPSTOP        ;spindle stop, the opposing mechanism of higher priority
MECH_INIT CW             ;abort a start in progress; its outputs are ours to drive
FL 0,SMP
LDR KSMP
EX1
MECH_END SPSTOP
MECH_BEGIN CW
FL 1,SMP
LDR KSMP
EX0
MECH_END CW
"""


def test_mech_init_from_an_opposing_mechanism_aborts_a_run_and_leaves_the_outputs_to_it():
    from plcsim import CPU, Tag
    from plcsim.frontends.mech import MechProgram

    tags = {"STOP": Tag("%I0.0"), "KSMP": Tag("%I0.1"), "SMP": Tag("%Q0.0")}
    c = CPU(tags=tags, program=MechProgram(OPPOSING, "opposing.mech"))
    c.write("CW.ACTIVE", True)
    c.scan(3)
    assert c.read("CW.STEP") == 1 and c.t.SMP is True
    c.set_input("STOP", True)
    c.scan()
    assert c.read("CW.ACTIVE") is False and c.read("CW.STEP") == 0 and c.read("CW.LINE") == 0
    assert c.t.SMP is False and c.read("SPSTOP.ACTIVE") is False  # KSMP open: the stop passed at once
    c.set_input("STOP", False)
    c.write("CW.ACTIVE", True)
    c.scan()
    assert c.read("CW.STEP") == 1 and c.t.SMP is True  # a new run, from the top
