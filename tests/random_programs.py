"""Random programs of the subset for the differential tests of the S7 CPU's fast paths (hypothesis).

One generator for the tests that run a program two ways and compare every trace row: the written-out boxes
and the tags as locals of a task's merged function (tests/frontends/test_inline_differential.py) and the
fused scan (tests/controllers/s7/test_fused.py). A :class:`Vocabulary` says what a test's programs may use
beyond the common core (seal-ins, set/reset coils, TON/TOF and their Q and ET, a CTU, -|P|- contacts, INT
arithmetic that wraps, a division that may fail, tags read several times, which the merged function keeps
in locals).
"""

from __future__ import annotations

from dataclasses import dataclass

import hypothesis.strategies as st

from plcsim import Int, Tag

INPUTS = [f"I{k}" for k in range(4)]
OUTPUTS = [f"Q{k}" for k in range(4)]
WORDS = ["M0", "M1"]
TIMERS = ["T0", "T1"]

HELPERS = """

def bump(t):
    t.M0 = t.M0 + 1


def add(t, n):
    t.M1 = t.M1 + n
    return t.M1 > 100


def light(t):
    t.Q3 = t.M0 > t.M1
"""
"""The program's own functions (FCs) the ``calls`` statements call: each stores into tags that the networks
around the call read, so a merged function must read them again after it."""


def tags() -> dict[str, Tag]:
    """I0..I3 and Q0..Q3 on bits, two INT words on %MW10 and %MW12."""
    table = {name: Tag(f"%I0.{k}") for k, name in enumerate(INPUTS)}
    table.update({name: Tag(f"%Q0.{k}") for k, name in enumerate(OUTPUTS)})
    table.update({name: Tag(f"%MW{10 + 2 * k}", Int) for k, name in enumerate(WORDS)})
    return table


@dataclass(frozen=True)
class Vocabulary:
    """What a test's programs may use beyond the common core."""

    leaves: tuple[str, ...] = ()
    """More Bool operands (``t.Clock_10Hz`` of the clock memory byte)."""
    compare: tuple[str, ...] = ("<", ">=")
    edges: tuple[str, ...] = ("E0",)
    """The edge memory bits (declared Bool by the program)."""
    max_ms: int = 9
    modulus: int = 9
    """The divisor of the failing division is ``t.Mk % modulus``."""
    more_boxes: bool = False
    """A TON as the test of an ``if``, a CTU without R, N edges, a write of a timer's PT."""
    jumps: bool = False
    """``JMP("last")`` to the last network."""
    calls: bool = False
    """Calls of :data:`HELPERS` and of MOVE, loops (run the CPU with a small ``watchdog_iterations``), typed
    stores and boxes that refuse an INT."""
    interrupt: bool = False
    """Now and then an OB30 that pre-empts OB1 between its networks."""
    blocks: bool = False
    """A data block ``D`` (:data:`BLOCK`): -|P|- and -|N|- on its bits, REAL arithmetic that rounds, overflows to an
    infinity and makes a NaN, constants stored into it, a REAL stored into an INT (a NaN or an infinity refused);
    now and then a network names it by a local, ``d = t.D`` (the merged function reads and writes ``d.X`` as
    ``t.D.X``), or by a local bound again in a branch (which stays a local)."""


BLOCK = "D = DB(r=Real(0.0), f=Bool(False), e0=Bool(False), e1=Bool(False), k=Int(0))"
"""The data block of :attr:`Vocabulary.blocks`."""


def bool_expr(vocabulary: Vocabulary, depth: int = 2) -> st.SearchStrategy[str]:
    leaves = st.one_of(
        st.sampled_from([f"t.{n}" for n in INPUTS + OUTPUTS] + list(vocabulary.leaves)),
        st.sampled_from([f"t.{n}.Q" for n in TIMERS] + ["t.C0.QU"]),
        st.builds(
            lambda w, op, n: f"t.{w} {op} {n}",
            st.sampled_from(WORDS),
            st.sampled_from(vocabulary.compare),
            st.integers(-5, 40),
        ),
    )
    if depth == 0:
        return leaves
    inner = bool_expr(vocabulary, depth - 1)
    return st.one_of(
        leaves,
        st.builds(lambda a: f"not ({a})", inner),
        st.builds(lambda a, op, b: f"({a}) {op} ({b})", inner, st.sampled_from(["and", "or"]), inner),
    )


def statement(v: Vocabulary) -> st.SearchStrategy[list[str]]:
    """One statement of a network, as its lines."""
    q, w, tm, e = (st.sampled_from(x) for x in (OUTPUTS, WORDS, TIMERS, v.edges))
    b = bool_expr(v)
    ms = st.integers(1, v.max_ms).map(lambda n: f'"{n}ms"')
    kinds = [
        st.builds(lambda q, x: [f"t.{q} = {x}"], q, b),
        st.builds(lambda x, q, val: [f"if {x}:", f"    t.{q} = {val}"], b, q, st.booleans()),
        st.builds(
            lambda tm, box, x, pt: [f"t.{tm}.{box}(IN={x}, PT={pt})"], tm, st.sampled_from(["TON", "TOF"]), b, ms
        ),
        st.builds(lambda w, tm: [f"t.{w} = t.{tm}.ET"], w, tm),
        st.builds(
            lambda x, r, pv, q: [f"if t.C0.CTU(CU={x}, R={r}, PV={pv}):", f"    t.{q} = True"],
            b,
            b,
            st.integers(1, 4),
            q,
        ),
        st.builds(lambda x, e, w: [f"if P({x}, {e!r}):", f"    t.{w} = t.{w} * 300 + 7"], b, e, w),
        st.builds(lambda w, v2, n: [f"t.{w} = t.{v2} + {n}"], w, st.sampled_from(WORDS), st.integers(-3, 30_000)),
        st.builds(lambda w, v2: [f"t.{w} = 1000 // (t.{v2} % {v.modulus})"], w, st.sampled_from(WORDS)),
        st.builds(  # one tag read several times: the merged function reads it into a local
            lambda q, w, a, c: [f"t.{q} = t.{w} > {a} and t.{w} < {a + 9} and t.{w} != {c} or t.{w} == {c + 1}"],
            q,
            w,
            st.integers(-3, 20),
            st.integers(-3, 20),
        ),
        st.builds(
            lambda w, q: [f"t.{w} = t.{w} + 1", f"t.{q} = t.{w} > 3", f"if t.{w} > 5:", f"    t.{w} = t.{w} - 6"], w, q
        ),
    ]
    if v.more_boxes:
        kinds += [
            st.builds(
                lambda tm, x, pt, q: [f"if t.{tm}.TON(IN={x}, PT={pt}):", f"    t.{q} = not t.{q}"], tm, b, ms, q
            ),
            st.builds(lambda tm, pt: [f"t.{tm}.PT = {pt}"], tm, ms),  # a read after it refreshes with this PT
            st.builds(lambda x, r: [f"t.C0.CTU(R={r}, CU={x}, PV=3)"], b, b),
            st.builds(lambda x, e, q: [f"edge = N({x}, {e!r})", f"t.{q} = edge"], b, e, q),
        ]
    if v.blocks:
        real = st.sampled_from(["0.1", "-0.0", "1e39", "16777217", "2.5", "t.D.r * 1.5", "t.D.r - t.D.r * 2.0"])
        kinds += [
            st.builds(lambda x: [f'if P({x}, "D.e0"):', "    t.D.r = t.D.r + 0.5"], b),
            st.builds(lambda x, q: [f'edge = N({x}, "D.e1")', f"t.{q} = edge"], b, q),
            st.builds(lambda x: [f"t.D.f = {x}"], b),
            st.builds(lambda q, n: [f"t.{q} = t.D.f and t.D.r > {n} or t.D.r != t.D.r"], q, st.integers(-3, 40)),
            st.builds(lambda w: [f"t.D.r = t.D.r * 1.1 - t.{w} / 3"], w),  # rounds; grows to an infinity
            st.builds(lambda value: [f"t.D.r = {value}"], real),  # a NaN from the infinity minus itself
            st.builds(lambda w: ["t.D.k = t.D.r", f"t.{w} = t.D.k + 1"], w),  # a NaN or an infinity is refused
        ]
    if v.jumps:
        kinds.append(st.builds(lambda x: [f"if {x}:", '    JMP("last")'], b))
    if v.calls:
        kinds += [
            st.just(["bump(t)"]),
            st.builds(lambda n, q: [f"t.{q} = add(t, {n})"], st.integers(-20, 400), q),
            st.builds(lambda x: [f"if {x}:", "    light(t)"], b),
            st.builds(lambda w, q: [f"MOVE(t.{w} > 2, t.{q})"], w, q),
            st.builds(lambda w: ["for k in range(3):", f"    t.{w} = t.{w} * 7 + k"], w),  # wraps, with a tick
            st.builds(lambda w: [f"while t.{w} > 20:", f"    t.{w} = t.{w} + 1"], w),  # the watchdog stops it
            st.builds(lambda q, w: [f"t.{q} = t.{w}"], q, w),  # an INT into a BOOL: a type error at run time
            st.builds(lambda tm, w: [f"t.{tm}.TON(IN=t.{w}, PT=3)"], tm, w),  # a box refusing an INT for IN
        ]
    return st.one_of(kinds)


@st.composite
def programs(draw: st.DrawFn, vocabulary: Vocabulary) -> str:
    """A program of 2 to 5 networks in OB1 (the last one labelled "last"), with the declarations it needs."""
    v = vocabulary
    lines = [f"{name} = IEC_TIMER()" for name in TIMERS] + ["C0 = IEC_COUNTER()"]
    lines += [f"{name} = Bool()" for name in v.edges]
    if v.blocks:
        lines.append(BLOCK)
    if v.calls:
        lines += HELPERS.splitlines()
    names = []
    count = draw(st.integers(2, 5))
    for k in range(count):
        names.append(f"n{k}")
        lines += ["", ""] + (['@label("last")'] if v.jumps and k == count - 1 else []) + [f"def n{k}(t):"]
        body = [line for lines_of in draw(st.lists(statement(v), min_size=1, max_size=3)) for line in lines_of]
        local = draw(st.sampled_from(["", "d = t.D", "d = t.D\nif t.I0:\n    d = t.D"])) if v.blocks else ""
        if local:
            body = [*local.splitlines(), *(line.replace("t.D.", "d.") for line in body)]
        lines += [f"    {line}" for line in body]
    lines += ["", "", f"OB1 = [{', '.join(names)}]", ""]
    if v.interrupt and draw(st.booleans()):
        period = draw(st.sampled_from(["3ms", "7ms", "10ms"]))
        body = draw(st.lists(statement(v).filter(lambda s: "JMP" not in s[-1]), min_size=1, max_size=2))
        lines += ["def irq(t):", *(f"    {line}" for s in body for line in s)]
        lines += ["", f'OB30 = CyclicInterrupt(irq, period="{period}")', ""]
    return "\n".join(lines)


def schedules(scans: int) -> st.SearchStrategy[list[dict[str, bool]]]:
    """The inputs of each scan."""
    return st.lists(st.fixed_dictionaries({n: st.booleans() for n in INPUTS}), min_size=scans, max_size=scans)
