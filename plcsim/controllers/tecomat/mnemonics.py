"""The NS950 standard instruction set as the manual defines it, and the mnemonics it only names.

57 mnemonics have semantics in the manual (§7: 5 read/write, 6 logic with an operand, NEG, 3 memory and
edge, 3 comparisons, 7 stack, 3 counters, 2 shift registers, 4 timers, 18 organisational, 4 table
instructions, ADD); AND, OR, XOR, EQ, LT, GT and ADD also have a form without an operand. The others
are only named (their semantics are in Teco handbooks we do not have): a program using one is refused
with a message saying so, never run with a guess.

>>> len(DEFINED), len(NAMED_ONLY), refusal("MUL").split(":")[0]
(57, 49, 'MUL is only named in the manual')
"""

from __future__ import annotations

GROUPS: dict[str, tuple[str, ...]] = {
    "read/write": ("LD", "LDC", "WR", "WRC", "PUT"),
    "logic": ("AND", "ANC", "OR", "ORC", "XOR", "XOC", "NEG"),
    "memory and edge": ("SET", "RES", "LET"),
    "comparison": ("EQ", "LT", "GT"),
    "stack": ("STK", "SWP", "POP", "FLG", "CHG", "NXT", "PRV"),
    "counters": ("CTU", "CTD", "CNT"),
    "shift registers": ("SFL", "SFR"),
    "timers": ("TON", "TOF", "RTO", "IMP"),
    "organisational": (
        "P",
        "E",
        "ED",
        "EC",
        "EOC",
        "BP",
        "L",
        "JMP",
        "JMD",
        "JMC",
        "JMI",
        "CAL",
        "CAD",
        "CAC",
        "CAI",
        "RET",
        "RED",
        "REC",
    ),
    "tables": ("LTB", "FTB", "LMS", "WMS"),
    "arithmetic": ("ADD",),
}
DEFINED = frozenset(m for group in GROUPS.values() for m in group)
WITHOUT_OPERAND_FORM = frozenset({"AND", "OR", "XOR", "EQ", "LT", "GT", "ADD"})

_STANDARD_TEXT = "SUB MUL DIV INR DCR ROL BIN BCD WTB FTM FTS SRC MOV MTN MNT LDS WRS FIT FNT"
_EXTENDED_TEXT = "LDL WRA ANL ORL XOL NGL BET CMP CML SWL LAC WAC SEQ JZ JNZ JC JNC JS JNS " + (
    "ADX ADL SUX SUL MUD DID ROR BIL BCL BAS ASB"
)
STANDARD_NAMED = tuple(_STANDARD_TEXT.split(" "))
EXTENDED_NAMED = tuple(_EXTENDED_TEXT.split(" "))
NAMED_ONLY = frozenset(STANDARD_NAMED) | frozenset(EXTENDED_NAMED)


def refusal(mnemonic: str) -> str:
    """Why a named-only instruction is refused."""
    which = "the standard set" if mnemonic in STANDARD_NAMED else "the extended set (D and B CPUs)"
    return (
        f"{mnemonic} is only named in the manual: it belongs to {which}, but the manual gives no semantics, "
        f"so the simulator does not run it; write the function with the 57 instructions the manual defines"
    )
