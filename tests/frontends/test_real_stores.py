"""Issue 29: a store into a REAL through the generated code's fast path against the conversion (hypothesis).

The rewrite stores a REAL whose value is a float within the REAL's range through a one-item ``array('f')``
(:data:`~plcsim.frontends.python.rewrite.REAL_STORE`), anything else through ``Real.coerce``; a constant is
converted once, at load. Every value a store can meet (floats of every kind: huge, subnormal, infinite, NaN with
any payload, -0.0, exact in single precision or not; ints of any size; a Bool) must give the bits, or the
error, that ``Real.coerce`` gives, into a tag of the root and into a member of a data block, in the merged
function and network by network.
"""

from __future__ import annotations

import dis
import struct

import hypothesis.strategies as st
import pytest
from hypothesis import example, given, settings

import plcsim.frontends.python.pipeline
import plcsim.frontends.python.rewrite
from plcsim import CPU, Tag
from plcsim.core.errors import PlcTypeError
from plcsim.tags.types import FLOAT32_MAX, LReal, Real

STORES = """
R = Real(0.0)
V = LReal(0.0)
D = DB(r=Real(0.0))


def into_root(t):
    t.R = t.V


def into_block(t):
    t.D.r = t.V


OB1 = [into_root, into_block]
"""
EDGES = [
    0.0,
    -0.0,
    0.1,
    1.0,
    2.5,
    16777217.0,  # 2**24 + 1: no REAL, rounds to even
    FLOAT32_MAX,
    -FLOAT32_MAX,
    FLOAT32_MAX * (1 + 2**-25),  # beyond the largest REAL but rounds down to it
    FLOAT32_MAX * (1 + 2**-24),  # half an ulp beyond: rounds to even, the infinity
    1e39,
    -1e300,
    1.4e-45,  # the smallest subnormal REAL
    7e-46,  # just under half of it: rounds to 0
    -1e-300,  # to -0.0
    float("inf"),
    float("-inf"),
    float("nan"),
    struct.unpack("<d", struct.pack("<Q", 0x7FF0_0000_0000_0001))[0],  # a signalling NaN
    struct.unpack("<d", struct.pack("<Q", 0xFFF8_1234_5678_9ABC))[0],  # a negative NaN with a payload
]
"""The values at the edges of single precision, with NaNs whose bits the conversion keeps its own way."""
NUMBERS = st.one_of(
    st.sampled_from(EDGES),
    st.floats(),
    st.floats(width=32),
    st.integers(0, 2**64 - 1).map(lambda bits: struct.unpack("<d", struct.pack("<Q", bits))[0]),
    st.integers(-(2**1100), 2**1100),  # beyond a double: the conversion's OverflowError
    st.booleans(),  # no number for a REAL: the conversion's error
)


def _bits(value: object) -> object:
    return struct.pack("<d", value) if isinstance(value, float) else value


def _converted(value: object) -> object:
    """What ``Real.coerce`` makes of ``value``: the bits of the float, or the error's type and message."""
    try:
        return _bits(Real.coerce(value, "R"))
    except (PlcTypeError, OverflowError) as exc:
        return type(exc), str(exc)


def _stored(cpu: CPU, value: object) -> tuple[object, object]:
    """``value`` put into V as it is (whatever its class: the store's own checks decide), one scan: the bits
    of R and D.r, or the error that stopped the CPU."""
    cpu.t.__dict__["V"] = value
    before = len(cpu.diagnostics)
    cpu.scan()
    if cpu.mode != "RUN":
        message = "\n".join(d.message for d in list(cpu.diagnostics)[before:])
        cpu.stop()
        cpu.start()
        return message, message
    return _bits(cpu.t.__dict__["R"]), _bits(cpu.t.__dict__["D"].__dict__["r"])


def _expected(value: object) -> object:
    converted = _converted(value)
    if isinstance(converted, tuple):  # the CPU stops with the conversion's message at the first store
        return converted
    return converted, converted


def _cpus() -> dict[str, CPU]:
    """The CPU with :data:`STORES` merged and network by network."""
    cpus = {}
    for way, limit in (("merged", 5000), ("by network", 0)):
        with pytest.MonkeyPatch.context() as monkeypatch:
            monkeypatch.setattr(plcsim.frontends.python.pipeline, "MAX_MERGED_STATEMENTS", limit)
            cpus[way] = CPU(tags={}, program=STORES)
    assert cpus["merged"]._ob1.merged is not None and cpus["by network"]._ob1.merged is None
    return cpus


def _agrees(got: tuple[object, object], expected: object) -> bool:
    if isinstance(expected, tuple) and isinstance(expected[0], type):  # an error, at the first store's line
        return all(isinstance(g, str) and "(into_root), line 8: " in g and expected[1] in g for g in got)
    return got == expected


@pytest.fixture(scope="module")
def cpus() -> dict[str, CPU]:
    return _cpus()


@settings(max_examples=400, deadline=None)
@given(value=NUMBERS)
@example(value=0.1)
@example(value=2**24 + 1)
@example(value=10**400)
@example(value=True)
def test_a_real_store_gives_what_the_conversion_gives(cpus, value: object) -> None:
    expected = _expected(value)
    for way, cpu in cpus.items():
        got = _stored(cpu, value)
        assert _agrees(got, expected), f"{way}: {value!r} stored as {got}, the conversion gives {expected}"


def test_the_comparison_catches_a_store_that_does_not_round(monkeypatch):
    """The same check on a store that keeps the double (the rounding lines taken out) fails on 0.1 and on an
    overflow: the test above can fail."""
    unrounded = "\n".join(
        line
        for line in plcsim.frontends.python.rewrite.REAL_STORE.splitlines()
        if "_f32" not in line and not line.startswith(("if ", "else", "    _real = CONVERT"))
    )
    assert "CONVERT" not in unrounded and "TARGET = _real" in unrounded
    monkeypatch.setattr(plcsim.frontends.python.rewrite, "REAL_STORE", unrounded)
    cpus = _cpus()
    for value in (0.1, 1e39, 2.5):
        results = [_agrees(_stored(cpu, value), _expected(value)) for cpu in cpus.values()]
        assert results == ([True, True] if value == 2.5 else [False, False]), value


CONSTANTS = """
R = Real(0.0)
S = Real(0.0)
Z = Real(1.0)
BIG = Real(0.0)
I = Int(0)
W = Time(0)
D = DB(r=Real(0.0), k=Int(0))


def first(t):
    t.R = 0.1
    t.S = 16777217
    t.Z = -0.0


def second(t):
    t.BIG = 1e39
    t.I = 40000
    t.W = "1s500ms"
    t.D.r = 1e-46
    t.D.k = 2.6


OB1 = [first, second]
"""


def test_a_constant_is_converted_at_load_to_what_each_store_would_convert_it_to():
    cpu = CPU(tags={}, program=CONSTANTS)
    names = {i.argval for i in dis.get_instructions(cpu._ob1.merged) if i.opname in ("LOAD_GLOBAL", "LOAD_NAME")}
    assert not {n for n in names if str(n).startswith("_to_")}  # no conversion left to run
    cpu.scan()
    d = cpu.t.__dict__
    assert _bits(d["R"]) == _bits(Real.coerce(0.1)) and d["R"] != 0.1
    assert d["S"] == 16777216.0 and _bits(d["Z"]) == _bits(-0.0) and d["BIG"] == float("inf")
    assert d["I"] == 40000 - 65536 and d["W"] == 1500
    assert _bits(d["D"].__dict__["r"]) == _bits(0.0) and d["D"].__dict__["k"] == 3


def test_a_bool_stored_into_a_real_stops_the_cpu_naming_the_store():
    cpu = CPU(
        tags={"B": Tag("%I0.0")}, program="R = Real(0.0)\nD = DB(r=Real(0.0))\n\n\ndef OB1(t):\n    t.D.r = t.B\n"
    )
    cpu.scan()
    assert cpu.mode == "STOP"
    assert any("D.r is Real; cannot store bool False" in d.message for d in cpu.diagnostics)


def test_an_lreal_store_is_not_rounded_to_single():
    cpu = CPU(tags={}, program="L = LReal(0.0)\nV = LReal(0.1)\n\n\ndef OB1(t):\n    t.L = t.V + 0.0\n")
    cpu.scan()
    assert cpu.t.L == LReal.coerce(0.1) == 0.1
