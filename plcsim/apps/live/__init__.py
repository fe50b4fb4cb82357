"""The live panel: run a program on a rig in the browser, press its buttons, place parts, inject faults.

:class:`LiveSession` is the core (no server): actions at simulated instants, recorded as a scenario that replays
bit for bit. :func:`open_live` serves it on a local page (``plcsim live`` on the command line; in a notebook the
handle shows the page inline). The server needs the ``live`` extra: ``pip install plcsim[live]``.
"""

from plcsim.apps.live.recording import Recording, load_scenario_file
from plcsim.apps.live.server import LivePanel, open_live
from plcsim.apps.live.session import LiveSession

__all__ = ["LivePanel", "LiveSession", "Recording", "load_scenario_file", "open_live"]
