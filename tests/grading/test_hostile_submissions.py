"""Submissions that attack the grader through its own messages and start-up, not through the sandbox: a
program error of megabytes, a file in no encoding a front end reads, a submission named like a module
the grader imports. Each is reported as the student's error, named, never as an invalid result or a crash."""

from __future__ import annotations

import pytest

from exercises import get
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.grading.run_result import MAX_TEXT

pytestmark = pytest.mark.xdist_group("sandbox")

HUGE_LABEL = "A" * 3_000_000
JUMPS_TO_NOWHERE = f'@label({HUGE_LABEL!r})\ndef n1(t):\n    JMP("nowhere")\n\n\nOB1 = [n1]\n'


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


def test_a_program_error_of_3_mb_arrives_cut_and_named_not_as_an_invalid_result(ex1, tmp_path):
    path = tmp_path / "huge.py"
    path.write_text(JUMPS_TO_NOWHERE, encoding="utf-8")
    report = grade_sandboxed(ex1, path)
    assert report.error_kind == "program error"
    assert report.error.startswith(f"{path}, line 3: JMP to 'nowhere'")
    assert len(report.error) <= MAX_TEXT and report.error.endswith("more characters cut]")


@pytest.mark.parametrize("sandboxed", [False, True])
def test_an_il_file_neither_utf8_nor_cp1250_is_named_not_a_crash(ex1, tmp_path, sandboxed):
    path = tmp_path / "lab.il"
    path.write_bytes(b"LD X0.0\nWR Y0.0 ; \x81\x98\n")  # 0x81 and 0x98 are in neither
    report = (grade_sandboxed if sandboxed else grade)(ex1, path)
    assert (report.error_kind, report.error) == (
        "program error",
        f"{path}, line 2: this file is not text in UTF-8 or cp1250 (byte 0x81 in column 11); save it as UTF-8",
    )
