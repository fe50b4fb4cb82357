"""The PLC836 profile: the mechanisms language of seed 003 (chapter 4), run on the S7 runtime.

A PLC836 program runs its mechanisms cooperatively inside one cyclic task, in program order, with no
pre-emption; a mechanism's state is its activation bit, a continuation address and ``NAME_LINE``.
That is the S7 runtime's task model, so the profile names the S7 CPU as its controller and the
``.mech`` front end (:mod:`plcsim.frontends.mech`) links each mechanism to a MECHANISM instance
(``docs/architecture.md``, "Adding a third"; ``docs/mechanisms.md``).

>>> PROFILE.parse_address("WORD.(REKONFIG+14)"), PROFILE.trigger_of(1).tasks
(('WORD', 'REKONFIG', 14), 'the program')
>>> {"TEX0", "MECH_INIT", "LDR"} <= PROFILE.instructions()
True
"""

from __future__ import annotations

from plcsim.controllers.profiles import MemoryArea, Profile, Restart, SystemBit, Trigger


def _instructions() -> frozenset[str]:
    from plcsim.controllers.plc836.grammar import ARITY

    return frozenset(ARITY)


def _parse_address(text: str) -> tuple[str, str, int]:
    """``BYTE.(AREA+n)`` / ``WORD.(AREA+n)`` / ``(AREA+n)`` -> (width, area, offset); ValueError otherwise."""
    from plcsim.controllers.plc836.grammar import address, split_typed

    kind, rest = split_typed(text.strip())
    where = address(rest)
    if where is None:
        raise ValueError(f"{text!r} is not a PLC836 address; write (AREA+n), BYTE.(AREA+n) or WORD.(AREA+n)")
    return kind or "BYTE", where[0], where[1]


PROFILE = Profile(
    name="plc836",
    family="PLC836 mechanisms (CNC836 interface)",
    byte_order="little",
    areas=(
        MemoryArea(
            "DS",
            "areas a program reserves (NAME: DS n), addressed by offset; words little-endian (not stated)",
            ("(CITAC+30)", "BYTE.(CITAC+13)", "WORD.(REKONFIG+14)"),
        ),
    ),
    parse_address=_parse_address,
    system_bits=(
        SystemBit("NAME", "a bit per mechanism", "activation: set to start it, cleared by MECH_END"),
        SystemBit("NAME_LINE", "a word per mechanism", "the line of the state it waits in; 0 while idle"),
        SystemBit("RLO, DR", "registers", "the logic result and the data register (not kept by EX-type states)"),
    ),
    restarts=(Restart("STOP->RUN", "nothing of the mechanisms: each is idle (MECH_INIT), as PIS_INIT would make it"),),
    triggers=(Trigger("cyclic", "the program", "the file top to bottom in every interface cycle", 1, 1),),
    instructions=_instructions,
    controller="plcsim.controllers.s7.cpu:CPU",
)
"""The PLC836 as its ``.mech`` programs see it (entry point ``plc836`` of ``plcsim.profiles``)."""
