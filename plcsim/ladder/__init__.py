"""The ladder (LAD) view of a Python program: its networks drawn as rungs, faithful to what runs.

``Ladder.from_file("mine.py")`` shows itself in a notebook; ``plcsim ladder mine.py -o mine.svg`` writes it.
"""

from plcsim.ladder.build import NotLadder, build_ladder
from plcsim.ladder.model import Block, Network, Rung, Series, TextBox
from plcsim.ladder.view import Ladder

__all__ = ["Block", "Ladder", "Network", "NotLadder", "Rung", "Series", "TextBox", "build_ladder"]
