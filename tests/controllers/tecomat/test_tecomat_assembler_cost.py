"""The ``.il`` assembler's work grows with the program, not with its square: a program of many ``#def``
constants and many ``#data`` items (a 2-million-line file is a way to stall a grading batch) evaluates
each ``#def`` once, not once for every item that follows it. Counted, never timed."""

from __future__ import annotations

import pytest

from plcsim.controllers.tecomat import assembler


def program(defs: int, items: int) -> str:
    lines = [f"#def KON{k} {k % 100}" for k in range(defs)]
    lines += [f"#data byte TAB{k} = KON{k % defs}, 1, 2" for k in range(items)]
    lines += [f"#reg byte REG{k}" for k in range(defs)]
    return "\n".join([*lines, "LD X0.0", "WR Y0.0", ""])


def evaluations(monkeypatch, defs: int, items: int) -> int:
    calls = 0
    real = assembler.expression

    def counted(*args, **kwargs):
        nonlocal calls
        calls += 1
        return real(*args, **kwargs)

    monkeypatch.setattr(assembler, "expression", counted)
    asm = assembler.assemble(program(defs, items), "many.il")
    assert asm.data[:3] == bytes([0, 1, 2]) and asm.data[-3:] == bytes([(items - 1) % defs % 100, 1, 2])
    return calls


@pytest.mark.parametrize("size", [100, 400])
def test_the_defs_are_evaluated_once_not_once_per_data_item(monkeypatch, size):
    n = evaluations(monkeypatch, size, size)
    assert n <= 2 * size + 3 * size  # a def once (and once more as a symbol), each item's three terms


def test_the_data_of_the_whole_program_is_bounded_not_each_data_line():
    """MAX_DATA bounds the program's #data in all, as its docstring says, not each line (two million lines
    of 64 KB each would otherwise take 128 GB)."""
    one = "#data byte A = 0[40000]\nLD X0.0\nWR Y0.0\n"
    assert len(assembler.assemble(one, "one.il").data) == 40_000
    two = "#data byte A = 0[40000]\n#data byte B = 0[40000]\nLD X0.0\nWR Y0.0\n"
    with pytest.raises(
        assembler.AssemblyError, match=r"two.il, line 2, .*#data B: the program's #data would pass 65536 bytes"
    ):
        assembler.assemble(two, "two.il")
