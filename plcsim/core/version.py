"""plcsim's version, in one place: reports carry it and a batch refuses workers that run another."""

__version__ = "0.1.0"
