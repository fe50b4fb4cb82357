"""Every rig's texts can be read in a recording: no two overlap, and none covers another text's anchor.

The texts are taken as the recording draws them (:mod:`plcsim.trace.rerun`: each fixed text once, a moving shape's
caption only where no fixed shape writes it) at 13 evenly spaced moments of the reference run of the first exercise
on each rig (each panel layout counts as a rig of its own), in its most crowded scenario (the one placing the most
parts; the first of them), and placed as rerun 0.41's 2-D view draws a label: the
text centred below its anchor (a label's or circle's point, the mean of a line strip's vertices, a polygon's closing
vertex counted twice), about 6.5 px a character and a 20 px high box starting 2 px below the anchor, in screen pixels
whatever the zoom. The scale is the recording's machine view as ``rrd-screenshot`` sees it (a 1400 × 900 window): a
wide machine above the signal lanes (about 1020 × 205 px), any other beside them (about 680 × 455 px), showing the
rig's bounds with the blueprint's 5 % margins.
"""

from __future__ import annotations

import numpy as np
import pytest

from exercises import all_exercises
from plcsim.plant.protocol import Drawable
from plcsim.trace.rerun import static_texts

CHAR_PX, PAD_PX, GAP_PX, BOX_PX = 6.5, 5.0, 2.0, 20.0
WIDE_VIEW_PX, TALL_VIEW_PX = (1020.0, 205.0), (680.0, 455.0)
MOMENTS = 13
LONGEST_NS = 120_000_000_000  # a long first scenario is sampled over its first two minutes

Box = tuple[float, float, float, float]  # x0, y0, x1, y1 in mm (y up)


def px_per_mm(bounds: tuple[float, float, float, float]) -> float:
    """The scale of the recording's machine view (see the module docstring)."""
    x0, y0, x1, y1 = bounds
    w, h = x1 - x0, y1 - y0
    view_w, view_h = WIDE_VIEW_PX if w > 2.0 * h else TALL_VIEW_PX
    return min(view_w / (1.1 * w + 2.0), view_h / (1.1 * h + 2.0))


def anchor(d: Drawable) -> tuple[float, float]:
    """Where rerun hangs a shape's text: the point of a label or circle, the mean of a strip's vertices."""
    pts = np.asarray(d.points, dtype=float).reshape(-1, 2)
    if d.kind == "polygon" and len(pts) > 2:
        pts = np.concatenate([pts, pts[:1]])  # the exporter closes a polygon's strip
    if d.kind in ("label", "circle"):
        pts = pts[:1]
    x, y = pts.mean(axis=0)
    return float(x), float(y)


def text_box(text: str, at: tuple[float, float], scale: float) -> Box:
    """The box (mm) rerun draws ``text`` in, hanging below ``at``."""
    lines = text.split("\n")
    half = (CHAR_PX * max(map(len, lines)) + 2.0 * PAD_PX) / 2.0 / scale
    top = at[1] - GAP_PX / scale
    return (at[0] - half, top - BOX_PX * len(lines) / scale, at[0] + half, top)


def drawn_texts(static: list[Drawable], dynamic: list[Drawable]) -> list[tuple[str, str, tuple[float, float]]]:
    """(path, text, anchor) of every text the recording draws for these shapes."""
    texts, written = static_texts(static)
    out = [(d.path, t, anchor(d)) for d, t in zip(static, texts, strict=True) if t]
    return out + [(d.path, d.text, anchor(d)) for d in dynamic if d.text and d.text not in written]


def clashes(texts: list[tuple[str, str, tuple[float, float]]], scale: float) -> list[str]:
    """Every pair of texts whose boxes overlap, and every text whose box covers another's anchor."""
    boxes = [text_box(t, at, scale) for _, t, at in texts]
    out = []
    for i, (pa, ta, _) in enumerate(texts):
        a = boxes[i]
        for j, (pb, tb, at_b) in enumerate(texts):
            b = boxes[j]
            if j > i and a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]:
                out.append(f"{ta!r} ({pa}) overlaps {tb!r} ({pb})")
            elif j != i and a[0] < at_b[0] < a[2] and a[1] < at_b[1] < a[3]:
                out.append(f"{ta!r} ({pa}) covers the anchor of {tb!r} ({pb})")
    return out


def crowded(ex) -> str:
    """The exercise's scenario that places the most parts (the first such)."""
    return max(ex.scenarios, key=lambda s: sum(a.verb == "place" for a in s.actions)).name


def _rigs() -> dict[str, object]:
    """One exercise per rig: the first that uses it (each distinct set of fixed texts is a rig)."""
    rigs: dict[str, object] = {}
    seen: set[tuple[str, ...]] = set()
    for ex in all_exercises():
        if ex.reference is None:
            continue
        plant = ex.simulation(ex.reference.program(), ex.scenarios[0].name, seed=1).plant
        if plant is None:
            continue
        key = (plant.name, *static_texts(plant.static_drawables())[1])
        if key not in seen:
            seen.add(key)
            rigs[f"{plant.name}-{ex.number}"] = ex
    return rigs


RIG_EXERCISES = _rigs()


def test_every_rig_module_is_sampled():
    names = {key.split("-")[0] for key in RIG_EXERCISES}
    assert {"SORT", "PUNCH", "HBW", "SKIP", "SLIDE", "SPINDLE", "CONV1", "ALIGN", "PANEL", "MACHINE"} <= names


@pytest.mark.parametrize("rig", sorted(RIG_EXERCISES))
def test_no_text_overlaps_another_in_a_recording(rig):
    ex = RIG_EXERCISES[rig]
    sim = ex.simulation(ex.reference.program(), crowded(ex), seed=1)
    plant = sim.plant
    scale = px_per_mm(plant.bounds())
    static = plant.static_drawables()
    end = min(sim.scenario.duration_ns, LONGEST_NS)
    found: list[str] = []
    for k in range(MOMENTS):
        target = end * k // (MOMENTS - 1)
        if target > sim.now:
            sim.run(target - sim.now)
        texts = drawn_texts(static, plant.dynamic_drawables())
        found += [f"at {sim.now / 1e9:.2f} s: {c}" for c in clashes(texts, scale)]
    assert not found, f"{rig} at {scale:.2f} px/mm:\n" + "\n".join(dict.fromkeys(found))


def test_the_check_sees_a_clash():
    a = Drawable("a", "label", np.array([[0.0, 0.0]]), text="OS1_Vstup")
    b = Drawable("b", "label", np.array([[40.0, 0.0]]), text="OS2_Detekcia")
    c = Drawable("c", "label", np.array([[400.0, 0.0]]), text="OS3_Farba1")
    assert clashes(drawn_texts([a, b, c], []), 0.7) == ["'OS1_Vstup' (a) overlaps 'OS2_Detekcia' (b)"]
