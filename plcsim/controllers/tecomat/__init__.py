"""The Tecomat NS950 / TC400-600 instruction-list controller (the manual of seeds 000/004).

``assembler`` (with ``decoder`` for the operands) reads ``.il`` source into an ``assembly``; ``machine``
holds the state it runs on, ``instructions``/``blocks``/``tables`` (and ``fused``) build its closures and
``linker`` links them; ``cpu`` is the controller the simulation drives (turnaround, processes, S registers,
restarts) and links each program it downloads.
"""
