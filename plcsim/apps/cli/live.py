"""``plcsim live``: the operator panel in the browser, and what the session leaves (scenario, recording, grade)."""

from __future__ import annotations

import argparse
from pathlib import Path

from plcsim.apps.cli.verdicts import print_verdicts
from plcsim.core.errors import PlcError


def live_command(args: argparse.Namespace) -> int:
    """``plcsim live``: serve the panel until the session ends, then save what was asked for and grade it."""
    import webbrowser

    from rich.console import Console

    from plcsim.apps.live.server import open_live
    from plcsim.apps.live.session import NO_PROGRAM

    console = Console()
    if args.save_scenario and not args.save_scenario.endswith((".toml", ".py")):
        raise PlcError(f"--save-scenario {args.save_scenario}: save as .toml (exact replay) or .py (a scenario)")
    panel = open_live(
        args.target,
        args.program or NO_PROGRAM,
        scenario=args.scenario,
        seed=args.seed,
        port=args.port,
        speed=_speed(args.speed),
        paused=args.paused,
        save_scenario=args.save_scenario,
    )
    console.print(f"live panel of {panel.session.target.name}: [bold]{panel.url}[/]  (Ctrl-C or 'End session' ends it)")
    if not args.no_browser:
        webbrowser.open(panel.url)
    try:
        while not panel.runner.finished.wait(0.5):
            pass
    except KeyboardInterrupt:
        console.print("ending the session")
    panel.stop()
    session = panel.session
    saved = panel.runner.save()
    ran = f"simulated {saved['t_ns'] / 1e9:g} s, {len(session.recorded)} actions"
    console.print(f"{ran}; trace digest {saved['digest'][:16]}")
    if saved["path"]:
        console.print(f"scenario: {saved['path']}  (replay: {session.recording().replay_command()})", highlight=False)
    if args.rrd:
        Path(args.rrd).parent.mkdir(parents=True, exist_ok=True)
        console.print(f"recording: {session.write_rrd(args.rrd)}  (open it with: rerun {args.rrd})", highlight=False)
    print_verdicts(session.grade(), console)
    return 0


def _speed(text: str) -> float | None:
    """``--speed``: a factor from 0.1 to 10, or ``max`` (None: as fast as possible)."""
    if text.strip().lower() == "max":
        return None
    try:
        speed = float(text)
    except ValueError:
        speed = 0.0
    if not 0.1 <= speed <= 10:
        raise PlcError(f"--speed {text}: give a factor from 0.1 to 10, or max")
    return speed
