"""A typical slip (not from the textbook): START assigned from TL by a coil instead of set by S START.

Network 2 reads ``START := TL``. The LED still comes one call after the call that sees the button,
as the analysis says, but START follows the button: the first call after the release clears it
and the next one puts the LED out. The textbook's START is set and stays set.
"""


def copy_start(t):
    """Network 1: LED := START."""
    t.LED = t.START


def follow_button(t):
    """Network 2 (wrong): START := TL."""
    t.START = t.TL


OB30 = CyclicInterrupt([copy_start, follow_button], period="1s")
