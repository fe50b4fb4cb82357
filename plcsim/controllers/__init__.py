"""The controllers a simulation drives: the Controller protocol, LoadedProgram, profiles; ``s7`` and ``tecomat``."""
