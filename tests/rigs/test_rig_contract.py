"""What a rig built from ``plants.components`` must keep, stated by protocols and checked loudly: a belt listed among
a top-view rig's components carries its parts by itself; ``check_plant`` catches a belt that does not; a component or
a sensor zone that lacks a member of its protocol is refused, naming the member (issue 28, item 2)."""

from __future__ import annotations

import pymunk
import pytest

from plants.components import Assembly, Beam, Piston, TopBelt, TopViewPlant, WorkpieceSpec, zone
from plcsim.plant import Station, check_plant


class ShortBelt(TopViewPlant):
    """A 200 mm belt with a barrier at each end and nothing else: the smallest top-view rig with a belt."""

    def __init__(self, *, seed: int = 0) -> None:
        super().__init__(
            "SHORT",
            components=[TopBelt("D1", "D1", (0.0, -20.0, 200.0, 20.0)), Beam("S1", 20.0, -20.0, 20.0)],
            stations=[Station("S1", 20.0, 0.0)],
            table=(-10.0, -60.0, 230.0, 60.0),
            workpiece=WorkpieceSpec(length=20.0, depth=20.0, height=20.0, mass_g=10.0),
            seed=seed,
        )


class SlippingBelt(ShortBelt):
    """The mistake the protocol used to hide: parts tied to the table although they lie on the belt."""

    def support_at(self, x: float, y: float) -> pymunk.Body:
        return self.space.static_body


def test_a_listed_belt_carries_its_parts_without_support_at():
    rig = ShortBelt()
    check_plant(rig)
    part = rig.place("S1", offset_mm=0.0)
    rig.actuate("D1", True)
    for _ in range(1000):
        rig.step(1_000_000)
    assert rig.parts[part].body.position.x == pytest.approx(20.0 + 50.0 * (1.0 - 0.05), abs=0.1)  # 1 s, less τ


def test_check_plant_catches_a_belt_that_does_not_carry_and_names_the_fix():
    with pytest.raises(AssertionError) as caught:
        check_plant(SlippingBelt())
    message = str(caught.value)
    assert "a part placed at station 'S1' lies on belt/D1, but no actuator switched on moves it" in message
    assert "TopBelt" in message and "support_at()" in message


def test_a_component_lacking_a_member_is_named_with_it():
    class Half:
        name, EVENTS = "P1", frozenset()

        def specs(self):
            return []

    with pytest.raises(TypeError, match=r"Half 'P1' lacks `subjects`, `reset`, `actuate`, `advance`, .*Component"):
        Assembly([Half()])
    piston = Piston("P1", "Y1", origin=(0.0, 30.0), direction=(0.0, -1.0), stroke=40.0)
    Assembly([piston])  # a whole one is accepted


def test_a_sensor_zone_made_by_hand_without_an_owner_is_refused_when_the_rig_resets():
    from plants.components.collide import CT_BEAM

    class HandMade(Beam):
        def _attach(self, host):
            shape = pymunk.Circle(host.space.static_body, 3.0, (self.x, self.y))
            shape.sensor, shape.collision_type = True, CT_BEAM  # no owner: the callbacks could not tell it
            host.space.add(shape)
            self.shape = shape

    class Rig(ShortBelt):
        def __init__(self):
            TopViewPlant.__init__(
                self,
                "HAND",
                components=[HandMade("S9", 50.0, -20.0, 20.0)],
                stations=[],
                table=(0.0, -30.0, 100.0, 30.0),
                workpiece=WorkpieceSpec(),
            )

    with pytest.raises(TypeError, match=r"HAND: a sensor zone in the space has no owner; make sensor zones with "):
        Rig()


def test_a_sensor_zone_whose_owner_cannot_be_told_is_refused():
    class Mute:
        name = "B9"

        def enter(self, host, part):
            pass

    rig = ShortBelt()
    with pytest.raises(TypeError, match=r"Mute 'B9' lacks `leave` of the zone-sensor protocol"):
        zone(rig, Mute(), pymunk.Circle(rig.space.static_body, 3.0))
