"""The S7-1200's task model: organization blocks named ``OB<n>``, their kinds and numbers.

This is the only place that reads an OB name: the Python front end asks it which task a name is, and a
trace recorded without task names (a hand-made one, an old file) numbers ``"OB30"`` as 30.

>>> task_kind("OB30"), ob_number("OB100"), trace_task_number("ob1")
(('interrupt', 8), 100, 1)
"""

from __future__ import annotations

import re

from plcsim.errors import ProgramError

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


def task_kind(name: str) -> tuple[str, int]:
    """Kind and default priority of an OB by its number (S7-1200 numbering)."""
    number = ob_number(name)
    if number == 1:
        return "cyclic", 1
    if 30 <= number <= 38:
        return "interrupt", DEFAULT_INTERRUPT_PRIORITY
    if number == 100:
        return "startup", 1
    raise ProgramError(
        f"{name} is not supported: use OB1 (program cycle), OB30..OB38 (cyclic interrupts) or OB100 (startup)"
    )


def trace_task_number(task: str) -> int:
    """The task column of an OB named in any case (``"ob30"`` -> 30), for traces without task names."""
    text = task.strip().upper()
    if not is_ob_name(text):
        raise ValueError(f"the trace has no task named {task!r}; an S7 task is named like 'OB1' or 'OB30'")
    return int(text[2:])
