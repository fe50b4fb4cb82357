"""plcsim benchmarks: ``python -m benchmarks`` prints one JSON line per figure.

Each line is ``{"figure": name, "value": number|bool|null, "unit": ..., **context}`` so that a figure can be
compared run to run (design.md, "Performance budgets"). Performance is measured here, never by timed tests.

Groups (one module each, registered in :mod:`benchmarks.__main__`):

* ``plc`` (:mod:`benchmarks.plc`): plcsim alone on the 25-network workload, and the compile time.
* ``pyrung`` (:mod:`benchmarks.pyrung_peer`): the same ladder logic on pyrung, in the same process.
* ``inlined`` (:mod:`benchmarks.inlined`): the same 25 networks hand-inlined into one Python function, the ceiling.
* ``equivalence`` (:mod:`benchmarks.equivalence`): plcsim against a hand-written reference, scan by scan.

The workload (25 networks, input schedule) is in :mod:`benchmarks.workload`; timing and output helpers
in :mod:`benchmarks.harness`.
"""
