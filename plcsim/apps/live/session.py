"""The core of a live session, without a server: the student's actions applied at simulated instants and recorded.

A live session runs one :class:`~plcsim.sim.simulation.Simulation` in chunks. Between chunks the simulation stands at
a step boundary ``t``; an action the student takes there is recorded at ``t`` and queued as a scenario action due at
``t``:
the step starting at ``t`` applies it (after the scenario's own actions due then, in the order they were taken).
The recording (:class:`~plcsim.apps.live.recording.Recording`) therefore replays to the same trace, bit for bit. Nothing
here reads the wall clock: the server says how far to advance (see :mod:`plcsim.apps.live.server`).

>>> session = LiveSession("PANEL", PANEL_DEMO, seed=1)
>>> session.advance(20_000_000); _ = session.do("press", "TL"); session.advance(30_000_000)
>>> session.sim.cpu.read("LED"), session.now
(True, 50000000)
>>> _ = session.release("TL"); session.advance(50_000_000)
>>> session.sim.cpu.read("LED"), [a.describe() for a in session.recording().actions]
(False, ['press TL at 20 ms', 'release TL at 50 ms'])
>>> session.replay().trace.digest() == session.sim.trace.digest()
True
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from plcsim.apps.live.build import LIVE, Target, open_ended
from plcsim.apps.live.recording import LIVE_ORIGIN, Recording, make_action
from plcsim.controllers.loaded import SourceProgram
from plcsim.controllers.protocol import RUN
from plcsim.core.clock import NEVER
from plcsim.core.errors import ExerciseError, PlcError
from plcsim.core.literals import format_ns
from plcsim.frontends import read_program
from plcsim.frontends.python.program import Program
from plcsim.plant.protocol import Drawable, rig_verbs
from plcsim.plant.verbs import RigVerb
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import Action
from plcsim.sim.simulation import Simulation

PANEL_DEMO = "def OB1(t):\n    t.LED = t.TL\n"
"""A one-line program for the PANEL rig: the lamp follows the button TL."""
NO_PROGRAM = '"""No program yet: every output stays off, the rig is operated by hand."""\n\n\ndef OB1(t):\n    pass\n'
"""The program of ``plcsim run RIG`` and ``plcsim live RIG`` without ``--program``: a student explores the
machine by hand (buttons, parts, the watch table) before writing one."""

FAULTS = {
    "stick": "stuck at",
    "break_wire": "wire break",
    "chatter": "contact bounce",
    "clear": "clear the fault",
    "shift": "shift the sensor",
    "jam_motor": "jam the motor",
    "free_motor": "free the motor",
}
"""The fault verbs the page's menu offers, with their captions."""
PART_VERBS = ("remove", "jam", "unjam", "knock_off")


class LiveSession:
    """A simulation the student drives: actions at the current instant, advancing on request, a recording.

    Args:
        target: an exercise (``4.3.7``, a slug or an exercise file) or a rig (``PANEL``, ``CONV1``), or a
            :class:`~plcsim.apps.live.build.Target`.
        program: the PLC program: a file, or its text (a Python-subset program).
        scenario: the exercise's scenario to start from (its actions happen as in a graded run); None: none.
        seed: the simulation's seed (placement noise, random times).
    """

    def __init__(self, target: str | Target, program: str | Path, *, scenario: str | None = None, seed: int = 1):
        self.target = target if isinstance(target, Target) else Target.find(target)
        self.base = self.target.base(scenario)
        self.name = self.base.name if self.base is not None else LIVE
        self.seed = seed
        self.program_file = str(program) if _is_file(program) else None
        self.program: SourceProgram = (
            read_program(program) if _is_file(program) else Program(str(program), "<live program>")
        )
        self.first_program = self.program
        """The program the session started with (a replay starts from it; downloads are actions)."""
        self.sim = self.target.simulation(self.program, open_ended(self.name, self.base), seed=seed)
        self.sim.run(until=self.sim.now)  # the outputs as the run starts, as a replay's first step sees them
        self.recorded: list[Action] = []
        self.error: str | None = None
        self.refused: list[str] = []
        plant = self.sim.plant
        self._switches = set(getattr(getattr(plant, "panel", None), "switches", ()))
        self._base_count = len(self.sim.scenario.actions)  # type: ignore[union-attr]
        self.verbs: dict[str, RigVerb] = {**getattr(self.sim.cpu, "VERBS", {}), **rig_verbs(plant)}
        """The verbs this run's rig and controller bring (``set_ambient``, ``interrupt``), besides the scenario's."""
        self.extra_watch: list[str] = []
        """Tags the student added to the watch table (a click on a contact in the Program card)."""
        self._ladder: Any = None
        self._done: set[str] = set()  # parts no operator verb applies to any more (see _parts_in_play)
        self._events_seen = 0
        self._program_mtime = Path(self.program_file).stat().st_mtime_ns if self.program_file else None

    # -- time ------------------------------------------------------------------------------------------

    @property
    def now(self) -> int:
        """The simulated time, ns (always a step boundary)."""
        return self.sim.now

    def advance(self, ns: int, stop: Callable[[], bool] | None = None) -> None:
        """Run ``ns`` of simulated time (whole steps), or until ``stop()`` says so (checked after each step).

        A plant failure ends the session's simulation: :attr:`error` says why, and nothing advances any more.
        """
        if self.error is not None:
            return
        condition = (lambda _sim: stop()) if stop is not None else None
        try:
            self.sim.run(until=self.sim.now + max(ns, 0), condition=condition)
        except ExerciseError as exc:  # the run refused an action at the top of a step: drop it, go on
            if not self._refuse(exc):
                raise
        except PlcError as exc:
            self.error = str(exc)

    def _refuse(self, exc: ExerciseError) -> bool:
        refused = next((a for a in self.recorded if str(exc).startswith(f"{a.defined_at}:")), None)
        if refused is not None:
            self.recorded.remove(refused)
            self.refused.append(str(exc))
        return refused is not None

    def scan(self) -> None:
        """Run until the next OB1 scan has ended (in STOP: one step)."""
        if self.error is None:
            try:
                self.sim.scan(1) if self.sim.cpu.mode == RUN else self.sim.step()
            except ExerciseError as exc:
                if not self._refuse(exc):
                    raise
            except PlcError as exc:
                self.error = str(exc)

    # -- actions -----------------------------------------------------------------------------------------

    def do(self, verb: str, target: str = "", **args: Any) -> Action:
        """Take an action now (``do("press", "TL")``, ``do("place", "p1", station="S1")``, ``do("stick", "S2",
        value=True)``): recorded at :attr:`now`, applied at the start of the step there (the next one to run).

        Raises:
            PlcError: the action names something the run lacks, or a value its tag cannot hold; nothing is
                recorded then. One the run refuses when it is applied is dropped and listed in :attr:`refused`.
        """
        return self._take(verb, target, args, self.now)

    def release(self, button: str, min_hold_ns: int | None = None) -> Action:
        """Let go of a push button; a press lasts at least ``min_hold_ns`` (default two scan cycles) so that the
        program sees it even when the click was quicker than a scan (the release then happens later)."""
        hold = self.min_hold_ns if min_hold_ns is None else min_hold_ns
        pressed = next((a.t.lo_ns for a in reversed(self.recorded) if a.verb == "press" and a.target == button), 0)  # type: ignore[union-attr]
        return self._take("release", button, {}, max(self.now, pressed + hold))

    @property
    def min_hold_ns(self) -> int:
        """Two scan cycles (two steps where the scan is free-running): the shortest press the page sends."""
        return 2 * max(self.sim.cpu.config.cycle_ns, self.sim.dt_ns)

    def toggle(self, switch: str) -> Action:
        """Flip a switch (or latch a push button: pressed stays pressed until toggled again)."""
        return self._take("switch", switch, {"on": not self.sim.plant.sensors.get(switch)}, self.now)  # type: ignore[union-attr]

    def write_text(self, tag: str, text: str, *, forced: bool = False) -> Action:
        """Write (or force) a tag from the watch table's text, read as the tag's current type (``1``/``true``)."""
        current = self.sim.cpu.read(tag)
        value = parse_value(text, current, tag)
        return self._take("force" if forced else "write", tag, {"value": value}, self.now)

    def _take(self, verb: str, target: str, args: dict[str, Any], at_ns: int) -> Action:
        if self.error is not None:
            raise PlcError(f"the simulation stopped: {self.error}")
        if verb == "place":
            target = target or self.next_part_name()
            args = {"noise": True, **args}
        action = make_action(verb, target, at_ns, args, self.verbs)
        action.defined_at = LIVE_ORIGIN.format(n=len(self.recorded) + 1)
        everything = (*self.sim.scenario.actions, *self.recorded, action)  # type: ignore[union-attr]
        self.sim._check_scenario(Scenario(self.name, *everything, duration=NEVER))
        if verb == "unforce" and target not in self.sim.cpu.forces:
            raise PlcError(f"{target} is not forced; forced: {', '.join(self.sim.cpu.forces) or 'nothing'}")
        if verb in ("write", "force"):
            _check_value(self.sim.cpu.read(target), args["value"], target)
        self.sim.actions.schedule(action, at_ns, self._base_count + len(self.recorded))
        self.recorded.append(action)
        return action

    def next_part_name(self) -> str:
        """``p1``, ``p2`` ...: the first name no part of the scenario or the session has."""
        taken = {a.target for a in (*self.sim.scenario.actions, *self.recorded) if a.verb == "place"}  # type: ignore[union-attr]
        return next(f"p{n}" for n in range(1, len(taken) + 2) if f"p{n}" not in taken)

    # -- the record -------------------------------------------------------------------------------------

    def recording(self) -> Recording:
        """What the session did up to now: the actions applied before :attr:`now` (one taken at :attr:`now`, or a
        release still to come, is left out: it has not acted yet)."""
        done = [a for a in self.recorded if a.t.lo_ns < self.now]  # type: ignore[union-attr]
        return Recording(
            self.target.name,
            self.seed,
            done,
            ended_ns=self.now,
            name=self.name,
            base=self.base.name if self.base is not None else None,
            program=self.program_file,
            first_program=self.first_program.source
            if any(a.verb == "download" for a in done) and isinstance(self.first_program, Program)
            else None,
        )

    def save(self, path: str | Path) -> Path:
        """Write :meth:`recording` to ``path`` (``.toml``: exact; ``.py``: the shipped scenario format)."""
        return self.recording().save(path)

    def replay(self, recording: Recording | None = None) -> Simulation:
        """Run ``recording`` (default: this session's, up to now) afresh and return the finished simulation."""
        rec = recording or self.recording()
        sim = self.target.simulation(self.first_program, rec.scenario(self.base), seed=rec.seed)
        sim.run()
        return sim

    def grade(self) -> list[tuple[Any, Any]]:
        """The exercise's checks that apply to this session's scenario, evaluated on the trace so far
        (``[(check, verdict)]``; a rig has none)."""
        from plcsim.check import evaluate_all

        exercise = self.target.exercise
        if exercise is None:
            return []
        checks = [g.check for g in exercise.checks_for(self.name)]
        analysis = self.sim.cpu.compiled.analysis if self.sim.cpu.compiled else None
        return evaluate_all(checks, self.sim.trace, analysis)

    def write_rrd(self, path: str | Path) -> Path:
        """Write the session's recording so far as a rerun ``.rrd``."""
        self.sim.trace.meta["end_ns"] = self.now
        return self.sim.trace.to_rrd(path)

    # -- what the page shows -----------------------------------------------------------------------------

    def layout(self) -> dict[str, Any]:
        """What never changes during the session: the machine's fixed shapes and what can be clicked."""
        sim, plant = self.sim, self.sim.plant
        signals = plant.signals if plant is not None else {}
        controls = [
            {"name": n, "kind": "switch" if n in self._switches else "button", "doc": s.doc}
            for n, s in signals.items()
            if s.operator
        ]
        exercise = self.target.exercise
        hmi = exercise.hmi if exercise is not None else {}
        controls += [
            {"name": tag, "kind": f"hmi {kind}", "doc": f"HMI {kind}: writes {tag}"} for tag, kind in hmi.items()
        ]
        wired = list(sim.wiring.by_tag) if sim.wiring is not None else []
        motors = [n for n, s in signals.items() if s.direction == "actuator"] if hasattr(plant, "jam_motor") else []
        faults = {k: v for k, v in FAULTS.items() if k not in ("shift", "jam_motor", "free_motor")}
        if hasattr(plant, "shift_sensor"):
            faults["shift"] = FAULTS["shift"]
        if motors:
            faults.update({k: FAULTS[k] for k in ("jam_motor", "free_motor")})
        return {
            "target": self.target.name,
            "title": f"{exercise.number} {exercise.title}" if exercise is not None else f"rig {self.target.name}",
            "graded": exercise is not None,
            "scenario": self.name,
            "seed": self.seed,
            "program": self.program_file or "<program text>",
            "view": getattr(plant, "view", "none"),
            "bounds": list(plant.bounds()) if plant is not None else [0, 0, 1, 1],
            "static": [drawable_json(d) for d in (plant.static_drawables() if plant is not None else [])],
            "controls": controls,
            "stations": [
                {"name": s.name, "x": s.x, "y": s.y, "doc": s.doc} for s in getattr(plant, "stations", {}).values()
            ],
            "wired": wired,
            "sensors": [n for n, s in signals.items() if s.direction == "sensor" and not s.operator],
            "motors": motors,
            "faults": faults,
            "rig_verbs": [self._verb_json(v) for v in self.verbs.values()],
            "watch": list(sim.trace.names),
            "inputs": list(sim.cpu.inputs),
            "outputs": list(sim.cpu.outputs),
            "min_hold_ns": self.min_hold_ns,
            "dt_ns": sim.dt_ns,
        }

    def ladder_svg(self) -> str | None:
        """The program's ladder with the power flow of the CPU's state now (the Program card); None for a
        program that is no Python (an instruction list has no ladder)."""
        if not isinstance(self.program, Program):
            return self._il_svg()
        if self._ladder is None:
            from plcsim.ladder.view import Ladder

            self._ladder = Ladder(self.program, self.sim.cpu.base_table, title="")
        return self._ladder.monitor(self.sim.cpu.t)

    # -- downloads ----------------------------------------------------------------------------------------

    def program_changed(self) -> bool:
        """Whether the program file was saved since the session loaded (or last downloaded) it."""
        if self.program_file is None:
            return False
        try:
            return Path(self.program_file).stat().st_mtime_ns != self._program_mtime
        except OSError:
            return False

    def download(self, text: str | None = None) -> Action:
        """Download the program file as it is now (or ``text``) into the running CPU, as TIA Portal does:
        STOP, load, RUN, the machine running on. The program is compiled first: an error names the file and
        line and nothing changes. The download is an action of the scenario, with the program's text, so
        that the saved session replays bit for bit."""
        if not isinstance(self.program, Program):
            raise PlcError("only a Python program (.py) can be downloaded into a running session")
        name = self.program_file or "<live program>"
        if text is None:
            if self.program_file is None:
                raise PlcError("this session's program is no file: give the program's text")
            text = Path(self.program_file).read_text(encoding="utf-8")
            self._program_mtime = Path(self.program_file).stat().st_mtime_ns
        program = Program(text, name)  # refuses what does not read, naming the line
        cpu = self.sim.cpu
        from plcsim.controllers.s7.cpu import CPU

        dry = CPU(cpu.base_table, program, config=cpu.config, start=False)
        missing = [n for n in self.sim.trace.names if n.split(".")[0].split("[")[0] not in dry.t.__dict__]
        missing = [n for n in missing if self.sim.trace.kinds.get(n) != "analog"]
        if missing:
            raise PlcError(
                f"{name}: the new program no longer declares {', '.join(missing)}, which this session's trace "
                f"records; keep the declaration (or end the session and start a new one)"
            )
        action = self._take("download", "CPU", {"program": text, "file": Path(name).name}, self.now)
        self.program = program
        self._ladder = None
        return action

    def _il_svg(self) -> str | None:
        """An instruction list with A0/A1 per line of the last pass (STL monitoring), or None."""
        text = getattr(self.program, "text", None)
        if text is None or getattr(self.sim.cpu, "machine", None) is None:
            return None
        from plcsim.ladder.il import IlMonitor, render_il_svg

        if self._ladder is None:
            self._ladder = IlMonitor(self.sim.cpu)
            self._ladder.attach()
        return render_il_svg(self._ladder.lines(text), Path(getattr(self.program, "filename", "")).name)

    def watch(self, tag: str) -> None:
        """Add a tag to the watch table (it must be readable: a typo is refused with the nearest names)."""
        _read(self.sim.cpu, tag)
        if tag not in self.sim.trace.names and tag not in self.extra_watch:
            self.extra_watch.append(tag)

    def _verb_json(self, verb: RigVerb) -> dict[str, Any]:
        """A rig's or a controller's verb as the page offers it: its caption, what its target may be (empty:
        typed, e.g. a time of day; ``parts``: a part on the machine) and the arguments its phrase names."""
        owner = self.sim.cpu if verb.controller else self.sim.plant
        targets = "parts" if verb.on_parts else sorted(getattr(owner, verb.targets, ())) if verb.targets else []
        caption = verb.name.replace("_", " ")
        return {
            "verb": verb.name,
            "caption": caption,
            "role": verb.role,
            "targets": targets,
            "args": list(verb.arguments),
            "doc": verb.doc,
        }

    def _parts_in_play(self) -> dict[str, str]:
        """Scenario name by id of the parts an operator can still act on (remove, jam, knock off): no event has put
        them in a bin, taken them away or dropped them since they were placed, and a plant that keeps its parts still
        has them, free or held. The events are read once each, as they come."""
        sim = self.sim
        events = sim.trace.events
        for e in events[self._events_seen :]:
            if e.kind in DONE_WITH and e.part is not None:
                self._done.add(e.part)
            elif e.kind == "part placed":  # an id given again to a new part
                self._done.discard(e.part)
        self._events_seen = len(events)
        kept = getattr(sim.plant, "parts", None)

        def playing(pid: str) -> bool:
            if pid in self._done:
                return False
            if kept is None:
                return True
            part = kept.get(pid)
            return part is not None and getattr(part, "state", "on") in ("on", "held")

        return {pid: name for name, pid in sim.actions.parts.items() if playing(pid)}

    def state(self) -> dict[str, Any]:
        """The state now: time, CPU, the machine's moving shapes, the watch table, faults, logs."""
        sim, cpu = self.sim, self.sim.cpu
        plant = sim.plant
        parts = self._parts_in_play()
        return {
            "t_ns": self.now,
            "time": format_ns(self.now),
            "mode": cpu.mode,
            "scans": cpu.scan_count,
            "error": self.error,
            "program_changed": self.program_changed(),
            "dynamic": [drawable_json(d) for d in (plant.dynamic_drawables() if plant is not None else [])],
            "sensors": {k: _jsonable(v) for k, v in (plant.sensors.items() if plant is not None else ())},
            "watch": {name: _jsonable(_read(cpu, name)) for name in [*sim.trace.names, *self.extra_watch]},
            "io": {k: _jsonable(v) for k, v in (*cpu.inputs.items(), *cpu.outputs.items())},
            "forces": {k: _jsonable(v) for k, v in getattr(cpu, "forces", {}).items()},
            "faults": sorted(sim.wiring.faults) if sim.wiring is not None else [],
            "parts": parts,
            "diagnostics": [f"{format_ns(e.time_ns)}  {e.event}: {e.message}" for e in list(cpu.diagnostics)[-40:]],
            "events": [str(e) for e in sim.trace.events[-40:]],
            "actions": [a.describe() for a in self.recorded[-40:]],
        }


DONE_WITH = frozenset({"part in bin", "part removed", "part fell off"})
"""Plant events after which an operator can no longer act on a part (it lies in a bin, is gone or fell)."""


def drawable_json(d: Drawable) -> list[Any]:
    """A shape as the page draws it: ``[path, kind, [[x, y], ...], [r, g, b], radius, text]`` (mm, y up)."""
    points = np.round(np.asarray(d.points, dtype=float), 2).tolist()
    return [d.path, d.kind, points, list(d.color), round(float(d.radius), 2), d.text]


def parse_value(text: str, current: Any, tag: str) -> Any:
    """The watch table's text as a value of ``current``'s type: ``1``/``true``/``TRUE`` for a Bool, an int, a float.

    >>> parse_value("true", False, "ACK"), parse_value("12", 0, "N"), parse_value("2.5", 0.0, "X")
    (True, 12, 2.5)
    """
    text = text.strip()
    try:
        if isinstance(current, bool):
            lowered = text.lower()
            if lowered not in ("1", "0", "true", "false"):
                raise ValueError
            return lowered in ("1", "true")
        if isinstance(current, int):
            return int(text, 0)
        if isinstance(current, float):
            return float(text)
    except ValueError:
        raise PlcError(f"{tag} is a {type(current).__name__}: {text!r} is not one (e.g. {current!r})") from None
    return text


def _check_value(current: Any, value: Any, tag: str) -> None:
    """Refuse, before it is recorded, a value of another type than the tag's (a watch table's typo)."""
    fits = isinstance(value, bool) if isinstance(current, bool) else isinstance(value, type(current))
    if isinstance(current, float) and isinstance(value, int) and not isinstance(value, bool):
        fits = True
    if not fits:
        raise PlcError(f"{tag} holds a {type(current).__name__}: {value!r} is not one (e.g. {current!r})")


def _read(cpu: Any, name: str) -> Any:
    """A traced value as the watch table shows it: the S7's ``read`` (never refreshing a timer); a controller
    without one (the Tecomat) by its symbols' values at the last cycle's end."""
    reader = getattr(cpu, "read", None)
    try:
        return reader(name) if reader is not None else getattr(cpu.t, name)
    except (PlcError, AttributeError):
        return None


def _jsonable(value: Any) -> Any:
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, np.generic):
        return value.item()
    return str(value)


def _is_file(program: str | Path) -> bool:
    return isinstance(program, Path) or "\n" not in program
