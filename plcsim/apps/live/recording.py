"""A live session written down as a scenario, and read back: ``.toml`` (exact) or ``.py`` (the shipped format).

``.toml`` is data: written by a TOML writer, read by :mod:`tomllib`, every name checked against the rig's
vocabulary. ``.py`` is Python, run when it is read: trusted code, like an exercise file (its values are written as
literals and its keywords as plain names, so that a saved session runs nothing a page sent; a file from elsewhere
may hold anything). Take a page's or a student's scenario as ``.toml``.

Each click of a live session becomes one scenario action at the simulated instant it was applied, so the
session replays bit for bit: same program, seed and actions give the same trace digest.

>>> from plcsim.scenario.verbs import press, release
>>> clicks = [press("TL", t=2_000_000)[0], release("TL", t="40ms")]
>>> rec = Recording("PANEL", seed=1, actions=clicks, ended_ns=50_000_000)
>>> print(rec.to_python(), end="")  # doctest: +ELLIPSIS
# plcsim live session on PANEL, seed 1: replay with  plcsim run PANEL --program FILE --scenario THIS_FILE
from plcsim.scenario import Scenario, press, release
<BLANKLINE>
SEED = 1
SCENARIO = Scenario(
    "live",
    press("TL", t="2ms"),
    release("TL", t="40ms"),
    duration="50ms",
)
>>> again = Recording.from_toml(rec.to_toml(), "live.toml")
>>> [(a.verb, a.target, a.t.lo_ns) for a in again.actions], again.ended_ns, again.seed
([('press', 'TL', 2000000), ('release', 'TL', 40000000)], 50000000, 1)
"""

from __future__ import annotations

import json
import runpy
import tomllib
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import tomli_w

from plcsim.core.errors import PlcError
from plcsim.plant.verbs import RigVerb
from plcsim.scenario import verbs
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import Action, ScenarioError

# verb -> (constructor in plcsim.scenario.verbs, positional arguments after the target, keyword arguments);
# an argument is (name in the call, key in Action.args)
_CALLS: dict[str, tuple[str, tuple[tuple[str, str], ...], tuple[tuple[str, str], ...]]] = {
    "press": ("press", (), ()),
    "release": ("release", (), ()),
    "switch": ("switch", (("on", "on"),), ()),
    "write": ("write", (("value", "value"),), ()),
    "force": ("force", (("value", "value"),), ()),
    "unforce": ("unforce", (), ()),
    "place": (
        "place",
        (),
        (("at", "station"), ("noise", "noise"), ("offset_mm", "offset_mm"), ("angle_deg", "angle_deg")),
    ),
    "remove": ("remove", (), ()),
    "jam": ("jam", (), ()),
    "unjam": ("unjam", (), ()),
    "knock_off": ("knock_off", (), ()),
    "stick": ("stuck", (("value", "value"),), ()),
    "break_wire": ("wire_break", (), ()),
    "chatter": ("chatter", (), (("transitions", "transitions"), ("width", "width"))),
    "clear": ("clear", (), ()),
    "shift": ("shift_sensor", (("mm", "mm"),), ()),
    "jam_motor": ("jam_motor", (), ()),
    "free_motor": ("free_motor", (), ()),
    "stop_cpu": ("stop_cpu", (), ()),
    "start_cpu": ("start_cpu", (), ()),
    "power_cycle": ("power_cycle", (), ()),
    "download": ("download", (("program", "program"),), (("file", "file"),)),
}
"""How each verb a live session can record is written as a call of :mod:`plcsim.scenario.verbs`."""
_NO_TARGET = {"stop_cpu", "start_cpu", "power_cycle", "download"}
_PLACE_ARGS = {"station", "noise", "offset_mm", "angle_deg"}
"""The arguments of ``place`` that are not the part's properties."""
LIVE_ORIGIN = "live session action {n}"
"""Where a recorded action was made (its ``defined_at``), the same live and replayed from ``.toml``."""


def time_literal(ns: int) -> str:
    """An exact duration literal: ``"1234ms"`` where whole milliseconds, else ``"1234567ns"``.

    >>> time_literal(1_234_000_000), time_literal(1_500)
    ('1234ms', '1500ns')
    """
    return f"{ns // 1_000_000}ms" if ns % 1_000_000 == 0 else f"{ns}ns"


def make_action(
    verb: str, target: str, t: str | int, args: dict[str, Any], rig_verbs: Mapping[str, RigVerb] | None = None
) -> Action:
    """The action ``verb`` on ``target`` at ``t`` built by its constructor in :mod:`plcsim.scenario.verbs`, or by the
    rig's or the controller's own verb in ``rig_verbs`` (``set_ambient``, ``interrupt``). A part placed keeps its
    properties (``colour=2``) besides the pose arguments. Every value must be one a scenario file holds as a literal
    (:func:`~plcsim.scenario.verbs.check_plain`): the arguments may come from a page or a student's file."""
    if not (isinstance(verb, str) and isinstance(target, str)):
        raise ScenarioError(f"an action names its verb and target as text, not {verb!r} and {target!r}")
    for key, value in args.items():
        verbs.check_plain(value, f"{verb} {target}: {key}")
    if verb not in _CALLS:
        if rig_verbs and verb in rig_verbs:
            return rig_verbs[verb](target, t=t, **args)
        known = [*_CALLS, *(rig_verbs or {})]
        raise ScenarioError(f"a live session cannot record {verb!r} here; verbs: {', '.join(known)}")
    name, positional, keywords = _CALLS[verb]
    call: Callable[..., Any] = getattr(verbs, name)
    pos = [] if verb in _NO_TARGET else [target]
    pos += [args[key] for _, key in positional]
    kw = {arg: _tuples(args[key]) for arg, key in keywords if args.get(key) is not None}
    if verb == "place":
        for key in args.keys() - _PLACE_ARGS:
            verbs.check_property_name(key, f"place {target}")  # before the call: "t" would be its time
        kw.update({k: _tuples(v) for k, v in args.items() if k not in _PLACE_ARGS})
    made = call(*pos, t=t, **kw)
    return made[0] if isinstance(made, list) else made


def _tuples(value: Any) -> Any:
    return tuple(value) if isinstance(value, list) else value


def action_args(action: Action) -> dict[str, Any]:
    """The arguments of ``action`` a recording keeps (by their ``Action.args`` keys), None left out."""
    if action.rig is not None:
        return {key: value for key, value in action.args.items() if value is not None}
    _, positional, keywords = _CALLS[action.verb]
    kept = {key: action.args[key] for _, key in positional + keywords if action.args.get(key) is not None}
    if action.verb == "place":  # the part's properties (colour=2), as keywords of their own
        kept.update(action.args.get("properties") or {})
    return kept


@dataclass
class Recording:
    """What a live session did: its target, seed, base scenario and the actions at their instants.

    Attributes:
        target: the exercise (``4.3.7``) or rig (``PANEL``) the session ran.
        seed: the simulation's seed.
        actions: the recorded actions, each at a fixed time, in the order they were applied.
        ended_ns: the simulated time the recording covers (the replay runs exactly this long).
        name: the scenario's name (the base scenario's, so its checks and CPU options apply).
        base: the exercise scenario whose actions come first (None: none).
        program: the program's file, for the reader.
        first_program: the text of the program the session started with, kept when the session downloaded
            another: the replay starts from it, whatever the file holds by then (None: the file as it is).
    """

    target: str
    seed: int
    actions: Sequence[Action] = field(default_factory=list)
    ended_ns: int = 0
    name: str = "live"
    base: str | None = None
    program: str | None = None
    first_program: str | None = None

    def scenario(self, base: Scenario | None = None) -> Scenario:
        """The scenario to replay: ``base``'s actions, then the recorded ones; it lasts :attr:`ended_ns`.

        Actions of the base that fall after the end never happened live, and do not happen in the replay.
        """
        if (base is None) != (self.base is None):
            raise PlcError(f"the recording's base scenario is {self.base!r}; give it (not {base!r}) to replay it")
        before = list(base.actions) if base is not None else []
        longest = max([self.ended_ns + 1] + [a.t.hi_ns + 1 for a in before if a.t is not None])
        made = Scenario(self.name, *before, *self.actions, duration=longest, description="recorded live")
        made.duration_ns = self.ended_ns
        return made

    def replay_command(self) -> str:
        """The command line that replays the saved file."""
        return f"plcsim run {self.target} --program {self.program or 'FILE'} --scenario THIS_FILE"

    # -- TOML: exact --------------------------------------------------------------------------------

    def to_toml(self) -> str:
        """The recording as TOML, written by a TOML writer (every name and text quoted as TOML quotes it); read back
        with :meth:`from_toml`, it replays bit for bit."""
        session: dict[str, Any] = {
            "target": self.target,
            "seed": self.seed,
            "scenario": self.name,
            "ended": time_literal(self.ended_ns),
        }
        if self.base is not None:
            session["base"] = self.base
        if self.program is not None:
            session["program"] = self.program
        if self.first_program is not None:
            session["first_program"] = self.first_program
        tables = []
        for a in self.actions:
            table: dict[str, Any] = {"t": time_literal(a.t.lo_ns), "verb": a.verb}  # type: ignore[union-attr]
            if a.verb not in _NO_TARGET:
                table["target"] = a.target
            for key, value in action_args(a).items():
                _check_key(a, key)
                verbs.check_plain(value, f"{a.describe()}: {key}")
                table[key] = list(value) if isinstance(value, tuple) else value
            tables.append(table)
        head = f"# plcsim live session on {self.target}: replay with  {self.replay_command()}"
        return _comment(head) + "\n" + tomli_w.dumps({"session": session, "action": tables})

    @classmethod
    def from_toml(
        cls, text: str, where: str = "<recording>", rig_verbs: Mapping[str, RigVerb] | None = None
    ) -> Recording:
        """Read :meth:`to_toml`'s text; a mistake is reported with ``where`` and what to fix. ``rig_verbs``: the
        verbs the target's rig and controllers bring (:meth:`~plcsim.apps.live.build.Target.verbs`), if it used any."""
        try:
            data = tomllib.loads(text)
            session = data["session"]
            actions = []
            for n, item in enumerate(data.get("action", []), 1):
                args = {k: v for k, v in item.items() if k not in ("t", "verb", "target")}
                action = make_action(item["verb"], item.get("target", "CPU"), item["t"], args, rig_verbs)
                action.defined_at = LIVE_ORIGIN.format(n=n)
                actions.append(action)
            return cls(
                target=session["target"],
                seed=int(session["seed"]),
                actions=actions,
                ended_ns=verbs.TimeSpec.parse(session["ended"]).lo_ns,
                name=session.get("scenario", "live"),
                base=session.get("base"),
                program=session.get("program"),
                first_program=_text_or_none(session.get("first_program"), "first_program"),
            )
        except (tomllib.TOMLDecodeError, KeyError, TypeError, ValueError, PlcError) as exc:
            what = f"missing key {exc}" if isinstance(exc, KeyError) else str(exc)
            raise ScenarioError(
                f"{where}: not a plcsim live recording ({what}); it needs a [session] with target, seed and ended, "
                f"and [[action]] tables with t and verb"
            ) from None

    # -- Python: the shipped format -----------------------------------------------------------------

    def to_python(self) -> str:
        """The recording as a Python file with ``SCENARIO = Scenario(...)``, as an exercise writes one."""
        used = sorted({_CALLS[a.verb][0] for a in self.actions if a.rig is None})
        head = [
            _comment(f"# plcsim live session on {self.target}, seed {self.seed}: replay with  {self.replay_command()}"),
            f"from plcsim.scenario import {', '.join(['Scenario', *used])}",
        ]
        body = ["", f"SEED = {self.seed}"]
        if self.first_program is not None:
            body.append(f"FIRST_PROGRAM = {_py(self.first_program)}  # the program the session started with")
        if any(a.rig is not None for a in self.actions):  # the rig's and the controller's own verbs, by name
            head.append("from plcsim.apps.live.build import Target")
            body.append(f"VERBS = Target.find({_py(self.target)}).verbs()")
        items = [f"    {_py(self.name)},"]
        if self.base is not None:
            head.append("from plcsim.exercise.catalog import get")
            body.append(f"BASE = get({_py(self.target)}).scenario({_py(self.base)})")
            items.append("    *BASE.actions,")
        items += [f"    {_call(a)}," for a in self.actions]
        duration = f"    duration={_py(time_literal(self.ended_ns))},"
        body += ["SCENARIO = Scenario(", *items, duration, ")"]
        if self.base is not None:
            body[-2] = "    duration=max(BASE.duration_ns, " + str(self.ended_ns + 1) + "),"
            ended = time_literal(self.ended_ns)
            body.append(f"SCENARIO.duration_ns = {self.ended_ns}  # the live session ended at {ended}")
        return "\n".join(head + body) + "\n"

    # -- files ---------------------------------------------------------------------------------------

    def save(self, path: str | Path) -> Path:
        """Write the recording: ``.toml`` or ``.py`` (Python: replaying it runs it) by the suffix."""
        path = Path(path)
        if path.suffix not in (".toml", ".py"):
            raise PlcError(f"{path}: save a live session as .toml (exact replay) or .py (a scenario to paste)")
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(self.to_toml() if path.suffix == ".toml" else self.to_python(), encoding="utf-8")
        return path


class SavedScenario(NamedTuple):
    """A scenario file read back: the scenario, its seed, and the program text a live session started with."""

    scenario: Scenario
    seed: int | None
    first_program: str | None = None
    """Kept when the session downloaded another program: a replay starts from this text (None: the file)."""


def load_scenario_file(
    path: str | Path,
    base: Callable[[str], Scenario] | None = None,
    rig_verbs: Mapping[str, RigVerb] | None = None,
) -> SavedScenario:
    """A scenario from a file, the seed it was recorded with (None if it names none), and the program text the
    session started with where it downloaded another (None otherwise).

    ``.toml``: a live recording (:meth:`Recording.to_toml`); ``base(name)`` gives its base scenario, ``rig_verbs``
    the verbs its rig and controllers bring.
    ``.py``: a file defining ``SCENARIO`` (and optionally ``SEED``), as :meth:`Recording.to_python` writes; it is
    run as Python, so only a trusted one (yours, an instructor's) may be given.
    """
    path = Path(path)
    if not path.is_file():
        raise PlcError(f"{path}: no such scenario file")
    if path.suffix == ".toml":
        rec = Recording.from_toml(path.read_text(encoding="utf-8"), str(path), rig_verbs)
        if rec.base is not None and base is None:
            raise PlcError(f"{path}: the recording builds on scenario {rec.base!r} of {rec.target}; replay it there")
        scenario = rec.scenario(base(rec.base) if rec.base is not None and base is not None else None)
        return SavedScenario(scenario, rec.seed, rec.first_program)
    if path.suffix == ".py":
        names = runpy.run_path(str(path))
        made = names.get("SCENARIO")
        if not isinstance(made, Scenario):
            raise PlcError(f"{path}: defines no SCENARIO = Scenario(...)")
        seed, first = names.get("SEED"), names.get("FIRST_PROGRAM")
        return SavedScenario(made, seed if isinstance(seed, int) else None, first if isinstance(first, str) else None)
    raise PlcError(f"{path}: a scenario file is .toml (a live recording) or .py (SCENARIO = Scenario(...))")


def _text_or_none(value: Any, key: str) -> str | None:
    if value is not None and not isinstance(value, str):
        raise ValueError(f"{key} must be a text (the program as it was), not {type(value).__name__}")
    return value


def _call(action: Action) -> str:
    """The action as a call of its constructor, every value a literal and every keyword a checked name."""
    if action.rig is not None:
        args = [f"{_keyword(action, k)}={_py(v)}" for k, v in action_args(action).items()]
        when = f"t={_py(time_literal(action.t.lo_ns))}"  # type: ignore[union-attr]
        return f"VERBS[{_py(action.verb)}]({', '.join([_py(action.target), when, *args])})"
    name, positional, keywords = _CALLS[action.verb]
    parts = [] if action.verb in _NO_TARGET else [_py(action.target)]
    parts += [_py(action.args[key]) for _, key in positional]
    parts.append(f"t={_py(time_literal(action.t.lo_ns))}")  # type: ignore[union-attr]
    parts += [f"{arg}={_py(action.args[key])}" for arg, key in keywords if action.args.get(key) is not None]
    if action.verb == "place":
        parts += [f"{_keyword(action, k)}={_py(v)}" for k, v in (action.args.get("properties") or {}).items()]
    return f"{name}({', '.join(parts)})"


def _keyword(action: Action, name: str) -> str:
    """``name`` as a keyword of the action's call; refused where it is no plain name (it would be code)."""
    _check_key(action, name)
    return name


def _check_key(action: Action, name: str) -> None:
    """A key the action writes besides its own (a part's property, a rig verb's argument) must be a plain name."""
    if action.rig is not None:
        if name not in action.rig.arguments:
            arguments = ", ".join(action.rig.arguments) or "none"
            raise ScenarioError(f"{action.describe()}: no argument {name!r}; its arguments: {arguments}")
    elif action.verb == "place" and name not in _PLACE_ARGS:
        verbs.check_property_name(name, action.describe())


def _py(value: Any) -> str:
    """A Python literal of ``value`` (text in double quotes, as ruff writes it); anything else is refused."""
    verbs.check_plain(value, "a value")
    if isinstance(value, str):
        return json.dumps(value)  # a JSON string (ASCII, escaped) is a Python string literal
    if isinstance(value, (list, tuple)):
        return "(" + ", ".join(_py(v) for v in value) + ("," if len(value) == 1 else "") + ")"
    return repr(value)  # None, a bool, an int or a finite float: repr is its literal


def _comment(text: str) -> str:
    """One comment line: a newline or another control character in a name must not end it."""
    return "".join(c if c.isprintable() else " " for c in text)
