"""Program files as students save them: encodings, a BOM, empty files, a misspelt OB1.

Issue 9: a Windows-1250 file was a "grader error: UnicodeDecodeError" with no file named, a UTF-8 BOM
was refused, and an empty file or ``def ob1`` earned 7/11 with nothing saying that OB1 is missing.
"""

from __future__ import annotations

import pytest

from plcsim import Program
from plcsim.core.errors import NoOB1Error, ProgramError, ProgramFileError

SLOVAK = "def OB1(t):\n    # Ľahký štart: žltá LED svieti\n    t.LED = t.TL\n"


def test_a_utf8_file_with_a_bom_loads(tmp_path):
    path = tmp_path / "bom.py"
    path.write_bytes(b"\xef\xbb\xbf" + SLOVAK.encode("utf-8"))
    assert list(Program.from_file(path).tasks) == ["OB1"]


def test_a_bom_in_source_text_loads_too():
    assert list(Program.from_source("\ufeff" + SLOVAK).tasks) == ["OB1"]


def test_a_pep263_coding_line_is_honoured(tmp_path):
    path = tmp_path / "cp1250.py"
    path.write_bytes(("# -*- coding: cp1250 -*-\n" + SLOVAK).encode("cp1250"))
    program = Program.from_file(path)
    assert "Ľahký štart" in program.source


def test_a_windows_1250_file_names_the_file_line_byte_encoding_and_fix(tmp_path):
    path = tmp_path / "zadanie.py"
    path.write_bytes(SLOVAK.encode("cp1250"))
    with pytest.raises(ProgramFileError) as info:
        Program.from_file(path)
    message = str(info.value)
    assert message.startswith(f"{path}, line 2: byte 0x{'Ľ'.encode('cp1250')[0]:02x} (column 7)")
    assert "read as utf-8" in message
    assert "Save it as UTF-8" in message


def test_an_unknown_coding_line_is_a_program_error(tmp_path):
    path = tmp_path / "odd.py"
    path.write_bytes(b"# coding: klingon\n" + SLOVAK.encode())
    with pytest.raises(ProgramError, match=r"odd.py: unknown encoding.*save the file as UTF-8"):
        Program.from_file(path)


def test_an_unreadable_file_is_a_program_error(tmp_path):
    with pytest.raises(ProgramFileError, match=r"cannot read program .*missing.py"):
        Program.from_file(tmp_path / "missing.py")


@pytest.mark.parametrize(
    "text", [pytest.param("", id="empty"), pytest.param("# only a comment\n\n", id="comments"), "\n\n"]
)
def test_a_file_without_code_says_no_ob1_and_how_to_write_it(tmp_path, text):
    path = tmp_path / "lab.py"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(NoOB1Error) as info:
        Program.from_file(path)
    message = str(info.value)
    assert message.startswith(f"{path}: no OB1: the file holds no code")
    assert "def OB1(t): ..." in message and "OB1 = [start_belt, stop_belt]" in message


@pytest.mark.parametrize(
    ("source", "line", "wrong"),
    [
        ("def ob1(t):\n    t.LED = t.TL\n", 1, "ob1"),
        ("def Ob1(t):\n    t.LED = t.TL\n", 1, "Ob1"),
        ("def net(t):\n    t.LED = t.TL\n\nob1 = [net]\n", 4, "ob1"),
        ("def blink(t):\n    pass\nOB30 = CyclicInterrupt(blink)\ndef oB1(t):\n    pass\n", 4, "oB1"),
    ],
)
def test_a_wrong_case_ob1_asks_did_you_mean(source, line, wrong):
    with pytest.raises(NoOB1Error) as info:
        Program.from_source(source, "lab.py")
    assert str(info.value).startswith(f"lab.py, line {line}: no OB1: {wrong} is not OB1")
    assert "did you mean OB1?" in str(info.value)


def test_networks_without_any_ob_say_no_ob1():
    with pytest.raises(ProgramError, match=r"lab.py: no OB1: nothing is bound to OB1"):
        Program.from_source("def start_belt(t):\n    t.LED = t.TL\n", "lab.py")


def test_a_program_of_interrupts_only_is_still_valid():
    program = Program.from_source("def blink(t):\n    pass\nOB30 = CyclicInterrupt(blink)\n", "lab.py")
    assert list(program.tasks) == ["OB30"]
