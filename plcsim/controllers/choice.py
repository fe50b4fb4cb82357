"""Which controller a program runs on: the one its front end brings, or the S7-1200 CPU.

A front end whose programs run on a controller of their own (the Tecomat's ``.il``) offers
``program.controller(tags, **options)``; any other program is linked into the S7 CPU.

>>> from plcsim.frontends.il import program_text
>>> from plcsim.tags.table import Tag
>>> cpu = controller_for(program_text("LD TL\\nWR LED\\n"), {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")})
>>> cpu.family, str(cpu.table["LED"].address), cpu.program.filename
('Tecomat NS950', '%Q0.0', '<il>')
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from plcsim.controllers.protocol import Controller
from plcsim.controllers.s7.config import CPUConfig
from plcsim.controllers.s7.cpu import CPU
from plcsim.tags.table import TagTable


def controller_for(program: Any, tags: TagTable | Mapping[str, Any] | None = None, **options: Any) -> Controller:
    """The controller ``program`` runs on, with the I/O table ``tags``: its front end's own controller
    (``program.controller(tags, **options)``), or the S7-1200 CPU with ``CPUConfig(**options)``."""
    own = getattr(program, "controller", None)
    if callable(own):
        return own(tags, **options)
    return CPU(tags, program, CPUConfig(**options))
