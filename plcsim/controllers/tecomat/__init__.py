"""The Tecomat NS950 / TC400-600 instruction-list controller (the manual of seeds 000/004).

``assembler`` reads ``.il`` source; ``machine`` + ``instructions``/``blocks``/``tables`` run it;
``cpu`` is the controller the simulation drives (turnaround, processes, S registers, restarts).
"""
