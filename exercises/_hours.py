"""Checks shared by the operating-hours meters 4.3.14 and 4.3.15 (computed from the trace).

Every reset is judged in the execution that handled it: the first row, among those ending after the
HMI write of NULUJ, in which NULUJ is FALSE again. It is the scan that saw the write (the first one of
its task starting at or after it), or the scan the write fell into, if a later network of that scan
already read it (with an OB30 pre-empting OB1 between networks). Rows are taken in the trace's order
(end times), so a program with an OB30 is judged like one without.
"""

from __future__ import annotations

import datetime as dt
from collections.abc import Callable

import numpy as np

from plcsim.check import Quantity, measure
from plcsim.core.literals import datetime_literal, format_ns, to_ns
from plcsim.scenario import Action, write
from plcsim.trace import Trace

Meter = Callable[[Trace], np.ndarray]
DTL_FIELDS = ("YEAR", "MONTH", "DAY", "HOUR", "MINUTE", "SECOND", "NANOSECOND")


def resets_in_every_phase(start: str, cycle: str = "100ms") -> list[Action]:
    """NULUJ written ten times, 3 s + one cycle apart, each at a random instant inside its own tenth of
    the second: whatever the phase of the scans against Clock_1Hz, one write is read by the scan that
    also sees the 1 s pulse, so a program that counts after it resets shows 1 s in the reset scan.

    >>> [a.t.lo_ns % 1_000_000_000 // 1_000_000 for a in resets_in_every_phase("30s")]
    [10, 110, 210, 310, 410, 510, 610, 710, 810, 910]
    """
    t0, step = to_ns(start), to_ns(cycle)
    out = []
    for j in range(10):
        at = t0 + j * (3_000_000_000 + step)
        out.append(write("MOTOR.NULUJ", True, t=f"{format_ns(at + step // 10)}..{format_ns(at + step * 9 // 10)}"))
    return out


def seconds_meter(tr: Trace) -> np.ndarray:
    """4.3.14: the meter is MOTOR.SEKUNDY."""
    return tr.column("MOTOR.SEKUNDY")


def hms_meter(tr: Trace) -> np.ndarray:
    """4.3.15: HODINY·3600 + MINUTY·60 + SEKUNDY."""
    return tr.column("MOTOR.HODINY") * 3600 + tr.column("MOTOR.MINUTY") * 60 + tr.column("MOTOR.SEKUNDY")


def _resets(tr: Trace) -> list[int]:
    """The times of the scenario's writes of NULUJ."""
    return [e.t_ns for e in tr.events_of("write", "MOTOR.NULUJ", "scenario")]


def _handler(tr: Trace, write_ns: int, before_ns: int | None = None) -> int | None:
    """The row of the execution that handled a NULUJ written at ``write_ns``: the first row ending after
    it in which NULUJ is FALSE (before the next write, if given), or the execution that row pre-empted;
    None if NULUJ stayed TRUE."""
    ends = tr.end_times
    window = ends > write_ns
    if before_ns is not None:
        window &= ends <= before_ns
    rows = np.flatnonzero(window & ~tr.column("MOTOR.NULUJ"))
    if not len(rows):
        return None
    k = int(rows[0])
    # an interrupt call inside a scan is recorded first: the scan around it is the one judged
    around = np.flatnonzero((np.arange(len(ends)) > k) & (tr.times <= tr.times[k]) & (tr.tasks != tr.tasks[k]))
    return int(around[-1]) if len(around) else k


def _handlers(tr: Trace) -> list[tuple[int, int | None]]:
    """Each NULUJ write with the row that handled it."""
    writes = _resets(tr)
    return [(w, _handler(tr, w, nxt)) for w, nxt in zip(writes, [*writes[1:], None])]


def _belt_on_since(tr: Trace, start: int) -> tuple[float, int]:
    end = int(tr.meta.get("end_ns") or tr.end_times[-1])
    total, count = 0, 0
    for on, off in tr.intervals("D1"):
        off = end if off is None else off
        lo, hi = max(on, start), min(off, end)
        if hi > lo:
            total += hi - lo
            count += 1
    return total / 1e9, count


def counts_running_seconds(meter: Meter, *signals: str) -> Quantity:
    """The meter at the end equals the seconds the belt ran since the last reset, within 1 s per start.

    The count starts at the end of the scan that zeroed the meter (the scan that saw NULUJ), not at the
    HMI write: the program cannot count before it has read the write."""

    def error(tr: Trace) -> float | None:
        handled = _handlers(tr)
        start = 0
        if handled:
            k = handled[-1][1]
            if k is None:
                return None
            start = int(tr.end_times[k])
        seconds, starts = _belt_on_since(tr, start)
        return abs(float(meter(tr)[-1]) - seconds) - max(1, starts)

    return (
        measure(
            "seconds by which the meter misses the belt's running time since NULUJ (1 s allowed per start)",
            error,
            "D1",
            *signals,
        )
        .at_most(0)
        .named("the meter counts the seconds the belt ran")
    )


def still_while_off(meter: Meter, *signals: str) -> Quantity:
    """No scan with the belt off (before and after) adds to the meter."""

    def increments(tr: Trace) -> float:
        m = meter(tr)
        d1 = tr.column("D1")
        added = (m[1:] > m[:-1]) & ~d1[1:] & ~d1[:-1]
        return float(added.sum())

    return (
        measure("scans in which the meter grew while the belt was off", increments, "D1", *signals)
        .equals(0)
        .named("the meter stands still while the belt is off")
    )


def _nested(tr: Trace, k: int) -> int:
    """How many executions of other tasks ran inside the execution of row ``k`` (interrupt calls that
    pre-empted it, each with its own row)."""
    inside = (tr.tasks != tr.tasks[k]) & (tr.times >= tr.times[k]) & (tr.end_times <= tr.end_times[k])
    return int(np.count_nonzero(inside))


def zero_after_reset(meter: Meter, *signals: str) -> Quantity:
    """At the end of the scan that handled each NULUJ the meter is 0: the scan adds nothing after the
    reset. An interrupt that pre-empts that scan after the reset may count its own second (one each)."""

    def values(tr: Trace) -> list[float | None] | None:
        m = meter(tr)
        out: list[float | None] = []
        for _, k in _handlers(tr):
            out.append(None if k is None else float(m[k] - min(m[k], _nested(tr, k))))
        return out or None

    return (
        measure(
            "the meter at the end of the scan that handled NULUJ (less 1 s per interrupt call inside that scan)",
            values,
            "MOTOR.NULUJ",
            *signals,
        )
        .equals(0)
        .named("NULUJ zeroes the meter in the same scan")
    )


def nuluj_resets_itself() -> Quantity:
    """NULUJ is FALSE at the end of the scan that saw it: the first execution of the handling task that
    started at or after the write (or the one the write fell into) handled it."""

    def late_scans(tr: Trace) -> list[float]:
        out = []
        for w, k in _handlers(tr):
            task = int(tr.tasks[k]) if k is not None else 1
            rows = tr.rows_of(task)
            saw = rows[(tr.times[rows] >= w) & (rows < (k if k is not None else len(tr)))]
            out.append(float(len(saw)))
        return out

    return (
        measure("scans that saw NULUJ and left it TRUE", late_scans, "MOTOR.NULUJ")
        .equals(0)
        .named("NULUJ resets itself in the same scan")
    )


def stores_reset_time() -> Quantity:
    """DATUM_CAS holds the CPU's local date and time of the scan that handled NULUJ (RD_LOC_T), ±1 scan."""

    def errors(tr: Trace) -> list[float | None] | None:
        start, nanos = datetime_literal(tr.meta["rtc_start"])
        out: list[float | None] = []
        for _, k in _handlers(tr):
            if k is None:
                out.append(None)
                continue
            f = {name: int(tr.column(f"MOTOR.DATUM_CAS.{name}")[k]) for name in DTL_FIELDS}
            try:
                stored = dt.datetime(f["YEAR"], f["MONTH"], f["DAY"], f["HOUR"], f["MINUTE"], f["SECOND"])
            except ValueError:
                out.append(float("inf"))
                continue
            # the CPU's time as simulated ns: the same origin as the row times
            at = round((stored - start).total_seconds()) * 1_000_000_000 + f["NANOSECOND"] - nanos
            lo, hi = int(tr.times[k]), int(tr.end_times[k])
            out.append(float(max(lo - at, at - hi, 0)))
        return out or None

    return (
        measure(
            "time between DATUM_CAS and the scan that handled NULUJ",
            errors,
            "MOTOR.NULUJ",
            "MOTOR.DATUM_CAS.SECOND",
            unit="ns",
        )
        .at_most("1 scan")
        .named("NULUJ stores the date and time of the reset")
    )


def survives_power_cycle(meter: Meter, *signals: str) -> Quantity:
    """The meter and DATUM_CAS read the same at the power cut (the last row ending by then: a scan the
    cut interrupted has its row) and in the first execution after the restart."""

    def change(tr: Trace) -> float | None:
        cycles = [e.t_ns for e in tr.events_of("power_cycle", source="scenario")]
        if not cycles:
            return None
        before = np.flatnonzero(tr.end_times <= cycles[0])
        after = np.flatnonzero(tr.times >= cycles[0])
        if not len(before) or not len(after):
            return None
        k0, k1 = int(before[-1]), int(after[0])
        m = meter(tr)
        stamp = sum(np.abs(tr.column(f"MOTOR.DATUM_CAS.{name}")[[k0, k1]] @ [1, -1]) for name in DTL_FIELDS)
        return float(abs(m[k1] - m[k0]) + stamp)

    return (
        measure("change of the meter and of DATUM_CAS across the power cycle", change, *signals)
        .equals(0)
        .named("the meter survives a power cycle (retain)")
    )
