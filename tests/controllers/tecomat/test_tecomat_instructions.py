"""The Tecomat instructions no example of the manual exercises, written from its prose (spec/tecomat.md §6),
the process model (§5), the S registers (§3.5), restarts, and the assembler's errors."""

from __future__ import annotations

import pytest

from plcsim.controllers.choice import controller_for
from plcsim.controllers.tecomat import linker
from plcsim.controllers.tecomat.assembler import assemble
from plcsim.controllers.tecomat.assembly import AssemblyError
from plcsim.controllers.tecomat.cpu import TecomatCPU
from plcsim.controllers.tecomat.mnemonics import DEFINED, NAMED_ONLY
from plcsim.core.errors import ConfigurationError
from plcsim.frontends.il import program_text
from plcsim.tags.table import Tag
from plcsim.tags.types import DWord


@pytest.fixture(autouse=True, params=["fused", "closures"])
def linking(request, monkeypatch):
    """Every test runs on the fast path (fused runs) and on the plain closures: the same behaviour."""
    if request.param == "closures":
        monkeypatch.setattr(linker, "fuse", lambda m, code, cycle=None: code)
    return request.param


def run(text: str, scans: int = 1, **options) -> TecomatCPU:
    cpu = TecomatCPU(text, **options)
    cpu.scan(scans)
    return cpu


# -- logic, memory, stack -----------------------------------------------------------------------------


def test_negated_and_exclusive_logic_with_an_operand():
    cpu = TecomatCPU(
        "LD $F0F0\nORC R0.0\nWR RW10\nLD $00FF\nXOR R1\nWR RW12\nLD $00FF\nXOC R1\nWR RW14\nLD $1234\nXOR $FFFF\nNEG\n"
    )
    cpu.write("R1", 0x0F)
    cpu.scan()
    assert cpu.peek("RW10") == 0xFFFF  # R0.0 = 0: its negation is all ones
    assert cpu.peek("RW12") == 0x00F0  # byte XOR on A0L, A0H unchanged
    assert cpu.peek("RW14") == 0x000F  # XOC: with the negated byte
    assert cpu.stack[0] == 0x1234  # XOR with FFFFH then NEG gives the value back


def test_no_operand_xor_pops_and_eq_without_an_operand_keeps_a1():
    cpu = run("LD $0F0F\nLD $00FF\nXOR\nLD 7\nLD 7\nEQ\n")
    assert cpu.stack[:3] == [0xFFFF, 7, 0x0FF0]
    assert cpu.peek("S0") & 0b111 == 0b101  # =, not <, <=


def test_put_writes_only_when_s1_0_is_set():
    cpu = run("LD 1\nFLG\nLD $AB\nPUT R3\nLD 3\nFLG\nLD $CD\nPUT R4\n")
    assert cpu.peek("R3") == 0xAB  # one 1-bit: N0 = 1
    assert cpu.peek("R4") == 0  # 3 = two 1-bits: N0 = 0


def test_flg_pushes_the_and_of_all_bits_and_sets_s1():
    cpu = run("LD $FFFF\nFLG\n")
    assert cpu.stack[:2] == [0xFFFF, 0xFFFF]
    assert cpu.peek("S1") == 0xF0  # N = 16 (N4 is ANL), ANL, ANH, ORL, ORH


def test_swp_pop_stk():
    cpu = run("LD 1\nLD 0\nLD $1234\nSWP\nLD 9\nPOP 1\nSTK\n")
    assert cpu.stack[:3] == [0b101, 0, 1]  # STK: OR of A0 (3412H), A1 (0), A2 (1)


def test_the_eight_stacks_and_chg_with_flags():
    cpu = run("LD 11\nCHG B\nLD 22\nNXT\nLD 33\nPRV\nPRV\nLD 1\nFLG\nCHG CS\nLD 3\nFLG\nCHG AS\n")
    stacks = cpu.machine.stacks
    assert stacks[0][:3] == [0, 1, 11] and stacks[1][0] == 22 and stacks[2][:3] == [0, 3, 33]
    assert cpu.peek("S1") & 1 == 1  # stack A's saved S1 (N = 1) is back after CHG AS


def test_stack_a_is_cleared_at_every_turnaround_and_b_is_kept_by_default():
    cpu = run("LD 5\nCHG B\nLD 6\n", scans=2)
    assert cpu.machine.stacks[0] == [5, 0, 0, 0, 0, 0, 0, 0]
    assert cpu.machine.stacks[1][:2] == [6, 6]
    cpu = run("LD 5\nCHG B\nLD 6\n", scans=2, clear_all_stacks=True)
    assert cpu.machine.stacks[1][:2] == [6, 0]


def test_a_ninth_push_drops_a7():
    cpu = run("".join(f"LD {n}\n" for n in range(1, 10)))
    assert cpu.stack == [9, 8, 7, 6, 5, 4, 3, 2]


def test_add_with_carry_out_and_without_operand():
    cpu = run("LD $FFFF\nADD 2\n")
    assert cpu.stack[0] == 1 and cpu.peek("S0") & 0b11 == 0b10  # carry out, not zero
    cpu = run("LD 40\nLD 2\nADD\n")
    assert cpu.stack[:2] == [42, 0]


def test_byte_set_and_res_by_mask_and_byte_let():
    cpu = TecomatCPU("LD $0F\nSET R0\nLD $03\nRES R0\nLD X0\nLET R1\n")
    cpu.set_input("X0", 0b0101)
    cpu.scan()
    assert cpu.peek("R0") == 0x0C and cpu.stack[0] == 0b0101
    cpu.set_input("X0", 0b0111)
    cpu.scan()
    assert cpu.stack[0] == 0b0010  # only the bit that rose


# -- long operands (extended set) ------------------------------------------------------------------


def test_ld_rl10_loads_r10_to_r13_into_two_levels_low_word_in_a0():
    """SX-1: ``LD RL10`` loads R10, R11, R12, R13; on the 16-bit stack (G16) as LD RW12 then LD RW10."""
    cpu = TecomatCPU("LD RL10\nLD RW12\nLD RW10\nLDC RL10\n")
    cpu.write("RL10", 0x12345678)
    assert [cpu.peek(f"R{k}") for k in range(10, 14)] == [0x78, 0x56, 0x34, 0x12]
    cpu.scan()
    assert cpu.stack[:6] == [0xA987, 0xEDCB, 0x5678, 0x1234, 0x5678, 0x1234]


def test_wr_and_wrc_of_a_long_write_both_words_little_endian_and_keep_the_stack():
    """EX-03's numbers widened: A0 = 9F75H, A1 = 1234H; ``WR RL4`` gives R4 = 75H, R5 = 9FH, R6 = 34H,
    R7 = 12H, ``WRC RL8`` the complement (R8 = 8AH, R9 = 60H as EX-03's RW4 = 608AH)."""
    cpu = TecomatCPU("LD $1234\nLD #2# 1001 1111 0111 0101\nWR RL4\nWRC RL8\nWR RL13\n")
    cpu.scan()
    assert [cpu.peek(f"R{k}") for k in range(4, 12)] == [0x75, 0x9F, 0x34, 0x12, 0x8A, 0x60, 0xCB, 0xED]
    assert cpu.stack[:3] == [0x9F75, 0x1234, 0]
    assert cpu.peek("RL4") == 0x12349F75 and cpu.peek("RW6") == 0x1234
    assert cpu.peek("RL12") == 0x349F7500  # RL13 overlaps: R13..R16 = 75 9F 34 12, R12 = 0


def test_put_of_a_long_depends_on_s1_0_and_the_word_order_is_a_setting():
    program = "LD $1111\nLD $2222\nLD 1\nFLG\nPOP 1\nPOP 1\nPUT RL0\nLD 3\nFLG\nPOP 1\nPOP 1\nPUT RL4\n"
    cpu = TecomatCPU(program)  # FLG: S1.0 = N0, the parity of the 1-count: 1 for 1, 0 for 3
    cpu.scan()
    assert (cpu.peek("RL0"), cpu.peek("RL4")) == (0x11112222, 0)
    high_first = TecomatCPU("LD RL0\nWR RL4\n", long_low_word_in_a0=False)
    high_first.write("RL0", 0xAAAABBBB)
    high_first.scan()
    assert high_first.stack[:2] == [0xAAAA, 0xBBBB] and high_first.peek("RL4") == 0xAAAABBBB


def test_reg_long_reserves_four_registers_and_a_long_symbol_is_traced_as_a_dword():
    cpu = TecomatCPU("#reg long total\n#reg word w\n#def TOTAL_OUT yl0\nLD RL100\nWR total\nLD total\nWR TOTAL_OUT\n")
    symbols = cpu.program.symbols
    assert (symbols["total"].operand.index, symbols["w"].operand.index) == (0, 4)
    assert str(cpu.table["TOTAL_OUT"].address) == "%QD0" and cpu.table["TOTAL_OUT"].member.type is DWord
    cpu.write("RL100", 0xDEADBEEF)
    cpu.scan()
    assert cpu.t.total == 0xDEADBEEF and cpu.outputs["TOTAL_OUT"] == 0xDEADBEEF


def test_a_double_word_tag_of_the_io_table_is_a_long_symbol():
    cpu = controller_for(program_text("LD RL0\nWR TOTAL\n", "t.il"), {"TOTAL": Tag("%QD4", DWord)})
    cpu.write("RL0", 70_000)
    cpu.scan()
    assert str(cpu.symbols["TOTAL"]) == "YL4" and cpu.outputs["TOTAL"] == 70_000


# -- function blocks ------------------------------------------------------------------------------


def test_ctd_sets_to_the_configured_value_counts_down_and_carries():
    text = "#reg word c\nLD X0.0\nLD X0.1\nCTD c\nWR RW10\n"
    cpu = TecomatCPU(text)
    cpu.scan()
    for level in (1, 0, 1, 0):
        cpu.set_input("X0.0", level)
        cpu.scan()
    assert cpu.peek("c") == 0xFFFE  # 0 -> FFFF (carry) -> FFFE
    cpu.set_input("X0.1", 1)
    cpu.scan()
    assert cpu.peek("c") == 0xFFFF
    cpu = TecomatCPU(text, ctd_set_value=100)
    cpu.set_input("X0.1", 1)
    cpu.scan()
    assert cpu.peek("c") == 100


def test_ctu_carry_to_the_next_cascade_is_a_mask_for_one_execution():
    cpu = TecomatCPU("#reg word c\nLD X0.0\nLD 0\nCTU c\nPOP 2\nWR Y0.0\n")
    cpu.write("c", 0xFFFF)
    cpu.scan()
    cpu.set_input("X0.0", 1)
    cpu.scan()
    assert cpu.peek("c") == 0 and cpu.peek("Y0.0") == 1 and cpu.peek("S0") == 0b111  # zero, carry, either
    cpu.scan()
    assert cpu.peek("Y0.0") == 0


def test_cnt_simultaneous_edges_cancel():
    cpu = TecomatCPU("#reg word c\nLD X0.0\nLD X0.1\nLD 0\nCNT c\n")
    cpu.scan()
    cpu.set_input("X0", 0b11)
    cpu.scan()
    assert cpu.peek("c") == 0
    cpu.set_input("X0", 0b00)
    cpu.scan()
    cpu.set_input("X0", 0b10)
    cpu.scan()
    assert cpu.peek("c") == 0xFFFF and cpu.stack[2] == 0xFFFF  # down through 0: DOWNC


@pytest.mark.parametrize(
    "mnemonic, start, serial, value, out", [("SFL", 0x8001, 1, 0x0003, 0xFFFF), ("SFR", 0x0003, 1, 0x8001, 0xFFFF)]
)
def test_shift_registers(mnemonic, start, serial, value, out):
    cpu = TecomatCPU(f"#reg word s\nLD X0.0\nLD {serial}\n{mnemonic} s\n")
    cpu.write("s", start)
    cpu.scan()
    cpu.set_input("X0.0", 1)
    cpu.scan()
    assert cpu.peek("s") == value and cpu.stack[:2] == [value, out]
    cpu.scan()
    assert cpu.peek("s") == value and cpu.stack[1] == 0  # no edge, no shift


def ms_run(cpu: TecomatCPU, levels: dict[int, int], until: int, watch: str = "Y0.0") -> list[tuple[int, int]]:
    seen, last = [], None
    for ms in range(until):
        if ms in levels:
            cpu.set_input("X0.0", levels[ms])
        cpu.run_until((ms + 1) * 1_000_000)
        value = cpu.peek(watch)
        if value != last:
            seen.append((ms, value))
            last = value
    return seen


def test_tof_stretches_the_falling_edge():
    cpu = TecomatCPU("#reg word t\nLD X0.0\nLD 10\nTOF t.1\nWR Y0.0\n")  # 10 x 100 ms
    assert ms_run(cpu, {100: 1, 300: 0}, 2000) == [(0, 0), (100, 1), (1300, 0)]


def test_imp_makes_a_pulse_of_the_preset_whatever_the_input_does():
    cpu = TecomatCPU("#reg word t\nLD X0.0\nLD 50\nIMP t.0\nWR Y0.0\n")  # 50 x 10 ms
    assert ms_run(cpu, {100: 1, 150: 0, 200: 1, 250: 0, 900: 1}, 1500) == [
        (0, 0),
        (100, 1),
        (600, 0),
        (900, 1),
        (1400, 0),
    ]


def test_rto_flags_and_reset():
    cpu = TecomatCPU("#reg word t\nLD X0.0\nLD X0.1\nLD 3\nRTO t.2\nWR Y0.0\n", cycle="100ms")
    cpu.set_input("X0.0", 1)
    cpu.run("3.05s")
    assert cpu.peek("t") == 3 and cpu.peek("Y0.0") == 1 and cpu.peek("S0") & 0b111 == 0b101  # preset = content
    cpu.set_input("X0.0", 0)
    cpu.run("5s")
    assert cpu.peek("t") == 3 and cpu.peek("Y0.0") == 1  # waiting keeps the content and YT
    cpu.set_input("X0.1", 1)
    cpu.run("200ms")
    assert cpu.peek("t") == 0 and cpu.peek("Y0.0") == 0 and cpu.peek("S0") == 0


def test_timer_overflow_flags_and_the_global_tick_setting():
    cpu = TecomatCPU("#reg word t\nLD 1\nLD 0\nLD $FFFF\nRTO t.3\n", cycle="1s")  # base 10 s
    cpu.write("t", 0xFFFE)
    cpu.run("30s")
    assert cpu.peek("t") == 0xFFFF and cpu.peek("S0") & 0b11_0000 == 0b01_0000 and cpu.stack[2] == 0xFFFF
    # per-timer units count from the timer's start; global ones from the time base's ticks
    text = "#reg word t\nLD X0.0\nLD 3\nTON t.2\nWR Y0.0\n"
    for ticks, on_at in (("per_timer", 3500), ("global", 3000)):
        cpu = TecomatCPU(text, cycle="100ms", timer_ticks=ticks)
        cpu.run("500ms")
        cpu.set_input("X0.0", 1)
        while not cpu.peek("Y0.0"):
            cpu.scan()
        assert cpu.scan_start_ns // 1_000_000 == on_at


# -- tables ---------------------------------------------------------------------------------------


def test_ltb_out_of_range_wraps_and_clears_s1_0():
    cpu = TecomatCPU("#table byte t = 10, 20, 30\nLD R0\nLTB t\n")
    cpu.write("R0", 4)
    cpu.scan()
    assert cpu.stack[:3] == [20, 1, 2] and cpu.peek("S1.0") == 0
    cpu = TecomatCPU("#table byte t = 10, 20, 30\nLD R0\nLTB t\n", ltb_reduced_index=False)
    cpu.write("R0", 4)
    cpu.scan()
    assert cpu.stack[:3] == [20, 4, 2]


def test_tables_in_the_scratchpad():
    cpu = TecomatCPU("#reg byte tab[4]\nLD 3\nLD 2\nLTB tab\nLD 3\nLD 77\nFTB tab\n")
    for k, v in enumerate((5, 6, 7, 77)):
        cpu.write(f"R{k}", v)
    cpu.scan()
    assert cpu.stack[:2] == [3, 3]  # FTB found 77 at index 3, A1 = the limit
    assert cpu.stack[2:5] == [7, 2, 3]  # LTB: item 7, index 2, limit 3


def test_wms_then_lms_is_a_circular_lifo():
    cpu = TecomatCPU("#table word t = 0, 0, 0\nLD X0\nWMS t\nLD X0.7\nJMC end\nLMS t\nWR YW0\nend:\n")
    for value in (11, 22):
        cpu.set_input("X0", value)
        cpu.scan()
    assert cpu.machine.tables["t"] == [0, 11, 22] and cpu.peek("RW0") == 2
    cpu.set_input("X0", 0x80 | 5)  # WMS writes 85H at index 0 (wrapped, S1.0 = 0), then LMS reads it back
    cpu.scan()
    assert cpu.machine.tables["t"] == [0x85, 11, 22] and cpu.peek("YW0") == 0x85 and cpu.peek("RW0") == 2


# -- organisational -------------------------------------------------------------------------------


def test_calls_returns_and_conditional_returns():
    text = "LD 0\nCAL sub\nWR Y0.1\nE 0\nP 60\nsub:\nLD 1\nWR Y0.0\nLD X0.0\nRED\nLD 1\nWR Y0.2\nRET\nE 60\n"
    cpu = run("P 0\n" + text)
    assert cpu.peek("Y0") == 0b111  # the call leaves the stack alone: A0 = 1 from the subroutine
    cpu = TecomatCPU("P 0\n" + text)
    cpu.set_input("X0.0", 1)
    cpu.scan()
    assert cpu.peek("Y0") == 0b011  # RED returned with A0 = FFFFH


def test_nesting_is_limited_to_eight():
    nine = "P 0\nCAL s1\nE 0\nP 60\n" + "".join(f"s{k}:\nCAL s{k + 1}\nRET\n" for k in range(1, 9)) + "s9:\nRET\nE 60\n"
    cpu = run(nine)
    assert cpu.mode == "STOP" and "ninth nested subroutine call" in cpu.error.message
    assert cpu.error.line == nine.splitlines().index("CAL s9") + 1
    eight = nine.replace("s8:\nCAL s9\nRET\n", "s8:\nRET\n")
    assert run(eight).mode == "RUN"


def test_ed_ec_eoc_and_jmc():
    cpu = TecomatCPU(
        "P 0\nLD X0.0\nED\nLD 1\nWR Y0.0\nLD X0.1\nJMC over\nEOC\nover:\nE 0\n"
        "P 64\nLD 1\nWR Y0.7\nE 64\nP 1\nLD 1\nWR Y1.0\nE 1\n"
    )
    cpu.scan()
    assert cpu.peek("Y0.0") == 1 and cpu.peek("Y0.7") == 1 and cpu.peek("Y1.0") == 1
    cpu.write("Y0", 0)
    cpu.set_input("X0.0", 1)
    cpu.scan()
    assert cpu.peek("Y0.0") == 0 and cpu.peek("Y0.7") == 1  # ED ended P0; P64 still ran


def test_eoc_ends_the_cycle_but_p64_runs_unless_configured():
    text = "P 0\nEOC\nE 0\nP 3\nLD 1\nWR Y0.3\nE 3\nP 64\nLD 1\nWR Y0.7\nE 64\n"
    cpu = run(text, scans=4)
    assert cpu.peek("Y0.3") == 0 and cpu.peek("Y0.7") == 1
    assert run(text, scans=4, final_after_eoc=False).peek("Y0.7") == 0


def test_p1_to_p4_rotate_one_per_cycle():
    text = "P 0\nLD 0\nWR Y0\nE 0\n" + "".join(f"P {k}\nLD {1 << k}\nWR Y0\nE {k}\n" for k in range(1, 5))
    cpu = TecomatCPU(text)
    seen = []
    for _ in range(8):
        cpu.scan()
        seen.append(cpu.peek("Y0"))
    assert seen == [2, 4, 8, 16] * 2


def test_p5_to_p9_run_by_their_periods():
    text = "P 0\nE 0\nP 5\nLD R0\nADD 1\nWR R0\nE 5\nP 9\nLD R1\nADD 1\nWR R1\nE 9\n"
    cpu = TecomatCPU(text)
    cpu.run("3s")
    # P5 every 10 ms and P9 every 1 s, each first one period after the start: 10..2990 ms, 1 s and 2 s
    assert (cpu.peek("R0"), cpu.peek("R1")) == (299 & 0xFF, 2)


def test_p10_to_p40_by_the_process_mask_in_s24():
    text = "P 0\nLD X0.0\nWR S24.0\nLD X0.1\nWR S27.6\nE 0\nP 10\nLD 1\nWR Y0.0\nE 10\nP 40\nLD 1\nWR Y0.1\nE 40\n"
    cpu = TecomatCPU(text)
    cpu.scan(2)
    assert cpu.peek("Y0") == 0
    cpu.set_input("X0", 0b11)
    cpu.scan()
    assert cpu.peek("Y0") == 0  # the plan is made at the turnaround: the mask set in this cycle acts in the next
    cpu.scan()
    assert cpu.peek("Y0") == 0b11


def test_p41_to_p48_run_when_their_source_is_raised_and_enabled():
    cpu = TecomatCPU("P 0\nLD X0.0\nWR S29.2\nE 0\nP 43\nLD R0\nADD 1\nWR R0\nE 43\n")
    cpu.scan()
    cpu.raise_event(3)
    cpu.scan(2)
    assert cpu.peek("R0") == 0  # disabled: ignored
    cpu.set_input("X0.0", 1)
    cpu.scan()
    cpu.raise_event(3)
    cpu.scan(2)
    assert cpu.peek("R0") == 1


def test_breakpoints_call_p50_to_p57_and_return():
    cpu = run("P 0\nLD 1\nBP 2\nWR Y0.0\nBP 3\nE 0\nP 52\nLD 1\nWR Y0.1\nLD 0\nE 52\n")
    # the handler ran (Y0.1 written) and the program goes on with its stack and flags as before the BP
    assert cpu.peek("Y0.1") == 1 and cpu.peek("Y0.0") == 1 and cpu.stack[0] == 1


def test_cold_and_warm_restart_processes_flags_and_retentive_r():
    text = "P 0\nLD S2\nWR R20\nLD R21\nADD 1\nWR R21\nE 0\nP 63\nLD 1\nWR R10\nE 63\nP 62\nLD 1\nWR R11\nE 62\n"
    cpu = TecomatCPU(text, retentive_r=(20, 22))
    cpu.scan(3)
    assert (cpu.peek("R10"), cpu.peek("R11"), cpu.peek("R21")) == (1, 0, 3)
    assert cpu.peek("R20") == 0b0010_0101  # SP, RUN, ON; RST only in the first cycle
    cpu.stop()
    cpu.start("warm")
    cpu.scan()
    assert (cpu.peek("R10"), cpu.peek("R11"), cpu.peek("R21")) == (0, 1, 4)  # R21 kept (retentive), R10 cleared
    assert cpu.peek("R20") == 0b0010_1101  # HOT: the first cycle after a warm restart
    cpu.power_cycle()
    cpu.scan()
    assert cpu.peek("R21") == 5
    cpu.stop()
    cpu.start("cold")
    cpu.scan()
    assert cpu.peek("R21") == 1 and cpu.peek("R20") == 0b0011_0101


def test_clock_bits_and_unit_counters():
    cpu = TecomatCPU("P 0\nE 0\n", cycle="50ms")
    cpu.run("1.3s")
    assert cpu.peek("SW14") == 12 and cpu.peek("SW16") == 1  # at the turnaround of 1.25 s
    # square waves, low in the first half of each period: at 1.25 s the 100 ms and 500 ms ones are high
    assert cpu.peek("S13") & 0b111 == 0b011


def test_a_jump_loop_trips_the_watchdog_and_names_the_line():
    cpu = run("P 0\nloop:\nJMP loop\nE 0\n", watchdog_jumps=1000)
    assert cpu.mode == "STOP" and cpu.error.line == 3 and "watchdog" in cpu.error.message


def test_indirect_jump_to_a_missing_label_stops_with_the_labels_known():
    cpu = run("LD 7\nJMI\nL 1\nL 2\n")
    assert cpu.mode == "STOP" and "no label L 7 (labels: L 1, L 2)" in cpu.error.message


# -- the assembler --------------------------------------------------------------------------------


def test_the_instruction_inventory():
    assert len(DEFINED) == 57 and not DEFINED & NAMED_ONLY
    for mnemonic in sorted(NAMED_ONLY):
        with pytest.raises(AssemblyError, match=f"{mnemonic} is only named in the manual"):
            assemble(f"LD 1\n{mnemonic} R0\n", "named.il")


@pytest.mark.parametrize(
    "text, message",
    [
        ("LD X0.0\nWX Y0.0\n", r"t\.il, line 2, column 1: no instruction 'WX'; did you mean WR"),
        ("#def START x0.0\nLD STRAT\n", r"line 2, column 4: no name 'STRAT'; did you mean 'START'"),
        ("LD X0.0\nJMP knoec\nkonec:\n", r"line 2, column 5: no label 'knoec'; did you mean 'konec'"),
        ("AND RL10\n", r"AND RL10: a long operand is not allowed \(in the extended set only LD, LDC, WR, WRC"),
        ("LD RL10.1\n", r"the manual has no bit of a long"),
        ("LD XL126\n", r"XL126 is outside X0..X127"),
        ("LD X0.9\n", r"a register has bits 0..7"),
        ("WR D0\n", r"WR does not take D0"),
        ("LD X200\n", r"X200 is outside X0..X127"),
        ("CTU RW255\n", r"register pair RW0..RW254"),
        ("TON RW0.4\n", r"time base 4 is not 0..3"),
        ("P 0\nLD 1\n", r"process P0 is not closed"),
        ("P 49\nE 49\n", r"there is no process P49"),
        ("P 0\nCAL x\nx:\nRET\nE 0\n", r"subroutines live in process P60"),
        (".*****\n", r"comments start with ';'"),
        ("LD 70000\n", r"does not fit 16 bits"),
        ("LD 1\nx:\nx:\nLD 2\n", r"the label x is defined twice"),
        ("#table byte t = 300\n", r"does not fit a byte"),
        ("ANC\n", r"ANC needs an operand"),
        ("AND XW0\n", r"a word operand is in the extended set"),
        ("#table byte t = 0[1000000000]\n", r"#table t: more than 256 items"),
        ("#data byte d = 0[1000000000]\n", r"#data d: more than 65536 items"),
        ("#reg word w[1000000000]\nLD w\n", r"no room left in R"),
        ("LD " + " " * 2000 + "1\n", r"longer than 1000 characters"),
    ],
)
def test_errors_name_the_line_and_column_and_the_fix(text, message):
    with pytest.raises(AssemblyError, match=message):
        assemble(text, "t.il")


def test_case_labels_directives_and_a_second_timer_on_one_word_is_warned():
    asm = assemble(
        "#include x.mdl\n#reg word t\np 0\nLd X0.0\nld 5\nton T.0\nLD 1\nTON t\nsekce_A: jmp SEKCE_a\ne 0\n", "c.il"
    )
    assert [i.mnemonic for i in asm.code][:3] == ["LD", "LD", "TON"]
    assert any("#include is ignored" in w for w in asm.warnings)
    assert any("second timer instruction on RW0" in w for w in asm.warnings)


def test_reg_avoids_registers_the_program_names_by_address():
    asm = assemble("#reg word a\n#reg bit f, g\nLD RW0\nWR R2\n")
    assert str(asm.symbols["a"].operand) == "RW3" and str(asm.symbols["f"].operand) == "R5.0"
    assert str(asm.symbols["g"].operand) == "R5.1"


def test_data_area_is_read_only_program_data():
    cpu = run("#data word limits = 1000, 2000\nLD limits\nLD DW2\n")
    assert cpu.stack[:2] == [2000, 1000]


def test_a_mode_switch_is_a_warm_restart_the_first_start_a_cold_one():
    cpu = TecomatCPU("LD R0\nADD 1\nWR R0\n", retentive_r=(0, 1))
    cpu.scan(3)
    cpu.stop()
    cpu.start()
    cpu.scan()
    assert cpu.peek("R0") == 4 and cpu.peek("S2.3") == 1  # warm: the retentive R0 kept, HOT set
    cpu.load("LD R0\nADD 1\nWR R0\n")
    cpu.start()
    cpu.scan()
    assert cpu.peek("R0") == 1 and cpu.peek("S2.4") == 1  # after a download: cold, RST set


@pytest.mark.parametrize("keep, a7", [(False, 0), (True, 1)])
def test_a_pop_fills_a7_with_zero_or_keeps_it(keep, a7):
    cpu = run("".join(f"LD {n}\n" for n in range(1, 9)) + "OR\nOR\n", pop_fill_keeps_a7=keep)
    assert cpu.stack == [8 | 7 | 6, 5, 4, 3, 2, 1, a7, a7]


@pytest.mark.parametrize(
    "option, message",
    [
        ({"timer_ticks": "wall"}, "use 'per_timer' or 'global'"),
        ({"cycle": "0ms"}, "must be positive"),
        ({"retentive_r": (10, 5)}, "a range"),
        ({"p5_p9_periods": ("soon",)}, "soon"),
    ],
)
def test_settings_are_checked(option, message):
    with pytest.raises(ConfigurationError, match=message):
        TecomatCPU("LD 1\n", **option)
