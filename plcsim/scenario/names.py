"""The names a scenario relies on, checked before a run: every station, button, tag, signal, part, event and
rig or controller verb it names must exist, or the instructor is told the line and the valid choices.

:func:`plant_vocabulary` reads what a plant declares (events, subjects, capabilities, rig verbs); :func:`name_problems`
lists every bad name at once (an exercise is checked when it is loaded) and :func:`check_names` raises on the first.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

from plcsim.core.errors import ConfigurationError, did_you_mean
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import VERB_CAPABILITY, Action, ScenarioError


def check_names(
    scenario: Scenario,
    *,
    stations: Iterable[str],
    buttons: Iterable[str],
    signals: Iterable[str],
    tags: Iterable[str],
    actuators: Iterable[str],
    sensors: Iterable[str] | None = None,
    events: Iterable[str] | None = None,
    subjects: Iterable[str] | None = None,
    capabilities: Iterable[str] | None = None,
    verbs: Mapping[str, Iterable[str]] | None = None,
    properties: Iterable[str] | None = None,
) -> None:
    """Check every name in the scenario before the run, naming the line and the valid choices."""
    for problem in name_problems(
        scenario,
        stations=stations,
        buttons=buttons,
        signals=signals,
        tags=tags,
        actuators=actuators,
        sensors=sensors,
        events=events,
        subjects=subjects,
        capabilities=capabilities,
        verbs=verbs,
        properties=properties,
    ):
        raise ScenarioError(": ".join(problem))


def name_problems(
    scenario: Scenario,
    *,
    stations: Iterable[str],
    buttons: Iterable[str],
    signals: Iterable[str],
    tags: Iterable[str],
    actuators: Iterable[str],
    sensors: Iterable[str] | None = None,
    events: Iterable[str] | None = None,
    subjects: Iterable[str] | None = None,
    capabilities: Iterable[str] | None = None,
    verbs: Mapping[str, Iterable[str]] | None = None,
    properties: Iterable[str] | None = None,
) -> list[tuple[str, str]]:
    """Every name of the scenario that does not exist: ``(file:line, "scenario ...: no ...; valid: ...")``.

    ``signals`` are what a fault can be put on (plant signals and wired tags), ``sensors`` what a trigger
    waits for (the plant's sensors: nothing else is polled); ``events`` the plant's event vocabulary and
    ``subjects`` the names its events are about, besides the scenario's parts; ``capabilities`` what the
    plant declares (a verb needing another one is refused), ``verbs`` its rig verbs with their valid
    targets and ``properties`` the part properties a ``place`` may give (None: no plant, not checked).
    """
    signal_list = list(signals)
    sensor_list = list(sensors) if sensors is not None else signal_list
    station_list = list(stations)
    parts = sorted({a.target for a in scenario.actions if a.verb == "place"})
    choices: dict[str, list[str]] = {
        "station": station_list,
        "button or switch": list(buttons),
        "tag": list(tags),
        "part or station": parts + station_list,
        "part": parts,
        "wired signal": signal_list,
        "sensor": sensor_list,
        "motor": list(actuators),
        "signal to wait for": sensor_list,
    }
    if events is not None:
        choices["plant event to wait for"] = sorted(events)
    if subjects is not None:
        choices["event subject (a part or plant name)"] = parts + sorted(set(subjects) - set(parts))
    problems = []
    caps = None if capabilities is None else set(capabilities)
    for a in scenario.actions:
        if a.rig is not None and a.rig.controller:
            continue  # the controller's verb: checked against the controller a run has (controller_verb_problems)
        rig_problem = _rig_verb_problem(a, verbs)
        if rig_problem:
            problems.append((a.defined_at, f"scenario {scenario.name!r}: {a.describe()}: {rig_problem}"))
            continue
        targets = None
        if a.rig is not None and verbs is not None:
            targets = parts if a.rig.on_parts else list(verbs[a.verb])
        found = len(problems)
        for k, (role, name) in enumerate(a.names()):
            is_target = a.rig is not None and k == 0  # a rig verb's first name is its target
            valid = targets if is_target else choices.get(role)
            key = name.split(".")[0].split("[")[0] if role == "tag" else name
            if valid is None or key in valid:
                continue
            listed = ", ".join(valid) if valid else "none"
            problems.append(
                (
                    a.defined_at,
                    f"scenario {scenario.name!r}: {a.describe()}: no {role} {name!r}"
                    f"{did_you_mean(name, valid)}; valid: {listed}",
                )
            )
        if properties is not None and a.verb == "place" and a.rig is None:
            property_list = sorted(properties)
            for name in a.args.get("properties") or {}:
                if name not in property_list:
                    valid = ", ".join(property_list) or "none"
                    problems.append(
                        (
                            a.defined_at,
                            f"scenario {scenario.name!r}: {a.describe()}: no part property {name!r}"
                            f"{did_you_mean(name, property_list)}; valid: {valid}",
                        )
                    )
        need = VERB_CAPABILITY.get(a.verb) if a.rig is None else None
        if len(problems) == found and caps is not None and need is not None and need not in caps:
            problems.append(
                (
                    a.defined_at,
                    f"scenario {scenario.name!r}: {a.describe()}: the rig cannot do this "
                    f"(it does not declare the capability {need!r})",
                )
            )
    return problems


def controller_verb_problems(scenario: Scenario, controller: Any) -> list[tuple[str, str]]:
    """Every action of the scenario that needs a verb ``controller`` does not bring, or names a target it
    lacks (an interrupt source the Tecomat does not have): ``(file:line, "scenario ...: ...")``."""
    own = getattr(controller, "VERBS", {})
    family = getattr(controller, "family", None) or getattr(controller.config, "family", "controller")
    problems = []
    for a in scenario.actions:
        if a.rig is None or not a.rig.controller:
            continue
        where, what = a.defined_at, f"scenario {scenario.name!r}: {a.describe()}"
        if own.get(a.verb) is not a.rig:
            problems.append((where, f"{what}: the {family} cannot do this ({a.rig.doc or 'another controller'})"))
        elif a.rig.targets and a.target not in (valid := list(getattr(controller, a.rig.targets))):
            listed = f"{did_you_mean(a.target, valid)}; valid: {', '.join(valid)}"
            problems.append((where, f"{what}: no {a.rig.role} {a.target!r}{listed}"))
    return problems


def _rig_verb_problem(a: Action, verbs: Mapping[str, Iterable[str]] | None) -> str:
    """Why the rig cannot carry out this rig verb at all ("" if it can, or for one of plcsim's verbs)."""
    if a.rig is None or verbs is None or a.verb in verbs:
        return ""
    return f"the rig has no verb {a.verb!r}{did_you_mean(a.verb, verbs)}; its verbs: {', '.join(verbs) or 'none'}"


def plant_vocabulary(plant: Any) -> dict[str, Any]:
    """What a scenario may ask of ``plant`` beyond its names: the ``events``, ``subjects``, ``capabilities``,
    ``verbs`` (with their valid targets) and ``properties`` (of a part it places: the plant's optional
    ``PART_PROPERTIES``, none if it declares none) arguments of :func:`name_problems` (all None for no plant)."""
    if plant is None:
        return {"events": None, "subjects": None, "capabilities": None, "verbs": None, "properties": None}
    missing = [m for m in ("EVENTS", "CAPABILITIES", "VERBS", "event_subjects") if not hasattr(plant, m)]
    if missing:
        raise ConfigurationError(
            f"the plant {getattr(plant, 'name', plant)!r} does not declare {missing}: a plant declares its event "
            "kinds, capabilities and rig verbs (see plcsim.plant.protocol.Plant)"
        )
    return {
        "events": sorted(plant.EVENTS),
        "subjects": sorted(plant.event_subjects()),
        "capabilities": sorted(plant.CAPABILITIES),
        "verbs": {name: verb.valid_targets(plant) for name, verb in plant.VERBS.items()},
        "properties": sorted(getattr(plant, "PART_PROPERTIES", {})),
    }
