"""The grading child and what confines it: the parent, the child, the fork server, confinement, the watchdog."""
