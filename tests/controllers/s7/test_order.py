"""Golden tests: LAD execution order written as Python networks (spec §5.1-§5.5).

Rules these tests pin:

* A rung translates to Python by evaluating every contact into a local first (every instruction
  executes every scan: no short-circuit), in the textbook's order: OR blocks are completed before
  moving right, a fan-out runs its upper branch to the end first, and every branch of a fan-out gets
  the RLO of the split node. Each contact below is logged, so the tests check the stated order and
  that it is the same for every input combination, as well as the Boolean results.
* Networks run top to bottom; a value written by an earlier network is seen by a later one in the
  same scan.
* The last write in a scan wins, and only the final output image reaches the output modules at the
  end of the scan (SET then RESET: the module never sees TRUE).
"""

from __future__ import annotations

import itertools

import pytest
from plcharness import Probe

from plcsim import CPU, Tag

LOGGER = """
LOG = DB(seq=Array(0, 31, Char), n=Int(0))
def c(t, name, v):
    t.LOG.seq[t.LOG.n] = name   # log the instruction by its letter, then pass its value on
    t.LOG.n += 1
    return v
"""


def _x10(v):
    return ((v["A"] or v["C"]) and not v["B"] and (v["E"] or v["D"])) or v["G"]


def _x61(v, first, second):
    return (v[first[0]] or v[first[1]]) and (v[second[0]] or v[second[1]])


# each case: stated order [T] (one character per instruction; coils O1, O2, O3 are logged as 1, 2, 3),
# the inputs, the network body (a LAD-faithful translation of the spec's structure), the Boolean results
CASES = {
    "3.1.1": ("AB", "A", '    a = c(t, "A", t.A)\n    t.B = c(t, "B", a)\n', {"B": lambda v: v["A"]}),
    "3.1.2-NW1": (
        "ABC",
        "AB",
        '    a = c(t, "A", t.A)\n    b = c(t, "B", t.B)\n    t.C = c(t, "C", a and b)\n',
        {"C": lambda v: v["A"] and v["B"]},
    ),
    "3.1.2-NW2": (
        "DEF",
        "DE",
        '    d = c(t, "D", t.D)\n    e = c(t, "E", t.E)\n    t.F = c(t, "F", d or e)\n',
        {"F": lambda v: v["D"] or v["E"]},
    ),
    "3.1.3": (
        "ABCD",
        "ABC",
        '    a = c(t, "A", t.A)\n    b = c(t, "B", t.B)\n    cc = c(t, "C", t.C)\n'
        '    t.D = c(t, "D", a and (b or cc))\n',
        {"D": lambda v: v["A"] and (v["B"] or v["C"])},
    ),
    "3.1.4": (  # A - { B - { =C ; =D } ; =E }
        "ABCDE",
        "AB",
        '    a = c(t, "A", t.A)\n    b = c(t, "B", t.B)\n    split = a and b\n'
        '    t.C = c(t, "C", split)\n    t.D = c(t, "D", split)\n    t.E = c(t, "E", a)\n',
        {"C": lambda v: v["A"] and v["B"], "D": lambda v: v["A"] and v["B"], "E": lambda v: v["A"]},
    ),
    "3.1.5": (  # (A | C) - (B | D) - =E
        "ACBDE",
        "ABCD",
        '    a = c(t, "A", t.A)\n    cc = c(t, "C", t.C)\n    b = c(t, "B", t.B)\n    d = c(t, "D", t.D)\n'
        '    t.E = c(t, "E", (a or cc) and (b or d))\n',
        {"E": lambda v: (v["A"] or v["C"]) and (v["B"] or v["D"])},
    ),
    "3.1.6": (  # A - (B | C - E) - =D
        "ABCED",
        "ABCE",
        '    a = c(t, "A", t.A)\n    b = c(t, "B", t.B)\n    cc = c(t, "C", t.C)\n    e = c(t, "E", t.E)\n'
        '    t.D = c(t, "D", a and (b or (cc and e)))\n',
        {"D": lambda v: v["A"] and (v["B"] or (v["C"] and v["E"]))},
    ),
    "3.1.7": (  # ((A | D) - (B | E) - C | F) - =G
        "ADBECFG",
        "ABCDEF",
        '    a = c(t, "A", t.A)\n    d = c(t, "D", t.D)\n    b = c(t, "B", t.B)\n    e = c(t, "E", t.E)\n'
        '    cc = c(t, "C", t.C)\n    f = c(t, "F", t.F)\n    t.G = c(t, "G", ((a or d) and (b or e) and cc) or f)\n',
        {"G": lambda v: ((v["A"] or v["D"]) and (v["B"] or v["E"]) and v["C"]) or v["F"]},
    ),
    "3.1.8": (  # (A | C) - (B | E) - (D | F) - (G - H - J | I) - =K
        "ACBEDFGHJIK",
        "ABCDEFGHIJ",
        '    a = c(t, "A", t.A)\n    cc = c(t, "C", t.C)\n    b = c(t, "B", t.B)\n    e = c(t, "E", t.E)\n'
        '    d = c(t, "D", t.D)\n    f = c(t, "F", t.F)\n    g = c(t, "G", t.G)\n    h = c(t, "H", t.H)\n'
        '    j = c(t, "J", t.J)\n    i = c(t, "I", t.I)\n'
        '    t.K = c(t, "K", (a or cc) and (b or e) and (d or f) and ((g and h and j) or i))\n',
        {
            "K": lambda v: (
                (v["A"] or v["C"])
                and (v["B"] or v["E"])
                and (v["D"] or v["F"])
                and ((v["G"] and v["H"] and v["J"]) or v["I"])
            )
        },
    ),
    "3.1.9": (  # (A | C | G) - (B | E | H) - (D | F) - I - =J
        "ACGBEHDFIJ",
        "ABCDEFGHI",
        '    a = c(t, "A", t.A)\n    cc = c(t, "C", t.C)\n    g = c(t, "G", t.G)\n    b = c(t, "B", t.B)\n'
        '    e = c(t, "E", t.E)\n    h = c(t, "H", t.H)\n    d = c(t, "D", t.D)\n    f = c(t, "F", t.F)\n'
        '    i = c(t, "I", t.I)\n    t.J = c(t, "J", (a or cc or g) and (b or e or h) and (d or f) and i)\n',
        {
            "J": lambda v: (
                (v["A"] or v["C"] or v["G"]) and (v["B"] or v["E"] or v["H"]) and (v["D"] or v["F"]) and v["I"]
            )
        },
    ),
    "3.1.10": (  # ((A | C) - /B - (E | D) | G) - { F - { H - =N ; =I } ; J - { =K ; L - =M } }
        "ACBEDGFHNIJKLM",
        "ABCDEFGHJL",
        '    a = c(t, "A", t.A)\n    cc = c(t, "C", t.C)\n    nb = c(t, "B", not t.B)\n    e = c(t, "E", t.E)\n'
        '    d = c(t, "D", t.D)\n    g = c(t, "G", t.G)\n    x = ((a or cc) and nb and (e or d)) or g\n'
        '    f = c(t, "F", t.F)\n    xf = x and f\n    h = c(t, "H", t.H)\n    t.N = c(t, "N", xf and h)\n'
        '    t.I = c(t, "I", xf)\n    j = c(t, "J", t.J)\n    xj = x and j\n    t.K = c(t, "K", xj)\n'
        '    l = c(t, "L", t.L)\n    t.M = c(t, "M", xj and l)\n',
        {
            "N": lambda v: _x10(v) and v["F"] and v["H"],
            "I": lambda v: _x10(v) and v["F"],
            "K": lambda v: _x10(v) and v["J"],
            "M": lambda v: _x10(v) and v["J"] and v["L"],
        },
    ),
    # §6.1 exercises: the official orders [T] with the spec's invented fixtures [I]
    "6.1.1": (  # (A | C - D) - B - =O1
        "ACDB1",
        "ABCD",
        '    a = c(t, "A", t.A)\n    cc = c(t, "C", t.C)\n    d = c(t, "D", t.D)\n    b = c(t, "B", t.B)\n'
        '    t.O1 = c(t, "1", (a or (cc and d)) and b)\n',
        {"O1": lambda v: (v["A"] or (v["C"] and v["D"])) and v["B"]},
    ),
    "6.1.2": (  # ((E | B) - (C | D) | A) - =O1
        "EBCDA1",
        "ABCDE",
        '    e = c(t, "E", t.E)\n    b = c(t, "B", t.B)\n    cc = c(t, "C", t.C)\n    d = c(t, "D", t.D)\n'
        '    a = c(t, "A", t.A)\n    t.O1 = c(t, "1", ((e or b) and (cc or d)) or a)\n',
        {"O1": lambda v: _x61(v, "EB", "CD") or v["A"]},
    ),
    "6.1.3": (  # (B | A) - C - (E | D) - F - { =O1 ; G - =O2 }
        "BACEDF1G2",
        "ABCDEFG",
        '    b = c(t, "B", t.B)\n    a = c(t, "A", t.A)\n    cc = c(t, "C", t.C)\n    e = c(t, "E", t.E)\n'
        '    d = c(t, "D", t.D)\n    f = c(t, "F", t.F)\n    x = (b or a) and cc and (e or d) and f\n'
        '    t.O1 = c(t, "1", x)\n    g = c(t, "G", t.G)\n    t.O2 = c(t, "2", x and g)\n',
        {
            "O1": lambda v: (v["B"] or v["A"]) and v["C"] and (v["E"] or v["D"]) and v["F"],
            "O2": lambda v: (v["B"] or v["A"]) and v["C"] and (v["E"] or v["D"]) and v["F"] and v["G"],
        },
    ),
    "6.1.4": (  # ((B | E) - (D | F) | A) - C - =O1
        "BEDFAC1",
        "ABCDEF",
        '    b = c(t, "B", t.B)\n    e = c(t, "E", t.E)\n    d = c(t, "D", t.D)\n    f = c(t, "F", t.F)\n'
        '    a = c(t, "A", t.A)\n    cc = c(t, "C", t.C)\n'
        '    t.O1 = c(t, "1", (((b or e) and (d or f)) or a) and cc)\n',
        {"O1": lambda v: (_x61(v, "BE", "DF") or v["A"]) and v["C"]},
    ),
    "6.1.5": (  # (B | A) - (D | E) - { =O1 ; =O2 ; C - =O3 }
        "BADE12C3",
        "ABCDE",
        '    b = c(t, "B", t.B)\n    a = c(t, "A", t.A)\n    d = c(t, "D", t.D)\n    e = c(t, "E", t.E)\n'
        '    x = (b or a) and (d or e)\n    t.O1 = c(t, "1", x)\n    t.O2 = c(t, "2", x)\n'
        '    cc = c(t, "C", t.C)\n    t.O3 = c(t, "3", x and cc)\n',
        {
            "O1": lambda v: _x61(v, "BA", "DE"),
            "O2": lambda v: _x61(v, "BA", "DE"),
            "O3": lambda v: _x61(v, "BA", "DE") and v["C"],
        },
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_execution_order_and_boolean_results_for_every_input_combination(case):
    order, inputs, body, results = CASES[case]
    tags = {name: Tag(f"%I{i // 8}.{i % 8}") for i, name in enumerate(inputs)}
    outputs = {name: Tag(f"%M{10 + i // 8}.{i % 8}") for i, name in enumerate(results)}
    program = LOGGER + "def net(t):\n    t.LOG.n = 0\n" + body + "OB1 = [net]\n"
    program = program.replace(
        "def net(t):", "\n".join(f"{n} = Tag('{o.address}')" for n, o in outputs.items()) + "\ndef net(t):"
    )
    cpu = CPU(tags=tags, program=program)
    for combo in itertools.product([False, True], repeat=len(inputs)):
        values = dict(zip(inputs, combo))
        for name, value in values.items():
            cpu.set_input(name, value)
        cpu.scan()
        assert cpu.mode == "RUN", cpu.error
        log = "".join(cpu.t.LOG.seq[k] for k in range(cpu.read("LOG.n")))
        assert log == order, f"{case}: order for {values}"
        for out, rule in results.items():
            assert cpu.read(out) is bool(rule(values)), f"{case}: {out} for {values}"


# --------------------------------------------------------------------------------------------
# Last write wins (§5.5 items 1 and 2)
# --------------------------------------------------------------------------------------------

PANEL = {"A": Tag("%I0.0"), "B": Tag("%I0.1"), "LED": Tag("%Q0.0")}

SET_RESET = """
def n1(t):
    if t.A:
        t.LED = True           # SET
def n2(t):
    if t.B:
        t.LED = False          # RESET
OB1 = [n1, n2]
"""
SR_BOX = """
def OB1(t):
    if t.A:                    # SR: S first ...
        t.LED = True
    if t.B:                    # ... then R1: reset dominant
        t.LED = False
"""
RS_BOX = """
def OB1(t):
    if t.B:                    # RS: R first ...
        t.LED = False
    if t.A:                    # ... then S1: set dominant
        t.LED = True
"""
TWO_ASSIGNMENTS = """
def OB1(t):
    t.LED = t.A
    t.LED = t.B                # only the last condition has an effect (Fig. 3.30)
"""


@pytest.mark.parametrize(
    ("program", "table"),
    [
        pytest.param(SET_RESET, {(1, 0): True, (0, 1): False, (1, 1): False}, id="set-then-reset"),
        pytest.param(SR_BOX, {(1, 0): True, (0, 1): False, (1, 1): False}, id="SR-reset-dominant"),
        pytest.param(RS_BOX, {(1, 0): True, (0, 1): False, (1, 1): True}, id="RS-set-dominant"),
        pytest.param(TWO_ASSIGNMENTS, {(1, 0): False, (0, 1): True, (1, 1): True}, id="two-assignments"),
    ],
)
def test_last_write_wins_at_the_end_of_the_scan(program, table):
    for (a, b), expected in table.items():
        cpu = CPU(tags=PANEL, program=program)
        probe = Probe(cpu, "LED", outputs=True)
        cpu.set_input("A", bool(a))
        cpu.set_input("B", bool(b))
        cpu.scan(3)
        assert cpu.outputs["LED"] is expected
        # only the final image value reaches the module, never the intermediate TRUE
        assert probe.changes("LED") == [(0.001, expected)]


def test_sr_with_both_inputs_never_drives_the_module():
    cpu = CPU(tags=PANEL, program=SET_RESET)
    writes = []
    cpu.on_scan_end = lambda c: writes.append((c.output_version, c.outputs["LED"]))
    cpu.set_input("A", True)
    cpu.set_input("B", True)
    cpu.scan(10)
    assert {value for _, value in writes} == {False}
    assert cpu.read("LED") is False


# --------------------------------------------------------------------------------------------
# Other same-scan consequences (§5.5)
# --------------------------------------------------------------------------------------------

SEAL_IN = """
TLACIDLO_SEEN = Tag("%M10.0")
LED_SEEN = Tag("%M10.1")
def OB1(t):
    upper = t.TLACIDLO
    lower = t.LED
    t.TLACIDLO_SEEN = upper
    t.LED_SEEN = lower
    t.LED = upper or lower
"""


def test_5_5_item_5_seal_in():
    cpu = CPU(tags={"TLACIDLO": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program=SEAL_IN)
    probe = Probe(cpu, "TLACIDLO_SEEN", "LED_SEEN", "LED")
    cpu.scan(2)
    cpu.set_input("TLACIDLO", True)
    cpu.scan(2)
    cpu.set_input("TLACIDLO", False)
    cpu.scan(2)
    rows = list(zip(*(probe.samples[n] for n in ("TLACIDLO_SEEN", "LED_SEEN", "LED"))))
    assert [tuple(v for _, v in row) for row in rows] == [
        (False, False, False),
        (False, False, False),
        (True, False, True),  # first pressed scan: only the upper branch
        (True, True, True),  # then both
        (False, True, True),  # after release the lower branch holds
        (False, True, True),
    ]


NETWORK_ORDER = """
POM = Tag("%M10.0")
EARLY = Tag("%M10.1")
LATE = Tag("%M10.2")
def n1(t):
    t.EARLY = t.POM            # sees the previous scan's POM
def n2(t):
    t.POM = t.A
def n3(t):
    t.LATE = t.POM             # sees this scan's POM
OB1 = [n1, n2, n3]
"""


def test_networks_run_top_to_bottom():
    cpu = CPU(tags=PANEL, program=NETWORK_ORDER)
    probe = Probe(cpu, "EARLY", "LATE")
    cpu.scan()
    cpu.set_input("A", True)
    cpu.scan(2)
    assert [v for _, v in probe.samples["EARLY"]] == [False, False, True]
    assert [v for _, v in probe.samples["LATE"]] == [False, True, True]


def test_input_image_is_constant_during_the_scan():
    program = """
FIRST = Tag("%M10.0")
LAST = Tag("%M10.1")
def n1(t):
    t.FIRST = t.A
def n2(t):
    t.LAST = t.A
OB1 = [n1, n2]
"""
    cpu = CPU(tags=PANEL, program=program, cycle="100ms")
    cpu.run_until(50_000_000)  # in the middle of the first scan (its networks at 0 and 50 ms)
    cpu.set_input("A", True)
    cpu.run_until(100_000_000)
    assert (cpu.read("FIRST"), cpu.read("LAST")) == (False, False)
    cpu.run_until(200_000_000)  # the second scan: networks at 100 and 150 ms
    assert (cpu.read("FIRST"), cpu.read("LAST")) == (True, True)
