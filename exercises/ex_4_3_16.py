"""4.3.16 Skip hoist control. Plant: SKIP (side view, ``plants/skip.py``).

The rig is variant A of spec §5.7 (40/25 mm/s): the textbook's 32 s is a small reserve over the full skip's
ascent (≈ 28.6 s), and the down alarm, whose time the textbook leaves open, is 45 s by the same rule over the slow
descent (≈ 39.4 s). What the plant saw is graded beside the bits: the speed at which the skip reached the top
sensor (``speed measured``), the share of the batch that reached the mixer (``pour ended``), the converter's
complaints and the end buffers. POZ1/POZ2 are compared scan by scan with the states the task defines, computed
from the input image and the skip's direction (``exercises/_skip.py``).
"""

from __future__ import annotations

from exercises._common import solution
from exercises._skip import DOLNY, HORNY, SPOMAL, WrongPosition, auto_cycle, refill
from plants.skip import FILL, Skip
from plcsim.check import all_of, any_of, becomes, event, event_data, holds, never, off, on, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, after_event, jam_motor, power_cycle, stuck, write
from plcsim.tags import DB
from plcsim.tags.types import Bool

NUMBER = "4.3.16"
FAULT_WORDS = (
    "Faults happen: the rope may jam (the skip then stands where it is), and a sensor may fail (it never reports the "
    "skip)"
)
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""
AUTO, PLNY, POVOL = "DB_SKIP.AUTO", "DB_SKIP.PLNY", "DB_MIESACKA.KAMENIVO_POVOL"
UP, DOWN, FAST, SLOW = "START_HORE", "START_DOLE", "RYCHLOST_RYCHLO", "RYCHLOST_POMALY"
ALARM_UP, ALARM_DOWN, ALARM_SLOW = (
    "DB_SKIP.ALARM_NEDOSIEL_HORE",
    "DB_SKIP.ALARM_NEDOSIEL_DOLE",
    "DB_SKIP.ALARM_CHYBA_SPOMAL_SN",
)
SLOW_SPEED = 25.0  # mm/s

ONE = "one AUTO cycle"
TWO = "two AUTO cycles"
MODE = "mode change mid-travel"
BETWEEN = "start between sensors"
MANUAL = "manual ascent"
BOTH = "both manual commands"
JAM_UP = "rope jam going up"
JAM_DOWN = "rope jam going down"
DEAD_SLOW = "slow-down sensor dead"
DEAD_TOP = "top sensor dead"
DEAD_BOTTOM = "bottom sensor dead"
MIXER_WAITS = "mixer not ready yet"
OTHER_MODE = "the other mode's commands"
CYCLES = (ONE, TWO)
"""Normal automatic cycles: everything the task asks of a cycle holds in them."""
NORMAL = (ONE, TWO, MODE, BETWEEN, MANUAL, BOTH, MIXER_WAITS, OTHER_MODE)
"""No fault: no alarm may be raised and the converter and the buffers must not be troubled."""
ARRIVALS = (ONE, TWO, MODE, JAM_UP, JAM_DOWN)
"""An automatic ascent with a working slow-down sensor reaches the top (or is meant to)."""

TASK = (
    "A skip carries the dosed aggregate of a concrete-batching plant from the weighing and dosing place up an "
    "inclined track to the mixer, which stands higher. A steel rope wound on a winch pulls it; the winch motor is "
    "fed by a frequency converter: START_HORE and START_DOLE select the direction, RYCHLOST_RYCHLO (fast, 40 mm/s) "
    "and RYCHLOST_POMALY (slow, 25 mm/s) the speed. The converter holds the skip with its brake whenever no "
    "direction is commanded; both directions at once trip it, and a direction without a speed bit gives 0 Hz "
    "(the brake stays on). Three sensors, all NO: SNIMAC_DOLNY at the bottom (the loading place under the dosing "
    "hopper), SNIMAC_SPOMAL a short way below the top (slow-down), SNIMAC_HORNY at the top, where the bucket has "
    "tipped on the curved end of the track and pours its aggregate into the mixer. End buffers lie just beyond "
    "the bottom and the top sensor. Upward the skip runs fast from SNIMAC_DOLNY to SNIMAC_SPOMAL and slow from "
    "there to SNIMAC_HORNY; downward it runs slow. A full skip climbs in about 29 s, the empty one descends in "
    "about 40 s, a manual (slow) ascent takes about 41 s.\n"
    "The operator works the HMI bits of DB_SKIP: AUTO (TRUE = automatic, FALSE = manual; it may be changed at any "
    "time, also while the skip travels), MAN_HORE and MAN_DOLE (manual up and down, held while pressed; both may "
    "be pressed together by mistake). When the dosing hopper has filled the skip, the dosing control sets "
    "DB_SKIP.PLNY; the mixer's control sets DB_MIESACKA.KAMENIVO_POVOL while it accepts aggregate and takes back "
    "DB_MIESACKA.KAMENIVO_DODANE when it has taken a batch. The PLC may be restarted with the skip anywhere. "
    "Faults happen: the rope may jam (the skip then stands where it is), and a sensor may fail (it never "
    "reports the skip).\n"
    "Task: create the skip control program with:\n"
    "1. automatic and manual mode: in AUTO the commands DB_SKIP.AUTO_HORE/AUTO_DOLE drive the skip, in manual mode "
    "MAN_HORE/MAN_DOLE (within 1 scan); the other mode's commands are ignored; START_HORE and START_DOLE are "
    "never TRUE together; the skip is never driven up while SNIMAC_HORNY or down while SNIMAC_DOLNY is actuated, "
    "and never reaches an end buffer when nothing is wrong;\n"
    "2. travel up in AUTO when the skip is at the bottom (SNIMAC_DOLNY), full (PLNY) and the mixer allows aggregate "
    "(KAMENIVO_POVOL): START_HORE with RYCHLOST_RYCHLO within 2 scans; no automatic cycle starts unless "
    "SNIMAC_DOLNY reports the skip at the bottom; stop within 1 scan at SNIMAC_HORNY;\n"
    "3. at the top in AUTO, dump for 6 s: then reset PLNY, set DB_MIESACKA.KAMENIVO_DODANE (aggregate delivered) "
    "and travel down; stop at SNIMAC_DOLNY. At least 95 % of the batch must reach the mixer;\n"
    "4. speeds: fast from the bottom to SNIMAC_SPOMAL, slow from SNIMAC_SPOMAL on (switched within 1 scan), so "
    "that the skip reaches SNIMAC_HORNY at the slow speed; slow downward; manual travel is always slow; a "
    "direction output always comes with exactly one speed output (within 1 scan); RYCHLOST_RYCHLO and "
    "RYCHLOST_POMALY are never TRUE together;\n"
    "5. alarms, latched with SET (acknowledging them is not part of this task): ALARM_NEDOSIEL_HORE when an "
    "automatic ascent has not reached SNIMAC_HORNY 32 s after START_HORE rose, ALARM_NEDOSIEL_DOLE when an "
    "automatic descent has not reached SNIMAC_DOLNY 45 s after START_DOLE rose (the textbook leaves this time "
    "open: 45 s is the same small reserve over the 40 s descent as 32 s is over the ascent); the travel alarms "
    "watch automatic travel only, since a manual ascent outlasts 32 s; ALARM_CHYBA_SPOMAL_SN within 1 scan of "
    "reaching SNIMAC_HORNY moving up without having passed SNIMAC_SPOMAL; no alarm when nothing is wrong;\n"
    "6. position states for the visualisation: DB_SKIP.POZ1 TRUE while the skip is between SNIMAC_DOLNY and "
    "SNIMAC_SPOMAL as the sensors report it (after leaving one of them towards the other), DB_SKIP.POZ2 "
    "likewise between SNIMAC_SPOMAL and SNIMAC_HORNY; both FALSE while any sensor is actuated, and after a restart "
    "of the PLC until the skip leaves a sensor again. Put the edge memory bits in %M."
)

# The words of the task each check grades (``plcsim show 4.3.16`` prints every requirement with its checks).
INTERLOCK = "START_HORE and START_DOLE are never TRUE together"
AT_AN_END = "the skip is never driven up while SNIMAC_HORNY or down while SNIMAC_DOLNY is actuated"
NO_BUFFER = "never reaches an end buffer when nothing is wrong"
MODES = (
    "in AUTO the commands DB_SKIP.AUTO_HORE/AUTO_DOLE drive the skip, in manual mode MAN_HORE/MAN_DOLE (within 1 "
    "scan); the other mode's commands are ignored"
)
ASCENT = (
    "travel up in AUTO when the skip is at the bottom (SNIMAC_DOLNY), full (PLNY) and the mixer allows aggregate "
    "(KAMENIVO_POVOL): START_HORE with RYCHLOST_RYCHLO within 2 scans"
)
FROM_THE_BOTTOM = "no automatic cycle starts unless SNIMAC_DOLNY reports the skip at the bottom"
DUMP = (
    "at the top in AUTO, dump for 6 s: then reset PLNY, set DB_MIESACKA.KAMENIVO_DODANE (aggregate delivered) and "
    "travel down"
)
POURED = "At least 95 % of the batch must reach the mixer"
FAST_FIRST = "fast from the bottom to SNIMAC_SPOMAL"
SLOW_AT_SPOMAL = "slow from SNIMAC_SPOMAL on (switched within 1 scan)"
SLOW_ARRIVAL = "so that the skip reaches SNIMAC_HORNY at the slow speed"
SLOW_DOWN = "slow downward"
SLOW_MANUAL = "manual travel is always slow"
ONE_SPEED = "a direction output always comes with exactly one speed output (within 1 scan)"
NOT_BOTH_SPEEDS = "RYCHLOST_RYCHLO and RYCHLOST_POMALY are never TRUE together"
LATCHED = "alarms, latched with SET"
UP_ALARM = "ALARM_NEDOSIEL_HORE when an automatic ascent has not reached SNIMAC_HORNY 32 s after START_HORE rose"
DOWN_ALARM = "ALARM_NEDOSIEL_DOLE when an automatic descent has not reached SNIMAC_DOLNY 45 s after START_DOLE rose"
SLOW_ALARM = (
    "ALARM_CHYBA_SPOMAL_SN within 1 scan of reaching SNIMAC_HORNY moving up without having passed SNIMAC_SPOMAL"
)
NO_ALARM = "no alarm when nothing is wrong"
POSITIONS = (
    "DB_SKIP.POZ1 TRUE while the skip is between SNIMAC_DOLNY and SNIMAC_SPOMAL as the sensors report it (after "
    "leaving one of them towards the other), DB_SKIP.POZ2 likewise between SNIMAC_SPOMAL and SNIMAC_HORNY; both "
    "FALSE while any sensor is actuated, and after a restart of the PLC until the skip leaves a sensor again"
)

EXERCISE = Exercise(
    number=NUMBER,
    slug="skip-hoist",
    title="Skip hoist control",
    title_sk="Príklad 16 – Riadenie skipu",
    task=TASK,
    io=[
        IO(DOLNY, "bottom position sensor", "Bool", "%I0.0", "NO"),
        IO(HORNY, "top position sensor", "Bool", "%I0.1", "NO"),
        IO(SPOMAL, "slow-down sensor", "Bool", "%I0.2", "NO"),
        IO(UP, "run up", "Bool", "%Q0.0"),
        IO(DOWN, "run down", "Bool", "%Q0.1"),
        IO(SLOW, "speed slow (converter fixed frequency)", "Bool", "%Q0.2"),
        IO(FAST, "speed fast", "Bool", "%Q0.3", comment="the prose's RYCHLOST_RYHCHLO is a typo (text issue 9)"),
        IO("HRANA_DOLNY", "edge memory of N(SNIMAC_DOLNY)", "Bool", "%M0.0", comment="name and address proposed"),
        IO("HRANA_SPOMAL_1", "edge memory of N(SNIMAC_SPOMAL) for POZ1", "Bool", "%M0.1", comment="proposed"),
        IO("HRANA_SPOMAL_2", "edge memory of N(SNIMAC_SPOMAL) for POZ2", "Bool", "%M0.2", comment="proposed"),
        IO("HRANA_HORNY", "edge memory of N(SNIMAC_HORNY)", "Bool", "%M0.3", comment="name and address proposed"),
    ],
    dbs={
        "DB_SKIP": DB(
            AUTO=Bool(False),
            AUTO_HORE=Bool(False),
            AUTO_DOLE=Bool(False),
            MAN_HORE=Bool(False),
            MAN_DOLE=Bool(False),
            POZ1=Bool(False),
            POZ2=Bool(False),
            PLNY=Bool(False),
            ALARM_NEDOSIEL_HORE=Bool(False),
            ALARM_NEDOSIEL_DOLE=Bool(False),
            ALARM_CHYBA_SPOMAL_SN=Bool(False),
            comment="the skip's HMI commands, states and alarms (Fig. 4.147)",
        ),
        "DB_MIESACKA": DB(
            KAMENIVO_POVOL=Bool(False),
            KAMENIVO_DODANE=Bool(False),
            comment="the mixer's: aggregate allowed (set by the mixer's control), aggregate delivered (name proposed)",
        ),
    },
    rig=Skip,
    hmi={
        AUTO: "switch",
        "DB_SKIP.MAN_HORE": "button",
        "DB_SKIP.MAN_DOLE": "button",
        PLNY: "switch",
        POVOL: "switch",
    },
    scenarios=[
        Scenario(
            ONE,
            *auto_cycle(),
            duration="77s",
            description="AUTO, the skip filled (PLNY) and the mixer ready: up, 6 s dump, down to the bottom",
        ),
        Scenario(
            TWO,
            *auto_cycle(),
            *refill(),
            duration="113s",
            description="two automatic cycles: back at the bottom the skip is filled again 1..1.5 s after it "
            "arrived; the run ends during the second dump",
        ),
        Scenario(
            MODE,
            *auto_cycle(),
            write(AUTO, False, t="9s..12s"),
            write(AUTO, True, t="14s..16s"),
            write(AUTO, False, when=after_event("pour ended"), delay="8s..10s"),
            write(AUTO, True, when=after_event("pour ended"), delay="12s..13s"),
            duration="58s",
            description="AUTO is switched off for 3..6 s during the fast ascent (the skip stops and waits), then on "
            "again: the ascent goes on; after the dump AUTO is switched off again for 2..5 s during the descent, "
            "then on: the descent goes on",
        ),
        Scenario(
            BETWEEN,
            write("DB_SKIP.MAN_HORE", True, t="0.5s"),
            write("DB_SKIP.MAN_HORE", False, t="8s..10s"),
            power_cycle(t="11s"),
            write("DB_SKIP.MAN_DOLE", True, t="12s..12.5s"),
            write("DB_SKIP.MAN_DOLE", False, when=after_event("speed measured", DOLNY), delay="0.3s..0.6s"),
            write(AUTO, True, when=after_event("speed measured", DOLNY), delay="1s..1.5s"),
            write(PLNY, True, when=after_event("speed measured", DOLNY), delay="1s..1.5s"),
            write(POVOL, True, when=after_event("speed measured", DOLNY), delay="1s..1.5s"),
            duration="32s",
            description="in manual mode the skip is run up 8..10 s; the PLC is then restarted with the skip "
            "between the sensors; the operator brings it down by hand and starts an automatic cycle",
        ),
        Scenario(
            MANUAL,
            write("DB_SKIP.MAN_HORE", True, t="0.5s"),
            write("DB_SKIP.MAN_HORE", False, when=after_event("speed measured", HORNY), delay="0.5s..1s"),
            duration="43s",
            description="in manual mode the operator holds MAN_HORE until the skip is at the top (about 41 s)",
        ),
        Scenario(
            BOTH,
            write("DB_SKIP.MAN_HORE", True, t="0.5s"),
            write("DB_SKIP.MAN_DOLE", True, t="3s..3.5s"),
            write("DB_SKIP.MAN_HORE", False, t="5s..5.5s"),
            duration="8s",
            description="in manual mode the operator runs the skip up and presses MAN_DOLE as well, then lets go "
            "of MAN_HORE",
        ),
        Scenario(
            MIXER_WAITS,
            *auto_cycle(mixer_ready="3s..4s"),
            duration="8s",
            description="AUTO and the skip full at the bottom, but the mixer allows aggregate only 2.3..3.5 s later: "
            "the skip waits for it, then goes up",
        ),
        Scenario(
            OTHER_MODE,
            FILL("skip", t="0.2s..0.4s"),
            write(PLNY, True, t="0.5s..0.7s"),
            write(POVOL, True, t="0.5s..0.9s"),
            write("DB_SKIP.MAN_HORE", True, t="1.5s..2s"),
            write("DB_SKIP.MAN_HORE", False, t="5s..6s"),
            write(AUTO, True, t="7s..7.5s"),
            write("DB_SKIP.MAN_DOLE", True, t="9s..9.5s"),
            write("DB_SKIP.MAN_DOLE", False, t="10.5s..11s"),
            write("DB_SKIP.MAN_HORE", True, t="12s..12.5s"),
            write("DB_SKIP.MAN_HORE", False, t="13.5s..14s"),
            duration="16s",
            description="in manual mode, the skip full at the bottom and the mixer ready, the operator runs the skip "
            "up by hand for 3..4.5 s, selects AUTO away from the bottom, then presses MAN_DOLE and MAN_HORE: "
            "nothing may move in AUTO",
        ),
        Scenario(
            JAM_UP,
            *auto_cycle(),
            jam_motor(UP, t="10s..14s"),
            outside={FAULTS: FAULT_WORDS},
            duration="35s",
            description="the rope jams during the fast ascent: the skip stands where it is",
        ),
        Scenario(
            JAM_DOWN,
            *auto_cycle(),
            jam_motor(DOWN, when=after_event("pour ended"), delay="8s..12s"),
            outside={FAULTS: FAULT_WORDS},
            duration="83s",
            description="the rope jams during the descent: the skip stands where it is",
        ),
        Scenario(
            DEAD_SLOW,
            stuck(SPOMAL, False, t="0s"),
            *auto_cycle(),
            outside={FAULTS: FAULT_WORDS},
            duration="28s",
            description="SNIMAC_SPOMAL never reports the skip (a dead sensor): an automatic ascent",
        ),
        Scenario(
            DEAD_TOP,
            stuck(HORNY, False, t="0s"),
            *auto_cycle(),
            outside={FAULTS: FAULT_WORDS},
            duration="35s",
            description="SNIMAC_HORNY never reports the skip (a dead sensor): an automatic ascent",
        ),
        Scenario(
            DEAD_BOTTOM,
            stuck(DOLNY, False, t="0s"),
            *auto_cycle(),
            outside={FAULTS: FAULT_WORDS},
            duration="5s",
            description="SNIMAC_DOLNY never reports the skip (a dead sensor) standing at the bottom, full, in AUTO",
        ),
    ],
    checks=[
        # criterion 1: interlocks
        never(all_of(UP, DOWN)).named("START_HORE and START_DOLE are never TRUE together").grades(INTERLOCK),
        never(all_of(FAST, SLOW))
        .named("RYCHLOST_RYCHLO and RYCHLOST_POMALY are never TRUE together")
        .grades(NOT_BOTH_SPEEDS),
        never(all_of(HORNY, UP)).named("never driven up while SNIMAC_HORNY is actuated").grades(AT_AN_END),
        never(all_of(DOLNY, DOWN)).named("never driven down while SNIMAC_DOLNY is actuated").grades(AT_AN_END),
        only(never(event("converter fault")).named("the converter never trips").grades(INTERLOCK), *NORMAL),
        only(
            never(all_of(any_of(UP, DOWN), off(FAST), off(SLOW)))
            .for_more_than("1 scan")
            .named("a direction output always comes with a speed output")
            .grades(ONE_SPEED),
            *NORMAL,
        ),
        only(never(event("end stop hit")).named("the skip never runs into an end buffer").grades(NO_BUFFER), *NORMAL),
        # criterion 2: the automatic ascent
        only(
            rises(UP)
            .within("2 scans")
            .after(becomes(all_of(AUTO, DOLNY, PLNY, POVOL)))
            .named("AUTO: START_HORE within 2 scans of a full skip at the bottom and the mixer ready")
            .grades(ASCENT),
            *CYCLES,
            MIXER_WAITS,
        ),
        only(
            never(all_of(AUTO, UP, DOLNY, off(POVOL)))
            .named("AUTO: no ascent before the mixer allows aggregate")
            .grades(ASCENT),
            MIXER_WAITS,
        ),
        only(
            never(all_of(UP, DOLNY, off(FAST)))
            .for_more_than("1 scan")
            .named("the automatic ascent starts fast")
            .grades(FAST_FIRST),
            *CYCLES,
            MIXER_WAITS,
        ),
        only(
            never(all_of(UP, SPOMAL, FAST))
            .for_more_than("1 scan")
            .named("slow within 1 scan of SNIMAC_SPOMAL")
            .grades(SLOW_AT_SPOMAL),
            *CYCLES,
            MODE,
        ),
        only(
            event_data("speed measured", "speed_mm_s", HORNY)
            .at_most(SLOW_SPEED * 1.05)
            .named("the skip reaches SNIMAC_HORNY at the slow speed (at most 5 % above it)")
            .grades(SLOW_ARRIVAL),
            *ARRIVALS[:3],
            MANUAL,
        ),
        # criterion 3: the dump and the descent
        only(
            rises(DOWN)
            .between("6s", "6s + 2 scans")
            .after(rises(HORNY), provided=AUTO)
            .named("AUTO: the skip dumps for 6 s at the top, then goes down")
            .grades(DUMP),
            *CYCLES,
        ),
        only(
            rises("DB_MIESACKA.KAMENIVO_DODANE")
            .between("6s", "6s + 2 scans")
            .after(rises(HORNY), provided=AUTO)
            .named("KAMENIVO_DODANE is set when the 6 s dump ends")
            .grades(DUMP),
            *CYCLES,
        ),
        only(
            event_data("pour ended", "fraction")
            .at_least(0.95)
            .named("at least 95 % of each batch reaches the mixer")
            .grades(POURED),
            *CYCLES,
            MODE,
        ),
        only(
            never(all_of(DOWN, FAST)).named("the skip always goes down slowly").grades(SLOW_DOWN),
            *NORMAL,
            JAM_DOWN,
        ),
        # criterion 5: manual mode
        only(
            never(all_of(off(AUTO), FAST)).named("manual travel is always slow").grades(SLOW_MANUAL),
            MANUAL,
            BETWEEN,
            MODE,
            BOTH,
        ),
        only(
            never(all_of(off(AUTO), "DB_SKIP.MAN_HORE", off("DB_SKIP.MAN_DOLE"), off(HORNY), off(UP)))
            .for_more_than("1 scan")
            .named("manual mode: MAN_HORE drives the skip up")
            .grades(MODES),
            MANUAL,
            BETWEEN,
            OTHER_MODE,
        ),
        only(
            never(all_of(off(AUTO), "DB_SKIP.MAN_DOLE", off("DB_SKIP.MAN_HORE"), off(DOLNY), off(DOWN)))
            .for_more_than("1 scan")
            .named("manual mode: MAN_DOLE drives the skip down")
            .grades(MODES),
            MANUAL,
            BETWEEN,
        ),
        only(
            never(all_of(off(AUTO), any_of(UP, DOWN), off("DB_SKIP.MAN_HORE"), off("DB_SKIP.MAN_DOLE")))
            .for_more_than("1 scan")
            .named("manual mode: no travel without a manual command (AUTO commands are ignored)")
            .grades(MODES),
            MODE,
            MANUAL,
            BETWEEN,
            OTHER_MODE,
        ),
        only(
            never(all_of(AUTO, any_of(UP, DOWN), any_of("DB_SKIP.MAN_HORE", "DB_SKIP.MAN_DOLE")))
            .for_more_than("1 scan")
            .named("AUTO: MAN_HORE and MAN_DOLE move nothing")
            .grades(MODES),
            OTHER_MODE,
        ),
        only(
            never(all_of(AUTO, UP, off(DOLNY), off("DB_SKIP.MAN_HORE"), off("DB_SKIP.MAN_DOLE")))
            .for_more_than("1 scan")
            .named("AUTO selected away from the bottom starts no automatic ascent")
            .grades(FROM_THE_BOTTOM),
            OTHER_MODE,
        ),
        # criterion 6: the position states
        never(WrongPosition("DB_SKIP.POZ1", 1))
        .named("POZ1 is TRUE exactly while the skip is between SNIMAC_DOLNY and SNIMAC_SPOMAL after moving there")
        .grades(POSITIONS),
        never(WrongPosition("DB_SKIP.POZ2", 2))
        .named("POZ2 is TRUE exactly while the skip is between SNIMAC_SPOMAL and SNIMAC_HORNY after moving there")
        .grades(POSITIONS),
        # criteria 4, 7, 8: the alarms
        only(never(on(ALARM_UP)).named("no up-travel alarm when nothing is wrong").grades(NO_ALARM), *NORMAL),
        only(never(on(ALARM_DOWN)).named("no down-travel alarm when nothing is wrong").grades(NO_ALARM), *NORMAL),
        only(never(on(ALARM_SLOW)).named("no slow-down sensor alarm when nothing is wrong").grades(NO_ALARM), *NORMAL),
        only(
            rises(ALARM_UP)
            .between("32s - 1 scan", "32s + 2 scans")
            .after(rises(UP))
            .named("ALARM_NEDOSIEL_HORE 32 s after START_HORE rose, if the top is not reached")
            .grades(UP_ALARM),
            JAM_UP,
            DEAD_TOP,
        ),
        only(
            holds(ALARM_UP).to_the_end().named("ALARM_NEDOSIEL_HORE stays latched").grades(LATCHED),
            JAM_UP,
            DEAD_TOP,
        ),
        only(
            rises(ALARM_DOWN)
            .between("45s - 1 scan", "45s + 2 scans")
            .after(rises(DOWN))
            .named("ALARM_NEDOSIEL_DOLE 45 s after START_DOLE rose, if the bottom is not reached")
            .grades(DOWN_ALARM),
            JAM_DOWN,
        ),
        only(
            holds(ALARM_DOWN).to_the_end().named("ALARM_NEDOSIEL_DOLE stays latched").grades(LATCHED),
            JAM_DOWN,
        ),
        only(
            rises(ALARM_SLOW)
            .within("1 scan")
            .after(rises(HORNY))
            .named("ALARM_CHYBA_SPOMAL_SN within 1 scan of reaching the top without passing SNIMAC_SPOMAL")
            .grades(SLOW_ALARM),
            DEAD_SLOW,
        ),
        only(
            never(rises(UP))
            .named("no automatic ascent unless SNIMAC_DOLNY reports the skip at the bottom")
            .grades(FROM_THE_BOTTOM),
            DEAD_BOTTOM,
        ),
    ],
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="the textbook's N1-N13 (N13 version 1, run first), with a direction interlock, the travel "
            "alarms for automatic travel only, and 45 s for the down alarm",
        ),
        solution(
            NUMBER,
            "solution-n13-speed",
            "alternative",
            "N13 version 2: the arrival at the top with RYCHLOST_RYCHLO still on (run before N9 rewrites it)",
            scenarios=(ONE, MANUAL, DEAD_SLOW, DEAD_TOP, JAM_DOWN),
        ),
        solution(
            NUMBER,
            "wrong-n13-after-reset",
            "wrong",
            "N13 version 1 placed after N5, the reset of POZ1/POZ2, with 'moving up' from AUTO_HORE: POZ2 is already "
            "cleared when the top is reached, a false alarm every cycle (the textbook's warning)",
            fails=("no slow-down sensor alarm when nothing is wrong",),
            scenarios=(ONE, DEAD_SLOW),
        ),
        solution(
            NUMBER,
            "wrong-n13-start-hore",
            "wrong",
            "N13 version 2 at the end of OB1 with 'moving up' from START_HORE: N1 has cleared START_HORE (and N9 "
            "RYCHLOST_RYCHLO) in the scan the top is reached, so a dead slow-down sensor is never reported",
            fails=("ALARM_CHYBA_SPOMAL_SN within 1 scan of reaching the top without passing SNIMAC_SPOMAL",),
            scenarios=(DEAD_SLOW,),
        ),
        solution(
            NUMBER,
            "wrong-manual-up-alarm",
            "wrong",
            "the textbook's N11 as printed, not restricted to AUTO: a full manual ascent (slow, ≈ 41 s) raises "
            "ALARM_NEDOSIEL_HORE although nothing is wrong",
            fails=("no up-travel alarm when nothing is wrong",),
            scenarios=(MANUAL,),
        ),
        solution(
            NUMBER,
            "wrong-down-alarm-32s",
            "wrong",
            "the down alarm with the up alarm's 32 s: the slow descent takes ≈ 39 s, a false alarm every cycle",
            fails=("no down-travel alarm when nothing is wrong",),
            scenarios=(ONE,),
        ),
        solution(
            NUMBER,
            "wrong-no-interlock",
            "wrong",
            "the textbook's N1/N2 as printed: MAN_HORE and MAN_DOLE together command both directions and trip the "
            "converter",
            fails=("START_HORE and START_DOLE are never TRUE together", "the converter never trips"),
            scenarios=(BOTH,),
        ),
        solution(
            NUMBER,
            "wrong-slow-only-at-sensor",
            "wrong",
            "(a slip) the slow speed only while SNIMAC_SPOMAL is actuated, POZ2 forgotten in N10: past the sensor the "
            "direction has no speed, the converter gives 0 Hz and the skip stops short of the top",
            fails=("a direction output always comes with a speed output", "no up-travel alarm when nothing is wrong"),
            scenarios=(ONE,),
        ),
        solution(
            NUMBER,
            "wrong-fast-all-the-way",
            "wrong",
            "(a slip) RYCHLOST_RYCHLO from START_HORE alone in AUTO: with the slow bit on too the converter runs "
            "fast, and the skip reaches the top at 40 mm/s",
            fails=(
                "RYCHLOST_RYCHLO and RYCHLOST_POMALY are never TRUE together",
                "the skip reaches SNIMAC_HORNY at the slow speed (at most 5 % above it)",
            ),
            scenarios=(ONE,),
        ),
        solution(
            NUMBER,
            "wrong-short-dump",
            "wrong",
            "(a slip) a 1 s dump timer: the skip leaves the top while the aggregate still pours, and part of the "
            "batch rides down again",
            fails=(
                "AUTO: the skip dumps for 6 s at the top, then goes down",
                "at least 95 % of each batch reaches the mixer",
            ),
            scenarios=(ONE,),
        ),
        solution(
            NUMBER,
            "wrong-poz-by-level",
            "wrong",
            "(a slip) POZ1 := no sensor actuated and not POZ2, POZ2 from the N edges only: POZ1 also shows "
            "between SNIMAC_SPOMAL and SNIMAC_HORNY until POZ2 is set, and after a restart",
            fails=("POZ1 is TRUE exactly while the skip is between SNIMAC_DOLNY and SNIMAC_SPOMAL after moving there",),
            scenarios=(BETWEEN,),
        ),
    ],
    spec_equivalent={
        "OB1: network directions moved to the end": (
            "START_HORE/START_DOLE are written at the end of the scan: a direction starts in the scan that sets "
            "AUTO_HORE, and its speed output follows one scan later, inside item 4's 'within 1 scan'; the "
            "direction still drops in the scan that reads SNIMAC_HORNY or SNIMAC_DOLNY (N1/N2 test the sensor "
            "themselves), and N13 and N3-N5 read the direction the skip was driven with, as the reference does"
        ),
        "s.MAN_HORE and (not s.MAN_DOLE) → s.MAN_HORE": (
            "with MAN_HORE and MAN_DOLE pressed together the skip goes on up where the reference stops it: the task "
            "says only that both may be pressed by mistake and that START_HORE and START_DOLE are never TRUE "
            "together (N2 still has NOT START_HORE), not which command wins or that neither does"
        ),
        "s.MAN_DOLE and (not s.MAN_HORE) → s.MAN_DOLE": (
            "with MAN_HORE and MAN_DOLE pressed together the skip goes down where the reference stops it: the task "
            "says only that both may be pressed by mistake and that START_HORE and START_DOLE are never TRUE "
            "together, not which command wins or that neither does"
        ),
        "s.AUTO and t.SNIMAC_HORNY and (not s.PLNY) → t.SNIMAC_HORNY and (not s.PLNY)": (
            "N8 without AUTO also sets AUTO_DOLE when an empty skip is run up to the top by hand: in manual mode it "
            "drives nothing (N2 reads AUTO_DOLE only in AUTO), SNIMAC_DOLNY resets it, and AUTO selected at the top "
            "takes the empty skip down at once, as the reference does (its N8 sets AUTO_DOLE in that first scan); "
            "it differs only when AUTO is selected with that empty skip between the sensors (it goes on down, the "
            "reference waits), of which the task says nothing"
        ),
        "not s.AUTO and (t.START_HORE or t.START_DOLE) → not s.AUTO": (
            "N10 without the direction test holds RYCHLOST_POMALY in manual mode also while the skip stands: item 4 "
            "asks that manual travel be slow and that every direction come with exactly one speed, never a speed "
            "only with a direction; the task's converter brakes whenever no direction is commanded, so a speed bit "
            "alone moves nothing (no check of the converter's complaints fails), and with a direction it is the "
            "manual speed the task asks for"
        ),
        "s.AUTO and t.SNIMAC_HORNY and (not s.PLNY) → s.AUTO and (not s.PLNY)": (
            "N8 without SNIMAC_HORNY is the textbook's item 3 as worded ('travel down in automatic mode if the skip is "
            "empty'); the reference is its solution (down from the top). Both set AUTO_DOLE when the dump ends, and "
            "at the bottom SNIMAC_DOLNY resets it in the same network. They differ only for an empty skip in AUTO "
            "that SNIMAC_DOLNY does not report: between the sensors it goes down to the bottom where the reference "
            "waits (the task says nothing of it); at the bottom with SNIMAC_DOLNY dead it runs into the bottom buffer "
            "and raises ALARM_NEDOSIEL_DOLE 45 s after START_DOLE rose. That is what the reference does on any "
            "descent once SNIMAC_DOLNY has failed (the sensor failing during the dump: the buffer ≈ 41 s after "
            "START_DOLE rose, the alarm at 45 s), since N2 stops a descent only at the sensor. The task's answer to a "
            "failed sensor is the alarm (the textbook: an alarm 'could' block the skip; its solution does not), so it "
            "asks no program to keep the skip out of the buffer once SNIMAC_DOLNY has failed"
        ),
    },
    notes=(
        "Variant A of spec §5.7 (fast 40 mm/s, slow 25 mm/s, 1000 mm track, SNIMAC_SPOMAL 200 mm below the top): a "
        "full skip climbs in ≈ 28.6 s, so the textbook's 32 s is the 'small reserve' it asks for; the empty skip "
        "descends in ≈ 39.4 s, and the down alarm the textbook leaves open is 45 s by the same rule. The travel "
        "alarms watch automatic travel only: with the textbook's N11 a full manual ascent (≈ 40.6 s) raises the up "
        "alarm, which the task rules out. N13 needs 'moving up' from the scan before the arrival: N1 clears "
        "START_HORE, N9 RYCHLOST_RYCHLO and N5 POZ2 in the arrival scan (spec §2 analysis); the reference runs N13 "
        "first. The textbook has no direction interlock; the task asks for one ('both may be pressed together by "
        "mistake'). Nobody acknowledges the alarms (DB_SKIP has no ACK). The pour is a mass flow: the bucket "
        "tilts from 900 mm, pours from 975 mm, and a skip at the top sensor is empty ≈ 2 s after arriving. "
        "POZ1/POZ2 are graded against the states computed from the input image and the skip's direction; a "
        "restart clears them. 'Bottom sensor dead': the skip is at the bottom but SNIMAC_DOLNY reads FALSE, so "
        "no automatic ascent may start (N6 needs the sensor)."
    ),
)
