"""Checks shared by the operating-hours meters 4.3.14 and 4.3.15 (computed from the trace)."""

from __future__ import annotations

import datetime as dt
from collections.abc import Callable

import numpy as np

from plcsim.check import Quantity, measure
from plcsim.literals import datetime_literal
from plcsim.trace import Trace

Meter = Callable[[Trace], np.ndarray]


def seconds_meter(tr: Trace) -> np.ndarray:
    """4.3.14: the meter is MOTOR.SEKUNDY."""
    return tr.column("MOTOR.SEKUNDY")


def hms_meter(tr: Trace) -> np.ndarray:
    """4.3.15: HODINY·3600 + MINUTY·60 + SEKUNDY."""
    return tr.column("MOTOR.HODINY") * 3600 + tr.column("MOTOR.MINUTY") * 60 + tr.column("MOTOR.SEKUNDY")


def _last_reset(tr: Trace) -> int:
    writes = [e.t_ns for e in tr.events_of("write", "MOTOR.NULUJ", "scenario")]
    return writes[-1] if writes else 0


def _row_after(tr: Trace, t_ns: int) -> int:
    """The first scan that saw something written at ``t_ns`` (an HMI write): the first starting after it."""
    return int(np.searchsorted(tr.times, t_ns, side="left"))


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
    """The meter at the end equals the seconds the belt ran since the last NULUJ, within 1 s per start."""

    def error(tr: Trace) -> float:
        reset = _last_reset(tr)
        seconds, starts = _belt_on_since(tr, reset)
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


def zero_after_reset(meter: Meter, *signals: str) -> Quantity:
    def value(tr: Trace) -> float | None:
        k = _row_after(tr, _last_reset(tr))
        return None if k >= len(tr) else float(meter(tr)[k])

    return (
        measure("the meter in the scan that saw NULUJ", value, "MOTOR.NULUJ", *signals)
        .equals(0)
        .named("NULUJ zeroes the meter in the same scan")
    )


def nuluj_resets_itself() -> Quantity:
    def value(tr: Trace) -> float | None:
        k = _row_after(tr, _last_reset(tr))
        return None if k >= len(tr) else float(tr.column("MOTOR.NULUJ")[k])

    return (
        measure("NULUJ at the end of the scan that saw it", value, "MOTOR.NULUJ")
        .equals(0)
        .named("NULUJ resets itself in the same scan")
    )


def stores_reset_time() -> Quantity:
    """DATUM_CAS holds the CPU's local date and time of the reset scan (RD_LOC_T)."""

    def error(tr: Trace) -> float | None:
        k = _row_after(tr, _last_reset(tr))
        if k >= len(tr):
            return None
        f = {
            name: int(tr.column(f"MOTOR.DATUM_CAS.{name}")[k])
            for name in ("YEAR", "MONTH", "DAY", "HOUR", "MINUTE", "SECOND", "NANOSECOND")
        }
        try:
            stored = dt.datetime(f["YEAR"], f["MONTH"], f["DAY"], f["HOUR"], f["MINUTE"], f["SECOND"])
        except ValueError:
            return float("inf")
        start, nanos = datetime_literal(tr.meta["rtc_start"])
        expected = start + dt.timedelta(microseconds=(nanos + int(tr.times[k])) // 1000)
        return abs((stored - expected).total_seconds() + f["NANOSECOND"] / 1e9)

    return (
        measure(
            "seconds between DATUM_CAS and the CPU's time of the reset", error, "MOTOR.NULUJ", "MOTOR.DATUM_CAS.SECOND"
        )
        .at_most(0.25)
        .named("NULUJ stores the date and time of the reset")
    )


def survives_power_cycle(meter: Meter, *signals: str) -> Quantity:
    """The meter and DATUM_CAS read the same just before and just after a power cycle."""

    def change(tr: Trace) -> float | None:
        cycles = [e.t_ns for e in tr.events_of("power_cycle", source="scenario")]
        if not cycles:
            return None
        k = _row_after(tr, cycles[0])
        if k == 0 or k >= len(tr):
            return None
        m = meter(tr)
        stamp = tr.column("MOTOR.DATUM_CAS.SECOND")
        return float(abs(m[k] - m[k - 1]) + abs(stamp[k] - stamp[k - 1]))

    return (
        measure("change of the meter and of DATUM_CAS across the power cycle", change, *signals)
        .equals(0)
        .named("the meter survives a power cycle (retain)")
    )
