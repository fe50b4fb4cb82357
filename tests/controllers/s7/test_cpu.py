"""Golden tests: the CPU around the program (spec §1.2, §1.5, §1.6, §3.6, §4.7, §4.8, §7).

Rules these tests pin:

* STOP->RUN: every non-retain tag takes its start value, retain tags keep theirs (4.3.14/4.3.15:
  MOTOR.SEKUNDY and DATUM_CAS retain, NULUJ not); counters are retentive, timers are not.
* In STOP no OB runs, the output modules are off (the output image keeps its values) and the inputs
  are still read into the input image.
* Clock memory (MB0 here) is latched at the start of each task execution: Clock_1Hz is FALSE in
  [0, 0.5) s, TRUE in [0.5, 1) s ...; system memory (MB1): FirstScan only in the first scan after
  STOP->RUN, AlwaysTRUE, AlwaysFALSE. Clock and system memory may not share a byte.
* Cycle watchdog: a scan that loops past the watchdog budget stops the CPU with a diagnostic naming
  OB1, the network and the line; the host does not hang. Any other exception in a network stops the
  CPU with the network, the line and the message.
* Scan time: fixed ``cycle`` (default 1 ms), at least ``min_cycle``; ``jitter`` is uniform and
  reproducible by ``seed``; with ``network_cost`` the cycle is N networks * cost.
* RD_LOC_T reads the simulated clock: ``rtc_start`` + simulated time of the execution's start.
* JMP skips networks entirely (their coils are not written, their timers do not run).
"""

from __future__ import annotations

import itertools
import sys
import time

import pytest
from plcharness import Probe, drive, held, ns

from plcsim import CPU, Tag
from plcsim.core.errors import ConfigurationError, ProgramError

PANEL = {"TL": Tag("%I0.0"), "ZAP": Tag("%I0.1"), "LED": Tag("%Q0.0"), "D1": Tag("%Q0.2")}

# --------------------------------------------------------------------------------------------
# STOP -> RUN and retain: 4.3.14 / 4.3.15
# --------------------------------------------------------------------------------------------

MOTOR_4_3_14 = """
AUX = Tag("%M10.3")
Takt1s = Tag("%M10.2")
MOTOR = DB(SEKUNDY=DInt(0, retain=True), DATUM_CAS=DTL(retain=True), NULUJ=Bool())
def conveyor(t):
    t.D1 = t.ZAP
def rung1(t):
    t.Takt1s = P(t.Clock_1Hz, "AUX")
def rung2(t):
    if t.Takt1s and t.D1:
        t.MOTOR.SEKUNDY += 1
def rung3(t):
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False
OB1 = [conveyor, rung1, rung2, rung3]
"""


def motor_cpu(program: str = MOTOR_4_3_14, cycle: str = "10ms") -> CPU:
    return CPU(
        tags=PANEL,
        program=program,
        cycle=cycle,
        clock_memory_byte=0,
        system_memory_byte=1,
        rtc_start="DTL#2022-01-25-14:49:00",
    )


def test_4_3_14_seconds_count_only_while_the_motor_runs():
    cpu = motor_cpu()
    drive(cpu, held("ZAP", (0, 10), (20, 25)), 30)
    assert cpu.read("MOTOR.SEKUNDY") == 15  # Takt1s at 0.5 .. 9.5 s and 20.5 .. 24.5 s


def test_4_3_14_nuluj_resets_and_stamps_the_date_in_the_same_scan():
    cpu = motor_cpu()
    drive(cpu, held("ZAP", (0, 20)), 17.01)
    assert cpu.read("MOTOR.SEKUNDY") == 17
    cpu.write("MOTOR.NULUJ", True)  # from the watch table / HMI, between two scans
    cpu.scan()
    stamp = {k: cpu.read(f"MOTOR.DATUM_CAS.{k}") for k in ("YEAR", "MONTH", "DAY", "WEEKDAY", "HOUR", "MINUTE")}
    assert stamp == {"YEAR": 2022, "MONTH": 1, "DAY": 25, "WEEKDAY": 3, "HOUR": 14, "MINUTE": 49}
    assert (cpu.read("MOTOR.DATUM_CAS.SECOND"), cpu.read("MOTOR.DATUM_CAS.NANOSECOND")) == (17, 10_000_000)
    assert (cpu.read("MOTOR.SEKUNDY"), cpu.read("MOTOR.NULUJ")) == (0, False)


@pytest.mark.parametrize("how", ["stop-run", "power-cycle"])
def test_4_3_14_retain_survives_stop_run_and_nuluj_does_not(how):
    cpu = motor_cpu()
    drive(cpu, held("ZAP", (0, 20)), 12.01)
    cpu.write("MOTOR.NULUJ", True)
    cpu.scan()
    drive(cpu, [], 15.01)
    before = (cpu.read("MOTOR.SEKUNDY"), cpu.read("MOTOR.DATUM_CAS.SECOND"))
    assert before == (3, 12)
    cpu.stop()
    cpu.write("MOTOR.NULUJ", True)  # set in STOP: not retain, so it is FALSE after the start
    if how == "stop-run":
        cpu.start()
    else:
        cpu.power_cycle()
    assert (cpu.read("MOTOR.SEKUNDY"), cpu.read("MOTOR.DATUM_CAS.SECOND"), cpu.read("MOTOR.NULUJ")) == (3, 12, False)
    assert cpu.read("MOTOR.DATUM_CAS.YEAR") == 2022


MOTOR_4_3_15 = """
AUX = Tag("%M10.3")
Takt1s = Tag("%M10.2")
MOTOR = DB(SEKUNDY=USInt(0, retain=True), MINUTY=USInt(0, retain=True), HODINY=UInt(0, retain=True),
           DATUM_CAS=DTL(retain=True), NULUJ=Bool())
def conveyor(t):
    t.D1 = t.ZAP
def takt(t):
    t.Takt1s = P(t.Clock_1Hz, "AUX")
def rung1(t):
    if t.Takt1s and t.D1:
        t.MOTOR.SEKUNDY += 1
def rung2(t):
    if t.MOTOR.SEKUNDY >= 60:
        t.MOTOR.MINUTY += 1
        MOVE(0, "MOTOR.SEKUNDY")
def rung3(t):
    if t.MOTOR.MINUTY >= 60:
        t.MOTOR.HODINY += 1
        MOVE(0, "MOTOR.MINUTY")
def rung4(t):
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY", "MOTOR.MINUTY", "MOTOR.HODINY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False
OB1 = [conveyor, takt, rung1, rung2, rung3, rung4]
"""


def test_4_3_15_hours_minutes_seconds_7325_after_2h_2min_5s():
    cpu = motor_cpu(MOTOR_4_3_15, cycle="100ms")
    bad = []

    def hook(c):
        if not (0 <= c.t.MOTOR.SEKUNDY <= 59 and 0 <= c.t.MOTOR.MINUTY <= 59):
            bad.append(c.scan_start_ns)

    cpu.on_scan_end = hook
    cpu.set_input("ZAP", True)
    cpu.run(ns(2 * 3600 + 2 * 60 + 5))
    h, m, s = cpu.read("MOTOR.HODINY"), cpu.read("MOTOR.MINUTY"), cpu.read("MOTOR.SEKUNDY")
    assert (h, m, s) == (2, 2, 5)
    assert h * 3600 + m * 60 + s == 7325
    assert bad == []  # the carry happens in the same scan
    cpu.write("MOTOR.NULUJ", True)
    cpu.scan()
    assert (cpu.read("MOTOR.HODINY"), cpu.read("MOTOR.MINUTY"), cpu.read("MOTOR.SEKUNDY")) == (0, 0, 0)
    assert (cpu.read("MOTOR.DATUM_CAS.HOUR"), cpu.read("MOTOR.DATUM_CAS.MINUTE")) == (16, 51)


def test_non_retain_tags_take_their_start_values_not_zero():
    program = """
POM = Tag("%M10.0")
OS_X = DB(ziadana=Real(1.0), aktualna=Real(0.0), KROK=Int(3), POCET=Int(0, retain=True))
T1 = IEC_TIMER()
def OB1(t):
    t.POM = True
    t.OS_X.ziadana = 2.5
    t.OS_X.KROK = 6
    t.OS_X.POCET = 9
    t.T1.TON(IN=True, PT="1s")
    t.LED = t.T1.Q
"""
    cpu = CPU(tags=PANEL, program=program)
    cpu.run("2s")
    assert (cpu.read("POM"), cpu.read("OS_X.ziadana"), cpu.read("T1.Q")) == (True, 2.5, True)
    cpu.stop()
    cpu.start()
    assert (cpu.read("POM"), cpu.read("OS_X.ziadana"), cpu.read("OS_X.KROK")) == (False, 1.0, 3)
    assert (cpu.read("OS_X.POCET"), cpu.read("T1.Q"), cpu.read("T1.ET")) == (9, False, 0)


def test_outputs_off_in_stop_inputs_still_read():
    cpu = CPU(tags=PANEL, program="def OB1(t):\n    t.LED = True\n    t.D1 = t.TL\n")
    cpu.scan()
    assert cpu.outputs == {"LED": True, "D1": False}
    cpu.stop()
    assert cpu.mode == "STOP"
    assert cpu.outputs == {"LED": False, "D1": False}
    assert cpu.read("LED") is True  # the output image keeps its value
    cpu.set_input("TL", True)
    cpu.run("10ms")
    assert cpu.read("TL") is True  # the input image is refreshed in STOP
    assert cpu.read("D1") is False and cpu.scan_count == 1  # no OB ran
    cpu.start()
    cpu.scan()
    assert cpu.outputs == {"LED": True, "D1": True}


# --------------------------------------------------------------------------------------------
# Clock and system memory (§7)
# --------------------------------------------------------------------------------------------

CLOCK_PROGRAM = """
SEEN_EARLY = Tag("%M10.0")
SEEN_LATE = Tag("%M10.1")
FIRST = Int(0)
def n1(t):
    t.SEEN_EARLY = t.Clock_1Hz
    if t.FirstScan:
        t.FIRST += 1
    t.LED = t.AlwaysTRUE and not t.AlwaysFALSE
def n2(t):
    t.SEEN_LATE = t.Clock_1Hz
OB1 = [n1, n2]
"""


def test_clock_1hz_toggles_every_half_second_latched_at_scan_start():
    cpu = CPU(tags=PANEL, program=CLOCK_PROGRAM, cycle="400ms", clock_memory_byte=0, system_memory_byte=1)
    probe = Probe(cpu, "SEEN_EARLY", "SEEN_LATE")
    cpu.run("4s")
    # scans at 0, 0.4, 0.8, ...; n2 runs 200 ms into each scan but sees the latched value
    expected = [(k * 0.4, (k * 400 // 500) % 2 == 1) for k in range(10)]  # run() includes the 3.6 s scan, ending at 4 s
    assert [(when / 1e9, v) for when, v in probe.samples["SEEN_EARLY"]] == [(pytest.approx(a), b) for a, b in expected]
    assert probe.samples["SEEN_LATE"] == probe.samples["SEEN_EARLY"]


@pytest.mark.parametrize(
    ("name", "bit", "half_ms"),
    [
        ("Clock_10Hz", 0, 50),
        ("Clock_5Hz", 1, 100),
        ("Clock_2_5Hz", 2, 200),
        ("Clock_2Hz", 3, 250),
        ("Clock_1_25Hz", 4, 400),
        ("Clock_1Hz", 5, 500),
        ("Clock_0_625Hz", 6, 800),
        ("Clock_0_5Hz", 7, 1000),
    ],
)
def test_clock_memory_byte_layout(name, bit, half_ms):
    cpu = CPU(tags=PANEL, program="def OB1(t):\n    pass\n", cycle="10ms", clock_memory_byte=0)
    assert cpu.table[name].address.byte == 0 and cpu.table[name].address.bit == bit
    probe = Probe(cpu, name)
    cpu.run("4s")
    changes = probe.changes(name)
    assert changes[0] == (0.0, False)
    assert [round(when * 1000) for when, _ in changes[1:]] == list(range(half_ms, 4000, half_ms))


def test_first_scan_and_always_bits():
    cpu = CPU(tags=PANEL, program=CLOCK_PROGRAM, clock_memory_byte=0, system_memory_byte=1)
    probe = Probe(cpu, "FirstScan", "AlwaysTRUE", "AlwaysFALSE", "%MB1")
    cpu.scan(5)
    assert [v for _, v in probe.samples["FirstScan"]] == [True, False, False, False, False]
    assert {v for _, v in probe.samples["AlwaysTRUE"]} == {True}
    assert {v for _, v in probe.samples["AlwaysFALSE"]} == {False}
    # FirstScan (bit 0), DiagStatusUpdate (bit 1: the STOP->RUN entry), AlwaysTRUE (bit 2), AlwaysFALSE (bit 3)
    assert [v for _, v in probe.samples["%MB1"]][:3] == [0b0111, 0b0100, 0b0100]
    assert (cpu.read("FIRST"), cpu.outputs["LED"]) == (1, True)
    cpu.stop()
    cpu.start()
    cpu.scan(3)
    assert cpu.read("FIRST") == 1  # FIRST is a start value 0 again: counted once more after STOP->RUN


def test_clock_and_system_memory_on_one_byte_is_rejected():
    with pytest.raises(ConfigurationError, match="MB0"):
        CPU(tags=PANEL, program=CLOCK_PROGRAM, clock_memory_byte=0, system_memory_byte=0)


# --------------------------------------------------------------------------------------------
# Watchdog and program errors at run time
# --------------------------------------------------------------------------------------------

ENDLESS = """
def first(t):
    t.LED = True
def looping(t):
    while True:
        pass
OB1 = [first, looping]
"""


def test_cycle_watchdog_stops_the_cpu_and_names_ob_network_and_line():
    cpu = CPU(tags=PANEL, program=ENDLESS)
    started = time.monotonic()
    cpu.scan(3)
    assert time.monotonic() - started < 10  # the host is not hung
    assert cpu.mode == "STOP"
    error = cpu.error
    assert error is not None and error.event == "cycle time monitoring exceeded"
    assert (error.task, error.network, error.line) == ("OB1", "2 (looping)", 5)
    assert "OB1 network 2 (looping), line 5" in str(error)
    assert cpu.outputs["LED"] is False
    assert cpu.scan_count == 0


FAILING = """
X = Int(0, retain=True)
def first(t):
    t.LED = True
def dividing(t):
    t.X = DIV(10, t.X)
OB1 = [first, dividing]
"""


def test_exception_in_a_network_stops_the_cpu_naming_network_line_and_message():
    cpu = CPU(tags=PANEL, program=FAILING)
    cpu.scan(2)
    assert cpu.mode == "STOP"
    error = cpu.error
    assert (error.event, error.task, error.network, error.line) == ("error in the program", "OB1", "2 (dividing)", 6)
    assert "division by zero" in error.message
    cpu.write("X", 2)
    cpu.start()
    cpu.scan()
    assert cpu.mode == "RUN" and cpu.error is None and cpu.read("X") == 5


# --------------------------------------------------------------------------------------------
# Forces (§3.6)
# --------------------------------------------------------------------------------------------

FORCE_PROGRAM = """
SEEN = Tag("%M10.0")
def OB1(t):
    t.SEEN = t.TL
    t.LED = False
    t.D1 = t.TL
"""


def test_force_input_and_output_then_unforce():
    cpu = CPU(tags=PANEL, program=FORCE_PROGRAM)
    cpu.force("TL", True)  # the terminal stays FALSE
    cpu.force("LED", True)  # the program writes FALSE every scan
    cpu.scan(3)
    assert cpu.read("SEEN") is True
    assert cpu.outputs == {"LED": True, "D1": True}
    assert cpu.read("LED") is True
    cpu.unforce("LED")
    cpu.unforce("TL")
    assert (cpu.read("TL"), cpu.read("LED")) == (True, True)  # the last forced values stay in memory
    cpu.scan()
    assert cpu.read("SEEN") is False  # the input image is refreshed from the terminal
    assert cpu.outputs == {"LED": False, "D1": False}  # the program writes LED again


def test_forced_input_overrides_the_terminal_in_every_scan():
    cpu = CPU(tags=PANEL, program=FORCE_PROGRAM)
    cpu.set_input("TL", True)
    cpu.force("TL", False)
    cpu.scan(5)
    assert cpu.read("SEEN") is False and cpu.outputs["D1"] is False


# --------------------------------------------------------------------------------------------
# Scan-time model
# --------------------------------------------------------------------------------------------


def scan_durations(**options) -> list[int]:
    program = "def n1(t):\n    t.LED = t.TL\ndef n2(t):\n    t.D1 = t.TL\ndef n3(t):\n    pass\nOB1 = [n1, n2, n3]\n"
    cpu = CPU(tags=PANEL, program=program, **options)
    durations: list[int] = []
    cpu.on_scan_end = lambda c: durations.append(c.scan_end_ns - c.scan_start_ns)
    cpu.scan(50)
    return durations


@pytest.mark.parametrize(
    ("options", "duration_ns"),
    [
        pytest.param({}, 1_000_000, id="default-1ms"),
        pytest.param({"cycle": "7ms"}, 7_000_000, id="cycle-7ms"),
        pytest.param({"cycle": "1ms", "min_cycle": "5ms"}, 5_000_000, id="min-cycle"),
        pytest.param({"network_cost": "2ms"}, 6_000_000, id="network-cost-3-networks"),
        pytest.param({"network_cost": "1ms", "min_cycle": "10ms"}, 10_000_000, id="network-cost-min-cycle"),
    ],
)
def test_fixed_scan_times(options, duration_ns):
    assert set(scan_durations(**options)) == {duration_ns}


def test_jitter_is_seeded_and_bounded():
    a = scan_durations(cycle="10ms", jitter="2ms", seed=1)
    b = scan_durations(cycle="10ms", jitter="2ms", seed=1)
    c = scan_durations(cycle="10ms", jitter="2ms", seed=2)
    assert a == b and a != c
    assert all(8_000_000 <= d <= 12_000_000 for d in a + c)
    assert len(set(a)) > 10


def test_scans_follow_each_other_without_gaps():
    cpu = CPU(tags=PANEL, program="def OB1(t):\n    pass\n", cycle="10ms", jitter="3ms", seed=7)
    spans: list[tuple[int, int]] = []
    cpu.on_scan_end = lambda c: spans.append((c.scan_start_ns, c.scan_end_ns))
    cpu.scan(20)
    assert spans[0][0] == 0
    assert all(prev[1] == nxt[0] for prev, nxt in itertools.pairwise(spans))
    assert cpu.now == spans[-1][1]


# --------------------------------------------------------------------------------------------
# RD_LOC_T, MOVE
# --------------------------------------------------------------------------------------------

RD_LOC_T_PROGRAM = """
D = DB(FIRST=DTL, LAST=DTL)
def n1(t):
    t.D.FIRST = RD_LOC_T()
def n2(t):
    t.D.LAST = RD_LOC_T()
OB1 = [n1, n2]
"""


def test_rd_loc_t_reads_the_simulated_clock_at_the_execution_start():
    cpu = CPU(tags=PANEL, program=RD_LOC_T_PROGRAM, cycle="100ms", rtc_start="DTL#2022-01-25-14:49:17.016180")
    cpu.run("1500ms")  # the last scan started at 1.4 s
    first = {k: cpu.read(f"D.FIRST.{k}") for k in ("YEAR", "MONTH", "DAY", "WEEKDAY", "HOUR", "MINUTE", "SECOND")}
    assert first == {"YEAR": 2022, "MONTH": 1, "DAY": 25, "WEEKDAY": 3, "HOUR": 14, "MINUTE": 49, "SECOND": 18}
    assert cpu.read("D.FIRST.NANOSECOND") == 416_180_000
    assert cpu.read("D.LAST.NANOSECOND") == 416_180_000  # every network sees the execution's start time


@pytest.mark.parametrize("step_ms", [None, 1, 30], ids=["one-call", "1ms-steps", "30ms-steps"])
def test_networks_see_the_execution_start_however_the_host_steps_the_clock(step_ms):
    program = (
        RD_LOC_T_PROGRAM.replace("OB1 = [n1, n2]", "")
        + """
T = IEC_TIMER()
ET_LATE = DInt(0)
def n3(t):
    t.T.TON(IN=True, PT="10s")
def n4(t):
    t.ET_LATE = t.T.ET
OB1 = [n1, n3, n2, n4]
"""
    )
    cpu = CPU(tags=PANEL, program=program, cycle="100ms", rtc_start="DTL#2022-01-25-14:49:17")
    if step_ms is None:
        cpu.run_until(ns(1))
    else:
        for k in range(1, 1000 // step_ms + 1):
            cpu.run_until(k * step_ms * 1_000_000)
    # the scan that started at 0.9 s ran its four networks at 0.9, 0.925, 0.95 and 0.975 s
    assert (cpu.read("D.FIRST.NANOSECOND"), cpu.read("D.LAST.NANOSECOND")) == (900_000_000, 900_000_000)
    assert cpu.read("ET_LATE") == 900


def test_rd_loc_t_crosses_midnight_and_the_weekday():
    cpu = CPU(tags=PANEL, program=RD_LOC_T_PROGRAM, cycle="1s", rtc_start="DTL#2022-01-29-23:59:59")
    cpu.run("2s")  # scans at 0 s and 1 s: Saturday 23:59:59, then Sunday 00:00:00
    assert [cpu.read(f"D.FIRST.{k}") for k in ("DAY", "WEEKDAY", "HOUR", "MINUTE", "SECOND")] == [30, 1, 0, 0, 0]


MOVE_PROGRAM = """
MOTOR = DB(SEKUNDY=USInt(5), MINUTY=USInt(7), HODINY=UInt(9), R=Real(1.0), S=Struct(A=Int, B=Bool),
           S2=Struct(A=Int, B=Bool))
def OB1(t):
    if t.TL:
        MOVE(0, "MOTOR.SEKUNDY", "MOTOR.MINUTY", "MOTOR.HODINY")
    if t.ZAP:
        MOVE(1.5, "MOTOR.HODINY")
"""


def test_move_with_several_outputs():
    cpu = CPU(tags=PANEL, program=MOVE_PROGRAM)
    cpu.scan()
    assert [cpu.read(f"MOTOR.{k}") for k in ("SEKUNDY", "MINUTY", "HODINY")] == [5, 7, 9]
    cpu.set_input("TL", True)
    cpu.scan()
    assert [cpu.read(f"MOTOR.{k}") for k in ("SEKUNDY", "MINUTY", "HODINY")] == [0, 0, 0]


def test_move_type_mismatch_stops_the_cpu():
    cpu = CPU(tags=PANEL, program=MOVE_PROGRAM)
    cpu.set_input("ZAP", True)
    cpu.scan()
    assert cpu.mode == "STOP"
    assert cpu.error.line == 8
    assert "MOVE" in cpu.error.message and "UInt" in cpu.error.message and "must match" in cpu.error.message


# --------------------------------------------------------------------------------------------
# JMP, labels, RET (§4.8)
# --------------------------------------------------------------------------------------------

JUMP_PROGRAM = """
T = IEC_TIMER()
N2 = Int(0)
def n1(t):
    if t.TL:
        JMP("lbl10")
def n2(t):
    t.N2 += 1
    t.LED = t.T.TON(IN=t.ZAP, PT="1s")
@label("lbl10")
def n3(t):
    t.D1 = True
OB1 = [n1, n2, n3]
"""


@pytest.mark.parametrize("dialect", ["s7_1200", "iec"])
def test_jumped_over_network_does_not_run_its_timer_or_coils(dialect):
    cpu = CPU(tags=PANEL, program=JUMP_PROGRAM, cycle="100ms", timer_dialect=dialect)
    cpu.set_input("TL", True)
    cpu.set_input("ZAP", True)
    cpu.run("3s")
    assert (cpu.read("N2"), cpu.read("T.ET"), cpu.read("T.IN"), cpu.outputs["LED"]) == (0, 0, False, False)
    assert cpu.outputs["D1"] is True  # the labelled network runs
    cpu.set_input("TL", False)
    cpu.run("1500ms")
    assert cpu.read("N2") == 15
    assert cpu.outputs["LED"] is True  # the timer starts only once its network runs: 1 s later


def test_jumped_over_coil_keeps_its_last_value():
    cpu = CPU(tags=PANEL, program=JUMP_PROGRAM, cycle="100ms")
    cpu.set_input("ZAP", True)
    cpu.run("1500ms")
    assert cpu.outputs["LED"] is True
    cpu.set_input("ZAP", False)
    cpu.set_input("TL", True)  # now n2 is skipped: LED is not written FALSE
    cpu.run("1s")
    assert cpu.outputs["LED"] is True


BACKWARD = """
@label("top")
def n1(t):
    t.LED = True
def n2(t):
    if t.TL:
        JMP("top")
OB1 = [n1, n2]
"""


def test_backward_jump_loop_trips_the_watchdog():
    cpu = CPU(tags=PANEL, program=BACKWARD, watchdog_iterations=10_000)  # a smaller budget keeps the test fast
    cpu.scan(3)
    assert cpu.mode == "RUN" and cpu.outputs["LED"] is True
    cpu.set_input("TL", True)
    cpu.scan()
    assert cpu.mode == "STOP"
    assert cpu.error.event == "cycle time monitoring exceeded" and cpu.error.task == "OB1"
    assert cpu.outputs["LED"] is False


def test_backward_jump_as_a_bounded_loop():
    program = """
LOOP = DB(i=Int(0), suma=Int(0), pocet=Array(0, 9, Int, ))
def init(t):
    t.LOOP.i = 0
    t.LOOP.suma = 0
@label("LBL123")
def body(t):
    t.LOOP.suma += t.LOOP.i
    t.LOOP.i += 1
    if t.LOOP.i < 10:
        JMP("LBL123")
OB1 = [init, body]
"""
    cpu = CPU(tags=PANEL, program=program)
    cpu.scan(2)
    assert cpu.mode == "RUN" and cpu.read("LOOP.suma") == 45


def test_jmp_to_a_missing_label_is_a_load_error():
    program = 'def n1(t):\n    if t.TL:\n        JMP("nowhere")\nOB1 = [n1]\n'
    with pytest.raises(ProgramError, match=r"line 3: JMP to 'nowhere'.*no labels"):
        CPU(tags=PANEL, program=program)


def test_duplicate_label_is_a_load_error():
    program = '@label("a")\ndef n1(t):\n    pass\n@label("a")\ndef n2(t):\n    pass\nOB1 = [n1, n2]\n'
    with pytest.raises(ProgramError, match="label 'a' is used twice"):
        CPU(tags=PANEL, program=program)


def test_ret_ends_the_ob():
    program = "N = Int(0)\ndef n1(t):\n    if t.TL:\n        RET()\ndef n2(t):\n    t.N += 1\nOB1 = [n1, n2]\n"
    cpu = CPU(tags=PANEL, program=program)
    cpu.scan(3)
    cpu.set_input("TL", True)
    cpu.scan(3)
    assert cpu.read("N") == 3 and cpu.mode == "RUN"


def test_ob100_runs_once_at_stop_run_before_ob1():
    program = """
STARTS = Int(0, retain=True)
SEEN = Int(0)
def startup(t):
    t.STARTS += 1
def main(t):
    t.SEEN = t.STARTS
OB100 = [startup]
OB1 = [main]
"""
    cpu = CPU(tags=PANEL, program=program)
    cpu.scan(3)
    assert (cpu.read("STARTS"), cpu.read("SEEN")) == (1, 1)
    cpu.stop()
    cpu.start()
    cpu.scan()
    assert (cpu.read("STARTS"), cpu.read("SEEN")) == (2, 2)


def test_a_cpu_without_a_program_stays_in_stop_and_keeps_reading_inputs():
    cpu = CPU(tags={"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")})
    cpu.set_input("TL", True)
    cpu.run("5ms")
    assert (cpu.mode, cpu.now, cpu.t.TL, cpu.outputs["LED"]) == ("STOP", 5_000_000, True, False)


def test_tag_names_are_the_interned_strings_of_the_programs_constants():
    """The generated code looks the tags up by constant names, which Python interns: the names of ``t`` (a DB's
    members too), of the input image and of the output getter are those very strings, so that every lookup
    matches by identity (issue 29: 8 % of a scan of the benchmark workload). Names built at run time, as a tag
    table read from a file has them, are not interned unless the CPU does it."""
    start, lamp = "".join(["Sta", "rt"]), "".join(["La", "mp"])
    program = "D = DB(number=1, Seen=Bool)\ndef OB1(t):\n    t.Lamp = t.Start\n    t.D.Seen = t.Start\n"
    cpu = CPU(tags={start: Tag("%I0.0"), lamp: Tag("%Q0.0")}, program=program)
    names = [*cpu.t.__dict__, *cpu.t.D.__dict__, *cpu.inputs, *cpu.image_in, *cpu.outputs, *cpu.output_names]
    assert {"Start", "Lamp", "D", "Seen"} <= set(names)
    assert [n for n in names if n is not sys.intern(n)] == []
    cpu.set_input("Start", True)
    cpu.scan()
    assert (cpu.outputs["Lamp"], cpu.read("D.Seen")) == (True, True)
