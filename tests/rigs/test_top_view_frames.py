"""The top-view rigs redraw a component only when what it shows has changed (plants/components/sketch.py): a frame
built from those kept drawables must equal one drawn afresh, at every frame of a run where parts ride, get pushed
and land in bins, pistons stroke and the pressure builds and decays."""

from __future__ import annotations

import numpy as np
import pytest

from exercises import get
from plcsim.plant.protocol import Drawable


def _fresh(plant) -> list[Drawable]:
    """The plant's moving shapes built now, none kept from an earlier frame."""
    parts = [p._sketch.build()[0] for p in plant.parts.values()]
    comps = [d for c in plant.assembly.components for d in (c._sketch.build() if hasattr(c, "_sketch") else [])]
    return [*plant.retired.values(), *parts, *comps]


def _same(a: Drawable, b: Drawable) -> bool:
    return (a.path, a.kind, a.color, a.radius, a.text) == (b.path, b.kind, b.color, b.radius, b.text) and bool(
        np.array_equal(a.points, b.points)
    )


@pytest.mark.parametrize(("number", "scenario"), [("4.3.17", "six mixed"), ("4.3.12", "two objects")])
def test_a_frame_from_kept_drawables_equals_one_drawn_afresh(number, scenario):
    ex = get(number)
    sim = ex.simulation(ex.reference.program(), scenario, seed=1)
    plant, frames, changed = sim.plant, 0, set()
    last: dict[str, Drawable] = {}
    while sim.now < sim.scenario.duration_ns:
        sim.run("40ms")
        kept, fresh = plant.dynamic_drawables(), _fresh(plant)
        assert [d.path for d in kept] == [d.path for d in fresh]
        for k, f in zip(kept, fresh, strict=True):
            assert _same(k, f), f"{number} at {sim.now / 1e9:.2f} s: {k.path} is drawn as it was, not as it is"
            if k.path in last and not _same(last[k.path], k):
                changed.add(k.path.split("/")[0])
            last[k.path] = k
        frames += 1
    assert frames > 100
    assert {"parts", "pistons", "sensors"} <= changed  # the run did move what it draws
