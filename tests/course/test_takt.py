"""Golden tests: exercise 4.3.11 "Takt 1s", the four solutions (spec §4.5.1, exercises.md §2 4.3.11).

Timing rules these tests pin:

* Clock memory is latched at the start of each scan; Clock_1Hz (%M0.5 with clock byte MB0) is FALSE
  in [0, 0.5) s and TRUE in [0.5, 1) s, so solution 1's edge comes every 1.000 s exactly, at x.5 s.
* A TON reset by RT in its expiry scan restarts in the next scan: solution 2 pulses every PT + 1 scan.
* Solution 3 feeds ``NOT Takt1s`` back to IN: the scan after the pulse resets the timer again, so its
  period is PT + 2 scans ("up to 10 %" longer at a 100 ms cycle).
* Solution 4 reads the instance's Q before the box runs. Under the ``s7_1200`` dialect the read
  refreshes the instance, IN becomes FALSE in the expiry scan and Takt1s is never TRUE; under ``iec``
  the read sees the old Q and the solution pulses like solution 2.
* Takt1s is TRUE for exactly one scan per period.
"""

from __future__ import annotations

import itertools

import pytest

from plcsim import CPU, Tag

SOLUTIONS = {
    1: """
AUX = Tag("%M10.3")
def OB1(t):
    t.Takt1s = P(t.Clock_1Hz, "AUX")
""",
    2: """
TON_T = IEC_TIMER()
def OB1(t):
    q = t.TON_T.TON(IN=t.AlwaysTRUE, PT="1s")
    t.Takt1s = q
    if q:
        RT(t.TON_T)
""",
    3: """
TON_T = IEC_TIMER()
def OB1(t):
    q = t.TON_T.TON(IN=not t.Takt1s, PT="1s")
    t.Takt1s = q
    if q:
        RT(t.TON_T)
""",
    4: """
TON_T = IEC_TIMER()
def OB1(t):
    q = t.TON_T.TON(IN=not t.TON_T.Q, PT="1s")
    t.Takt1s = q
    if q:
        RT(t.TON_T)
""",
}

COUNTER = """
C = IEC_COUNTER()
def count(t):
    t.C.CTU(CU=t.Takt1s, PV=1000)
"""


def run_takt(solution: int, cycle: str, dialect: str = "s7_1200", duration: str = "10s", extra: str = ""):
    """Run a solution and return (pulse start times in ns, pulse lengths in scans, the CPU)."""
    program = SOLUTIONS[solution] + extra
    cpu = CPU(
        tags={"Takt1s": Tag("%M10.2")},
        program=program,
        cycle=cycle,
        clock_memory_byte=0,
        system_memory_byte=1,
        timer_dialect=dialect,
    )
    rises: list[int] = []
    runs: list[int] = []
    prev = [False]

    def hook(c):
        v = c.t.Takt1s
        if v:
            if prev[0]:
                runs[-1] += 1
            else:
                rises.append(c.scan_start_ns)
                runs.append(1)
        prev[0] = v

    cpu.on_scan_end = hook
    cpu.run(duration)
    assert cpu.mode == "RUN"
    return rises, runs, cpu


def periods_ms(rises: list[int]) -> list[float]:
    return [(b - a) / 1e6 for a, b in itertools.pairwise(rises)]


@pytest.mark.parametrize("cycle", ["1ms", "100ms"])
@pytest.mark.parametrize("dialect", ["s7_1200", "iec"])
def test_solution_1_clock_edge_exactly_every_second(cycle, dialect):
    rises, runs, _ = run_takt(1, cycle, dialect)
    assert [r / 1e9 for r in rises] == [k + 0.5 for k in range(10)]
    assert set(periods_ms(rises)) == {1000.0}
    assert set(runs) == {1}


@pytest.mark.parametrize(("cycle", "period_ms"), [("1ms", 1001.0), ("10ms", 1010.0), ("100ms", 1100.0)])
@pytest.mark.parametrize("dialect", ["s7_1200", "iec"])
def test_solution_2_period_is_pt_plus_one_scan(cycle, period_ms, dialect):
    rises, runs, _ = run_takt(2, cycle, dialect)
    assert rises[0] == 1_000_000_000  # first expiry exactly PT after STOP->RUN
    assert set(periods_ms(rises)) == {period_ms}
    assert set(runs) == {1}


@pytest.mark.parametrize(("cycle", "period_ms"), [("1ms", 1002.0), ("10ms", 1020.0), ("100ms", 1200.0)])
@pytest.mark.parametrize("dialect", ["s7_1200", "iec"])
def test_solution_3_period_is_pt_plus_two_scans(cycle, period_ms, dialect):
    rises, runs, _ = run_takt(3, cycle, dialect)
    assert set(periods_ms(rises)) == {period_ms}
    assert set(runs) == {1}


def test_solution_3_at_100ms_is_9_to_10_percent_slower_than_solution_2():
    p2 = periods_ms(run_takt(2, "100ms")[0])[0]
    p3 = periods_ms(run_takt(3, "100ms")[0])[0]
    assert (p2, p3) == (1100.0, 1200.0)
    assert 0.09 <= p3 / p2 - 1 <= 0.10
    assert p3 / 1000.0 - 1 == pytest.approx(0.20)  # against the wanted 1 s


@pytest.mark.parametrize("cycle", ["1ms", "100ms"])
def test_solution_4_never_pulses_on_an_s7_1200(cycle):
    rises, _, cpu = run_takt(4, cycle, "s7_1200")
    assert rises == []
    # the timer silently restarts every period: it is timing right now, never expired
    assert cpu.read("TON_T.Q") is False
    assert cpu.read("TON_T.IN") is True


@pytest.mark.parametrize(("cycle", "period_ms"), [("1ms", 1001.0), ("100ms", 1100.0)])
def test_solution_4_pulses_under_the_iec_dialect(cycle, period_ms):
    rises, runs, _ = run_takt(4, cycle, "iec")
    assert len(rises) == 9
    assert set(periods_ms(rises)) == {period_ms}
    assert set(runs) == {1}


@pytest.mark.parametrize(("solution", "expected"), [(1, 60), (2, 59)])
def test_counter_on_takt1s_counts_60_in_60s(solution, expected):
    _, _, cpu = run_takt(solution, "1ms", duration="60s", extra=COUNTER + "OB1 = [OB1, count]\n")
    count = cpu.read("C.CV")
    assert count == expected  # pulses at 0.5 .. 59.5 s; at 1.000 + k * 1.001 s
    assert abs(count - 60) <= 1
