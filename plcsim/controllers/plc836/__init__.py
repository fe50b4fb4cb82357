"""The PLC836 mechanisms (seed 003, chapter 4): a profile only; its programs run on the S7 runtime."""
