"""The PLC836 mechanisms front end: ``.mech`` files (seed 003, chapter 4) on the S7 runtime.

:mod:`.parse` reads the text (errors name the file, the line and the fix); :mod:`.program` links it
into the S7 CPU's one cyclic task, each mechanism driving a MECHANISM instance.
"""

from plcsim.frontends.mech.program import MechProgram, read_mech

__all__ = ["MechProgram", "read_mech"]
