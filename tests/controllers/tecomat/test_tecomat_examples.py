"""Golden tests: every example of the Tecomat manual (spec/tecomat.md §7, next-phase.md §b.7) run from
its ``.il`` file in ``examples/tecomat/``, asserting the behaviour the manual states or implies: truth
tables, stack contents, register values, pulse timings."""

from __future__ import annotations

import datetime as dt
import itertools
from pathlib import Path

import pytest

from plcsim.controllers.tecomat import linker
from plcsim.controllers.tecomat.assembler import assemble
from plcsim.controllers.tecomat.cpu import TecomatCPU, load_file

EXAMPLES = Path(__file__).resolve().parents[3] / "examples" / "tecomat"


@pytest.fixture(autouse=True, params=["fused", "closures"])
def linking(request, monkeypatch):
    """Every test runs on the fast path (fused runs) and on the plain closures: the same behaviour."""
    if request.param == "closures":
        monkeypatch.setattr(linker, "fuse", lambda m, code, cycle=None: code)
    return request.param


def cpu_of(name: str, **options) -> TecomatCPU:
    return load_file(EXAMPLES / name, **options)


def bits(cpu: TecomatCPU, **levels: int) -> None:
    for address, level in levels.items():
        cpu.set_input(address.replace("_", "."), level)


def test_every_example_file_assembles():
    files = sorted(EXAMPLES.glob("*.il"))
    assert len(files) >= 34
    for path in files:
        assemble(path.read_text(encoding="utf-8"), str(path))


# -- syntax and data movement ----------------------------------------------------------------------


def test_sx1_sx3_operand_widths():
    cpu = TecomatCPU("LD X0.5\nWR Y0\nLD SW0\nLDC R0.0\nLD X0\n", filename="sx.il")
    cpu.set_input("X0", 0b0010_0000)
    cpu.scan()
    # LD X0 -> A0 = X0 with A0H = 0; LDC R0.0 (R0.0 = 0) -> FFFFH; LD SW0 -> S0 low, S1 high; LD X0.5 -> mask
    assert cpu.stack[:4] == [0x20, 0xFFFF, cpu.peek("SW0"), 0xFFFF]
    assert cpu.peek("Y0") == 0xFF  # WR Y0 wrote A0L of the mask


@pytest.mark.parametrize(
    "text, value",
    [("45", 45), ("# 2# 1011", 11), ("%1011", 11), ("#16# AF", 175), ("$AF", 175), ("# 60# 15.28.35", 55715)],
)
def test_sx2_immediates(text, value):
    cpu = TecomatCPU(f"LD {text}\n")
    cpu.scan()
    assert cpu.stack[0] == value


def test_ex02_ld_pushes():
    cpu = cpu_of("ex02_ld_pushes.il")
    cpu.set_clock(dt.datetime(2024, 7, 1, 9, 0, 0))
    cpu.set_input("X0.0", 1)
    cpu.write("R10", 0x40)  # G2: the prose says 100H, the result the manual prints is 40H
    cpu.scan()
    assert cpu.stack[:3] == [0x0701, 0x0040, 0xFFFF]


def test_ex03_wr_and_wrc_stepwise():
    cpu = cpu_of("ex03_wr_wrc.il")
    cpu.scan()
    assert cpu.peek("Y0.0") == 0 and cpu.peek("R1") == 0x8A
    assert (cpu.peek("R4"), cpu.peek("R5"), cpu.peek("RW4")) == (0x8A, 0x60, 0x608A)
    assert cpu.stack[0] == 0x9F75 and cpu.stack[1] == 0  # the stack is unchanged throughout
    for stop, expected in ((2, ("Y0.0", 1)), (4, ("R1", 0x75)), (6, ("RW4", 0x9F75))):
        lines = (EXAMPLES / "ex03_wr_wrc.il").read_text(encoding="utf-8").splitlines()[1 : 1 + stop]
        step = TecomatCPU("\n".join(lines))
        step.scan()
        assert step.peek(expected[0]) == expected[1]


# -- logic ------------------------------------------------------------------------------------------


def test_ex04_truth_table():
    cpu = cpu_of("ex04_and_andc.il")
    for a, b, c in itertools.product((0, 1), repeat=3):
        bits(cpu, X0_0=a, X0_1=b, X0_2=c)
        cpu.scan()
        assert cpu.peek("Y0.0") == (a and b and not c)


def test_ex05_byte_masking_by_one_bit():
    cpu = cpu_of("ex05_byte_mask.il")
    for x0 in (0x00, 0x5A, 0xFF):
        for button in (0, 1):
            cpu.set_input("X0", x0)
            cpu.set_input("X1.0", button)
            cpu.scan()
            assert cpu.peek("Y0") == (0 if button else x0)


def test_ex06_parenthesised_expression_over_16_rows():
    cpu = cpu_of("ex06_parentheses.il")
    for a, b, c, d in itertools.product((0, 1), repeat=4):
        bits(cpu, X0_0=a, X0_1=b, X0_2=c, X0_3=d)
        cpu.scan()
        assert cpu.peek("Y1.2") == ((a or b) and (c or d))
        assert cpu.stack[1] == 0  # the level went 1 -> 2 -> 1


@pytest.mark.parametrize("name", ["ex07_low_nibble.il", "ex07b_low_nibble_binary.il"])
def test_ex07_low_nibble(name):
    cpu = cpu_of(name)
    cpu.write("Y0", 0xFF)
    cpu.write("R10", 0xA7)
    cpu.scan()
    assert cpu.peek("Y0") == 0x07


@pytest.mark.parametrize("name", ["ex08_from_rw0.il", "ex08b_ns940.il"])
def test_ex08_from_the_register_pair(name):
    cpu = cpu_of(name)
    cpu.write("RW0", 0x12A7)
    cpu.scan()
    assert (cpu.peek("R0"), cpu.peek("R1"), cpu.peek("Y0")) == (0xA7, 0x12, 0x07)
    assert cpu.stack[1] == 0


@pytest.mark.parametrize("name", ["ex01_start_stop.il", "ex09_set_res.il"])
def test_ex01_ex09_start_stop_is_stop_dominant(name):
    cpu = cpu_of(name)
    out = cpu.output_names[0]

    def step(start, stop):
        cpu.set_input("START", start)
        cpu.set_input("STOP", stop)
        cpu.scan()
        return cpu.outputs[out]

    assert step(0, 0) is False
    assert step(1, 0) is True and step(0, 0) is True  # latched
    assert step(0, 1) is False and step(0, 0) is False
    assert step(1, 0) is True and step(1, 1) is False  # both pressed -> off


def test_ex10_byte_res_by_mask():
    cpu = cpu_of("ex10_byte_res.il")
    cpu.write("R2", 0xFF)
    cpu.set_input("X0", 0xF0)
    cpu.scan()
    assert cpu.peek("R2") == 0xF0


@pytest.mark.parametrize("name, edge", [("ex11_rising_edge.il", (0, 1)), ("ex12_falling_edge.il", (1, 0))])
def test_ex11_ex12_clear_rw0_on_an_edge(name, edge):
    cpu = cpu_of(name)
    before, after = edge
    cpu.set_input("X0.0", before)
    cpu.scan(2)
    cpu.write("RW0", 0x1234)
    cpu.scan()
    assert cpu.peek("RW0") == 0x1234  # no edge, no clearing
    cpu.set_input("X0.0", after)
    cpu.scan()
    assert cpu.peek("RW0") == 0 and cpu.stack[0] == 0xFFFF
    cpu.write("RW0", 0x1234)
    cpu.scan(3)
    assert cpu.peek("RW0") == 0x1234  # a new value survives while the input stays
    assert cpu.peek("R5.0") == (after if name.startswith("ex11") else 1 - after)


@pytest.mark.parametrize("name", ["ex13_compare.il", "ex13b_compare_stack.il"])
def test_ex13_unsigned_less_than(name):
    cpu = cpu_of(name)
    for rw0, xw0, expected in ((5, 6, 1), (6, 6, 0), (7, 6, 0), (0x8000, 1, 0), (1, 0x8000, 1)):
        cpu.write("RW0", rw0)
        cpu.set_input("XW0", xw0)
        cpu.scan()
        assert cpu.peek("Y0.0") == expected
        s0 = cpu.peek("S0")
        assert (s0 & 1, s0 >> 1 & 1, s0 >> 2 & 1) == (rw0 == xw0, rw0 < xw0, rw0 <= xw0)
    cpu.set_input("X0", 0x34)
    cpu.set_input("X1", 0x12)
    cpu.write("RW0", 0x1233)
    cpu.scan()
    assert cpu.peek("Y0.0") == 1  # XW0 = X0 + 256 * X1


@pytest.mark.parametrize("x0, s1, majority", [(0x1F, 0x45, 1), (0x0F, 0x44, 0), (0xFF, 0x58, 1), (0x00, 0x00, 0)])
def test_ex14_majority_with_flg(x0, s1, majority):
    cpu = cpu_of("ex14_majority_flg.il")
    cpu.set_input("X0", x0)
    cpu.scan()
    assert cpu.peek("S1") == s1 and cpu.peek("Y0.0") == majority


# -- counters ---------------------------------------------------------------------------------------


def pulse(cpu: TecomatCPU, name: str, times: int = 1) -> None:
    for _ in range(times):
        cpu.set_input(name, 1)
        cpu.scan()
        cpu.set_input(name, 0)
        cpu.scan()


def test_ex15_counts_rising_edges_and_resets():
    cpu = cpu_of("ex15_counter.il")
    pulse(cpu, "snimac")
    assert cpu.peek("citac") == 0  # H7: a block starts with its edge memory set; an input on at once is no edge
    pulse(cpu, "snimac", 7)
    assert cpu.peek("citac") == 7
    cpu.set_input("snimac", 1)
    cpu.scan(5)  # a held sensor is one product
    assert cpu.peek("citac") == 8
    cpu.set_input("nuluj", 1)
    pulse(cpu, "snimac", 3)
    assert cpu.peek("citac") == 0  # held at 0 while reset
    cpu.set_input("nuluj", 0)
    pulse(cpu, "snimac", 2)
    assert cpu.peek("citac") == 2


def test_ex16_decade_counter_never_shows_10():
    cpu = cpu_of("ex16_decade_counter.il")
    cpu.scan()
    seen = []
    for _ in range(23):
        pulse(cpu, "snimac")
        seen.append(cpu.peek("citac"))
    assert seen == [n % 10 for n in range(1, 24)]


def test_ex17a_up_down_and_the_spurious_step():
    cpu = cpu_of("ex17a_up_down.il")
    cpu.scan()
    cpu.set_input("volba", 1)
    pulse(cpu, "snimac", 5)
    assert cpu.peek("vystupy") == 5
    cpu.set_input("volba", 0)
    cpu.scan()
    pulse(cpu, "snimac", 2)
    assert cpu.peek("vystupy") == 3
    cpu.set_input("snimac", 1)
    cpu.scan()  # counts down once: 2
    cpu.set_input("volba", 1)
    cpu.scan()  # snimac still on: UP rises -> a spurious step
    assert cpu.peek("vystupy") == 3
    cpu.set_input("nuluj", 1)
    cpu.scan()
    assert cpu.peek("vystupy") == 0


def test_ex17b_no_spurious_step_and_the_next_edge_counts():
    cpu = cpu_of("ex17b_up_down_immune.il")
    cpu.scan()
    cpu.set_input("volba", 1)
    pulse(cpu, "snimac", 4)
    assert cpu.peek("vystupy") == 4
    cpu.set_input("snimac", 1)
    cpu.scan()
    assert cpu.peek("vystupy") == 5
    cpu.set_input("volba", 0)
    cpu.scan(3)  # volba changes while snimac is on: no step
    assert cpu.peek("vystupy") == 5
    cpu.set_input("snimac", 0)
    cpu.scan()
    pulse(cpu, "snimac")  # the next rising edge clears hrana_volba and counts down
    assert cpu.peek("vystupy") == 4
    # the deepest listing of the manual: six levels in use after CNT (VAL, RESET, DOWNC, UPC and two edges)
    assert cpu.stack[0] == 4 and cpu.stack[6:] == [0, 0]


# -- timers -----------------------------------------------------------------------------------------


def run_with(cpu: TecomatCPU, changes: list[tuple[int, str, int]], until_ms: int, watch: str) -> list[tuple[int, int]]:
    """Drive inputs at times (ms), run 1 ms cycles to ``until_ms``; return (ms, value) whenever ``watch`` changed."""
    seen, last = [], None
    changes = sorted(changes)
    for ms in range(until_ms):
        while changes and changes[0][0] == ms:
            _, name, value = changes.pop(0)
            cpu.set_input(name, value)
        cpu.run_until((ms + 1) * 1_000_000)
        value = cpu.peek(watch)
        if value != last:
            seen.append((ms, value))
            last = value
    return seen


def test_ex18_pulse_filter_suppresses_200ms_and_delays_1s_by_250ms():
    cpu = cpu_of("ex18_pulse_filter.il")
    seen = run_with(
        cpu, [(100, "signal", 1), (300, "signal", 0), (1000, "signal", 1), (2000, "signal", 0)], 2500, "vystup"
    )
    # the cycle at t reads the input set at t; Y changes in the cycle at 1250 (250 ms after), falls with the input
    assert seen == [(0, 0), (1250, 1), (2000, 0)]


def test_ex18_a_timer_skipped_by_a_jump_does_not_advance():
    text = (
        (EXAMPLES / "ex18_pulse_filter.il")
        .read_text(encoding="utf-8")
        .replace("    ld      signal\n", "    ld      x0.1\n    jmd     skip\n    ld      signal\n")
        .replace("    wr      vystup\n", "    wr      vystup\nskip:\n")
    )
    cpu = TecomatCPU(text)
    seen = run_with(cpu, [(0, "signal", 1), (100, "X0.1", 1), (400, "X0.1", 0)], 1000, "vystup")
    # 100 ms timed, 300 ms skipped (time stops), then 150 ms more: on at 400 + 150 (one cycle lost at resuming)
    assert seen == [(0, 0), (551, 1)]


def test_ex19_feed_slide_waits_5s_at_k5():
    cpu = cpu_of("ex19_feed_slide.il", cycle="10ms")
    cpu.set_input("k1", 1)
    cpu.set_input("start1", 1)
    cpu.set_input("start2", 1)
    cpu.run("50ms")
    assert cpu.outputs["em1"] and not cpu.outputs["em2"]
    for name in ("start1", "start2", "k1"):
        cpu.set_input(name, 0)
    cpu.run("1s")
    cpu.set_input("k5", 1)
    cpu.run("100ms")
    assert not cpu.outputs["em1"]
    cpu.run("4.8s")
    assert not cpu.outputs["em2"]
    cpu.run("200ms")
    assert cpu.outputs["em2"]
    cpu.set_input("k5", 0)
    cpu.run("1s")
    assert cpu.outputs["em2"]  # latched after leaving K5
    cpu.set_input("k1", 1)
    cpu.run("20ms")
    assert not cpu.outputs["em2"]


def test_ex20_run_time_over_one_hour_in_simulated_time():
    cpu = cpu_of("ex20_run_time.il", cycle="100ms")
    cpu.write("motor", 1)  # the harness drives the motor output; nothing else in the program writes it
    cpu.run("1800s")
    cpu.write("motor", 0)
    cpu.run("600s")
    # the last turnaround that saw the motor on was at 1799.9 s: 1799 whole seconds, 0.9 s kept
    assert not cpu.outputs["signalizace"] and cpu.peek("casovac") == 1799
    cpu.write("motor", 1)
    cpu.run("1799.5s")
    assert not cpu.outputs["signalizace"]
    cpu.run("1s")
    assert cpu.outputs["signalizace"] and cpu.peek("casovac") == 3600
    cpu.set_input("nuluj", 1)
    cpu.run("200ms")
    assert not cpu.outputs["signalizace"] and cpu.peek("casovac") == 0


# -- control flow -----------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["ex21a_weekday_jump.il", "ex21b_weekday_call.il"])
def test_ex21_working_days_run_section_a(name):
    cpu = cpu_of(name)
    for day in range(1, 8):
        cpu.set_clock(dt.datetime(2024, 7, day, 12, 0))  # 1 July 2024 is a Monday
        cpu.scan()
        assert cpu.peek("S9") == day
        assert (cpu.outputs["v_sekci_A"], cpu.outputs["v_sekci_B"]) == ((True, False) if day <= 5 else (False, True))


def test_ex21_the_subroutine_version_s_hazard_runs_both_sections():
    cpu = cpu_of("ex21c_weekday_call_hazard.il")
    cpu.set_clock(dt.datetime(2024, 7, 6, 12, 0))  # Saturday
    cpu.scan()
    assert cpu.outputs["v_sekci_B"] and cpu.outputs["v_sekci_A"]


def test_ex22_four_modes_by_indirect_call():
    cpu = cpu_of("ex22_modes_cai.il")
    for b, a in itertools.product((0, 1), repeat=2):
        cpu.set_input("a", a)
        cpu.set_input("b", b)
        cpu.scan()
        assert cpu.outputs["rezim"] == 1 << (2 * b + a)


def test_t1_t3_table_layouts():
    tables = assemble((EXAMPLES / "tables_layout.il").read_text(encoding="utf-8")).tables
    bit, byte, word = tables["logik_bit"], tables["cisla_byte"], tables["data_word"]
    assert bit.layout() == bytes([0x09, 0x16]) and bit.limit == 12
    assert byte.layout() == bytes([22, 45, 240, 10, 100])
    # G12: the manual prints 00 FF for $FF; little-endian, as every other entry, gives FF 00
    assert word.layout() == bytes.fromhex("A7560F25AAB9FF00")


def test_ex23_majority_by_table():
    cpu = cpu_of("ex23_truth_table.il")
    for a, b, c in itertools.product((0, 1), repeat=3):
        cpu.set_input("a", a)
        cpu.set_input("b", b)
        cpu.set_input("c", c)
        cpu.scan()
        assert cpu.outputs["z"] == (a + b + c >= 2)
        assert cpu.stack[1:3] == [4 * a + 2 * b + c, 7]  # A1 = index, A2 = limit


def test_ex24_decoder():
    cpu = cpu_of("ex24_decoder.il")
    for n in range(8):
        cpu.set_input("X0", n)
        cpu.scan()
        assert cpu.peek("Y0") == 1 << n
    assert cpu.peek("S1.0") == 1


def test_ex25_membership_by_ftb():
    cpu = cpu_of("ex25_membership.il")
    for r10 in range(256):
        cpu.write("R7", 0x5A)
        cpu.write("R10", r10)
        cpu.scan()
        assert cpu.peek("R7") == (0x5A if r10 in (3, 15, 30, 65, 137, 240) else 0)


@pytest.mark.parametrize(
    "name, cases",
    [
        ("ex26_branch_ordered.il", {2: 10, 10: 11, 40: 12, 0: 13, 3: 13, 255: 13}),
        ("ex27_branch_table.il", {2: 20, 20: 8, 35: 25, 100: 8, 0: 50, 7: 50}),
    ],
)
def test_ex26_ex27_branching_by_value(name, cases):
    cpu = cpu_of(name)
    for r7, label in cases.items():
        cpu.write("R7", r7)
        cpu.scan()
        assert cpu.peek("Y0") == label


ON = ["08:00", "08:50", "09:45", "10:50", "11:40", "14:10", "15:05"]
OFF_TASK = ["08:45", "09:35", "10:30", "11:35", "12:25", "14:55", "15:50"]
OFF_PRINTED = ["08:45", "09:35", "10:29", "11:19", "12:25", "14:55", "15:50"]


@pytest.mark.parametrize(
    "name, offs",
    [("ex28_time_switch_corrected.il", OFF_TASK), ("ex28_time_switch_printed.il", OFF_PRINTED)],
)
def test_ex28_time_switch_over_a_day(name, offs):
    cpu = cpu_of(name, cycle="20s", rtc_start="2024-07-01-07:00:00")
    changes, last = [], False
    for _ in range(10 * 180):  # 07:00 .. 17:00 in 20 s cycles
        cpu.scan()
        if cpu.peek("Y0.0") != last:
            last = not last
            moment = cpu.local_time() - dt.timedelta(seconds=20)
            changes.append(moment.strftime("%H:%M"))
    assert changes == [t for pair in zip(ON, offs) for t in pair]
