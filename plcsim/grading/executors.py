"""Where a batch is graded: a :class:`concurrent.futures.Executor` named by ``plcsim grade --executor``.

Every executor runs the same task (:func:`plcsim.grading.batch.grade_task`): one submission, graded in a
fresh confined child process that it starts and waits on, the checks evaluated in the task's own
process. The executors differ only in where that task runs:

``local`` (the default)
    ``jobs`` threads of this process. A thread only starts its child (``subprocess``, never
    ``os.fork``), waits on its pipe and evaluates the checks, so threads are enough.
``dask``
    A Dask distributed ``LocalCluster`` of ``jobs`` worker processes on this machine (started with
    ``spawn``, one thread each), torn down afterwards with the temporary folder its workers use (so
    that a worker killed mid-grade leaves nothing behind).
``dask://host:port`` or ``tcp://host:port``
    The scheduler of an existing Dask cluster (``dask scheduler`` and ``dask worker`` on the
    machines). Its workers need plcsim at the same version, and the submissions, the exercise and
    the output folders at the same paths (a shared filesystem).

Dask distributed rather than Ray: it is a pure-Python wheel that installs from PyPI on Windows,
macOS and Linux alike, its ``LocalCluster`` tests the whole path on one machine, and its ``Client``
already is a ``concurrent.futures`` executor (``Client.get_executor``), so the batch code knows no
Dask at all.

>>> parse_executor("tcp://10.0.0.5:8786"), parse_executor("dask://head:8786"), parse_executor("local")
(('scheduler', 'tcp://10.0.0.5:8786'), ('scheduler', 'tcp://head:8786'), ('local', None))
>>> parse_executor("ray")
Traceback (most recent call last):
...
plcsim.core.errors.ConfigurationError: unknown executor 'ray': use local, dask, or dask://HOST:PORT ...
"""

from __future__ import annotations

import contextlib
import tempfile
from collections.abc import Iterator
from concurrent.futures import Executor, ThreadPoolExecutor
from typing import Any

from plcsim.core import version
from plcsim.core.errors import ConfigurationError

LOCAL, DASK, SCHEDULER = "local", "dask", "scheduler"
CONNECT_TIMEOUT_S = 30
"""How long to wait for an existing scheduler to answer."""


def parse_executor(spec: str) -> tuple[str, str | None]:
    """The kind of executor ``spec`` names (local, dask, scheduler) and, for a scheduler, its address."""
    text = spec.strip()
    if text in (LOCAL, DASK):
        return text, None
    for scheme in ("dask://", "tcp://", "tls://"):
        if text.startswith(scheme) and len(text) > len(scheme):
            address = text[len(scheme) :]
            return SCHEDULER, f"{'tls' if scheme == 'tls://' else 'tcp'}://{address}"
    raise ConfigurationError(
        f"unknown executor {spec!r}: use local, dask, or dask://HOST:PORT (tcp://HOST:PORT) for the scheduler "
        f"of an existing Dask cluster (--executor dask://head-node:8786)"
    )


@contextlib.contextmanager
def open_executor(spec: str = LOCAL, *, jobs: int = 1) -> Iterator[Executor]:
    """The executor ``spec`` names, open for the ``with`` block and shut down after it.

    ``jobs`` is the number of threads (local) or worker processes (dask); an existing cluster has
    the workers it has."""
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ConfigurationError(f"--jobs must be a whole number of at least 1, got {jobs!r}")
    kind, address = parse_executor(spec)
    if kind == LOCAL:
        with ThreadPoolExecutor(max_workers=jobs, thread_name_prefix="plcsim-grade") as pool:
            yield pool
        return
    distributed = _distributed()
    with contextlib.ExitStack() as stack:
        if kind == DASK:
            # the workers' temporary folder is ours: a killed worker's leftovers go with the cluster
            folder = tempfile.TemporaryDirectory(prefix="plcsim-dask-", ignore_cleanup_errors=True)
            scratch = stack.enter_context(folder)
            cluster = stack.enter_context(
                distributed.LocalCluster(
                    n_workers=jobs,
                    threads_per_worker=1,
                    processes=True,
                    host="127.0.0.1",
                    dashboard_address=None,
                    local_directory=scratch,
                    env=dict.fromkeys(("TMPDIR", "TEMP", "TMP"), scratch),
                )
            )
            client = stack.enter_context(distributed.Client(cluster))
        else:
            try:
                client = stack.enter_context(distributed.Client(address, timeout=CONNECT_TIMEOUT_S))
            except OSError as exc:  # the scheduler did not answer in time
                raise ConfigurationError(
                    f"cannot reach the Dask scheduler at {address}: {exc}; is `dask scheduler` running there?"
                ) from None
        _check_workers(client)
        executor = client.get_executor(pure=False)  # every grade is its own task, never merged with another
        try:
            yield executor
        finally:
            executor.shutdown(wait=False)


def _check_workers(client: Any) -> None:
    """Load the grader on every worker now (in parallel, instead of in each worker's first task) and
    refuse a cluster whose workers run another plcsim version than this one."""

    versions = client.run(worker_version)
    other = {worker: theirs for worker, theirs in versions.items() if theirs != version.__version__}
    if other:
        raise ConfigurationError(
            f"the Dask workers {', '.join(sorted(other))} run plcsim {', '.join(sorted(set(other.values())))}, "
            f"this grader {version.__version__}: install the same plcsim on every worker"
        )


def worker_version() -> str:
    """Run on a worker: import the grading code (for its cost, before the first task) and say which
    plcsim it is."""
    import importlib

    importlib.import_module("plcsim.grading.sandbox.parent")
    return importlib.import_module("plcsim.core.version").__version__


def _distributed() -> Any:
    """The ``distributed`` module, imported only when a Dask executor is asked for."""
    try:
        import distributed
    except ImportError:
        raise ConfigurationError("the dask executor needs Dask distributed: pip install 'plcsim[cluster]'") from None
    return distributed
