"""The exit codes a grading child ends with, beyond its own: the child exits with them, the parent reads them.

Both sides import this module (and nothing of each other), so that the parent can tell a memory limit
or a death by signal from a crash without importing the child's module.
"""

SIGNAL_EXIT_BASE = 128
"""With a PID namespace, the child exits with 128 + N when its worker (process 1 there) died of signal N."""
MEMORY_EXIT = 86
"""Exit code of a child that ran out of memory even for its failure message."""
