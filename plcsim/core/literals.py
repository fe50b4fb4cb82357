"""Parse and format the literals of the S7 course: TIME, integer bases, dates.

Durations inside plcsim are integers: nanoseconds on the one clock (names end in ``_ns``) and
milliseconds for S7 ``TIME`` values, exactly as an S7-1200 stores them.
"""

from __future__ import annotations

import datetime as _dt
import re
from functools import lru_cache

from plcsim.core.errors import LiteralError

NS_PER_UNIT = {
    "d": 86_400_000_000_000,
    "h": 3_600_000_000_000,
    "m": 60_000_000_000,
    "min": 60_000_000_000,
    "s": 1_000_000_000,
    "ms": 1_000_000,
    "us": 1_000,
    "ns": 1,
}
_UNIT_ORDER = ["d", "h", "m", "s", "ms", "us", "ns"]
_COMPONENT = re.compile(r"(\d+(?:\.\d+)?)(ms|us|ns|min|d|h|m|s)")
_TIME_PREFIX = re.compile(r"^(?:L?T|L?TIME)#", re.IGNORECASE)


@lru_cache(maxsize=4096)
def duration_ns(text: str) -> int:
    """Parse a duration literal into integer nanoseconds.

    Accepts the IEC forms ``T#1s500ms``, ``T#-24d20h31m23s648ms``, ``LT#5us``, ``TIME#2h``
    and the short forms ``"10s"``, ``"1.5s"``, ``"250ms"``, ``"1 h 30 m"``. Units are
    d, h, m (or min), s, ms, us, ns; ``_`` separators and spaces are ignored.

    >>> duration_ns("T#1s500ms")
    1500000000
    >>> duration_ns("2ms")
    2000000
    """
    if not isinstance(text, str):
        raise LiteralError(f"a duration must be a string such as '10s' or 'T#1s500ms', not {text!r}")
    body = _TIME_PREFIX.sub("", text.strip()).replace("_", "").replace(" ", "").lower()
    sign = 1
    if body.startswith(("-", "+")):
        sign = -1 if body[0] == "-" else 1
        body = body[1:]
    if not body:
        raise LiteralError(f"empty duration {text!r}; write e.g. '10s', '500ms' or 'T#1s500ms'")
    total = 0
    pos = 0
    last_rank = -1
    for match in _COMPONENT.finditer(body):
        if match.start() != pos:
            break
        number, unit = match.groups()
        unit = "m" if unit == "min" else unit
        rank = _UNIT_ORDER.index(unit)
        if rank <= last_rank:
            raise LiteralError(f"duration {text!r}: unit {unit!r} is out of order; write units from days down to ns")
        last_rank = rank
        if "." in number:
            whole, frac = number.split(".")
            scale = NS_PER_UNIT[unit]
            total += int(whole) * scale + (int(frac) * scale) // (10 ** len(frac))
        else:
            total += int(number) * NS_PER_UNIT[unit]
        pos = match.end()
    if pos != len(body):
        raise LiteralError(
            f"cannot read duration {text!r}; write e.g. '10s', '500ms', '1.5s' or 'T#1s500ms' "
            f"(units: d, h, m, s, ms, us, ns)"
        )
    return sign * total


def to_ns(value: str | int, what: str = "duration") -> int:
    """Return ``value`` in nanoseconds: an int is already ns, a string is parsed as a duration."""
    if isinstance(value, bool):
        raise LiteralError(f"{what} must be a duration such as '10ms', not {value!r}")
    if isinstance(value, int):
        return value
    if isinstance(value, str):
        return duration_ns(value)
    raise LiteralError(f"{what} must be a duration string such as '10ms' or an int of ns, not {value!r}")


@lru_cache(maxsize=4096)
def time_ms(text: str) -> int:
    """Parse a TIME literal into the S7 representation, a signed count of milliseconds.

    >>> time_ms("T#1s500ms")
    1500
    >>> time_ms("10s")
    10000
    """
    ns = duration_ns(text)
    if ns % 1_000_000:
        raise LiteralError(f"TIME {text!r} has a fraction of a millisecond; TIME counts whole ms (use LTIME)")
    return ns // 1_000_000


def format_time_ms(ms: int) -> str:
    """Format an S7 TIME (ms) the way TIA Portal shows it.

    >>> format_time_ms(1500)
    'T#1s_500ms'
    >>> format_time_ms(0)
    'T#0ms'
    """
    sign = "-" if ms < 0 else ""
    rest = abs(ms)
    parts = []
    for unit, size in (("d", 86_400_000), ("h", 3_600_000), ("m", 60_000), ("s", 1000), ("ms", 1)):
        if rest >= size:
            parts.append(f"{rest // size}{unit}")
            rest %= size
    return f"T#{sign}{'_'.join(parts) or '0ms'}"


def format_ns(ns: int) -> str:
    """Format a duration in ns compactly for reports.

    >>> format_ns(10_001_000_000)
    '10.001 s'
    >>> format_ns(1_500_000)
    '1.5 ms'
    """
    if abs(ns) >= 1_000_000_000:
        return f"{ns / 1e9:.6g} s" if ns % 1_000_000 else f"{ns / 1e9:.10g} s"
    if abs(ns) >= 1_000_000:
        return f"{ns / 1e6:.6g} ms"
    if abs(ns) >= 1_000:
        return f"{ns / 1e3:.6g} us"
    return f"{ns} ns"


_INT_LITERAL = re.compile(
    r"^(?:(?P<type>[A-Z]+)#)?(?:(?P<base>2|8|16)#)?(?P<sign>[-+]?)(?P<digits>[0-9A-F_]+)$", re.IGNORECASE
)
_TYPED_PREFIX = {"B": "Byte", "W": "Word", "DW": "DWord", "LW": "LWord"}


def integer_literal(text: str) -> tuple[int, str | None]:
    """Parse an integer literal with an optional base and type prefix.

    Returns ``(value, type_name)``, the type name being ``None`` when the literal does not give one.

    >>> integer_literal("16#FFFF")
    (65535, None)
    >>> integer_literal("2#0000_0000_0000_1100")
    (12, None)
    >>> integer_literal("W#16#000C")
    (12, 'Word')
    """
    m = _INT_LITERAL.match(text.strip())
    if not m:
        raise LiteralError(f"cannot read integer {text!r}; write e.g. 65535, 16#FFFF, 2#1010, 8#177777, W#16#FF")
    base = int(m["base"] or 10)
    digits = m["digits"].replace("_", "")
    try:
        value = int(digits, base)
    except ValueError:
        raise LiteralError(f"{text!r}: {digits!r} are not base-{base} digits") from None
    if m["sign"] == "-":
        value = -value
    type_name = m["type"]
    if type_name is not None:
        type_name = _TYPED_PREFIX.get(type_name.upper(), type_name.upper())
    return value, type_name


_DATE_TIME = re.compile(
    r"^(?P<y>\d{4})-(?P<mo>\d{1,2})-(?P<d>\d{1,2})(?:-(?P<h>\d{1,2}):(?P<mi>\d{1,2}):(?P<s>\d{1,2})(?:\.(?P<f>\d{1,9}))?)?$"
)


def datetime_literal(text: str) -> tuple[_dt.datetime, int]:
    """Parse ``DTL#``/``DT#``/``D#`` literals into a naive datetime plus its nanoseconds.

    >>> datetime_literal("DTL#2022-01-25-14:49:17.016180")
    (datetime.datetime(2022, 1, 25, 14, 49, 17), 16180000)
    """
    body = re.sub(r"^(?:DTL|DT|DATE_AND_TIME|D|DATE)#", "", text.strip(), flags=re.IGNORECASE)
    m = _DATE_TIME.match(body)
    if not m:
        raise LiteralError(f"cannot read date/time {text!r}; write e.g. 'DTL#2022-01-25-14:49:17.016180'")
    frac = m["f"] or "0"
    nanos = int(frac.ljust(9, "0"))
    try:
        value = _dt.datetime(
            int(m["y"]), int(m["mo"]), int(m["d"]), int(m["h"] or 0), int(m["mi"] or 0), int(m["s"] or 0)
        )
    except ValueError as exc:
        raise LiteralError(f"date/time {text!r} is not a valid date: {exc}") from None
    return value, nanos
