"""The pytest plugin for instructors (plcsim.apps.pytest_plugin), through pytest's own plugin-testing fixture:
a correct and a wrong shipped solution of 4.3.1 must be reported as passed and failed, with the check's
explanation, by the fixtures, by a folder of submissions, over seeds and as one item per check.
"""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from exercises import get

pytest_plugins = ["pytester"]

HOG = "def OB1(t):\n    x = 0\n    for i in range(300000):\n        x = x + i\n    t.LED = t.TLACIDLO\n"


@pytest.fixture
def subs(pytester):
    """A folder with alice.py (the reference of 4.3.1) and bob.py (its wrong latch), and a test file beside them."""
    ex = get("4.3.1")
    folder = pytester.path / "subs"
    folder.mkdir()
    shutil.copy(ex.reference.path, folder / "alice.py")
    shutil.copy(ex.solution("wrong-latch").path, folder / "bob.py")
    (folder / "test_not_a_submission.py").write_text("def test_nothing():\n    pass\n", encoding="utf-8")
    return folder


def test_plcsim_run_passes_the_reference_and_fails_the_wrong_latch_with_the_checks_explanation(pytester):
    pytester.makepyfile(
        """
        from plcsim.check import always, same

        def test_reference(plcsim_run):
            run = plcsim_run("4.3.1", solution="reference", scenario="presses", seed=1)
            run.require(always(same("LED", "TLACIDLO")))
            assert run.sandboxed and run.cpu_mode == "RUN" and run.scans == 4000
            assert len(run.trace.rises("LED")) == 12

        def test_wrong_latch(plcsim_run):
            plcsim_run("4.3.1", solution="wrong-latch").require(always(same("LED", "TLACIDLO")))
        """
    )
    result = pytester.runpytest_subprocess("-p", "no:cacheprovider")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(
        [
            "*AssertionError: wrong-latch.py, scenario 'presses', seed 1:",
            "*always LED == TLACIDLO: expected always LED == TLACIDLO; it failed in the scan at 78 ms "
            "(LED=TRUE, TLACIDLO=FALSE)",
            "FAILED test_plcsim_run_passes_the_reference_and_fails_the_wrong_latch_with_the_checks_explanation.py"
            "::test_wrong_latch*",
        ]
    )


def test_a_folder_of_submissions_and_seeds_make_one_test_per_student_and_seed(pytester, subs):
    tests = pytester.makepyfile(
        """
        def test_grade(plcsim_grade, plcsim_program, plcsim_seed):
            report = plcsim_grade("4.3.1")
            assert report.seed == plcsim_seed and report.submission == str(plcsim_program.resolve())
            assert report.passed, [c.message for c in report.failed()]
        """
    )
    options = ["-p", "no:cacheprovider", "-v", "--plcsim-program", "subs", "--plcsim-seeds", "1,2"]
    result = pytester.runpytest_subprocess(tests, *options)  # subs/test_not_a_submission.py is no student
    result.assert_outcomes(passed=2, failed=2)
    for line in ("alice-seed1] PASSED", "alice-seed2] PASSED", "bob-seed1] FAILED", "bob-seed2] FAILED"):
        result.stdout.fnmatch_lines([f"*test_grade[[]{line}*"])
    result.stdout.fnmatch_lines(["*'expected number of times LED rises = 12; measured 1'*"])


def test_an_exercise_s_checks_become_test_items_with_pytest_s_reporting_and_junit(pytester, subs):
    junit = pytester.path / "grades.xml"
    result = pytester.runpytest_subprocess(
        *("-p", "no:cacheprovider", "-v", "--ignore=subs", f"--junitxml={junit}"),
        *("--plcsim-exercise", "4.3.1", "--plcsim-program", "subs"),
    )
    result.assert_outcomes(passed=3, failed=3)
    result.stdout.fnmatch_lines(
        [
            "*plcsim 4.3.1 alice seed 1::presses: every press is reproduced on the LED PASSED*",
            "*plcsim 4.3.1 bob seed 1::presses: every press is reproduced on the LED FAILED*",
            "failed: expected number of times LED rises = 12; measured 1",
        ]
    )
    cases = ET.parse(junit).getroot().iter("testcase")
    failed = sorted(c.get("name") for c in cases if c.find("failure") is not None)
    assert failed == [
        "presses: LED equals the button in every scan",
        "presses: LED lights within 2 scans",
        "presses: every press is reproduced on the LED",
    ]


def test_programs_run_in_the_sandbox_unless_the_instructor_opts_out(pytester):
    pytester.makepyfile(hog=HOG)
    pytester.makepyfile(
        test_sandbox="""
        import pytest
        from plcsim.grading.sandbox.limits import Limits
        from plcsim.apps.pytest_plugin import SubmissionError

        def test_sandboxed(plcsim_run):
            assert plcsim_run("4.3.1", solution="reference").sandboxed
            with pytest.raises(SubmissionError, match=r"hog.py did not run [(]time limit[)]: .* 1 s of CPU"):
                plcsim_run("4.3.1", program="hog.py", limits=Limits(cpu_seconds=1, wall_seconds=30))

        def test_trusted(plcsim_run):
            assert not plcsim_run("4.3.1", solution="reference", sandbox=False).sandboxed
        """
    )
    pytester.runpytest_subprocess("-p", "no:cacheprovider").assert_outcomes(passed=2)
    pytester.makepyfile(
        test_sandbox="""
        def test_opted_out(plcsim_run):
            assert not plcsim_run("4.3.1", solution="reference").sandboxed
            assert plcsim_run("4.3.1", solution="reference", sandbox=True).sandboxed
        """
    )
    pytester.runpytest_subprocess("-p", "no:cacheprovider", "--plcsim-no-sandbox").assert_outcomes(passed=1)


def test_mistakes_are_reported_with_the_fix(pytester):
    pytester.makepyfile(broken="def OB1(t):\n    t.LED = t.TLACIDLO +\n")
    pytester.makepyfile(
        test_mistakes="""
        def test_no_program(plcsim_run):
            plcsim_run("4.3.1")

        def test_broken_program(plcsim_run):
            plcsim_run("4.3.1", program="broken.py")

        def test_no_exercise(plcsim_grade):
            plcsim_grade("9.9.9", solution="reference")
        """
    )
    result = pytester.runpytest_subprocess("-p", "no:cacheprovider")
    result.assert_outcomes(failed=3)
    result.stdout.fnmatch_lines(
        [
            "*plcsim: which program? pass program='FILE.py' (or solution='reference') or run pytest with "
            "--plcsim-program FILE.py",
            "*SubmissionError: broken.py did not run (program error): *broken.py, line 2: syntax error*",
            "*UsageError: plcsim: *9.9.9*",
        ]
    )
    result = pytester.runpytest_subprocess("-p", "no:cacheprovider", "--plcsim-exercise", "4.3.1")
    result.stderr.fnmatch_lines(["*--plcsim-exercise needs the submission(s) to grade: --plcsim-program PATH"])
    result = pytester.runpytest_subprocess(
        "-p", "no:cacheprovider", "--plcsim-program", "missing.py", "--plcsim-exercise", "4.3.1"
    )
    result.stderr.fnmatch_lines(["*--plcsim-program missing.py: no such file or folder"])


def test_the_example_of_the_documentation_passes_the_reference_of_4_3_6(pytester):
    page = (Path(__file__).resolve().parents[2] / "docs" / "pytest-plugin.md").read_text(encoding="utf-8")
    example = page.split("```python\n", 1)[1].split("```", 1)[0]
    (pytester.path / "submissions").mkdir()
    shutil.copy(get("4.3.6").reference.path, pytester.path / "submissions" / "alice.py")
    tests = pytester.makepyfile(test_example=example)
    result = pytester.runpytest_subprocess(tests, "-p", "no:cacheprovider", "--plcsim-program", "submissions/alice.py")
    result.assert_outcomes(passed=2)


def test_a_hostile_label_and_file_name_reach_pytests_output_as_escapes(pytester, monkeypatch):
    """A label the jump check echoes and a file name with a screen clear: pytest's report shows their
    escapes, and its JUnit file parses."""
    monkeypatch.setenv("PYTHONPATH", str(Path(__file__).resolve().parents[2]))  # this checkout's plugin
    folder = pytester.path / "subs"
    folder.mkdir()
    label = "\x1b[2J\x1b[1;32mPASSED\x1b[0m\u202e"
    program = f'@label({label!r})\ndef n1(t):\n    JMP("nowhere")\n\n\nOB1 = [n1]\n'
    (folder / "evil\x1b[2J.py").write_text(program, encoding="utf-8")
    junit = pytester.path / "grades.xml"
    result = pytester.runpytest_subprocess(
        *("-p", "no:cacheprovider", "-v", "--ignore=subs", f"--junitxml={junit}"),
        *("--plcsim-exercise", "4.3.1", "--plcsim-program", "subs"),
    )
    printed = "\n".join(result.outlines + result.errlines)
    assert "\x1b" not in printed and "\u202e" not in printed
    assert "labels in OB1: \\x1b[2J" in printed
    ET.parse(junit)
