"""The Tecomat NS950 profile: byte registers X/Y/S/R/D/U, processes P0..P64, cold and warm restarts.

Its controller is :class:`plcsim.controllers.tecomat.cpu.TecomatCPU` (a controller of its own behind
:class:`plcsim.controllers.protocol.Controller`, not a profile inside the S7 runtime: ``docs/architecture.md``
says why); this module only describes it, from the tables the controller itself runs on.

>>> PROFILE.parse_address("RW4").width, PROFILE.trigger_of(63).kind, "EOC" in PROFILE.instructions()
('word', 'first cycle', True)
"""

from __future__ import annotations

from plcsim.controllers.profiles import MemoryArea, Profile, Restart, SystemBit, Trigger


def _instructions() -> frozenset[str]:
    from plcsim.controllers.tecomat.mnemonics import DEFINED

    return DEFINED


def _parse_address(text: str) -> object:
    from plcsim.controllers.tecomat.memory import parse_address

    return parse_address(text)


PROFILE = Profile(
    name="tecomat-ns950",
    family="Tecomat NS950",
    byte_order="little",
    areas=(
        MemoryArea("X", "input images (sampled at the turnaround)", ("X0.0", "X0", "XW0")),
        MemoryArea("Y", "output images (written at the cycle's end)", ("Y0.0", "Y0", "YW0")),
        MemoryArea("S", "system registers", ("S1.0", "S13", "SW0")),
        MemoryArea("R", "user registers (a retentive part kept by a warm restart)", ("R5.0", "R10", "RW4")),
        MemoryArea("D", "program data (read-only)", ("D0.0", "D0", "DW0")),
        MemoryArea("U", "direct inputs (the terminals now)", ("U0.0", "U0", "UW0")),
    ),
    parse_address=_parse_address,
    system_bits=(
        SystemBit("S0", "S0.0..S0.6", "flags of the last comparison, counter, timer or BCD (zero, carry, ...)"),
        SystemBit("S1", "S1.0..S1.7", "logic flags (FLG; the result of table instructions; PUT's condition)"),
        SystemBit("S2", "S2.0..S2.6", "state: external start, RUN, outputs on; first cycle after a warm/cold restart"),
        SystemBit("S5..S12", "S5..S12", "real-time clock: 1/100 s, s, min, h, weekday, day, month, year"),
        SystemBit("S13", "S13.0..S13.7", "clock bits: 100 ms, 500 ms, 1 s, 10 s, 1 min, 10 min, 1 h, 24 h periods"),
        SystemBit("S14..S19", "SW14, SW16, SW18", "unit counters of 100 ms, 1 s, 10 s"),
        SystemBit("S24..S27", "S24..S27", "the mask of processes P10..P40"),
        SystemBit("S29", "S29.0..S29.7", "enable of the interrupt processes P41..P48"),
    ),
    restarts=(
        Restart("cold", "nothing: R cleared, blocks initialised; P63 runs in the first cycle"),
        Restart("warm", "the retentive part of R; P62 runs in the first cycle (also after a power cycle)"),
    ),
    triggers=(
        Trigger("first cycle", "P62, P63", "first cycle after a warm (P62) or cold (P63) restart", 62, 63),
        Trigger("event", "P41..P48", "at the turnaround after interrupt source 1..8 was raised, if enabled", 41, 48),
        Trigger("cyclic", "P0", "every cycle", 0, 0),
        Trigger("rotating", "P1..P4", "one of them per cycle, in turn", 1, 4),
        Trigger("interleaved", "P5..P9", "at the first turnaround at or after each one's period (p5_p9_periods)", 5, 9),
        Trigger("masked", "P10..P40", "every cycle while its bit of the process mask is set", 10, 40),
        Trigger("breakpoint", "P50..P57", "when BP calls it", 50, 57),
        Trigger("subroutines", "P60", "holds the subroutines CAL calls", 60, 60),
        Trigger("final", "P64", "last in every cycle (also after EOC)", 64, 64),
    ),
    instructions=_instructions,
    controller="plcsim.controllers.tecomat.cpu:TecomatCPU",
)
"""The Tecomat as its ``.il`` programs see it (entry point ``tecomat-ns950`` of ``plcsim.profiles``)."""
