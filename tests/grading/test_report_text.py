"""Every report format against text a submission chose (plcsim.core.untrusted_text): control characters, a
screen clear, a forged green verdict, an OSC-8 link, bidirectional overrides, lone surrogates, characters
XML 1.0 forbids, spreadsheet formulas, Rich and HTML markup, a megabyte. Each output is read back with a
real parser (ElementTree, csv, json) and must render nothing the student chose: no control or format
character reaches a terminal, a JUnit file or a gradebook cell, and JSON stays valid UTF-8.
"""

from __future__ import annotations

import csv
import io
import json
import re
import unicodedata
from xml.etree import ElementTree as ET

import pytest
from rich.console import Console

from plcsim.core.untrusted_text import for_csv, for_json, for_terminal, for_xml, visible
from plcsim.grading.report import CheckResult, Report, ScenarioRun, gradescope_results, write_gradebook, write_junit
from plcsim.grading.terminal import print_batch_line, print_report

SCREEN_CLEAR = "\x1b[2J\x1b[H"
FORGED_VERDICT = "\x1b[1;32mPASSED\x1b[0m  score 13 / 13"
OSC8_LINK = "\x1b]8;;http://evil.example/\x1b\\click me\x1b]8;;\x1b\\"
HOSTILE = {
    "screen clear": SCREEN_CLEAR + "gone",
    "forged verdict": SCREEN_CLEAR + FORGED_VERDICT,
    "forged line": "oops\nPASSED  score 13 / 13\n\rPASSED",
    "osc-8 link": OSC8_LINK,
    "c0 and c1": "nul\x00 bell\x07 bs\x08 vt\x0b ff\x0c cr\r del\x7f csi\x9b31m nel\x85",
    "bidi": "abc\u202egnp.exe \u2066x\u2069 \u200f\u061c \u202d",
    "invisible": "zero\u200bwidth \ufeffbom \u2028line\u2029para \U000e0001tag",
    "surrogates": "name\udcff\udc80.py",
    "noncharacters": "x\ufffe\uffff",
    "rich markup": "[bold green]PASSED[/bold green] [/] [link=http://x]y",
    "html": "<script>alert(1)</script>&amp;]]><![CDATA[x]]>",
    "formula": '=HYPERLINK("http://evil.example","x")',
    "formula plus": "+cmd|' /C calc'!A0",
    "formula tab": "\t=1+1",
    "megabyte": "x" * 1_000_000 + "\x1b[2J",
    "megabyte of escapes": "\x1b" * 300_000,
    "slovak": "Žltý kôň úpel ďábelské ódy",
}
XML_ALLOWED = re.compile("^[\t\n\r\x20-\ud7ff\ue000-\ufffd\U00010000-\U0010ffff]*$")
SGR = re.compile(r"\x1b\[[0-9;]*m")


def rendered_unsafely(text: str, *, newlines: bool = True) -> list[str]:
    """The characters of ``text`` that a terminal or reader would act on instead of showing."""
    return sorted(
        {
            ch
            for ch in text
            if (ch != "\n" or not newlines)
            and (unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp", "Cs") or ch in "\ufffe\uffff")
        }
    )


def hostile_reports(text: str) -> list[Report]:
    """A report that ran (a failed, a passed and a not-exercised check, a CPU STOP, a warning) and one that
    did not load, with ``text`` in every string a submission can reach."""
    ran = Report(
        "4.3.1",
        "LED",
        f"subs/{text}.py",
        checks=[
            CheckResult("presses", f"lamp {text}", False, f"the lamp {text}", 0.0, 1.0, diagram=f"out/{text}.png"),
            CheckResult("presses", "ok", True, f"held {text}", 1.0, 1.0),
            CheckResult("presses", "idle", False, f"not exercised: {text}", 0.0, 1.0, status="not exercised"),
        ],
        runs=[ScenarioRun("presses", 1, 4, 4, "STOP", f"JMP to {text}", rrd=f"out/{text}.rrd")],
        warnings=[f"warning {text}"],
        score=1.0,
        max_score=3.0,
        seed=1,
    )
    broken = Report(
        "4.3.1",
        "LED",
        f"{text}.py",
        error=f"{text}.py, line 3: JMP to 'x', but no network carries that label; labels in OB1: {text}",
        error_kind="program error",
        max_score=3.0,
        seed=1,
    )
    return [ran, broken]


def terminal_output(report: Report, *, colour: bool) -> str:
    buffer = io.StringIO()
    console = Console(file=buffer, width=200, force_terminal=colour, color_system="standard" if colour else None)
    print_report(report, console, verbose=True)
    print_batch_line(report, console)
    return buffer.getvalue()


@pytest.mark.parametrize("kind", HOSTILE)
def test_the_terminal_report_shows_escapes_and_sends_none(kind):
    for report in hostile_reports(HOSTILE[kind]):
        plain = terminal_output(report, colour=False)
        assert rendered_unsafely(plain) == []
        assert [line for line in plain.splitlines() if line.startswith("PASSED")] == []  # no verdict of its own
        assert len(plain) < 100_000  # a megabyte is cut, and says so
        coloured = SGR.sub("", terminal_output(report, colour=True))  # only the report's own colours are SGR
        assert "\x1b" not in coloured
    if "\x1b" in HOSTILE[kind] and kind != "megabyte":
        assert "\\x1b" in terminal_output(hostile_reports(HOSTILE[kind])[1], colour=False)  # shown, not sent


@pytest.mark.parametrize("kind", HOSTILE)
def test_a_batch_junit_file_parses_and_holds_only_xml_characters(kind, tmp_path):
    path = tmp_path / "junit.xml"
    write_junit(hostile_reports(HOSTILE[kind]) * 2, path)
    root = ET.parse(path).getroot()  # one student's file cannot break the class's report
    assert (root.get("tests"), root.get("failures"), root.get("errors"), root.get("skipped")) == ("10", "2", "4", "2")
    texts = [v for e in root.iter() for v in (*e.attrib.values(), e.text or "")]
    for value in texts:
        assert XML_ALLOWED.match(value)
        assert rendered_unsafely(value) == []
    assert max(map(len, texts)) < 30_000


@pytest.mark.parametrize("kind", HOSTILE)
def test_the_gradebook_parses_and_no_cell_is_a_formula_or_a_control(kind, tmp_path):
    path = write_gradebook(hostile_reports(HOSTILE[kind]), tmp_path / "grades.csv")
    rows = list(csv.reader(path.open(encoding="utf-8", newline="")))
    assert len(rows) == 3 and len({len(row) for row in rows}) == 1
    for cell in (cell for row in rows for cell in row):
        assert cell == "-" or not cell.startswith(("=", "+", "-", "@", "\t", "\r")), cell[:80]  # "-": did not run
        assert rendered_unsafely(cell, newlines=False) == []
        assert len(cell) < 1_000


@pytest.mark.parametrize("kind", HOSTILE)
def test_json_and_gradescope_parse_and_are_valid_utf8(kind):
    for report in hostile_reports(HOSTILE[kind]):
        data = json.loads(report.to_json())
        json.dumps(data, ensure_ascii=False).encode("utf-8")  # no lone surrogate: a strict reader accepts it
        if kind != "surrogates":
            assert Report.from_dict(data) == report  # JSON keeps the text as it is
        results = gradescope_results(report)
        shown = json.loads(json.dumps(results))
        for test in shown["tests"]:
            assert rendered_unsafely(test["name"] + test["output"]) == []
        assert rendered_unsafely(shown["output"]) == []


def test_the_media_functions_on_one_string():
    text = "=a\x1b[2J\u202eb\nc\udcff"
    assert for_terminal(text) == "=a\\x1b[2J\\u202eb\\x0ac\\udcff"
    assert for_terminal(text, newlines=True) == "=a\\x1b[2J\\u202eb\nc\\udcff"
    assert for_xml(text) == "=a\\x1b[2J\\u202eb\nc\\udcff"
    assert for_csv(text) == "'=a\\x1b[2J\\u202eb …"
    assert for_terminal("\x1b" * 10, limit=12) == "\\x1b\\x1b\\x1b… [7 more characters cut]"
    assert for_terminal("x" * 30, limit=10) == "xxxxxxxxxx… [20 more characters cut]"
    assert for_json(text) == "=a\x1b[2J\u202eb\nc\\udcff"
    assert visible("Žltý kôň\ttab") == "Žltý kôň\\x09tab"


def test_every_control_and_format_character_of_this_python_is_escaped():
    unsafe = [chr(c) for c in range(0x110000) if unicodedata.category(chr(c)) in ("Cc", "Cf", "Zl", "Zp", "Cs")]
    shown = visible("".join(unsafe), newlines=False)
    assert rendered_unsafely(shown, newlines=False) == []
    assert shown.count("\\") == len(unsafe)


LABEL = SCREEN_CLEAR + FORGED_VERDICT + OSC8_LINK + "\u202e\x00"
JUMPS_TO_NOWHERE = f'@label({LABEL!r})\ndef n1(t):\n    JMP("nowhere")\n\n\nOB1 = [n1]\n'


@pytest.mark.xdist_group("sandbox")
def test_a_batch_with_hostile_labels_and_file_names_reports_them_escaped(tmp_path, capsys):
    """The issue's case, through the grade command: a label the jump check echoes, a file name with a
    screen clear, a file name that is not UTF-8, one whose stem is ``..``; every file the batch writes
    parses, stays in its folder and holds none of it."""
    from exercises import get
    from plcsim.apps.cli import main

    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "evil\x1b[2J.py").write_text(JUMPS_TO_NOWHERE, encoding="utf-8")
    reference = get("4.3.1").reference.path.read_bytes()
    with open(bytes(subs) + b"/\xff\xfename.py", "wb") as f:
        f.write(reference)
    (subs / "...py").write_bytes(reference)  # its stem is ".."
    out = tmp_path / "out"
    book, xml, js, gs = out / "grades.csv", out / "junit.xml", out / "json", out / "gs"
    argv = ["grade", "4.3.1", str(subs), "--gradebook", str(book), "--junit", str(xml), "--json", str(js)]
    main([*argv, "--gradescope", str(gs)])
    printed = capsys.readouterr().out
    assert rendered_unsafely(printed) == [] and "\\x1b[2J" in printed
    root = ET.parse(xml).getroot()
    assert (root.get("tests"), root.get("errors")) == ("7", "1")
    error = root.find(".//error")
    assert "labels in OB1: \\x1b[2J" in error.get("message") and rendered_unsafely(error.get("message")) == []
    rows = list(csv.reader(book.open(encoding="utf-8", newline="")))
    assert rendered_unsafely("".join(cell for row in rows for cell in row), newlines=False) == []
    stems = sorted(["_..", "\\udcff\\udcfename", "evil\\x1b[2J"])
    assert sorted(p.parent.name for p in gs.rglob("results.json")) == stems
    assert sorted(p.name for p in js.iterdir()) == [f"{stem}.json" for stem in stems]
    assert sorted(p.name for p in out.iterdir()) == ["grades.csv", "gs", "json", "junit.xml"]  # nothing beside
    for path in [*js.iterdir(), *gs.rglob("*.json")]:
        json.loads(path.read_bytes().decode("utf-8"))


def test_plcsim_run_prints_a_hostile_label_in_its_error_as_escapes(tmp_path, capsys):
    from plcsim.apps.cli import EXIT_USAGE, main

    path = tmp_path / "evil.py"
    path.write_text(JUMPS_TO_NOWHERE, encoding="utf-8")
    assert main(["run", "4.3.1", "--program", str(path)]) == EXIT_USAGE
    captured = capsys.readouterr()
    assert "OB1:\\x1b[2J\\x1b[H" in "".join(captured.err.split())  # shown, whatever the width
    assert rendered_unsafely(captured.out + captured.err) == []


def test_gradescope_shows_every_output_and_name_as_text_never_markup():
    results = gradescope_results(hostile_reports(HOSTILE["html"])[0])
    assert (results["output_format"], results["test_output_format"], results["test_name_format"]) == ("text",) * 3
