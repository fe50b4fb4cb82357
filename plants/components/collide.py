"""Collision types and filter categories shared by the side-view components.

Every kind of shape has its own category bit (pitfall 2 of the pymunk notes: the default "all bits" makes filtered
queries and sensors see walls). A knocked-off part keeps only the fall-zone bit in its mask, so it drops through the
belt and the beams without touching them.
"""

from __future__ import annotations

CT_PART = 1
CT_BEAM = 2
CT_STOP = 3
CT_FALL = 4
CT_BELT = 5
CT_PLATE = 6

PART_CAT = 0x01
BEAM_CAT = 0x02
STOP_CAT = 0x04
FALL_CAT = 0x08
BELT_CAT = 0x10
PLATE_CAT = 0x20
OFF_CAT = 0x40  # a part that has been pushed off the machine
