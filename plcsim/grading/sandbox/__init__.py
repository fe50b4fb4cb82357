"""The grading child and what confines it.

The parent starts and watches the child (``parent``, ``forkserver``, ``watchdog``) within its limits
(``limits``), tells it what it may read (``readable``, ``importable``) and checks its result against the
trusted probe (``probes``); the child confines itself (``child``, ``confine``) and ends with the exit
codes both sides know (``exits``).
"""
