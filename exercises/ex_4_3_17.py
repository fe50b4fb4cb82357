"""4.3.17 Sorting objects by colour. Plant: SORT (top view, ``plants/sort.py``).

Two acceptance criteria of the spec fail the textbook's own reference as written (spec §4 item 1): its
compressor rung (Fig. 4.156) and conveyor rung (Fig. 4.155) run before the piston and occupancy rungs, so
Kompresor follows the pistons, and D1_VPRED the occupancies, one scan late. They are checked "within 1 scan".
Where each object ends is the plant's record (``part in bin`` with the object's colour), not the program's bits.
Each wrong solution is graded only on the scenarios that show its flaw: "three colours" for a slip every run shows,
daylight and worn objects for intervals drawn too narrow, the objects of no colour for intervals without outer bounds.
"""

from __future__ import annotations

from exercises._common import solution
from exercises._sort import NoMissort, OnlyAfter, Phantom, Unmarked, WrongType
from plants.sort import FAIL_COMPRESSOR, SET_AMBIENT, Sort
from plcsim.check import (
    action,
    all_of,
    any_of,
    assumes,
    count,
    durations,
    event,
    event_data,
    final,
    never,
    not_,
    off,
    spacing,
)
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, after_event, place
from plcsim.tags import DB
from plcsim.tags.types import Bool, Int

NUMBER = "4.3.17"
FAULT_WORDS = "also when the compressor fails to build pressure"
APART = "The operator loads the objects at least 3 s apart"
"""The operating condition the task states, left by the scenario 'objects too close', where the task says what must
happen then."""
CLOSER = (
    "loaded closer, the sorter may lose some (they end unsorted), but a piston still pushes only an object of its own "
    "colour"
)
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""
PISTONS = ("Piest1_Farba1", "Piest2_Farba2", "Piest3_Farba3")
OCCUPANCY = tuple(
    f"DATA.{n}"
    for n in ("POZ1_OBS_Nakladanie", "POZ2_OBS_Detekcia", "POZ3_OBS_Farba1", "POZ4_OBS_Farba2", "POZ5_OBS_Farba3")
)
ANY_PISTON = any_of(*PISTONS)
ANY_OCCUPIED = any_of(*OCCUPANCY)

THREE = "three colours"
SIX = "six mixed"
AMBIENT = "ambient light"
NO_AIR = "compressor fails"
SPACED = "mixed spacing"
EDGES = "colours near the interval edges"
CLOSE = "objects too close"
DARK = "a colour above every interval"
BRIGHT = "a colour below every interval"
SORTED = (THREE, SIX, AMBIENT, SPACED, EDGES)
OUT_OF_RANGE = (DARK, BRIGHT)
"""An object of none of the three colours among sorted ones (text issue e): it must get no piston and no type, and
run off the end of the belt; the textbook's POZ5 then stays occupied and its belt never stops (not graded there)."""
ONE_AT_A_TIME = (THREE, EDGES)
"""Where criterion 6 can hold: at 3..5 s a colour-3 object followed by a colour-1 one puts P3 (7.9 s after its
loading) and P1 (3.9 s after the next's) out together whatever the program does; these load colours in
ascending order."""
EDGE_RAW = ((1, 4000), (1, 7000), (2, 11000), (2, 15000), (3, 19000), (3, 23000))
"""Worn and tinted objects: 2000 raw (4 σ) inside an edge of the §5.8 intervals (2000 / 9000 / 17000 / 25000)."""
BLACK = {"colour": 0, "colour_raw": 27000.0, "color": (30, 30, 30)}
"""A black object: darker than the bare belt (26500), 2000 raw (4 σ) above colour 3's interval."""
STEEL = {"colour": 0, "colour_raw": 0.0, "color": (195, 200, 205)}
"""A polished steel object: brighter than white, it reads 0 (plus the noise, clipped), 4 σ below colour 1's interval."""


def loads(colours: tuple[int, ...], *, spacing_s: float = 3.2) -> list:
    """One object per colour, loaded at OS1 every ``spacing_s`` (±0.2 s, seeded): ≥ 3 s as §5.8 asks."""
    return [
        place(f"p{k + 1}", at="OS1", t=f"{0.5 + k * spacing_s:.1f}s..{0.7 + k * spacing_s:.1f}s", colour=c)
        for k, c in enumerate(colours)
    ]


def spaced(*objects: tuple) -> list:
    """Objects p1, p2 … as ``(colour, gap)`` or ``(gap, properties)``: each loaded a seeded ``gap``
    (``"3s..3.4s"``) after the one before (the first at 0.5..0.7 s)."""
    actions = []
    for k, (what, gap) in enumerate(objects, start=1):
        when = {"t": "0.5s..0.7s"} if k == 1 else {"when": after_event("part placed", f"p{k - 1}"), "delay": gap}
        props = what if isinstance(what, dict) else {"colour": what}
        actions.append(place(f"p{k}", at="OS1", **when, **props))
    return actions


EXERCISE = Exercise(
    number=NUMBER,
    slug="colour-sorting",
    title="Sorting objects by colour",
    title_sk="Príklad 17 – Triedenie objektov podľa farby",
    task=(
        "One conveyor D1 moves forward only (D1_VPRED). An object loaded at the entry sensor OS1_Vstup starts it; at "
        "the detection sensor OS2_Detekcia an analogue sensor FARBA measures its colour (raw 0…27648). Further on "
        "are the sensors OS3_Farba1, OS4_Farba2 and OS5_Farba3, and behind each a piston (Piest1_Farba1 … "
        "Piest3_Farba3) that pushes an object of its colour off the belt into a bin; the pistons are driven forward "
        "only and return when their output is FALSE, and they need the compressor (Kompresor) switched on while a "
        "piston moves. All optical sensors are NC (TRUE while no object interrupts them). Several objects may be on "
        "the belt with suitable spacing.\n"
        "Task: with occupancy states in DB DATA, control the conveyor, the pistons (each out for 1 s) and the "
        "compressor so that each object is carried in front of its piston and pushed off there; with the last piece "
        "the conveyor stops. Choose the analogue values of the three colours as intervals.\n"
        "The colour sensor reads FARBA in raw units 0…27648, the brighter the lower: a white object (colour 1) reads "
        "about 5000, a red one (colour 2) about 13000, a blue one (colour 3) about 21000, and the bare belt about "
        "26500. Each reading scatters by about 500 (one standard deviation); a worn or tinted object reads up to 2000 "
        "away from its colour's value, and daylight may add up to 1500 to every reading. An object of none of the "
        "three colours (a polished steel one reads about 0, a black one about 27000) gets no piston and runs off the "
        "end of the belt. The operator loads the objects at least 3 s apart; loaded closer, the sorter may lose some "
        "(they end unsorted), but a piston still pushes only an object of its own colour.\n"
        "Each piston goes out only just after an object of its colour has passed its sensor, and is out for 1 s "
        "each time, also when the compressor fails to build pressure; with the objects loaded in the order of their "
        "colours no two pistons are out at once. Within 1 scan the compressor runs exactly while a piston is out, "
        "and the belt exactly while a position is occupied; every object's position is marked occupied, with the "
        "object's colour as its type, and no position is marked without its object except while its piston is out "
        "(an object of no colour may leave the last position marked). Every object of a colour lands in its own bin, "
        "none ends unsorted."
    ),
    io=[
        IO("OS1_Vstup", "entry light barrier", "Bool", "%I0.0", "NC"),
        IO("OS3_Farba1", "barrier before piston 1 (table: OS2_Farba 1)", "Bool", "%I0.1", "NC"),
        IO("OS4_Farba2", "barrier before piston 2 (table: OS2_Farba 2)", "Bool", "%I0.2", "NC"),
        IO("OS5_Farba3", "barrier before piston 3 (table: OS2_Farba 3)", "Bool", "%I0.3", "NC"),
        IO(
            "OS2_Detekcia", "detection barrier at the colour sensor", "Bool", "%I0.4", "NC", comment="missing; proposed"
        ),
        IO("FARBA", "analogue colour value 0…27648", "Int", "%IW64", signal="FARBA", comment="missing; proposed"),
        IO("D1_VPRED", "conveyor forward (table: Dopravník)", "Bool", "%Q0.0"),
        IO("Piest1_Farba1", "piston 1 forward", "Bool", "%Q0.1"),
        IO("Piest2_Farba2", "piston 2 forward", "Bool", "%Q0.2"),
        IO("Piest3_Farba3", "piston 3 forward", "Bool", "%Q0.3"),
        IO("Kompresor", "compressor", "Bool", "%Q0.4"),
    ],
    dbs={
        "DATA": DB(
            POZ1_OBS_Nakladanie=Bool(False),
            POZ2_OBS_Detekcia=Bool(False),
            POZ3_OBS_Farba1=Bool(False),
            POZ4_OBS_Farba2=Bool(False),
            POZ5_OBS_Farba3=Bool(False),
            POZ2_DETEKCIA=Int(0),
            POZ3_FARBA1=Int(0),
            POZ4_FARBA2=Int(0),
            POZ5_FARBA3=Int(0),
            comment="occupancy and object type of the five positions (Fig. 4.149)",
        )
    },
    aliases={  # the tag table's (Fig. 4.148) and data block's (Fig. 4.149) spelling: text issue 10, accept both
        "Dopravník": "D1_VPRED",
        "OS2_Farba 1": "OS3_Farba1",
        "OS2_Farba 2": "OS4_Farba2",
        "OS2_Farba 3": "OS5_Farba3",
        "Piest1_Farba 1": "Piest1_Farba1",
        "Piest2_Farba 2": "Piest2_Farba2",
        "Piest3_Farba 3": "Piest3_Farba3",
        "DATA.POZ3_OBS_Farba 1": "DATA.POZ3_OBS_Farba1",
        "DATA.POZ4_OBS_Farba 2": "DATA.POZ4_OBS_Farba2",
        "DATA.POZ5_OBS_Farba 3": "DATA.POZ5_OBS_Farba3",
    },
    rig=Sort,
    scenarios=[
        Scenario(THREE, *loads((1, 2, 3)), duration="18s", description="colours 1, 2, 3 loaded 3.2 s apart"),
        Scenario(SIX, *loads((2, 3, 1, 3, 1, 2)), duration="28s", description="six objects of mixed colours"),
        Scenario(
            AMBIENT,
            SET_AMBIENT("FARBA", t="0s", offset=1500.0),
            *loads((3, 1, 2)),
            duration="18s",
            description="daylight adds 1500 raw to every colour reading (the intervals must allow for it)",
        ),
        Scenario(
            NO_AIR,
            FAIL_COMPRESSOR("Kompresor", t="0s"),
            *loads((1,)),
            outside={FAULTS: FAULT_WORDS},
            duration="10s",
            description="the compressor runs but builds no pressure: the piston cannot move, the object ends unsorted",
        ),
        Scenario(
            SPACED,
            *spaced((3, ""), (1, "3s..3.4s"), (1, "5s..5.5s"), (2, "3s..3.3s"), (3, "4s..4.5s"), (2, "6s..6.5s")),
            duration="34s",
            description="six objects of mixed colours at gaps of 3 to 6.5 s (never under the task's 3 s)",
        ),
        Scenario(
            EDGES,
            *spaced(*(({"colour": c, "colour_raw": raw}, "3s..3.4s") for c, raw in EDGE_RAW)),
            duration="28s",
            description="worn and tinted objects whose colour reads up to 2000 raw away from its colour's value: "
            "4000 and 7000 (colour 1), 11000 and 15000 (colour 2), 19000 and 23000 (colour 3)",
        ),
        Scenario(
            CLOSE,
            *spaced((1, ""), (2, "1.4s..1.6s"), (3, "1.4s..1.6s"), (1, "1.4s..1.6s")),
            outside={APART: CLOSER},
            duration="20s",
            description="four objects 1.5 s apart, closer than the task's 3 s: the sorter's positions lose objects, "
            "which end unsorted or stuck; a piston may still only push an object of its colour",
        ),
        Scenario(
            DARK,
            *spaced((3, ""), (BLACK, "3s..3.4s"), (1, "3s..3.4s"), (2, "3s..3.4s")),
            duration="22s",
            description="a black object (raw 27000, above colour 3's interval) after a colour 3 and before a colour 1 "
            "and a colour 2: it gets no type and no piston and runs off the end of the belt",
        ),
        Scenario(
            BRIGHT,
            *spaced((1, ""), (3, "3s..3.4s"), (STEEL, "3s..3.4s"), (2, "3s..3.4s")),
            duration="22s",
            description="a polished steel object (raw 0, below colour 1's interval) after a colour 1 and a colour 3 "
            "and before a colour 2: it gets no type and no piston and runs off the end of the belt",
        ),
    ],
    checks=[
        # criterion 1
        only(
            event_data("part in bin", "colour", "bin1").equals(1).named("bin 1 receives colour 1 only"),
            *SORTED,
            *OUT_OF_RANGE,
        ),
        only(
            event_data("part in bin", "colour", "bin2").equals(2).named("bin 2 receives colour 2 only"),
            *SORTED,
            *OUT_OF_RANGE,
        ),
        only(
            event_data("part in bin", "colour", "bin3").equals(3).named("bin 3 receives colour 3 only"),
            *SORTED,
            *OUT_OF_RANGE,
        ),
        NoMissort().named("no object lands in another colour's bin"),
        only(count(event("part in bin", "unsorted")).equals(0).named("no object ends unsorted"), *SORTED),
        only(
            event_data("part in bin", "colour", "unsorted")
            .equals(0)
            .named("the object of no colour, and only it, runs off the end into the unsorted bin"),
            *OUT_OF_RANGE,
        ),
        only(
            durations("Piest1_Farba1")
            .between("1s - 2 scans", "1s + 2 scans")
            .named("with no air the pulse is 1 s too"),
            NO_AIR,
        ),
        # criterion 2, within 1 scan (the compressor rung runs before the piston rungs)
        never(all_of(ANY_PISTON, off("Kompresor")))
        .for_more_than("1 scan")
        .named("the compressor runs whenever a piston is out (within 1 scan)"),
        never(all_of("Kompresor", not_(ANY_PISTON)))
        .for_more_than("1 scan")
        .named("the compressor is off when no piston is out (within 1 scan)"),
        # criterion 3
        *[
            only(
                durations(p).between("1s - 2 scans", "1s + 2 scans").named(f"{p} is out for 1 s each time"),
                *SORTED,
                *OUT_OF_RANGE,
            )
            for p in PISTONS
        ],
        *[
            OnlyAfter(p, barrier, k).named(f"{p} goes out only just after an object of colour {k} passed {barrier}")
            for k, (p, barrier) in enumerate(zip(PISTONS, ("OS3_Farba1", "OS4_Farba2", "OS5_Farba3"), strict=True), 1)
        ],
        # criterion 4, within 1 scan (the conveyor rung runs before the rungs that clear the positions)
        never(all_of("D1_VPRED", not_(ANY_OCCUPIED)))
        .for_more_than("1 scan")
        .named("the belt does not run with every position free (within 1 scan)"),
        never(all_of(off("D1_VPRED"), ANY_OCCUPIED))
        .for_more_than("1 scan")
        .named("the belt runs while a position is occupied (within 1 scan)"),
        only(final("D1_VPRED").equals(0).named("the belt stops after the last piece"), *SORTED),
        # criterion 5, within 1 scan (a position is taken over in the scan whose input image shows the object)
        only(
            never(any_of(*(Unmarked(k) for k in range(5))))
            .for_more_than("1 scan")
            .named("every object's position is marked occupied (within 1 scan)"),
            *SORTED,
            *OUT_OF_RANGE,
        ),
        only(
            never(any_of(*(Phantom(k) for k in range(5))))
            .for_more_than("1 scan")
            .named("no position is marked occupied without its object, but while its piston is out (within 1 scan)"),
            *SORTED,
        ),
        only(
            never(any_of(*(Phantom(k) for k in range(4))))
            .for_more_than("1 scan")
            .named("no position before the last is marked occupied without its object (within 1 scan)"),
            *OUT_OF_RANGE,
        ),
        only(
            never(any_of(*(WrongType(k) for k in range(1, 5))))
            .for_more_than("1 scan")
            .named("each position's type is the colour of its object (within 1 scan)"),
            *SORTED,
            *OUT_OF_RANGE,
        ),
        # criterion 6 (optional in the spec), where the loading order allows it
        only(
            never(any_of(*(all_of(a, b) for i, a in enumerate(PISTONS) for b in PISTONS[i + 1 :]))).named(
                "no two pistons are out at once"
            ),
            *ONE_AT_A_TIME,
        ),
    ],
    conditions=[assumes(APART, spacing(action("place")).at_least("3s"))],
    requirements={
        "bin 1 receives colour 1 only": "Every object of a colour lands in its own bin",
        "bin 2 receives colour 2 only": "Every object of a colour lands in its own bin",
        "bin 3 receives colour 3 only": "Every object of a colour lands in its own bin",
        "no object lands in another colour's bin": "but a piston still pushes only an object of its own colour",
        "no object ends unsorted": "none ends unsorted",
        "the object of no colour, and only it, runs off the end into the unsorted bin": (
            "gets no piston and runs off the end of the belt"
        ),
        "with no air the pulse is 1 s too": "also when the compressor fails to build pressure",
        "the compressor runs whenever a piston is out (within 1 scan)": (
            "Within 1 scan the compressor runs exactly while a piston is out"
        ),
        "the compressor is off when no piston is out (within 1 scan)": (
            "Within 1 scan the compressor runs exactly while a piston is out"
        ),
        "Piest1_Farba1 is out for 1 s each time": "is out for 1 s each time",
        "Piest2_Farba2 is out for 1 s each time": "is out for 1 s each time",
        "Piest3_Farba3 is out for 1 s each time": "is out for 1 s each time",
        "Piest1_Farba1 goes out only just after an object of colour 1 passed OS3_Farba1": (
            "Each piston goes out only just after an object of its colour has passed its sensor"
        ),
        "Piest2_Farba2 goes out only just after an object of colour 2 passed OS4_Farba2": (
            "Each piston goes out only just after an object of its colour has passed its sensor"
        ),
        "Piest3_Farba3 goes out only just after an object of colour 3 passed OS5_Farba3": (
            "Each piston goes out only just after an object of its colour has passed its sensor"
        ),
        "the belt does not run with every position free (within 1 scan)": (
            "and the belt exactly while a position is occupied"
        ),
        "the belt runs while a position is occupied (within 1 scan)": (
            "and the belt exactly while a position is occupied"
        ),
        "the belt stops after the last piece": "with the last piece the conveyor stops",
        "every object's position is marked occupied (within 1 scan)": "every object's position is marked occupied",
        "no position is marked occupied without its object, but while its piston is out (within 1 scan)": (
            "no position is marked without its object except while its piston is out"
        ),
        "no position before the last is marked occupied without its object (within 1 scan)": (
            "an object of no colour may leave the last position marked"
        ),
        "each position's type is the colour of its object (within 1 scan)": "with the object's colour as its type",
        "no two pistons are out at once": (
            "with the objects loaded in the order of their colours no two pistons are out at once"
        ),
    },
    solutions=[
        solution(NUMBER, "reference", explanation="the textbook's rungs 1-10 (Figs. 4.150-4.159)"),
        solution(
            NUMBER,
            "wrong-no-compressor",
            "wrong",
            "(a slip) without the compressor rung the pistons get no air: nothing is pushed off",
            fails=("no object ends unsorted", "the compressor runs whenever a piston is out (within 1 scan)"),
            scenarios=(THREE,),
        ),
        solution(
            NUMBER,
            "wrong-belt-stops-early",
            "wrong",
            "(a slip) the belt runs only for positions 1 and 2: it stops with an object in the OS3 beam, and the last "
            "object never reaches its piston",
            fails=("the belt runs while a position is occupied (within 1 scan)",),
            scenarios=(THREE,),
        ),
        solution(
            NUMBER,
            "wrong-narrow-intervals",
            "wrong",
            "(a slip) the colour intervals drawn ±1000 raw around the lab's means: daylight or a worn object reads "
            "between them, the object gets no type and ends unsorted",
            fails=("no object ends unsorted", "each position's type is the colour of its object (within 1 scan)"),
            scenarios=(AMBIENT, EDGES),
        ),
        solution(
            NUMBER,
            "wrong-no-outer-bounds",
            "wrong",
            "(a slip) the intervals as thresholds (colour 1 up to 9000, colour 3 above 17000): every object of the "
            "three colours is sorted, but a black object is pushed off as colour 3 and a polished one as colour 1",
            fails=(
                "no object lands in another colour's bin",
                "each position's type is the colour of its object (within 1 scan)",
            ),
            scenarios=OUT_OF_RANGE,
        ),
        solution(
            NUMBER,
            "wrong-piston-in-the-beam",
            "wrong",
            "(a slip) the piston rungs without 'its sensor free': a piston fires as the object breaks its barrier, "
            "35 mm before the piston",
            fails=tuple(
                f"{p} goes out only just after an object of colour {k} passed {b}"
                for k, (p, b) in enumerate(zip(PISTONS, ("OS3_Farba1", "OS4_Farba2", "OS5_Farba3"), strict=True), 1)
            ),
            scenarios=(THREE,),
        ),
        solution(
            NUMBER,
            "wrong-type-cleared-first",
            "wrong",
            "(a slip) in rungs 3-5 the previous type is cleared before it is copied: every type after the detection "
            "is 0, no piston fires",
            fails=("each position's type is the colour of its object (within 1 scan)", "no object ends unsorted"),
            scenarios=(THREE,),
        ),
        solution(
            NUMBER,
            "wrong-compressor-with-belt",
            "wrong",
            "(a slip) the compressor switched with the conveyor, as the caption of Fig. 4.156 reads: it runs while no "
            "piston needs air",
            fails=("the compressor is off when no piston is out (within 1 scan)",),
            scenarios=(THREE,),
        ),
    ],
    spec_equivalent={
        "OB1: network compressor moved to the end": (
            "the compressor follows the pistons in the same scan: criterion 2 as the spec words it ('Kompresor == "
            "Piest1 or Piest2 or Piest3 in every scan'), which the textbook's rung order misses by a scan"
        ),
        "OB1: network conveyor moved to the end": (
            "the belt stops in the scan that clears the last position: criterion 4 as the spec words it ('D1_VPRED "
            "TRUE iff at least one occupancy bit is TRUE')"
        ),
        "OB1: network loading moved to the end": (
            "position 1 is taken at the end of the scan that sees the object, so the belt starts a scan later: "
            "criterion 4 bounds the belt by the occupancy within 1 scan, and it follows it within 1 scan"
        ),
        **{
            f"line {line}: if-blocks at lines {line} and {line + 2} swapped": (
                "the piston's TON runs before the SET, so it starts timing a scan after the piston goes out: the "
                "pulse lasts 1 s + 1 scan, inside criterion 3's 1 s ± 2 scans"
            )
            for line in (79, 89, 99)
        },
        **{
            key: (
                "the shift rungs in another order: at the spacing of §5.8 each position is taken and freed within "
                "1 scan of the reference (criterion 5); they differ only where objects closer than the sorter can "
                "take meet at a barrier ('objects too close'), where they lose other objects than the reference"
            )
            for key in (
                "OB1: networks loading and detection swapped",
                "OB1: networks detection and colour_1 swapped",
                "OB1: networks colour_1 and colour_2 swapped",
                "OB1: networks colour_2 and colour_3 swapped",
                "OB1: network detection moved to the end",
                "OB1: network colour_1 moved to the end",
                "OB1: network colour_2 moved to the end",
                "OB1: network colour_3 moved to the end",
            )
        },
        "OB1: networks colour_3 and conveyor swapped": (
            "the belt follows the occupancy in the same scan (criterion 4 as the spec words it); it differs only in "
            "'objects too close': when position 5 is freed while an object nobody tracks stands in OS5's beam, the "
            "belt stops before rung 5 can take it over, and the object stays there; the reference takes it over with "
            "type 0 and runs it off the end for ever. Both lose it; the spec asks nothing of an object the sorter "
            "has lost"
        ),
        "OB1: networks compressor and piston_1 swapped": (
            "the compressor follows piston 1 in the same scan and pistons 2 and 3 a scan later: inside criterion 2's "
            "'within 1 scan' (spec §4 item 1)"
        ),
    },
    notes=(
        "Addresses of OS2_Detekcia (%I0.4) and FARBA (%IW64) are proposals (the table lacks them); the prose names "
        "are used (D1_VPRED for 'Dopravník', OS3_Farba1… for 'OS2_Farba 1'…, names without spaces). Colour means and "
        "noise as §5.8 (σ 500 raw); the intervals of the reference are §5.8's. Criteria 2 and 4 are checked within 1 "
        "scan (spec §4 item 1). Criterion 5 compares DB DATA with the plant's account of each object: an object is "
        "at position n from breaking barrier n until it breaks the next one or lands in a bin; a position pushed "
        "off stays occupied until its piston's 1 s pulse ends, as the textbook clears it. Criterion 6 (optional) is "
        "graded where the loading order lets any program meet it (colours in ascending order): at 3-5 s spacing a "
        "colour 3 followed by a colour 1 puts P3 and P1 out together whatever the program does. 'Objects too close' "
        "(1.5 s, under §5.8's 3 s) grades only what a sorter that cannot keep up must still do: no mis-sort, the "
        "compressor, the pulses and the belt following the occupancy; which objects it loses depends on the seed. "
        "An object of none of the three colours (text issue e: a black one above every interval, a polished steel "
        "one below) must get type 0 at every position, no piston, and run off the end of the belt into the unsorted "
        "bin, while the objects around it are sorted. The task's 'with the last piece the conveyor stops' is not "
        "graded there, nor position 5's occupancy after it: the textbook's program never clears a position whose "
        "type matches no piston, so its POZ5 stays occupied and its belt runs on for ever (a colour 3 loaded after "
        "it would not be taken over at OS5 either, so the scenarios load none). "
        "With the compressor failed the program cannot tell (the task gives no pressure switch): it is graded on "
        "its outputs only."
    ),
)
