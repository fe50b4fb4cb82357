"""The Tecomat controller's fast paths give what the plain ones give: the cycle's end (the traced values
copied and decoded only when read, the outputs from the copy of Y) and the generated code (see
``test_tecomat_fast_equivalence.py``)."""

from __future__ import annotations

import datetime as dt

from plcsim.controllers.tecomat.cpu import TecomatCPU

PROGRAM = "#def B x0.0\n#def L y0.0\n#def N r4\nLD B\nWR L\nLD N\nADD 1\nWR N\n"


def test_the_traced_values_are_those_of_the_last_cycle_end_even_when_read_later():
    cpu = TecomatCPU(PROGRAM)
    cpu.set_input("B", True)
    cpu.scan(3)
    cpu.write("N", 200)  # an HMI write after the cycle's end: the trace still shows the end's value
    assert (cpu.t.L, cpu.t.N) == (True, 3)
    cpu.run_until(cpu.now + 500_000)  # the next cycle ran its program but has not ended: still cycle 3
    assert cpu.t.N == 3
    cpu.scan()
    assert cpu.t.N == 201


def test_a_subscriber_holding_the_values_dict_sees_every_cycle_end():
    cpu = TecomatCPU(PROGRAM)
    values = cpu.t.__dict__
    seen = []
    cpu.on_scan_end = lambda c: seen.append(values["N"])
    cpu.scan(3)
    assert seen == [1, 2, 3]


def test_outputs_come_back_after_a_stop_and_a_restart():
    """The outputs are switched off in STOP; after the restart the first cycle drives them again even
    though the program computes what it computed before the stop (the old code kept them off)."""
    cpu = TecomatCPU("#def L y0.0\nLD 1\nWR L\n")
    cpu.scan()
    assert cpu.outputs == {"L": True}
    version = cpu.output_version
    cpu.stop()
    assert cpu.outputs == {"L": False} and cpu.output_version == version + 1
    cpu.start()
    cpu.scan()
    assert cpu.outputs == {"L": True} and cpu.output_version == version + 2


def test_input_bits_of_one_register_are_loaded_together_and_other_bits_kept():
    cpu = TecomatCPU("#def A x0.1\n#def B x0.6\n#def W xw2\nLD X0\nWR Y0\nLD XW2\nWR YW2\n")
    cpu.set_input("X0.3", True)  # a terminal no symbol names
    cpu.inputs.update(A=True, B=True, W=0x1234)
    cpu.scan()
    assert cpu.peek("Y0") == 0b0100_1010 and cpu.peek("YW2") == 0x1234
    cpu.inputs.update(A=False)
    cpu.scan()
    assert cpu.peek("Y0") == 0b0100_1000


def test_the_real_time_clock_rolls_over_midnight_into_the_next_date():
    cpu = TecomatCPU("LD SW5\nWR RW0\nLD SW7\nWR RW2\nLD SW9\nWR RW4\nLD SW11\nWR RW6\n", cycle="10ms")
    cpu.set_clock(dt.datetime(2028, 2, 29, 23, 59, 59, 985_000))  # a Tuesday, a leap day
    cpu.scan()
    regs = [cpu.peek(f"R{k}") for k in range(8)]
    assert regs == [98, 59, 59, 23, 2, 29, 2, 28]  # S5 10 ms, s, min, h, weekday, day, month, year
    cpu.scan(2)
    regs = [cpu.peek(f"R{k}") for k in range(8)]
    assert regs == [0, 0, 0, 0, 3, 1, 3, 28]  # 00:00:00.00 on Wednesday 1 March
