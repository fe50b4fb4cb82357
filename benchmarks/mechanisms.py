"""Group ``mechanisms``: eight PLC836 step mechanisms, the same logic written three ways, on the S7 runtime.

Each of the eight sequences is started by its input ``S<k>``, switches ``Y<k>`` on, waits until ``A<k>``
holds (at most 1 s, else an error exit that switches ``Y<k>`` off), switches ``Y<k>`` off, waits while
``A<k>`` holds, and ends. Written as

* ``.mech`` (the chapter's text, :mod:`plcsim.frontends.mech`),
* the Python form (``MECHANISM()`` and a step per state),
* plain S7 Python: an Int step per sequence and an IEC timer for the time limit (the S7 figure).

Figures (best of ``--repeats`` runs, driven like the ``plc`` group through ``cpu.inputs`` on the same
input schedule): ``mechanisms_mech_scans_per_s`` and ``mechanisms_python_scans_per_s``, each with the plain
S7 figure of the same run (``s7_scans_per_s``) and the ratio to it (budget, issue 24: >= 0.5);
``load_1min`` is the machine's load when they were taken.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

from benchmarks.harness import Figure, Settings, drive, figure, measure, progress

COUNT = 8
MAX_S = 20.0


def mech_source() -> str:
    lines = ["EQUI D1,50 ;1 s"]
    for k in range(1, COUNT + 1):
        lines += [
            f"LDR S{k}",
            f"LO M{k}",
            f"WR M{k}",
            f"MECH_BEGIN M{k}",
            f"FL 1,Y{k}",
            f"LDR A{k}",
            f"TEX0 -,D1,E{k},1",
            f"FL 0,Y{k}",
            f"LDR A{k}",
            "EX1",
            f"JUM N{k}",
            f"E{k}: FL 0,Y{k}",
            f"N{k}:",
            f"MECH_END M{k}",
        ]
    return "\n".join(lines) + "\n"


def python_form_source() -> str:
    out = [f"M{k} = MECHANISM()" for k in range(1, COUNT + 1)]
    for k in range(1, COUNT + 1):
        out += [
            "",
            "",
            f"def m{k}(t):",
            f"    t.M{k}.ACTIVE = t.S{k} or t.M{k}.ACTIVE",
            f"    if t.M{k}.begin():",
            f"        if t.M{k}.step(1):",
            f"            t.Y{k} = True",
            f'            t.M{k}.wait_until(t.A{k}, timeout=1000, error="E", code=1)',
            f"        if t.M{k}.step(2):",
            f"            t.Y{k} = False",
            f"            t.M{k}.wait_while(t.A{k})",
            f'        if t.M{k}.error("E"):',
            f"            t.Y{k} = False",
            f"        t.M{k}.end()",
        ]
    out += ["", "", f"OB1 = [{', '.join(f'm{k}' for k in range(1, COUNT + 1))}]"]
    return "\n".join(out) + "\n"


def s7_source() -> str:
    out = []
    for k in range(1, COUNT + 1):
        out += [f"STEP{k} = Int(0)", f"T{k} = IEC_TIMER()"]
    for k in range(1, COUNT + 1):
        out += [
            "",
            "",
            f"def m{k}(t):",
            f"    if t.S{k} and t.STEP{k} == 0:",
            f"        t.STEP{k} = 1",
            f"    if t.STEP{k} == 1:",
            f"        t.Y{k} = True",
            f"        if t.A{k}:",
            f"            t.Y{k} = False",
            f"            t.STEP{k} = 2",
            f"    late = t.T{k}.TON(IN=t.STEP{k} == 1, PT=1000)",
            "    if late:",
            f"        t.Y{k} = False",
            f"        t.STEP{k} = 0",
            f"    if t.STEP{k} == 2 and not t.A{k}:",
            f"        t.STEP{k} = 0",
        ]
    out += ["", "", f"OB1 = [{', '.join(f'm{k}' for k in range(1, COUNT + 1))}]"]
    return "\n".join(out) + "\n"


def tags() -> dict[str, Any]:
    from plcsim import Tag

    found: dict[str, Any] = {}
    for k in range(COUNT):
        found[f"S{k + 1}"] = Tag(f"%I{k // 8}.{k % 8}")
        found[f"A{k + 1}"] = Tag(f"%I{2 + k // 8}.{k % 8}")
        found[f"Y{k + 1}"] = Tag(f"%Q{k // 8}.{k % 8}")
    return found


def schedule(n: int) -> list[dict[str, Any] | None]:
    """Starts every 50 scans, each sequence's condition on for a while and off again (some never: time-outs)."""
    sched: list[dict[str, Any] | None] = [None] * n
    for k in range(1, COUNT + 1):
        period = 40 + 7 * k
        for start in range(k, n, period * 30):
            for offset, changes in ((0, {f"S{k}": True}), (1, {f"S{k}": False})):
                if start + offset < n:
                    sched[start + offset] = {**(sched[start + offset] or {}), **changes}
            if k % 4:  # three of four sequences see their condition; the fourth times out after 1 s
                for offset, value in ((period, True), (2 * period, False)):
                    if start + offset < n:
                        sched[start + offset] = {**(sched[start + offset] or {}), f"A{k}": value}
    return sched


def new_cpu(source: str, mech: bool) -> Any:
    from plcsim import CPU
    from plcsim.frontends.mech import MechProgram

    program: Any = MechProgram(source, "bench.mech") if mech else source
    return CPU(tags=tags(), program=program)


def _rates(source: str, mech: bool, n: int, max_s: float, sched: list, repeats: int):
    def once(k: int, s: float) -> tuple[int, float]:
        cpu = new_cpu(source, mech)
        return drive(cpu.inputs.update, cpu.scan, sched, k, s)

    return measure(once, n, max_s, repeats)


def run(settings: Settings) -> Iterator[Figure]:
    n = settings.size(100_000, 2_000)
    max_s = settings.size(MAX_S, 2.0)
    sched = schedule(n)
    progress(f"mechanisms: 3 forms x {settings.repeats} x {n} scans")
    s7 = _rates(s7_source(), False, n, max_s, sched, settings.repeats)
    forms = (("mech", mech_source(), True), ("python", python_form_source(), False))
    load = round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None  # not on Windows
    for name, source, mech in forms:
        rates = _rates(source, mech, n, max_s, sched, settings.repeats)
        yield figure(
            f"mechanisms_{name}_scans_per_s",
            round(rates.best),
            "scans/s",
            median=round(rates.median),
            s7_scans_per_s=round(s7.best),
            ratio_to_s7=round(rates.best / s7.best, 3),
            budget_ratio=0.5,
            load_1min=load,
            stat="best",
            repeats=settings.repeats,
            scans=rates.best_scans,
            mechanisms=COUNT,
        )
