"""Golden tests: programs in the cyclic interrupt OB30 (spec §1.3-§1.4, exercises 4.3.19-4.3.22).

Timing rules these tests pin (cpu.py's timing model):

* OB30 (period 1 s) is first called at the STOP->RUN instant (t = 0), then at 1 s, 2 s ...
* Each OB30 execution reads the inputs its networks use at its start and writes the outputs they
  use at its end; it lasts ``interrupt_duration`` (1 ms, as in the textbook). An output set by the
  call at T therefore reaches the output module at T + 1 ms; a memory or DB value changes at T.
* A press that begins and ends between two calls is never seen.
* ``run_until(T)`` runs the events strictly before T, so an input set at T is seen by the call at T.
* OB30 pre-empts OB1 between two networks (never inside one): a multi-network OB1 can see two values
  of one %M tag in one scan, a single-network OB1 cannot.
"""

from __future__ import annotations

import pytest
from plcharness import held, sample

from plcsim import CPU, Tag

PANEL = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}


def led(cpu: CPU) -> bool:
    return cpu.outputs["LED"]


def run(program: str, events, until: float, read=led, **options):
    cpu = CPU(tags=PANEL, program=program, **options)
    changes = sample(cpu, events, until, read)
    assert cpu.mode == "RUN"
    return changes, cpu


# --------------------------------------------------------------------------------------------
# 4.3.19: TL -> S LED
# --------------------------------------------------------------------------------------------

P_4_3_19 = """
def net(t):
    if t.TL:
        t.LED = True
OB30 = CyclicInterrupt(net, period="1s")
"""


@pytest.mark.parametrize(
    ("press", "expected"),
    [
        pytest.param((0, 5), [(0.0, False), (0.001, True)], id="held-from-0s-on-at-0s+1ms"),
        pytest.param((0.1, 5), [(0.0, False), (1.001, True)], id="pressed-at-0.1s-on-at-1s"),
        pytest.param((0.1, 0.6), [(0.0, False)], id="short-press-between-calls-never"),
        pytest.param((1.5, 2.6), [(0.0, False), (2.001, True)], id="held-1.1s-always-seen"),
    ],
)
def test_4_3_19_led_rises_at_the_first_call_that_sees_tl(press, expected):
    changes, _ = run(P_4_3_19, held("TL", press), 6)
    assert changes == expected


# --------------------------------------------------------------------------------------------
# 4.3.20: LED := START ; TL -> S START
# --------------------------------------------------------------------------------------------

P_4_3_20 = """
START = Tag("%M10.0")
def n1(t):
    t.LED = t.START
def n2(t):
    if t.TL:
        t.START = True
OB30 = CyclicInterrupt([n1, n2], period="1s")
"""


@pytest.mark.parametrize(
    ("press", "expected"),
    [
        # START is set by the call at 0 s / 1 s (the networks of an execution run at its start);
        # LED follows at the next call, physically at that call's end (+1 ms).
        pytest.param((0, 5), [(0.0, (True, False)), (1.001, (True, True))], id="pressed-from-0s"),
        pytest.param(
            (0.1, 5), [(0.0, (False, False)), (1.0, (True, False)), (2.001, (True, True))], id="pressed-at-0.1s"
        ),
    ],
)
def test_4_3_20_led_comes_one_call_after_start(press, expected):
    changes, _cpu = run(P_4_3_20, held("TL", press), 6, read=lambda c: (c.read("START"), c.outputs["LED"]))
    assert changes == expected


# --------------------------------------------------------------------------------------------
# 4.3.21: TL -> TON(100 ms) -> Q -> S LED
# --------------------------------------------------------------------------------------------

TON_NET = """
TON_L = IEC_TIMER()
def n1(t):
    if t.TON_L.TON(IN=t.TL, PT="100ms"):
        t.LED = True
"""


@pytest.mark.parametrize(
    ("press", "led_at"),
    [
        pytest.param((0, 5), 1.001, id="pressed-from-0s-on-at-1s"),
        pytest.param((0.1, 5), 2.001, id="pressed-0.1s-on-2s"),
    ],
)
def test_4_3_21_timer_in_ob30_is_quantised_to_the_period(press, led_at):
    changes, _ = run(TON_NET + 'OB30 = CyclicInterrupt(n1, period="1s")\n', held("TL", press), 6)
    assert changes == [(0.0, False), (led_at, True)]


def test_4_3_21_press_shorter_than_the_time_to_the_second_call_is_lost():
    # pressed at 0.1 s: the calls at 1 s and 2 s must both see it; released at 1.5 s, the LED never comes
    changes, cpu = run(TON_NET + 'OB30 = CyclicInterrupt(n1, period="1s")\n', held("TL", (0.1, 1.5)), 6)
    assert changes == [(0.0, False)]
    assert cpu.read("TON_L.ET") == 0


def test_4_3_21_same_program_in_ob1_sets_the_led_100ms_after_the_press():
    press = 0.1
    cpu = CPU(tags=PANEL, program=TON_NET + "OB1 = [n1]\n", cycle="1ms")
    image = sample(cpu, held("TL", (press, 5)), 1, lambda c: c.read("LED"))
    outputs = sample(CPU(tags=PANEL, program=TON_NET + "OB1 = [n1]\n", cycle="1ms"), held("TL", (press, 5)), 1, led)
    assert image == [(0.0, False), (0.2, True)]  # the scan starting 100 ms after the press sets it
    assert outputs == [(0.0, False), (0.201, True)]  # and the module gets it at that scan's end
    for changes in (image, outputs):
        assert changes[-1][0] - press == pytest.approx(0.100, abs=0.002)


# --------------------------------------------------------------------------------------------
# 4.3.22: -|P|- TL (SB1) -> ADD D.CISLO
# --------------------------------------------------------------------------------------------

P_4_3_22 = """
SB1 = Tag("%M0.0")
D = DB(CISLO=Int())
def n1(t):
    if P(t.TL, "SB1"):
        t.D.CISLO += 1
OB30 = CyclicInterrupt(n1, period="1s")
"""


def cislo(cpu: CPU) -> int:
    return cpu.read("D.CISLO")


@pytest.mark.parametrize(
    ("presses", "seen", "expected"),
    [
        # TL at the calls 0..5 s: case a 0 0 0 1 1 0, case b 1 1 1 1 1 0 (textbook table)
        pytest.param([(0.1, 0.6), (2.5, 4.5)], [0, 0, 0, 1, 1, 0], [(0.0, 0), (3.0, 1)], id="case-a-edge-at-3s"),
        pytest.param([(0, 4.5)], [1, 1, 1, 1, 1, 0], [(0.0, 1)], id="case-b-edge-at-0s"),
    ],
)
def test_4_3_22_one_increment(presses, seen, expected):
    changes, _cpu = run(P_4_3_22, held("TL", *presses), 5.5, read=cislo)
    assert changes == expected
    # the table row: what each call saw (SB1 holds TL as sampled by the last call)
    cpu2 = CPU(tags=PANEL, program=P_4_3_22)
    sb1 = sample(cpu2, held("TL", *presses), 5.5, lambda c: c.read("SB1"))
    seen_at_calls = [int(dict_at(sb1, k)) for k in range(6)]
    assert seen_at_calls == seen


def dict_at(changes, when):
    """The sampled value at ``when`` seconds from a list of changes."""
    value = None
    for t, v in changes:
        if t <= when:
            value = v
    return value


@pytest.mark.parametrize(
    ("retentive_markers", "expected"),
    [
        pytest.param(0, [(0.0, 1)], id="SB1-cleared-at-STOP-RUN-edge-at-0s"),
        pytest.param(1, [(0.0, 0)], id="SB1-retentive-and-TRUE-no-increment"),
    ],
)
def test_4_3_22_case_b_depends_on_sb1_being_cleared(retentive_markers, expected):
    cpu = CPU(tags=PANEL, program=P_4_3_22, retentive_markers=retentive_markers, start=False)
    cpu.write("SB1", True)  # TRUE before the start (e.g. from the last run)
    cpu.start()
    assert cpu.read("SB1") is (retentive_markers == 1)
    assert sample(cpu, held("TL", (0, 4.5)), 5.5, cislo) == expected


def test_4_3_22_retentive_sb1_survives_a_real_stop_run():
    cpu = CPU(tags=PANEL, program=P_4_3_22, retentive_markers=1)
    assert sample(cpu, held("TL", (0, 9)), 2.5, cislo) == [(0.0, 1)]
    cpu.stop()
    cpu.start()  # D is not retentive: CISLO back to 0; SB1 (MB0) is: no edge with TL still TRUE
    assert (cpu.read("SB1"), cpu.read("D.CISLO")) == (True, 0)
    cpu.run("3s")
    assert cpu.read("D.CISLO") == 0


# --------------------------------------------------------------------------------------------
# Pre-emption between networks
# --------------------------------------------------------------------------------------------

PREEMPT = """
X = Tag("%M20.0")
A = Tag("%M20.1")
B = Tag("%M20.2")
def irq(t):
    t.X = not t.X
NETWORKS
OB30 = CyclicInterrupt(irq, period="10ms", phase="PHASE")
"""
MULTI = "def n1(t):\n    t.A = t.X\ndef n2(t):\n    t.B = t.X\nOB1 = [n1, n2]\n"
SINGLE = "def n1(t):\n    t.A = t.X\n    t.B = t.X\nOB1 = [n1]\n"


@pytest.mark.parametrize(
    ("networks", "phase", "torn_scans"),
    [
        pytest.param(MULTI, "500us", 10, id="two-networks-due-between-them"),
        pytest.param(MULTI, "0ms", 0, id="two-networks-due-at-a-scan-boundary"),
        pytest.param(SINGLE, "500us", 0, id="one-network-is-atomic"),
    ],
)
def test_ob30_preempts_between_networks(networks, phase, torn_scans):
    cpu = CPU(tags=PANEL, program=PREEMPT.replace("NETWORKS", networks).replace("PHASE", phase), cycle="1ms")
    torn: list[tuple[int, int]] = []

    def hook(c):
        if c.read("A") != c.read("B"):
            torn.append((c.scan_start_ns, c.scan_end_ns))

    cpu.on_scan_end = hook
    cpu.run("100ms")
    assert len(torn) == torn_scans
    if torn_scans:
        # the scan that starts at 0 is interrupted at 0.5 ms and ends 1 ms (the OB30 run time) later
        assert torn[0] == (0, 2_000_000)
        assert torn[1] == (10_000_000, 12_000_000)


def test_ob30_calls_run_at_exact_multiples_of_the_period_under_a_busy_ob1():
    program = """
CALLS = Int(0)
def irq(t):
    t.CALLS += 1
def busy(t):
    t.LED = not t.LED
OB1 = [busy]
OB30 = CyclicInterrupt(irq, period="1s")
"""
    cpu = CPU(tags=PANEL, program=program, cycle="7ms")
    calls = sample(cpu, [], 5.5, lambda c: c.read("CALLS"))
    assert calls == [(0.0, 1), (1.0, 2), (2.0, 3), (3.0, 4), (4.0, 5), (5.0, 6)]
