"""The S7-1200 runtime: the CPU, task execution, host access, configuration, the instruction set and its profile."""
