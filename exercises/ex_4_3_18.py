"""4.3.18 Stacker crane (high-bay warehouse). Plant: HBW (``plants/hbw.py``).

The sensors' names follow the spec's reading of text issue 11: z1 back, z2 middle, z3 forward; odd y below a
shelf, even y above it. Where a part ends is the plant's record (``part put down`` / ``part picked up`` at a
place), the position estimates are compared with the crane's true position (``plant:X.s`` …).
"""

from __future__ import annotations

import itertools

from exercises._common import solution
from exercises._hbw import DONE, Estimate, FinalStep, OneRowInRack, Served, operator, random_requests
from plants.hbw import HBW, Z_ZONE
from plcsim.check import all_of, any_of, count, event, never, not_, value
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, shift_sensor, stuck
from plcsim.tags import DB
from plcsim.tags.types import Bool, Int, Real

NUMBER = "4.3.18"
FAULT_WORDS = "A position sensor may be mounted a few millimetres off its place, or fail: the crane must then stay safe"
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""
STEPS = ("s0_request", "s1_z_middle", "s2_x_y_target", "s3_z_forward", "s4_y_opposite", "s5_z_back")
"""The reference's step networks, in their order (the mutants that reorder them are one scan apart)."""
HALF_STEP_LATE = (
    "Fb3 reads na_snimaci of the scan before: the half step is taken one scan after the axis left its sensor; "
    "the task asks the estimate within one scan"
)
POSITION_LATE = (
    "the sensor's number is written after the drive and the steps have read the estimate: the axis is switched "
    "off one scan later (0.1 mm at 100 mm/s, deep inside the cam) and each step moves on a scan later; the task "
    "bounds neither"
)
DRIVE_EARLY = (
    "the drive follows a set-point in the scan the step wrote it, not the next: the axis starts one scan earlier; "
    "no requirement depends on that scan"
)
STEP_LATE = (
    "a step's set-point or its transition is seen one scan later: the sequence takes a scan longer per step; the "
    "task bounds no step's duration (only the 2 s to finish a request, which it keeps)"
)
START_AT = HBW.VERBS["start_at"]

NINE = "all nine places"
MIXED = "random put-in and take-out"
MIXED_2 = "random put-in and take-out, second sequence"
POSE = "switched on anywhere"
SHIFTED = "a cam mounted off its place"
FAILED = "a cam that fails"
NINE_ORDER = ((2, 1), (3, 3), (1, 3), (3, 1), (2, 2), (1, 2), (3, 2), (2, 3), (1, 1))
"""The places of 'all nine places', in an order in which every axis travels far."""
SERVED = (NINE, MIXED, MIXED_2, POSE, SHIFTED)
"""Where every request can be served (in 'a cam that fails' no program can find column 2)."""

X_CAM, Y_CAM = any_of("x1", "x2", "x3"), any_of("y1", "y2", "y3", "y4", "y5", "y6")
X_DRIVEN, Y_DRIVEN = any_of("x_vpravo", "x_vlavo"), any_of("y_hore", "y_dole")
PAST_Z2 = value("plant:Z.s") > Z_ZONE + 0.5  # the fork forward of z2 (the cam's zone and its hysteresis)


def axis_db(up: str, down: str) -> DB:
    """OS_X / OS_Y / OS_Z (Figs. 4.162-4.164): set-point, actual position, the edge bits, the direction memory."""
    return DB(
        ziadana=Real(1.0),
        aktualna=Real(0.0),
        na_snimaci=Bool(False),
        na_snimaci_sb=Bool(False),
        **{f"bol_pohyb_{up}": Bool(False), f"bol_pohyb_{down}": Bool(False)},
        comment="set-point and actual position of the axis; start values as Fig. 4.162",
    )


IO_TABLE = [
    IO("x1", "X at column 1 (left)", "Bool", "%I0.0", "NO"),
    IO("x2", "X at column 2 (middle)", "Bool", "%I0.1", "NO"),
    IO("x3", "X at column 3 (right)", "Bool", "%I0.2", "NO"),
    IO("y1", "Y below row 1", "Bool", "%I0.3", "NO"),
    IO("y2", "Y above row 1", "Bool", "%I0.4", "NO"),
    IO("y3", "Y below row 2", "Bool", "%I0.5", "NO"),
    IO("y4", "Y above row 2", "Bool", "%I0.6", "NO"),
    IO("y5", "Y below row 3", "Bool", "%I0.7", "NO"),
    IO("y6", "Y above row 3", "Bool", "%I1.0", "NO"),
    IO("z1", "Z back (loading)", "Bool", "%I1.1", "NO", comment="text issue 11: the text says z3"),
    IO("z2", "Z middle (transport)", "Bool", "%I1.2", "NO"),
    IO("z3", "Z forward (in the rack)", "Bool", "%I1.3", "NO"),
    IO("x_vpravo", "X right", "Bool", "%Q0.0"),
    IO("x_vlavo", "X left", "Bool", "%Q0.1"),
    IO("y_hore", "Y up", "Bool", "%Q0.2"),
    IO("y_dole", "Y down", "Bool", "%Q0.3"),
    IO("z_vpred", "Z forward", "Bool", "%Q0.4"),
    IO("z_vzad", "Z back", "Bool", "%Q0.5"),
]
"""Fig. 4.161 (the contacts' NO wiring is proposed: the figure does not say)."""

TASK = (
    "A stacker crane serves a rack of 3 columns × 3 rows; place [1,1] is bottom left. Axis X moves right "
    "(x_vpravo) and left (x_vlavo) in front of the rack; the contact sensors x1, x2, x3 report it in front of "
    "column 1, 2, 3. Axis Y lifts the fork (y_hore up, y_dole down); for each row two sensors report the fork "
    "below the shelf (y1, y3, y5) and above it (y2, y4, y6). Axis Z moves the fork forward into the rack (z_vpred) "
    "and back (z_vzad): z1 back (loading), z2 middle (transport), z3 forward (in the rack). All sensors are "
    "normally open contacts, TRUE while the axis stands within a few millimetres of the position. Putting a part "
    "into row 1 is: Y to y2, Z forward to z3, Y down to y1 (the shelf takes the part), Z back to z2; taking it out "
    "is the reverse: Y to y1, Z forward, Y up to y2 (the fork lifts the part), Z back. A switched-off drive coasts "
    "about 2 mm; nothing else stops an axis but its end stops beyond the first and the last sensor.\n"
    "Task: write a program that controls each axis by a set-point: OS_X/OS_Y/OS_Z.ziadana is the position wanted "
    "(1.0, 2.0 … the sensor's number) and OS_X/OS_Y/OS_Z.aktualna must always hold (within one scan) the axis's "
    "actual position once it has seen its first sensor: the sensor's number while on it, half-way values between "
    "two sensors (1.5 between x1 and x2), 0.5 before the first and 3.5 (6.5 for Y) past the last. Then put "
    "parts in and take them out by step control (DATA.KROK, steps 1 … 6 as in the textbook, 6 = done) that only "
    "changes the set-points. A put-in request (DATA.Poziadavka_naloz) "
    "or a take-out request (DATA.Poziadavka_vyloz) for place [DATA.x, DATA.y] must end with the part on that "
    "place (put-in) or on the fork (take-out) and the fork back at z2; the program then clears the request, "
    "and not before the fork is back at z2, in step 6.\n"
    "Keep the crane safe: never drive an axis both ways, never drive an axis against an end stop; move X only "
    "while the fork is at z2 or behind it; move Y inside the rack only with the fork fully in (z3) and only "
    "between the two sensors of one row; move the fork forward past z2 only while X and Y stand still on a "
    "sensor. Nothing may hit the rack, no part may fall "
    "and no place may get a second part.\n"
    "The operator works at the HMI, one request at a time: (for a put-in) puts a part on the fork wherever it "
    "waits in front of the rack, writes DATA.x and DATA.y (1.0 … 3.0), then sets one request, a few tenths of a "
    f"second apart. {DONE.replace('s..', ' to ').replace('s', ' s')} after the fork has put the part down or "
    "lifted it, the operator "
    "takes a retrieved part off the fork and begins the next request: the program has those 2 s to bring the fork "
    "back to z2 and clear the request. A put-in goes to a free place, a take-out to an occupied one. The crane is "
    "switched on with X anywhere from left of x1 to x3, Y anywhere from below y1 "
    "to y6, and the fork at z2 or behind it; the rack may hold parts already. A position sensor may be mounted a "
    "few millimetres off its place, or fail: the crane must then stay safe, even if a request cannot be served."
)

# The words of the task each check grades (``plcsim show 4.3.18`` prints every requirement with its checks).
ESTIMATE = (
    "OS_X/OS_Y/OS_Z.aktualna must always hold (within one scan) the axis's actual position once it has seen its "
    "first sensor: the sensor's number while on it, half-way values between two sensors (1.5 between x1 and x2), "
    "0.5 before the first and 3.5 (6.5 for Y) past the last"
)
STEP_6 = "step control (DATA.KROK, steps 1 … 6 as in the textbook, 6 = done)"
REQUEST = (
    "A put-in request (DATA.Poziadavka_naloz) or a take-out request (DATA.Poziadavka_vyloz) for place [DATA.x, "
    "DATA.y] must end with the part on that place (put-in) or on the fork (take-out) and the fork back at z2; the "
    "program then clears the request, and not before the fork is back at z2"
)
ONE_WAY = "never drive an axis both ways"
END_STOPS = "never drive an axis against an end stop"
X_BEHIND = "move X only while the fork is at z2 or behind it"
Y_IN_RACK = "move Y inside the rack only with the fork fully in (z3) and only between the two sensors of one row"
FORK_FORWARD = "move the fork forward past z2 only while X and Y stand still on a sensor"
NO_DAMAGE = "Nothing may hit the rack, no part may fall and no place may get a second part"

EXERCISE = Exercise(
    number=NUMBER,
    slug="stacker-crane",
    title="Stacker crane (high-bay warehouse)",
    title_sk="Príklad 18 – Regálový zakladač",
    task=TASK,
    io=IO_TABLE,
    dbs={
        "OS_X": axis_db("vpravo", "vlavo"),
        "OS_Y": axis_db("hore", "dole"),
        "OS_Z": axis_db("vpred", "vzad"),
        "DATA": DB(
            KROK=Int(0),
            x=Real(1.0),
            y=Real(1.0),
            Poziadavka_naloz=Bool(False),
            Poziadavka_vyloz=Bool(False),
            Poziadavka_naloz_sb=Bool(False),
            Poziadavka_vyloz_sb=Bool(False),
            comment="step number, the requested place and the requests (Fig. 4.165)",
        ),
    },
    rig=HBW,
    # the operator's two request switches on the live page (the program clears them); DATA.x and DATA.y, the
    # place, are written from the watch table before the request
    hmi={"DATA.Poziadavka_naloz": "switch", "DATA.Poziadavka_vyloz": "switch"},
    scenarios=[
        Scenario(
            NINE,
            *operator([("put", x, y) for x, y in NINE_ORDER]),
            duration="70s",
            description="a part put into each of the nine places, in an order that makes every axis travel far",
        ),
        Scenario(
            MIXED,
            *operator(random_requests(6, 4, {(1, 1), (3, 2), (2, 3)}), stocked={"R11": "a", "R32": "b", "R23": "c"}),
            duration="32s",
            description="three places stocked; four put-in or take-out requests drawn with seed 6",
        ),
        Scenario(
            MIXED_2,
            *operator(random_requests(2, 3, {(2, 2)}), stocked={"R22": "a"}),
            duration="24s",
            description="one place stocked; three put-in or take-out requests drawn with seed 2",
        ),
        Scenario(
            POSE,
            START_AT("X", t="0s", mm=(50.0, 330.0)),
            START_AT("Y", t="0s", mm=(35.0, 265.0)),
            START_AT("Z", t="0s", mm=(-75.0, -5.0)),
            *operator([("put", 2, 3), ("take", 2, 3)], first="5s..5.2s"),
            duration="21s",
            description="the crane switched on where it was left (a seeded pose between the sensors), then a part "
            "put into [2,3] and taken out again",
        ),
        Scenario(
            SHIFTED,
            shift_sensor("y4", 3.0, t="0s"),
            shift_sensor("x3", -4.0, t="0s"),
            *operator([("put", 3, 2), ("take", 3, 2)]),
            outside={FAULTS: FAULT_WORDS},
            duration="17s",
            description="the cams y4 and x3 mounted 3 and 4 mm off their places (still inside the zones' margins)",
        ),
        Scenario(
            FAILED,
            stuck("x2", False, t="0s"),
            *operator([("put", 2, 1)]),
            outside={FAULTS: FAULT_WORDS},
            duration="10s",
            description="the cam x2 fails (its contact never closes): a put-in for column 2 cannot be served; the "
            "crane must stay safe",
        ),
    ],
    checks=[
        # criterion 1
        never(all_of("x_vpravo", "x_vlavo")).named("X is never driven both ways at once").grades(ONE_WAY),
        never(all_of("y_hore", "y_dole")).named("Y is never driven both ways at once").grades(ONE_WAY),
        never(all_of("z_vpred", "z_vzad")).named("Z is never driven both ways at once").grades(ONE_WAY),
        # criterion 2
        never(all_of(X_DRIVEN, PAST_Z2)).named("X moves only while the fork is at z2 or behind it").grades(X_BEHIND),
        never(all_of(Y_DRIVEN, PAST_Z2, not_("z3")))
        .named("Y moves inside the rack only with the fork fully in")
        .grades(Y_IN_RACK),
        OneRowInRack().named("in the rack Y moves only between the two sensors of one row").grades(Y_IN_RACK),
        never(all_of("z_vpred", PAST_Z2, any_of(not_(X_CAM), not_(Y_CAM), X_DRIVEN, Y_DRIVEN)))
        .named("the fork goes forward past z2 only while X and Y stand still on a sensor")
        .grades(FORK_FORWARD),
        # criteria 3 and 4
        only(
            Served()
            .named("every request ends at the requested place, then is cleared with the fork at z2")
            .grades(REQUEST),
            *SERVED,
        ),
        only(FinalStep().named("DATA.KROK is 6 when a request is cleared").grades(STEP_6), *SERVED),
        only(count(event("part put down")).equals(9).named("all nine places are served").grades(REQUEST), NINE),
        # criterion 5
        never(event("axis stalled")).named("no axis is driven against an end stop").grades(END_STOPS),
        never(event("collision")).named("nothing hits the rack, and no place gets a second part").grades(NO_DAMAGE),
        never(event("part fell off")).named("no part falls").grades(NO_DAMAGE),
        never(event("interlock violated")).named("the crane reports no interlock violation").grades(ONE_WAY),
        # criterion 6
        only(Estimate(axis="X").named("OS_X.aktualna holds the true position of X").grades(ESTIMATE), *SERVED),
        only(Estimate(axis="Y").named("OS_Y.aktualna holds the true position of Y").grades(ESTIMATE), *SERVED),
        only(Estimate(axis="Z").named("OS_Z.aktualna holds the true position of Z").grades(ESTIMATE), *SERVED),
    ],
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="per axis: the sensor's number into aktualna, ±0.5 on leaving a sensor in the remembered "
            "direction, the drive toward ziadana; steps S1 Z to 2.0, S2 X to DATA.x and Y to 2y (put-in) or 2y-1 "
            "(take-out), S3 Z to 3.0, S4 Y to the row's other sensor, S5 Z to 2.0 and the requests cleared",
        ),
        solution(
            NUMBER,
            "wrong-zero-setpoints",
            "wrong",
            "the textbook's warning: with 0.0 as the set-points' start values, the crane standing on its sensors "
            "drives every axis 'to positions outside the rack', into the end stops",
            fails=("no axis is driven against an end stop",),
            scenarios=(FAILED,),
        ),
        solution(
            NUMBER,
            "wrong-z-before-y",
            "wrong",
            "(not from the textbook) S2 goes on to S3 when X has arrived, without asking Y: the fork goes into the "
            "rack while Y is still on its way",
            fails=("the fork goes forward past z2 only while X and Y stand still on a sensor",),
            scenarios=(MIXED_2,),
        ),
        solution(
            NUMBER,
            "wrong-request-cleared-early",
            "wrong",
            "(not from the textbook) the requests are cleared in S4, as soon as the part is down (or up): the HMI "
            "shows the job done while the fork is still in the rack",
            fails=("every request ends at the requested place, then is cleared with the fork at z2",),
            scenarios=(SHIFTED,),
        ),
        solution(
            NUMBER,
            "wrong-direction-never-reset",
            "wrong",
            "(not from the textbook) Ax sets the direction bit of the motion but never resets the other one: after "
            "the first moves both are TRUE and leaving a sensor adds +0.5 and -0.5, so the estimate between two "
            "sensors stays the number of the last one",
            # Z: the fork goes in and back out on every request, so Z reverses whatever pose the seed draws (X
            # need not: on seeds 3 and 11 it does not, and OS_X.aktualna stays right)
            fails=("OS_Z.aktualna holds the true position of Z",),
            scenarios=(POSE,),
        ),
    ],
    spec_equivalent={
        **{f"OB1: networks {a}_on_sensor and {a}_between swapped": HALF_STEP_LATE for a in "xyz"},
        **{f"OB1: network {a}_on_sensor moved to the end": HALF_STEP_LATE for a in "xyz"},
        **{f"OB1: network {a}_position moved to the end": POSITION_LATE for a in "xyz"},
        **{f"OB1: network {a}_drive moved to the end": DRIVE_EARLY for a in "xyz"},
        **{f"OB1: networks {a} and {b} swapped": STEP_LATE for a, b in itertools.pairwise(STEPS)},
        **{f"OB1: network {a} moved to the end": STEP_LATE for a in STEPS[:4]},
    },
    notes=(
        "Sensors: z1 back, z2 middle, z3 forward and odd y below a shelf, even y above it (text issue 11). The rig "
        "is kinematic (spec §5.9, about twice as fast): a drive switched off coasts speed × 20 ms, inside the ±6 mm "
        "(X) and ±4 mm (Y, Z) cam zones at any scan up to ~30 ms; a later stop, or a cam that fails, lets the axis "
        "run out of the zone and the estimate must follow (the textbook's ±0.5 on the N edge does; the axis then "
        "hunts back). 'A cam that fails' grades only safety: the reference hunts between x1 and x3 and never puts "
        "the fork in. The textbook's stated limitations (simultaneous requests, a request changed during the "
        "sequence) are outside the scenarios: the operator waits for the previous request to finish. Grading one "
        "solution simulates 174 s (≈ 2.2 s of CPU at a 1 ms scan); each wrong one is graded in the one scenario that "
        "shows its flaw (10 to 24 s)."
    ),
)
