"""Timing diagrams: one lane per signal, steps where the trace says, highlight windows, PNG files."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("matplotlib")

from matplotlib.collections import LineCollection
from matplotlib.figure import Figure

from plcsim import CPU, Int, Tag
from plcsim.core.errors import UnknownTagError
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import press
from plcsim.sim.simulation import Simulation
from plcsim.trace.facade import Trace, TraceEvent
from plcsim.trace.plot import HIGH, LANE, save_timing_diagram, steps, timing_diagram

MS = 1_000_000


def synthetic() -> Trace:
    """10 scans of 1 ms; outputs written 0.4 ms into the scan; S1 rises in scan 2, D1 in scan 3, N counts."""
    tr = Trace(
        ["S1", "D1", "M1", "N"],
        kinds={"S1": "input", "D1": "output", "M1": "memory", "N": "counter"},
        types={"S1": "bool", "D1": "bool", "M1": "bool", "N": "int"},
        meta={"exercise": "demo", "seed": 1},
    )
    s1 = [0, 0, 1, 1, 1, 1, 0, 0, 0, 0]
    d1 = [0, 0, 0, 1, 1, 1, 1, 0, 0, 0]
    n = [0, 0, 0, 1, 1, 1, 1, 1, 2, 2]
    for k in range(10):
        tr.add_row(k * MS, k * MS + 400_000, 1, (bool(s1[k]), bool(d1[k]), k % 2 == 0, n[k]))
    tr.add_event(TraceEvent(2 * MS, "plant", "part entered", "S1", "p1"))
    tr.add_event(TraceEvent(7 * MS, "scenario", "press", "TL"))  # not a plant/cpu event: no marker by default
    tr.meta["end_ns"] = 10 * MS
    return tr


def lanes(fig: Figure) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Signal name -> (x, y) of its step line."""
    return {
        line.get_gid()[5:]: (np.asarray(line.get_xdata()), np.asarray(line.get_ydata()))
        for line in fig.axes[0].lines
        if (line.get_gid() or "").startswith("lane:")
    }


def span_x(patch) -> tuple[float, float]:
    """The x extent of a highlight span, in data coordinates."""
    box = patch.get_path().transformed(patch.get_patch_transform()).get_extents()
    return float(box.x0), float(box.x1)


def edges(x: np.ndarray, y: np.ndarray) -> list[tuple[float, str]]:
    """Where a step line changes: (time in s, 'up' or 'down')."""
    return [(round(float(x[k]), 9), "up" if y[k] > y[k - 1] else "down") for k in range(1, len(y)) if y[k] != y[k - 1]]


def test_one_lane_per_signal_with_steps_at_valid_times():
    fig = timing_diagram(synthetic(), ["S1", "D1", "N"])
    ax = fig.axes[0]
    got = lanes(fig)
    assert list(got) == ["S1", "D1", "N"]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["S1", "D1", "N"]
    # lanes stacked top to bottom: S1 highest
    assert got["S1"][1].min() == 2 * LANE and got["D1"][1].min() == LANE and got["N"][1].min() == 0
    # an input steps at the scan start, an output at the scan end (when it was written)
    assert edges(*got["S1"]) == [(0.002, "up"), (0.006, "down")]
    assert edges(*got["D1"]) == [(0.0034, "up"), (0.0074, "down")]
    assert got["S1"][1].max() == pytest.approx(2 * LANE + HIGH)
    # the line runs from the start to the end of the run
    assert got["S1"][0][0] == 0 and got["S1"][0][-1] == pytest.approx(0.010)
    assert ax.get_xlim() == pytest.approx((0.0, 0.010))
    assert ax.get_xlabel().startswith("simulated time [s]")
    # a number: steps at its changes, each labelled with its value
    assert [e[0] for e in edges(*got["N"])] == [0.003, 0.008]
    labels = [t.get_text().strip() for t in ax.texts if t.get_gid() == "value:N"]
    assert labels == ["0", "1", "2"]
    # the plant event marked with a dotted line and a label; the scenario action is not
    event_lines = [line for line in ax.lines if line.get_gid() == "event"]
    assert [line.get_xdata()[0] for line in event_lines] == [pytest.approx(0.002)]
    assert [t.get_text().strip() for t in ax.texts if t.get_gid() == "event-label"] == ["part entered S1"]
    assert ax.get_title(loc="left") == "demo · seed 1"


def test_window_scan_ticks_and_highlight():
    tr = synthetic()
    fig = timing_diagram(
        tr,
        ["D1", "S1"],
        start="2.5ms",
        end=6 * MS,
        scan_ticks=True,
        highlight=(5 * MS, 6 * MS, "expected D1 to fall within 1 scan"),
    )
    ax = fig.axes[0]
    got = lanes(fig)
    # the window starts with the value valid then (D1 still FALSE at 2.5 ms, S1 already TRUE)
    x, y = got["D1"]
    assert x[0] == pytest.approx(0.0025) and y[0] == LANE and edges(x, y) == [(0.0034, "up")]
    x, y = got["S1"]
    assert x[0] == pytest.approx(0.0025) and y[0] == pytest.approx(HIGH) and edges(x, y) == [(0.006, "down")]
    assert ax.get_xlim() == pytest.approx((0.0025, 0.006))
    # a thin tick at each OB1 scan start in view: 3, 4, 5, 6 ms
    (ticks,) = [c for c in ax.collections if c.get_gid() == "scan_ticks"]
    assert isinstance(ticks, LineCollection)
    assert sorted(round(seg[0][0], 6) for seg in ticks.get_segments()) == [0.003, 0.004, 0.005, 0.006]
    # the highlight: a shaded span with red edges and its text
    (span,) = [p for p in ax.patches if p.get_gid() == "highlight"]
    assert span_x(span) == pytest.approx((0.005, 0.006))
    assert sorted(line.get_xdata()[0] for line in ax.lines if line.get_gid() == "highlight-edge") == pytest.approx(
        [0.005, 0.006]
    )
    (note,) = [t for t in ax.texts if t.get_gid() == "highlight-text"]
    assert note.get_text().strip() == "expected D1 to fall within 1 scan"


def test_a_one_scan_highlight_stays_visible_on_a_long_axis():
    tr = synthetic()
    fig = timing_diagram(tr, highlight=[(3 * MS, 3 * MS + 1, "here"), (8 * MS, None)])
    spans = [p for p in fig.axes[0].patches if p.get_gid() == "highlight"]
    widths = [span_x(p)[1] - span_x(p)[0] for p in spans]
    assert widths[0] >= 0.004 * 0.010 * 0.99  # widened to 0.4 % of the axis
    assert widths[1] == pytest.approx(0.002)  # 8 ms to the end of the run


def test_simulated_run_and_png(tmp_path):
    tags = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0"), "N": Tag("%MW10", Int)}
    program = "def OB1(t):\n    t.LED = t.TL\n    if t.TL:\n        t.N += 1\n"
    cpu = CPU(tags=tags, program=program)
    sim = Simulation(cpu, scenario=Scenario("press", press("TL", t="20ms", hold="30ms"), duration="100ms"))
    sim.run()
    trace = sim.trace
    fig = trace.plot(["TL", "LED", "N"], title="TL lights LED")
    got = lanes(fig)
    tl_up, tl_down = int(trace.rises("TL")[0]), int(trace.falls("TL")[0])
    led_up = int(trace.rises("LED")[0])
    assert edges(*got["TL"]) == [(tl_up / 1e9, "up"), (tl_down / 1e9, "down")]
    assert edges(*got["LED"])[0] == (led_up / 1e9, "up")
    assert led_up == int(trace.end_times[trace.rise_scans("TL")[0]])  # same scan, at its end
    assert fig.axes[0].get_title(loc="left") == "TL lights LED"

    path = save_timing_diagram(
        trace,
        tmp_path / "led.png",
        ["TL", "LED", "N"],
        scan_ticks=True,
        highlight=(led_up, led_up + 1_000_000, "LED on in the same scan"),
    )
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    import matplotlib.image

    image = matplotlib.image.imread(path)
    assert image.shape[1] == 1200 and 250 < image.shape[0] < 500  # 10 in × 120 dpi, 3 lanes
    assert fig._repr_png_()[:4] == b"\x89PNG"  # notebooks show it without pyplot


def test_many_lanes_default_order_and_own_axes():
    names = [f"I{k}" for k in range(6)] + [f"Q{k}" for k in range(6)] + ["M0", "T1.ET", "C1.CV"]
    kinds = {n: {"I": "input", "Q": "output", "M": "memory", "T": "timer", "C": "counter"}[n[0]] for n in names}
    types = {n: "int" if "." in n else "bool" for n in names}
    tr = Trace(names[::-1], kinds, types)  # stored numbers first: the default order still puts inputs first
    rng = np.random.default_rng(0)
    for k in range(200):
        tr.add_row(k * MS, k * MS + MS // 2, 1, tuple(rng.integers(0, 2, len(names)).tolist()))
    fig = timing_diagram(tr)
    assert list(lanes(fig))[:6] == [f"I{k}" for k in range(5, -1, -1)]  # inputs first, in trace order
    assert len(lanes(fig)) == 15
    assert 6.5 < fig.get_size_inches()[1] < 8  # about 0.42 in per lane
    # many changes: a number lane says its range instead of labelling each value
    labels = [t.get_text() for t in fig.axes[0].get_yticklabels()]
    assert "T1.ET\n0..1" in labels

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    own, axes = plt.subplots(2, 1)
    try:
        assert timing_diagram(tr, ["I0"], ax=axes[1]) is own
        assert len(lanes_of(axes[1])) == 1 and not axes[0].lines
    finally:
        plt.close(own)


def lanes_of(ax) -> list[str]:
    return [line.get_gid() for line in ax.lines if (line.get_gid() or "").startswith("lane:")]


def test_unknown_signal_and_steps_helper():
    tr = synthetic()
    with pytest.raises(UnknownTagError, match=r"did you mean|traced"):
        timing_diagram(tr, ["S2x"])
    t, v = steps(tr, "D1", 0, 10 * MS)
    # an output is known from the end of the first scan
    assert t.tolist() == [400_000, 3_400_000, 7_400_000, 10 * MS] and v.tolist() == [0, 1, 0, 0]
    empty = Trace(["A"], kinds={"A": "input"}, types={"A": "bool"})
    assert lanes(timing_diagram(empty)) == {}


def test_one_scan_pulse_is_drawn_at_full_height_in_the_png():
    """4.3.7's jam run: TON_A.Q is TRUE for one scan (10.374 s) of 16 s. Its lane goes up and down
    one scan apart at the full TRUE height, ET drops from 10000 to 0 at the next scan, and the pulse
    is visible in the rendered pixels (a 1 ms pulse is a 0.07-pixel-wide step at this size)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from exercises import get

    ex = get("4.3.7")
    sim = ex.simulation(ex.reference.program(), ex.scenario("jam"), seed=1)
    sim.run()
    fig = timing_diagram(sim.trace)
    drawn = lanes(fig)
    assert list(drawn) == ["S1", "S2", "D1", "ALARM", "ACK", "TON_A.Q", "TON_A.ET"]
    x, y = drawn["TON_A.Q"]
    base = 1 * LANE  # second lane from the bottom
    assert edges(x, y) == [(10.374, "up"), (10.375, "down")]
    assert y.max() == pytest.approx(base + HIGH)
    x, y = drawn["TON_A.ET"]
    drop = [k for k in range(1, len(y)) if y[k] < y[k - 1]]
    assert [round(float(x[k]), 3) for k in drop] == [10.375]
    assert y[drop[0] - 1] == pytest.approx(HIGH) and y[drop[0]] == pytest.approx(0.0)  # 10000 -> 0, lane's full range

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    pixels = np.asarray(canvas.buffer_rgba())[:, :, :3].astype(int)
    ax = fig.axes[0]
    height = pixels.shape[0]
    px, top = ax.transData.transform((10.3745, base + 0.9 * HIGH))
    _, low = ax.transData.transform((10.3745, base + 0.1 * HIGH))
    col, rows = round(px), range(round(height - top), round(height - low))
    window = pixels[list(rows), col - 1 : col + 2]
    assert (window.sum(axis=2) < 600).any(axis=1).all()  # a dark stroke in every row of the pulse's height
