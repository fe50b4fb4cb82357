"""The rerun export: real .rrd files written and read back with rerun's own reader (no viewer)."""

from __future__ import annotations

import datetime as dt
from typing import Any

import numpy as np
import pytest

rr = pytest.importorskip("rerun")

from plcsim import CPU, Tag  # noqa: E402
from plcsim.plant.protocol import Drawable, PlantEvent, SignalSpec, Station  # noqa: E402
from plcsim.scenario.planning import Scenario  # noqa: E402
from plcsim.scenario.verbs import place, stop_cpu  # noqa: E402
from plcsim.sim.simulation import Simulation  # noqa: E402
from plcsim.sim.wiring import NO  # noqa: E402
from plcsim.trace.facade import Trace, TraceEvent  # noqa: E402
from plcsim.trace.rerun import (  # noqa: E402
    GROUPS,
    default_recording_id,
    event_level,
    export_rrd,
    group_rows,
    lane_entity,
    signal_groups,
    static_texts,
    step_rows,
)

# rerun logs conversion errors as warnings and drops the data: make them fail the tests
pytestmark = pytest.mark.filterwarnings("error::rerun.error_utils.RerunWarning")

# -- a small plant: a belt carrying parts at 100 mm/s past two light barriers -------------------


class FakeBelt:
    """A belt (x 0..300 mm, side view), light barriers S1 at 20 mm and S2 at 200 mm, motor D1, lamp H1."""

    name = "fake_belt"
    view = "side"
    EVENTS = frozenset({"part placed", "part entered", "part left"})
    CAPABILITIES = frozenset({"parts"})
    VERBS: dict = {}
    SPEED = 100.0  # mm/s
    WIDTH = 30.0
    BEAMS = {"S1": 20.0, "S2": 200.0}

    def __init__(self) -> None:
        self.signals = {
            "S1": SignalSpec("S1", "sensor", doc="light barrier at 20 mm"),
            "S2": SignalSpec("S2", "sensor", doc="light barrier at 200 mm"),
            "D1": SignalSpec("D1", "actuator", doc="belt motor"),
            "H1": SignalSpec("H1", "actuator", doc="lamp"),
        }
        self.stations = {"S1": Station("S1", 20.0)}
        self.reset()

    def reset(self, *, seed: int | None = None) -> None:
        self.sensors: dict[str, Any] = {"S1": False, "S2": False}
        self.now_ns = 0
        self.events: list[PlantEvent] = []
        self.parts: dict[str, float] = {}
        self.motor = False
        self.lamp = False

    def actuate(self, name: str, value: Any) -> None:
        if name == "D1":
            self.motor = bool(value)
        else:
            self.lamp = bool(value)

    def step(self, dt_ns: int) -> None:
        self.now_ns += dt_ns
        if self.motor:
            for pid in self.parts:
                self.parts[pid] += self.SPEED * dt_ns / 1e9
        for sensor, x in self.BEAMS.items():
            inside = [p for p, px in self.parts.items() if abs(px - x) <= self.WIDTH / 2]
            if bool(inside) != self.sensors[sensor]:
                self.sensors[sensor] = bool(inside)
                kind = "part entered" if inside else "part left"
                self.events.append(PlantEvent(self.now_ns, kind, sensor, inside[0] if inside else None))

    def place(
        self,
        station: str,
        *,
        part: str | None = None,
        offset_mm: float = 0.0,
        angle_deg: float = 0.0,
        **properties: Any,
    ) -> str:
        pid = part or f"p{len(self.parts) + 1}"
        self.parts[pid] = self.stations[station].x + offset_mm
        self.events.append(PlantEvent(self.now_ns, "part placed", station, pid))
        return pid

    def remove(self, target: str) -> None:
        self.parts.pop(target)

    def static_drawables(self) -> list[Drawable]:
        return [
            Drawable("belt", "line", np.array([[0.0, 0.0], [300.0, 0.0]]), (60, 60, 60)),
            Drawable("belt", "line", np.array([[0.0, -10.0], [300.0, -10.0]]), (60, 60, 60)),
            *[
                Drawable(f"sensors/{s}", "label", np.array([[x, 60.0]]), (0, 0, 0), text=s)
                for s, x in self.BEAMS.items()
            ],
        ]

    def dynamic_drawables(self) -> list[Drawable]:
        out = []
        for pid, x in self.parts.items():
            w = self.WIDTH / 2
            box = np.array([[x - w, 0.0], [x + w, 0.0], [x + w, 30.0], [x - w, 30.0]])
            out.append(Drawable(f"parts/{pid}", "polygon", box, (200, 120, 0), text=pid))
        for s, x in self.BEAMS.items():
            lit = (255, 0, 0) if self.sensors[s] else (0, 200, 0)
            out.append(Drawable(f"beams/{s}", "line", np.array([[x, 0.0], [x, 50.0]]), lit, text=s))
        out.append(
            Drawable(
                "lamp/H1", "circle", np.array([[280.0, 80.0]]), (255, 220, 0) if self.lamp else (90, 90, 90), radius=8.0
            )
        )
        return out

    def event_subjects(self) -> set[str]:
        return {"S1", "S2"}

    def bounds(self) -> tuple[float, float, float, float]:
        return (0.0, -20.0, 300.0, 100.0)


PROGRAM = """
T1 = IEC_TIMER()

def OB1(t):
    t.D1 = (t.S1 or t.D1) and not t.S2
    t.T1.TON(IN=t.S2, PT="200ms")
    t.H1 = t.T1.Q
"""


def belt_run(duration: str = "2.5s", *, stop_at: str | None = None) -> Trace:
    """S1 sees the part at 0.1 s, D1 runs, the part reaches S2 after about 1.65 s, D1 stops, H1 200 ms later."""
    tags = {"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0"), "H1": Tag("%Q0.1")}
    cpu = CPU(tags=tags, program=PROGRAM)
    plant = FakeBelt()
    actions = [place("p1", at="S1", t="0.1s", noise=False)]
    if stop_at:
        actions.append(stop_cpu(t=stop_at))
    scenario = Scenario("one part", *actions, duration=duration)
    sim = Simulation(cpu, plant, [NO("S1"), NO("S2"), NO("D1"), NO("H1")], scenario, seed=7)
    sim.run()
    return sim.trace


@pytest.fixture(scope="module")
def belt_trace() -> Trace:
    return belt_run()


# -- reading a file back -----------------------------------------------------------------------


def read_rrd(path) -> dict[tuple[str, bool], dict[str, list]]:
    """{(entity, static): {column: values}} of the recording in ``path``, chunks concatenated in time order
    (rerun's row ids are left out: they are fresh on every write)."""
    reader = rr.chunk.RrdReader(path)
    out: dict[tuple[str, bool], dict[str, list]] = {}
    for chunk in reader.stream().to_chunks():
        batch = chunk.to_record_batch().to_pydict()
        batch.pop("rerun.controls.RowId", None)
        cols = out.setdefault((chunk.entity_path, chunk.is_static), {})
        for name, values in batch.items():
            cols.setdefault(name, []).extend(values)
    for cols in out.values():
        if "sim" in cols:
            order = sorted(range(len(cols["sim"])), key=lambda k: cols["sim"][k])
            for name in cols:
                cols[name] = [cols[name][k] for k in order]
    return out


def ns(t: dt.timedelta) -> int:
    return (t.days * 86_400 + t.seconds) * 1_000_000_000 + t.microseconds * 1_000


def series(data, entity: str) -> tuple[list[str], np.ndarray, np.ndarray]:
    """Names, times (ns) and values (rows, series) of a signal group read back from a file."""
    names = data[(entity, True)]["SeriesLines:names"][0]
    temporal = data[(entity, False)]
    times = np.array([ns(t) for t in temporal["sim"]], dtype=np.int64)
    values = np.array(temporal["Scalars:scalars"], dtype=float).reshape(len(times), len(names))
    return names, times, values


def lane(data, trace: Trace, name: str) -> tuple[list[str], np.ndarray, np.ndarray]:
    """The lane of one Bool signal read back from a file."""
    group = next(g for g, names in signal_groups(trace).items() if name in names)
    return series(data, "/" + lane_entity(group, name))


def value_in_file(names, times, values, name: str, t_ns: int) -> float:
    k = int(np.searchsorted(times, t_ns, side="right")) - 1
    return float(values[max(k, 0), names.index(name)])


# -- tests -------------------------------------------------------------------------------------


def test_signals_events_and_plant_read_back(belt_trace, tmp_path):
    trace = belt_trace
    path = trace.to_rrd(tmp_path / "belt.rrd")
    assert path.stat().st_size > 0
    data = read_rrd(path)
    entities = {e for e, _ in data}

    # Bools: one entity (lane) per signal; the first row, both values at each change, the last row
    assert {"/signals/inputs/S1", "/signals/inputs/S2", "/signals/outputs/D1", "/signals/numbers"} <= entities
    for name in ("S1", "S2"):
        names, times, values = lane(data, trace, name)
        assert names == [name]
        expected_t, expected_v = group_rows(trace, [name])
        assert times.tolist() == expected_t.tolist()
        assert np.array_equal(values, expected_v)
        edges = [*trace.rises(name), *trace.falls(name)]
        assert len(times) == 2 * len(edges) + 2
        for t in edges:
            assert value_in_file(names, times, values, name, int(t)) == float(trace.value_at(name, int(t)))
            assert value_in_file(names, times, values, name, int(t) - 1) == float(trace.value_at(name, int(t) - 1))

    # outputs are stamped at scan end: D1 falls when the scan that saw S2 ends
    names, times, values = lane(data, trace, "D1")
    d1_fall = int(trace.falls("D1")[0])
    assert d1_fall in times.tolist()
    assert d1_fall in trace.end_times.tolist()
    assert value_in_file(names, times, values, "D1", d1_fall) == 0.0
    assert value_in_file(names, times, values, "D1", d1_fall - 1) == 1.0
    names, times, values = lane(data, trace, "H1")
    h1_rise = int(trace.rises("H1")[0])
    assert 190_000_000 <= h1_rise - d1_fall <= 210_000_000

    # numbers: the timer's elapsed time, every row while it counts
    names, times, values = series(data, "/signals/numbers")
    assert names == ["T1.ET"]
    assert value_in_file(names, times, values, "T1.ET", int(trace.times[-1])) == trace.value_at(
        "T1.ET", trace.times[-1]
    )
    assert data[("/signals/inputs/S1", True)]["SeriesLines:interpolation_mode"] == [[2]]  # StepAfter

    # events: a text log per source, with levels, at their simulated times
    plant_log = data[("/events/plant", False)]
    plant_events = trace.events_of(source="plant")
    assert len(plant_log["sim"]) == len(plant_events)
    entered = next(e for e in plant_events if e.kind == "part entered" and e.subject == "S2")
    k = [ns(t) for t in plant_log["sim"]].index(entered.t_ns)
    assert plant_log["TextLog:text"][k] == ["part entered S2 (p1)"]
    assert plant_log["TextLog:level"][k] == ["INFO"]
    assert data[("/events/scenario", False)]["TextLog:level"] == [["DEBUG"]]

    # the plant: fixed shapes once (static, y flipped), moving shapes once per geometry frame
    assert ("/plant/static/belt", True) in data
    belt = data[("/plant/static/belt", True)]["LineStrips2D:strips"][0]
    assert belt[1] == [[0.0, 10.0], [300.0, 10.0]]  # y = -10 drawn at +10 (rerun's 2D view is y down)
    assert data[("/plant/static/sensors/S1", True)]["Points2D:labels"] == [["S1"]]
    # each text once: the beams' captions S1, S2 are the sensors' labels, so they are left out
    assert "LineStrips2D:labels" not in data[("/plant/moving/beams", False)]
    frames = trace.frames
    parts = data[("/plant/moving/parts", False)]
    assert len(parts["sim"]) == len(frames) == 63  # 25 Hz for 2.5 s (first frame at 1 ms)
    assert [len(s) for s in parts["LineStrips2D:strips"]][:3] == [0, 0, 0]  # before the part is placed
    assert parts["LineStrips2D:labels"][-1] == ["p1"]  # a part's caption is written by nothing else
    last_box = parts["LineStrips2D:strips"][-1][0]
    assert len(last_box) == 5  # a closed polygon
    x_part = (last_box[0][0] + last_box[1][0]) / 2
    assert 185 <= x_part <= 187  # stopped within a scan of reaching S2's zone (beam at 200, part 30 mm wide)
    beams = data[("/plant/moving/beams", False)]
    assert beams["LineStrips2D:colors"][0] == [0x00C800FF, 0x00C800FF]  # both beams free
    assert beams["LineStrips2D:colors"][-1] == [0x00C800FF, 0xFF0000FF]  # S2 interrupted
    lamp = data[("/plant/moving/lamp", False)]
    assert lamp["Points2D:radii"][-1] == [8.0]
    assert lamp["Points2D:positions"][-1] == [[280.0, -80.0]]

    # metadata and the recording's identity
    meta = data[("/meta", True)]["TextDocument:text"][0][0]
    assert "| scenario | one part |" in meta and "| seed | 7 |" in meta and "| T1.ET | timer | int |" in meta
    reader = rr.chunk.RrdReader(path)
    (recording,) = reader.recordings()
    assert recording.application_id == "plcsim"
    assert recording.recording_id == default_recording_id(trace)
    timelines = {tl for chunk in reader.stream().to_chunks() for tl in chunk.timeline_names}
    assert timelines == {"sim"}  # no wall-clock log_time, no log_tick


def blueprint_views(path) -> dict[str, tuple[str, str]]:
    """Origin -> (view class, view name) of the blueprint stored in a file."""
    reader = rr.chunk.RrdReader(path)
    (blueprint,) = reader.blueprints()
    views = {}
    for chunk in reader.stream(store=blueprint).to_chunks():
        batch = chunk.to_record_batch()
        if "ViewBlueprint:class_identifier" in batch.schema.names:
            row = {
                n: batch.column(n).to_pylist()[0][0]
                for n in ("ViewBlueprint:class_identifier", "ViewBlueprint:space_origin", "ViewBlueprint:display_name")
            }
            origin = "/" + row["ViewBlueprint:space_origin"].lstrip("/")
            views[origin] = (row["ViewBlueprint:class_identifier"], row["ViewBlueprint:display_name"])
    return views


def test_blueprint_shows_machine_signals_and_events(belt_trace, tmp_path):
    views = blueprint_views(export_rrd(belt_trace, tmp_path / "bp.rrd"))
    assert views["/plant"] == ("2D", "Machine (fake_belt)")
    # one lane per Bool, the group's title on its first lane
    assert views["/signals/inputs/S1"] == ("TimeSeries", "Inputs (I)")
    assert views["/signals/inputs/S2"] == ("TimeSeries", "S2")
    assert views["/signals/outputs/D1"] == ("TimeSeries", "Outputs (Q)")
    assert views["/signals/outputs/H1"] == ("TimeSeries", "H1")
    assert views["/signals/internal/T1.Q"][0] == views["/signals/numbers"][0] == "TimeSeries"
    assert views["/events"] == ("TextLog", "Events")
    assert views["/meta"][0] == "TextDocument"


def test_same_trace_gives_equal_data(belt_trace, tmp_path):
    """Bytes differ (rerun gives every row and chunk a fresh id), so compare what the files hold:
    every entity's columns, row ids left out, rows in time order."""
    a = export_rrd(belt_trace, tmp_path / "a.rrd")
    b = export_rrd(belt_trace, tmp_path / "b.rrd")
    assert read_rrd(a) == read_rrd(b)
    ra, rb = rr.chunk.RrdReader(a).recordings()[0], rr.chunk.RrdReader(b).recordings()[0]
    assert ra.recording_id == rb.recording_id
    # a different run gets a different recording id, so the viewer never merges two runs
    other = belt_run("2s")
    assert default_recording_id(other) != default_recording_id(belt_trace)


def test_every_row_and_stop_events(tmp_path):
    trace = belt_run("1s", stop_at="0.5s")
    path = export_rrd(trace, tmp_path / "stop.rrd", every_row=True, title="stopped run")
    data = read_rrd(path)
    _, times, values = lane(data, trace, "S1")
    edges = len(trace.rises("S1")) + len(trace.falls("S1"))
    assert len(times) == len(trace) + edges  # every row, scans and STOP rows, and the held value at each edge
    held = np.zeros(len(times), dtype=bool)  # the old value, sent just before the new one at the same time
    held[:-1] = times[1:] == times[:-1]
    assert held.sum() == edges
    assert np.array_equal(values[~held, 0], trace.column("S1")[np.argsort(trace.times, kind="stable")])
    cpu_log = data[("/events/cpu", False)]
    assert ["RUN->STOP"] in [[t.split(":")[0]] for (t,) in cpu_log["TextLog:text"]]
    levels = dict(
        zip(
            [t[0].split(":")[0] for t in cpu_log["TextLog:text"]],
            [lv[0] for lv in cpu_log["TextLog:level"]],
            strict=True,
        )
    )
    assert levels["RUN->STOP"] == "WARN"
    assert data[("/__properties", True)]["RecordingInfo:name"] == [["stopped run"]]


def test_plc_only_and_synthetic_traces(tmp_path):
    """No plant, no events, a group with no rows, unusual names: still a valid file and a blueprint."""
    tr = Trace(
        ["TL", "LED", "Level", "DATA.x y"],
        kinds={"TL": "input", "LED": "output", "Level": "input", "DATA.x y": "db"},
        types={"TL": "bool", "LED": "bool", "Level": "int", "DATA.x y": "real"},
        meta={"seed": 1},
    )
    for k in range(6):
        tr.add_row(k * 2_000_000, k * 2_000_000 + 1_000_000, 1, (k >= 2, k >= 3, 10 * k, 0.5))
    tr.add_event(TraceEvent(4_000_000, "cpu", "error in the program", "OB1", None, "division by zero"))
    path = export_rrd(tr, tmp_path / "plc.rrd")
    data = read_rrd(path)
    assert not any(e.startswith("/plant") for e, _ in data)
    names, times, values = series(data, "/signals/numbers")
    assert names == ["Level", "DATA.x y"]
    ms = 1_000_000
    assert times.tolist() == [0, 2 * ms, 2 * ms, 4 * ms, 4 * ms, 6 * ms, 6 * ms, 8 * ms, 8 * ms, 10 * ms, 10 * ms]
    assert values[:, 0].tolist() == [0, 0, 10, 10, 20, 20, 30, 30, 40, 40, 50]
    names, times, values = series(data, "/signals/outputs/LED")
    assert times.tolist() == [1 * ms, 7 * ms, 7 * ms, 11 * ms] and values[:, 0].tolist() == [0, 0, 1, 1]
    assert not any(e.startswith("/signals/internal") for e, _ in data)
    assert data[("/events/cpu", False)]["TextLog:level"] == [["ERROR"]]
    views = blueprint_views(path)  # no machine: the signals beside the events
    assert "/plant" not in views
    assert set(views) == {"/signals/inputs/TL", "/signals/outputs/LED", "/signals/numbers", "/events", "/meta"}

    empty = Trace(["A"], kinds={"A": "input"}, types={"A": "bool"})
    data = read_rrd(export_rrd(empty, tmp_path / "empty.rrd"))
    assert ("/signals/inputs/A", True) in data and ("/signals/inputs/A", False) not in data
    assert len(rr.chunk.RrdReader(tmp_path / "empty.rrd").blueprints()) == 1


def test_three_analog_lines_keep_their_own_colours(tmp_path):
    """A crane's X, Y and Z positions (three analog columns): their colours are one per line, not one RGB colour
    made of the three (rerun warned and the export failed)."""
    names = ["plant:X.s", "plant:Y.s", "plant:Z.s"]
    tr = Trace(names, kinds=dict.fromkeys(names, "analog"), types=dict.fromkeys(names, "real"))
    for k in range(4):
        tr.add_row(k * 1_000_000, (k + 1) * 1_000_000, 1, (100.0 + k, 50.0 + k, float(k)))
    got, _, values = series(read_rrd(export_rrd(tr, tmp_path / "crane.rrd")), "/signals/analog")
    assert got == names and values[-1].tolist() == [103.0, 53.0, 3.0]


def test_export_ignores_rerun_off(belt_trace, tmp_path, monkeypatch):
    """RERUN=off silences live logging; an explicit export still writes its file (and leaves the variable)."""
    monkeypatch.setenv("RERUN", "off")
    path = export_rrd(belt_trace, tmp_path / "off.rrd")
    assert ("/signals/inputs/S1", False) in read_rrd(path)
    import os

    assert os.environ["RERUN"] == "off"


def test_grouping_and_levels():
    tr = Trace(
        ["I", "Q", "M", "T.Q", "T.ET", "AQ"],
        kinds={"I": "input", "Q": "output", "M": "memory", "T.Q": "timer", "T.ET": "timer", "AQ": "output"},
        types={"I": "bool", "Q": "bool", "M": "bool", "T.Q": "bool", "T.ET": "int", "AQ": "int"},
    )
    assert signal_groups(tr) == {
        "inputs": ["I"],
        "outputs": ["Q"],
        "internal": ["M", "T.Q"],
        "numbers": ["T.ET"],
        "number_outputs": ["AQ"],
    }
    assert GROUPS["number_outputs"].startswith(GROUPS["numbers"] + "/")
    assert event_level(TraceEvent(0, "plant", "part fell off", "belt")) == "WARN"
    assert event_level(TraceEvent(0, "plant", "plant fault", "belt")) == "ERROR"
    assert event_level(TraceEvent(0, "cpu", "cycle time monitoring exceeded")) == "ERROR"
    assert event_level(TraceEvent(0, "cpu", "STOP->RUN")) == "INFO"
    assert event_level(TraceEvent(0, "scenario", "action failed")) == "WARN"


def test_conv1_rig_when_the_plants_package_has_it(tmp_path):
    """The real CONV1 rig (skipped while plants/ does not provide it): the part rides from S1 to S2 in about 4.83 s."""
    plants = pytest.importorskip("plants")
    if not hasattr(plants, "Conv1"):
        pytest.skip("plants has no Conv1 yet")
    cpu = CPU(
        tags={"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0")},
        program="def OB1(t):\n    t.D1 = (t.S1 or t.D1) and not t.S2\n",
    )
    scenario = Scenario("one part", place("part", at="S1", t="0.1s", noise=False), duration="5.5s")
    sim = Simulation(cpu, plants.Conv1(), [NO("S1"), NO("S2"), NO("D1")], scenario)
    sim.run()
    trace = sim.trace
    data = read_rrd(export_rrd(trace, tmp_path / "conv1.rrd"))
    names, times, values = lane(data, trace, "S2")
    s2_rise = int(trace.rises("S2")[0])
    assert 4.7e9 < s2_rise - int(trace.rises("S1")[0]) < 5.0e9
    assert value_in_file(names, times, values, "S2", s2_rise) == 1.0
    assert value_in_file(names, times, values, "S2", s2_rise - 1) == 0.0
    static = {e for e, is_static in data if is_static and e.startswith("/plant/static/")}
    assert static == {"/plant/static/" + "/".join(d.path.split("/")) for d in trace.static_drawables}
    moving = [cols for (e, is_static), cols in data.items() if e.startswith("/plant/moving/") and not is_static]
    assert moving and all(len(cols["sim"]) == len(trace.frames) for cols in moving)
    assert len(trace.frames) >= 130  # 25 Hz over 5.5 s


# -- exact step functions, lanes and labels on a real exercise ---------------------------------


@pytest.fixture(scope="module")
def jam_trace() -> Trace:
    """4.3.7's reference in its jam scenario: TON_A.Q is TRUE for one scan at 10.374 s, and ET resets."""
    from exercises import get

    ex = get("4.3.7")
    sim = ex.simulation(ex.reference.program(), ex.scenario("jam"), seed=1)
    sim.run()
    return sim.trace


def file_values_at(times: np.ndarray, values: np.ndarray, at: np.ndarray) -> np.ndarray:
    """What the file says at each time in ``at``: the last row sent at or before it."""
    k = np.searchsorted(times, at, side="right") - 1
    assert np.all(k >= 0)
    return values[k]


def test_every_signal_reads_exactly_as_the_trace(jam_trace, tmp_path):
    """Read back every lane and the numbers: at every scan and just before every change, the file's
    step function is the trace's value; a line in the file joins only equal values."""
    trace = jam_trace
    data = read_rrd(export_rrd(trace, tmp_path / "alarm.rrd"))
    groups = signal_groups(trace)
    entities = [("/" + lane_entity(g, n), [n]) for g in ("inputs", "outputs", "internal") for n in groups.get(g, [])]
    entities.append(("/signals/numbers", groups["numbers"]))
    assert [n for _, names in entities for n in names] == ["S1", "S2", "D1", "ALARM", "ACK", "TON_A.Q", "TON_A.ET"]
    off = rr.components.AggregationPolicy.Off.value
    for entity, names in entities:
        style = data[(entity, True)]
        assert style["SeriesLines:aggregation_policy"] == [[off]], entity  # the viewer never averages
        assert style["SeriesLines:interpolation_mode"] == [[2]], entity  # StepAfter
        got_names, times, values = series(data, entity)
        assert got_names == names
        # a step function: between two rows at different times the values are equal
        moves = np.any(values[1:] != values[:-1], axis=1)
        assert np.all(times[1:][moves] == times[:-1][moves]), entity
        for j, name in enumerate(names):
            when, col = trace.signal_times(name), trace.column(name).astype(float)
            assert np.array_equal(file_values_at(times, values[:, j], when), col), name  # every scan
            changes = np.flatnonzero(col[1:] != col[:-1]) + 1
            before = file_values_at(times, values[:, j], when[changes] - 1)
            assert np.array_equal(before, col[changes - 1]), name  # just before each change

    # the pulse the issue found drawn as a 0.5 plateau: both edges, one scan apart, at full height
    _, times, values = lane(data, trace, "TON_A.Q")
    ms = 1_000_000
    assert times.tolist() == [0, 10_374 * ms, 10_374 * ms, 10_375 * ms, 10_375 * ms, int(trace.times[-1])]
    assert values[:, 0].tolist() == [0, 0, 1, 1, 0, 0]
    _, times, values = series(data, "/signals/numbers")
    at_reset = values[times == 10_375 * ms, 0].tolist()
    assert at_reset == [10_000, 0]  # ET holds 10000 up to the reset, then 0 (never a 5000 between)
    assert set(values[times > 10_375 * ms, 0].tolist()) == {0.0}


def test_step_rows_edge_cases():
    empty_t, empty_v = step_rows(np.zeros(0, dtype=np.int64), np.zeros((0, 2)))
    assert len(empty_t) == 0 and empty_v.shape == (0, 2)
    t, v = step_rows(np.array([5]), np.array([[1.0]]))
    assert t.tolist() == [5] and v.tolist() == [[1.0]]
    t, v = step_rows(np.array([0, 1, 2, 3]), np.array([[0.0, 5.0], [0.0, 5.0], [1.0, 6.0], [1.0, 6.0]]))
    assert t.tolist() == [0, 2, 2, 3]
    assert v.tolist() == [[0.0, 5.0], [0.0, 5.0], [1.0, 6.0], [1.0, 6.0]]
    t, v = step_rows(np.array([0, 1, 2, 3]), np.array([[0.0], [1.0], [1.0], [0.0]]), every_row=True)
    assert t.tolist() == [0, 1, 1, 2, 3, 3] and v[:, 0].tolist() == [0, 0, 1, 1, 1, 0]


def test_static_texts_draws_each_text_once():
    pt = np.array([[0.0, 0.0], [1.0, 1.0]])
    drawables = [
        Drawable("sensors/S1", "line", pt, text="S1"),  # caption of the sensor: its label writes S1
        Drawable("sensors/S1/label", "label", pt[:1], text="S1"),
        Drawable("frame/stop", "polygon", pt, text="stop"),  # a caption nothing else writes
        Drawable("frame/stop2", "polygon", pt, text="stop"),  # the same caption again
        Drawable("frame/base", "polygon", pt),
    ]
    texts, written = static_texts(drawables)
    assert texts == ["", "S1", "stop", "", ""]
    assert written == {"S1", "stop"}


def test_each_label_drawn_once_on_conv1(jam_trace, tmp_path):
    """The real CONV1: the sensors' and the belt's names once each, in the fixed layer; no moving
    shape writes them again in any frame; the part keeps its caption."""
    data = read_rrd(export_rrd(jam_trace, tmp_path / "labels.rrd"))
    static = [
        text
        for (entity, is_static), cols in data.items()
        if is_static and entity.startswith("/plant/static/")
        for key in ("Points2D:labels", "LineStrips2D:labels")
        for text in (cols.get(key) or [[]])[0]
        if text
    ]
    assert sorted(static) == ["D1", "S1", "S2"]
    moving = {
        text
        for (entity, is_static), cols in data.items()
        if not is_static and entity.startswith("/plant/moving/")
        for key in ("Points2D:labels", "LineStrips2D:labels")
        for frame in cols.get(key, [])
        for text in frame or []
    }
    assert moving == {"p1"}


def blueprint_columns(path) -> dict[str, list[list[str]]]:
    """Name -> the view origins in each child column, for the named containers of a file's blueprint."""
    reader = rr.chunk.RrdReader(path)
    (blueprint,) = reader.blueprints()
    containers, origins = {}, {}
    for chunk in reader.stream(store=blueprint).to_chunks():
        batch = chunk.to_record_batch()
        key = chunk.entity_path.lstrip("/")
        if "ContainerBlueprint:contents" in batch.schema.names:
            name = (
                (batch.column("ContainerBlueprint:display_name").to_pylist()[0] or [""])[0]
                if ("ContainerBlueprint:display_name" in batch.schema.names)
                else ""
            )
            containers[key] = (name, batch.column("ContainerBlueprint:contents").to_pylist()[0])
        if "ViewBlueprint:space_origin" in batch.schema.names:
            origins[key] = "/" + batch.column("ViewBlueprint:space_origin").to_pylist()[0][0].lstrip("/")
    return {
        name: [[origins[v] for v in containers[c][1]] for c in contents if c in containers]
        for name, contents in containers.values()
        if name
    }


def test_many_lanes_go_in_two_columns(tmp_path):
    """Nine Bool lanes would be too low to read in one column: inputs and outputs go left, the
    internal bits right, each still its own view."""
    names = ["I0", "I1", "I2", "Q0", "Q1", "M0", "M1", "M2", "M3"]
    kinds = {n: {"I": "input", "Q": "output", "M": "memory"}[n[0]] for n in names}
    tr = Trace(names, kinds=kinds, types=dict.fromkeys(names, "bool"))
    for k in range(4):
        tr.add_row(k * 1_000_000, k * 1_000_000 + 500_000, 1, tuple((k + j) % 2 == 0 for j in range(len(names))))
    columns = blueprint_columns(export_rrd(tr, tmp_path / "many.rrd"))
    left = [
        "/signals/inputs/I0",
        "/signals/inputs/I1",
        "/signals/inputs/I2",
        "/signals/outputs/Q0",
        "/signals/outputs/Q1",
    ]
    right = ["/signals/internal/M0", "/signals/internal/M1", "/signals/internal/M2", "/signals/internal/M3"]
    assert columns["Signals"] == [left, right]
    # eight or fewer: one column
    few = Trace(names[:8], kinds=kinds, types=dict.fromkeys(names[:8], "bool"))
    few.add_row(0, 500_000, 1, (False,) * 8)
    assert blueprint_columns(export_rrd(few, tmp_path / "few.rrd"))["Signals"] == []  # views, no columns


def test_a_plants_analog_value_is_a_line_through_its_samples(tmp_path):
    """PUNCH traces its ram height (kind ``analog``): in the recording it is a straight-line series of its
    own (the issue: the press's analog value drawn as a line), with a plateau's ends and every sample of
    a ramp, so the line is the trace's value at every scan."""
    from exercises import get

    ex = get("6.3.3")
    sim = ex.simulation(ex.reference.program(), ex.scenarios[0], seed=1)
    sim.run()
    trace = sim.trace
    assert signal_groups(trace)["analog"] == ["plant:M2.z"]
    data = read_rrd(trace.to_rrd(tmp_path / "punch.rrd"))
    style = data[("/signals/analog", True)]
    assert style["SeriesLines:interpolation_mode"] == [[1]]  # Linear
    names, times, values = series(data, "/signals/analog")
    assert names == ["plant:M2.z"]
    when, col = trace.signal_times("plant:M2.z"), trace.column("plant:M2.z").astype(float)
    assert len(times) < len(when) / 2  # the plateaus are sent by their ends
    assert np.array_equal(np.interp(when, times, values[:, 0]), col)  # the line is the trace at every scan
    assert col.max() > col.min() + 20  # the ram went down and up
