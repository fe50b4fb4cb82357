"""The hosted CI a public repository runs (.github/workflows): it cannot run here, so this checks what can
be checked without GitHub: both files are valid YAML of the shape GitHub reads, the tests run the README's
own test command on Linux, Windows and macOS with the oldest and the newest Python plcsim supports, and the
site is built the way tests/test_docs_site.py builds it (--strict)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

yaml = pytest.importorskip("yaml")  # PyYAML comes with mkdocs (the test extra's docs)

ROOT = Path(__file__).resolve().parent.parent
WORKFLOWS = ROOT / ".github" / "workflows"


def workflow(name: str) -> dict:
    data = yaml.safe_load((WORKFLOWS / name).read_text(encoding="utf-8"))
    assert isinstance(data, dict) and "jobs" in data, f"{name}: not a workflow"
    # PyYAML reads the key `on:` as True (YAML 1.1); GitHub reads it as "on"
    assert "on" in data or True in data, f"{name}: no trigger"
    return data


def commands(job: dict) -> list[str]:
    return [step["run"].strip() for step in job["steps"] if "run" in step]


def readme_test_command() -> str:
    """The README's second command, after its install: ``python -m pytest``."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    found = re.search(r"^    pip install -e '\.\[test\]' && (.+)$", text, re.MULTILINE)
    assert found, "the README's test command is gone"
    return found.group(1).strip()


def test_the_tests_run_the_readmes_command_on_three_systems_and_two_pythons():
    job = workflow("tests.yml")["jobs"]["test"]
    matrix = job["strategy"]["matrix"]
    assert set(matrix["os"]) == {"ubuntu-latest", "windows-latest", "macos-latest"}
    assert set(matrix["python"]) == {"3.11", "3.13"}
    oldest = re.search(r'requires-python = ">=([\d.]+)"', (ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    assert oldest and oldest.group(1) in matrix["python"]  # the oldest Python plcsim promises is tested
    assert job["strategy"]["fail-fast"] is False  # the first push shows every system's failures
    assert readme_test_command() in commands(job)
    assert 'python -m pip install -e ".[test]"' in commands(job)


def test_the_docs_site_is_built_strictly_and_published_on_pages():
    data = workflow("docs.yml")
    build, deploy = data["jobs"]["build"], data["jobs"]["deploy"]
    assert "mkdocs build --strict" in commands(build)
    uses = [step.get("uses", "") for step in build["steps"] + deploy["steps"]]
    assert any(u.startswith("actions/upload-pages-artifact@") for u in uses)
    assert any(u.startswith("actions/deploy-pages@") for u in uses)
    assert data["permissions"]["pages"] == "write" and data["permissions"]["id-token"] == "write"
