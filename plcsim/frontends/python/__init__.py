"""The Python front end: the PLC subset of Python, checked, typed, rewritten and merged into network callables."""
