"""The ladder (LAD) view of a Python program: its networks drawn as rungs, faithful to what runs."""

from plcsim.ladder.build import NotLadder, build_ladder
from plcsim.ladder.model import Block, Network, Rung, Series, TextBox

__all__ = ["Block", "Network", "NotLadder", "Rung", "Series", "TextBox", "build_ladder"]
