"""The teaching notebooks run headless, as a reader would run them top to bottom.

Every ``notebooks/*.ipynb`` is found here (a new notebook is picked up without touching this file)
and executed with nbclient in a kernel of its own, in a fresh temporary directory: the notebook is
copied there and runs with that directory as its working directory, so whatever it writes
(``out/*.rrd``, figures) lands there and never in the repository, and two notebooks can run in
parallel. A notebook passes when

* no cell raises (an error output fails the test, naming the cell and the exception);
* it shows at least one figure (an ``image/png`` output): the notebooks teach with pictures;
* it leaves behind the files it promises: every string literal in its code that names a ``.rrd``
  file (``Path("out/01_scan_cycle.rrd")``), and the paths listed in its metadata under
  ``plcsim.outputs``, exist and are not empty after the run.

The notebooks are committed executed, so that a reader browsing the repository sees their figures: every
code cell ran, in order, from a fresh kernel, without an error, and the outputs name no folder of the machine
that ran them. After editing a notebook, store it executed again with

    python tests/test_notebooks.py notebooks/05_edges.ipynb   # or no argument: every notebook

which runs it exactly as the test does (a temporary working directory) and writes the outputs back.

Timeouts allow for a slow machine and for nbclient's occasional 4 s wait on the iopub channel
(see shared/background/pymunk-rerun-notes.md §4); each notebook is meant to run in well under 20 s.
"""

from __future__ import annotations

import re
import shutil
import tempfile
import time
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipykernel")
from jupyter_client.manager import KernelManager  # noqa: E402 - after the importorskip guards
from nbclient.exceptions import CellExecutionError  # noqa: E402

NOTEBOOKS = sorted((Path(__file__).resolve().parent.parent / "notebooks").glob("*.ipynb"))
CELL_TIMEOUT_S = 120
"""Longest a single cell may run (generous: a stalled kernel, not a slow notebook, should trip it)."""
NOTEBOOK_BUDGET_S = 90
"""Longest a whole notebook may take, kernel start included (they are written for under 20 s)."""
RRD_LITERAL = re.compile(r"""["']([^"'\s]+\.rrd)["']""")


def _ids(path: Path) -> str:
    return path.stem


def promised_files(nb) -> list[str]:
    """The files a notebook says it writes: ``.rrd`` string literals in its code, plus ``plcsim.outputs``."""
    found: list[str] = []
    for cell in nb.cells:
        if cell.cell_type == "code":
            found += [f for f in RRD_LITERAL.findall(cell.source) if "{" not in f and not Path(f).is_absolute()]
    found += list(nb.metadata.get("plcsim", {}).get("outputs", []))
    return sorted(set(found))


def _error_text(index: int, output) -> str:
    tb = "\n".join(output.get("traceback", [])[-6:])
    tb = re.sub(r"\x1b\[[0-9;]*m", "", tb)  # the kernel colours its tracebacks
    return f"cell {index}: {output.get('ename')}: {output.get('evalue')}\n{tb}"


def execute(path: Path, workdir: Path):
    """Run a copy of the notebook in ``workdir``; return the executed notebook and the wall time."""
    copy = workdir / path.name
    shutil.copy(path, copy)
    nb = nbformat.read(copy, as_version=4)
    # The kernel's ZeroMQ sockets are files with the ipc transport. Their path must be absolute (a relative
    # one resolves against the kernel's working directory on one side and ours on the other) and short
    # (a Unix socket path has at most about 100 bytes), so they get a short directory of their own.
    sockets = Path(tempfile.mkdtemp(prefix="nbk-"))
    client = nbclient.NotebookClient(
        nb,
        km=KernelManager(kernel_name="python3", transport="ipc", ip=str(sockets / "ipc")),
        timeout=CELL_TIMEOUT_S,
        shutdown_kernel="immediate",
        resources={"metadata": {"path": str(workdir)}},
    )
    start = time.perf_counter()
    try:
        client.execute(cleanup_kc=True)  # we made the kernel manager, so nbclient would leave the kernel running
    except CellExecutionError as exc:
        pytest.fail(f"{path.name} raised while running:\n{_short(str(exc))}", pytrace=False)
    finally:
        shutil.rmtree(sockets, ignore_errors=True)
    elapsed = time.perf_counter() - start
    nbformat.write(nb, workdir / f"{path.stem}.executed.ipynb")  # kept in the tmp dir for a look after a failure
    return nb, elapsed


def _short(text: str, lines: int = 30) -> str:
    text = re.sub(r"\x1b\[[0-9;]*m", "", text)
    rows = text.splitlines()
    return "\n".join(rows if len(rows) <= lines else ["...", *rows[-lines:]])


def test_there_are_notebooks():
    assert NOTEBOOKS, "no notebooks found in notebooks/"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=_ids)
def test_notebook_is_committed_executed(path: Path):
    nb = nbformat.read(path, as_version=4)
    code = [cell for cell in nb.cells if cell.cell_type == "code"]
    counts = [cell.get("execution_count") for cell in code]
    assert counts == list(range(1, len(code) + 1)), (
        f"{path.name}: not stored executed top to bottom (execution counts {counts}); "
        f"run: python tests/test_notebooks.py notebooks/{path.name}"
    )
    outputs = [out for cell in code for out in cell.get("outputs", [])]
    assert not [out for out in outputs if out.get("output_type") == "error"], f"{path.name}: stored with an error"
    assert any("image/png" in out.get("data", {}) for out in outputs), f"{path.name}: stored without a figure"
    text = "\n".join(  # what a reader sees as text (base64 images hold '/tmp' by chance)
        str(out.get("text", "")) + "".join(str(v) for k, v in out.get("data", {}).items() if k.startswith("text/"))
        for out in outputs
    )
    leaked = [
        folder
        for folder in (tempfile.gettempdir(), str(Path.home()), str(NOTEBOOKS[0].parent.parent))
        if folder in text
    ]
    assert not leaked, f"{path.name}: its outputs name folders of the machine that ran it: {leaked}"
    kernel = nb.metadata.get("kernelspec", {}).get("name")
    assert kernel == "python3", f"{path.name}: kernelspec is {kernel!r}, expected 'python3'"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=_ids)
def test_notebook_runs(path: Path, tmp_path: Path, record_property):
    nb, elapsed = execute(path, tmp_path)
    record_property("seconds", round(elapsed, 2))
    print(f"{path.name}: {elapsed:.1f} s")

    errors = [
        _error_text(i, out)
        for i, cell in enumerate(nb.cells)
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
        if out.get("output_type") == "error"
    ]
    assert not errors, f"{path.name}: error outputs:\n" + "\n".join(errors)

    figures = sum(
        "image/png" in out.get("data", {})
        for cell in nb.cells
        if cell.cell_type == "code"
        for out in cell.get("outputs", [])
    )
    assert figures >= 1, f"{path.name}: no figure (image/png output); a notebook should show its point"

    missing = [f for f in promised_files(nb) if not (tmp_path / f).is_file() or (tmp_path / f).stat().st_size == 0]
    assert not missing, f"{path.name}: promised files not written (or empty): {missing}"

    assert elapsed < NOTEBOOK_BUDGET_S, f"{path.name} took {elapsed:.0f} s (budget {NOTEBOOK_BUDGET_S} s)"


def store_executed(paths: list[Path]) -> None:
    """Execute each notebook as :func:`test_notebook_runs` does and write it back with its outputs."""
    for path in paths:
        with tempfile.TemporaryDirectory(prefix="nb-") as workdir:
            nb, elapsed = execute(path.resolve(), Path(workdir))
        nb.metadata.pop("widgets", None)
        nbformat.write(nb, path)
        print(f"{path.name}: stored executed ({elapsed:.1f} s)")


if __name__ == "__main__":
    import sys

    store_executed([Path(arg) for arg in sys.argv[1:]] or NOTEBOOKS)
