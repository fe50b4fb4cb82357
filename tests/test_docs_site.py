"""The API reference site (mkdocs.yml, mkdocstrings): it builds with --strict (no broken link, no
docstring the renderer cannot read) and its pages hold the API they are about, so CI builds it."""

from __future__ import annotations

import html
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent

PAGES = {
    "index.html": ["the PLC subset", "Testing programs with pytest"],
    "instructions/index.html": ["IEC_TIMER", "CTUD", "Bool"],
    "writing-an-exercise/index.html": ["Scenario", "EXERCISE"],
    "grading-sandbox/index.html": ["PLCSIM_SANDBOX=portable", "Landlock"],
    "tecomat/index.html": ["plcsim grade T-01 mine.il", "event_enable_byte", "little-endian"],
    "pytest-plugin/index.html": ["plcsim_run", "--plcsim-exercise"],
    "reference/check/index.html": [
        "rises",
        "within",
        "never",
        "always",
        "holds",
        "measure",
        "program_uses_no",
        "Verdict",
    ],
    "reference/exercise/index.html": ["Exercise", "IO", "Scenario", "place", "press", "after_event"],
    "reference/plant/index.html": ["Plant", "SignalSpec", "PlantEvent", "check_plant"],
    "writing-a-rig/index.html": ["TopBelt", "class Reject(TopViewPlant)", "check-exercise", "one_of", "carrier_at"],
    "reference/plants/index.html": ["TopViewPlant", "ZoneSensor", "Carrier", "Bins", "Piston", "rig_figure"],
    "reference/tecomat/index.html": ["TecomatCPU", "load_file", "set_input", "peek", "G36", "base-60"],
    "reference/grading/index.html": ["grade_sandboxed", "Limits", "Report", "write_junit", "PlcRun"],
    "reference/cli/index.html": ["usage: plcsim grade", "--cpu-seconds", "usage: plcsim reference", "Exit codes"],
}


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    out = tmp_path_factory.mktemp("site")
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "mkdocs",
            "build",
            "--strict",
            "--config-file",
            str(ROOT / "mkdocs.yml"),
            "--site-dir",
            str(out),
        ],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env={**os.environ, "NO_MKDOCS_2_WARNING": "1"},
        timeout=300,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    return out


def text_of(page: Path) -> str:
    return html.unescape(re.sub(r"<[^>]+>", "", page.read_text(encoding="utf-8")))


@pytest.mark.parametrize("page", sorted(PAGES))
def test_each_page_is_built_and_names_its_api(site, page):
    text = text_of(site / page)
    missing = [name for name in PAGES[page] if name not in text]
    assert not missing, f"{page} lacks {missing}"


def test_the_docstrings_restructuredtext_is_rendered_as_code_not_left_raw(site):
    for page in (site / "reference").glob("*/index.html"):
        assert not re.search(r":(mod|func|class|meth|attr):`", text_of(page)), page
    grading = (site / "reference/grading/index.html").read_text(encoding="utf-8")
    assert "<code>run_scenarios</code>" in grading  # :func:`run_scenarios` in plcsim/grading/grader.py
    check = (site / "reference/check/index.html").read_text(encoding="utf-8")
    assert re.search(r"<pre[^>]*>(?:(?!</pre>).)*conveyor_checks", check, re.DOTALL)  # a >>> example, as code
