"""4.3.22 Fourth program in OB30 (edge detection). Plant: PANEL. (Analysis exercise.)"""

from exercises._common import solution
from exercises._panel import OB30_CPU
from plants import Panel
from plcsim.check import eventually, final, never, value
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, press, start_cpu, stop_cpu
from plcsim.tags import DB
from plcsim.tags.types import Int

NUMBER = "4.3.22"
IN_OB30 = "enter the program in OB30"
"""What the checks grade: the task's program entered in OB30, as the task gives it."""
CASE_A, CASE_B = "case a", "case b"
RESTART, RETAIN = "case b with a restart", "case b, SB1 retentive"

EXERCISE = Exercise(
    number=NUMBER,
    slug="ob30-4-edge",
    title="Fourth program in OB30 (edge detection)",
    title_sk="Príklad 22 – Štvrtý program v OB30",
    task=(
        "A rising-edge program (Fig. 4.186) runs in OB30 with a period of 1 s; its execution takes about 1 ms: "
        "a positive-edge contact on the push-button TL (wired NO; edge memory bit SB1) enables an ADD that "
        "increments D.CISLO (variable CISLO, 'number', in data block D) by 1. OB30 is called at the STOP->RUN "
        "instant (0 s), then at 1 s, 2 s ...\n"
        "Task: enter the program in OB30 and analyse how often the ADD executes for the two press timings of "
        "Figs. 4.187 and 4.188. TL as the calls at 0, 1, 2, 3, 4, 5 s see it: case a 0 0 0 1 1 0 (with a short "
        "press between 0.1 s and 0.6 s); case b 1 1 1 1 1 0 (pressed already at STOP->RUN). Analyse case b also "
        "when the CPU is stopped and started again (STOP->RUN) while TL is held, once with SB1 an ordinary memory "
        "bit and once with MB0, which holds SB1, configured retentive."
    ),
    io=[
        IO("TL", "push-button", "Bool", "%I0.0", "NO", comment="address proposed; the textbook gives none"),
        IO("SB1", "edge memory bit of the P contact", "Bool", "%M0.0", comment="non-retentive %M; address proposed"),
    ],
    dbs={"D": DB(CISLO=Int())},
    rig=lambda: Panel(buttons=("TL",), switches=(), lamps=()),
    cpu=OB30_CPU,
    scenario_cpu={RETAIN: {"retentive_markers": 1}},
    scenarios=[
        Scenario(
            CASE_A,
            *press("TL", t="50ms..300ms", hold="100ms..500ms"),
            *press("TL", t="2.05s..2.95s", hold="2s..2.04s"),
            duration="6s",
            description="Fig. 4.187: a short press between the 0 s and 1 s calls, then a press from 2.05..2.95 s "
            "to 4.05..4.99 s (seen by the calls at 3 s and 4 s)",
        ),
        Scenario(
            CASE_B,
            *press("TL", t="0s", hold="4.05s..4.95s"),
            duration="6s",
            description="Fig. 4.188: TL pressed at STOP->RUN (0 s) and held until 4.05..4.95 s",
        ),
        Scenario(
            RESTART,
            *press("TL", t="0s", hold="6s"),
            stop_cpu(t="1.3s..1.7s"),
            start_cpu(t="2.3s..2.7s"),
            duration="5s",
            description="TL held all the time; the CPU is switched to STOP and back to RUN in between",
        ),
        Scenario(
            RETAIN,
            *press("TL", t="0s", hold="6s"),
            stop_cpu(t="1.3s..1.7s"),
            start_cpu(t="2.3s..2.7s"),
            duration="5s",
            description="as 'case b with a restart', but MB0 (and with it SB1) is configured retentive",
        ),
    ],
    checks=[
        only(
            never(value("D.CISLO") > 0)
            .during("0s", "3s")
            .named("case a: the short press and the calls at 0, 1, 2 s add nothing"),
            CASE_A,
        ),
        only(
            eventually(value("D.CISLO") == 1).before("3s + 1ms").named("case a: the edge is seen by the call at 3 s"),
            CASE_A,
        ),
        only(
            eventually(value("D.CISLO") == 1)
            .before("1ms")
            .named("case b: the edge is seen by the call at 0 s (SB1 cleared at STOP->RUN)"),
            CASE_B,
            RESTART,
            RETAIN,
        ),
        only(final("D.CISLO").equals(1).named("D.CISLO is incremented exactly once"), CASE_A, CASE_B),
        only(
            final("D.CISLO").equals(1).named("after STOP->RUN with TL held, the first call counts the edge again"),
            RESTART,
        ),
        only(
            final("D.CISLO").equals(0).named("with SB1 retentive, TL held through STOP->RUN gives no new edge"), RETAIN
        ),
    ],
    requirements={
        "case a: the short press and the calls at 0, 1, 2 s add nothing": IN_OB30,
        "case a: the edge is seen by the call at 3 s": IN_OB30,
        "case b: the edge is seen by the call at 0 s (SB1 cleared at STOP->RUN)": IN_OB30,
        "D.CISLO is incremented exactly once": IN_OB30,
        "after STOP->RUN with TL held, the first call counts the edge again": (
            "when the CPU is stopped and started again (STOP->RUN) while TL is held"
        ),
        "with SB1 retentive, TL held through STOP->RUN gives no new edge": (
            "once with MB0, which holds SB1, configured retentive"
        ),
    },
    solutions=[
        solution(NUMBER, "reference", explanation="-|P|- TL (SB1) -> ADD D.CISLO + 1 in OB30 (1 s)"),
        solution(
            NUMBER,
            "wrong-no-edge",
            "wrong",
            "a plain contact instead of the edge: every call that finds TL pressed adds 1",
            fails=(
                "D.CISLO is incremented exactly once",
                "with SB1 retentive, TL held through STOP->RUN gives no new edge",
            ),
        ),
        solution(
            NUMBER,
            "wrong-in-ob1",
            "wrong",
            "the edge in OB1: the short press between two OB30 calls is counted too",
            fails=(
                "case a: the short press and the calls at 0, 1, 2 s add nothing",
                "D.CISLO is incremented exactly once",
            ),
        ),
    ],
    notes=(
        "D is a non-retentive global DB with CISLO Int (type [R]); SB1 sits at %M0.0 (proposed) so that "
        "'retentive_markers = 1' (MB0 retentive) makes it retentive in the last scenario. The CPU starts at t = 0 "
        "with the OB30 call at 0 s, which is the STOP->RUN of case b. After a STOP->RUN both D.CISLO and SB1 "
        "start from 0/FALSE, and the call at the restart instant counts the held button again: the trace shows "
        "D.CISLO = 1 before and after (zeroed and incremented within that call), so the restart scenario checks "
        "the end value. With MB0 retentive SB1 stays TRUE, no edge is seen and D.CISLO stays 0 after the "
        "restart (acceptance criterion 2). The textbook shows no wrong program; 'wrong-no-edge' and "
        "'wrong-in-ob1' are plausible slips."
    ),
)
