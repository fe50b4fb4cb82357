"""The S7-1200 profile: organization blocks named ``OB<n>``, their kinds and numbers, and :data:`PROFILE`.

This is where the runtime reads an OB name: the Python front end asks it which task a name is (from the
profile's triggers). (A trace recorded without task names numbers ``"OB30"`` as 30 by a rule of the
trace file's own, :func:`plcsim.trace.table.trace_task_number`.)

>>> task_kind("OB30"), ob_number("OB100")
(('interrupt', 8), 100)
"""

from __future__ import annotations

import re

from plcsim.controllers.profiles import MemoryArea, Profile, Restart, SystemBit, Trigger
from plcsim.core.errors import ProgramError

DEFAULT_INTERRUPT_PERIOD = "100ms"
DEFAULT_INTERRUPT_PRIORITY = 8
OB_NAME = re.compile(r"^OB(\d+)$")


def is_ob_name(name: str) -> bool:
    """Whether ``name`` names an organization block (``OB1``, ``OB30``; case-sensitive)."""
    return OB_NAME.match(name) is not None


def ob_number(name: str) -> int:
    """The number of an OB name: ``"OB30"`` -> 30 (the trace's task column on an S7)."""
    match = OB_NAME.match(name)
    if match is None:
        raise ProgramError(f"{name!r} is not an OB name (OB1, OB30..OB38, OB100)")
    return int(match.group(1))


TRIGGERS = (
    Trigger("cyclic", "OB1", "program cycle", 1, 1),
    Trigger("interrupt", "OB30..OB38", "cyclic interrupts", 30, 38, DEFAULT_INTERRUPT_PRIORITY),
    Trigger("startup", "OB100", "startup", 100, 100),
)
"""The S7-1200's task triggers by OB number: OB1 runs again as soon as it ends, OB30..OB38 are due at
start + phase + k * period and pre-empt between networks, OB100 runs once at STOP -> RUN."""


def task_kind(name: str) -> tuple[str, int]:
    """Kind and default priority of an OB by its number (S7-1200 numbering, :data:`TRIGGERS`)."""
    number = ob_number(name)
    for trigger in TRIGGERS:
        if trigger.covers(number):
            return trigger.kind, trigger.priority
    choices = [f"{t.tasks} ({t.meaning})" for t in TRIGGERS]
    raise ProgramError(f"{name} is not supported: use {', '.join(choices[:-1])} or {choices[-1]}")


def _instructions() -> frozenset[str]:
    from plcsim.controllers.s7.instructions import BLOCKS, FUNCTIONS

    return frozenset(FUNCTIONS) | {box for block in BLOCKS.values() for box in block.boxes}


def _parse_address(text: str) -> object:
    from plcsim.tags.memory import parse_address

    return parse_address(text)


def _system_bits() -> tuple[SystemBit, ...]:
    from plcsim.controllers.s7.config import CLOCK_BITS, SYSTEM_BITS

    clock = tuple(
        SystemBit(name, f"clock memory byte, bit {bit}", f"square wave, {half * 2} ms period")
        for bit, name, half in CLOCK_BITS
    )
    meaning = {
        "FirstScan": "TRUE in the first OB1 scan after STOP -> RUN",
        "DiagStatusUpdate": "TRUE in the scan after the diagnostic buffer changed",
        "AlwaysTRUE": "always TRUE",
        "AlwaysFALSE": "always FALSE",
    }
    system = tuple(SystemBit(name, f"system memory byte, bit {bit}", meaning[name]) for bit, name in SYSTEM_BITS)
    return clock + system


PROFILE = Profile(
    name="s7-1200",
    family="Siemens S7-1200",
    byte_order="big",
    areas=(
        MemoryArea("I", "input process image", ("%I0.0", "%IB0", "%IW64", "%ID0")),
        MemoryArea("Q", "output process image", ("%Q0.0", "%QB0", "%QW80", "%QD0")),
        MemoryArea("M", "bit memory (markers)", ("%M10.0", "%MB10", "%MW10", "%MD10")),
        MemoryArea("DB", "non-optimized data blocks", ("%DB1.DBX0.0", "%DB1.DBB0", "%DB1.DBW2", "%DB1.DBD4")),
    ),
    parse_address=_parse_address,
    system_bits=_system_bits(),
    restarts=(
        Restart("STOP->RUN", "retain tags, counters and the retentive %M bytes; the rest takes its start value"),
        Restart("power cycle", "as STOP->RUN; an execution the cut interrupts keeps what it already did"),
    ),
    triggers=TRIGGERS,
    instructions=_instructions,
    controller="plcsim.controllers.s7.cpu:CPU",
    source_reader="plcsim.frontends.python.program:Program.from_source",
)
"""The S7-1200 as the course's programs see it (entry point ``s7-1200`` of ``plcsim.profiles``)."""
