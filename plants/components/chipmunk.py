"""Direct Chipmunk calls for the per-step paths: a body's position, velocity and force, a belt shape's surface
velocity, and a space's step.

pymunk 7's ``Body.position`` builds a ``Vec2d`` from the C struct and every property write passes a Python
``__setattr__`` mixin; each costs about 1 µs, three times the C call it wraps, and a piston reads two and writes one in
every step it moves. These helpers call the same C functions pymunk calls (so the floats are the same bit for bit)
on a body's handle (:func:`handle`). The readers return an object with ``.x`` and ``.y`` (the C struct, or a
``Vec2d``). If pymunk's internals differ in another release they fall back to the public properties.

``Space.step`` adds bookkeeping around ``cpSpaceStep`` for objects added or removed inside collision callbacks and
for the mass check of new bodies; a rig that never changes the space inside a step (it defers such changes to after
it) and steps once with pymunk's own step after adding a body can call :func:`stepper`'s C step instead.

>>> import pymunk
>>> b = pymunk.Body(1.0, 1.0); b.position = (3.0, 4.0); h = handle(b)
>>> p = get_position(h); (p.x, p.y)
(3.0, 4.0)
>>> set_velocity(h, (1.5, 0.0)); b.velocity
Vec2d(1.5, 0.0)
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import pymunk

try:
    from pymunk._chipmunk_cffi import lib

    pymunk.Body(1.0, 1.0)._body  # noqa: B018 - the handles the C calls take
    pymunk.Circle(None, 1.0)._shape  # noqa: B018
    get_position = lib.cpBodyGetPosition
    get_velocity = lib.cpBodyGetVelocity
    set_velocity = lib.cpBodySetVelocity
    set_force = lib.cpBodySetForce
    get_angle = lib.cpBodyGetAngle
    get_angular_velocity = lib.cpBodyGetAngularVelocity
    set_surface_velocity = lib.cpShapeSetSurfaceVelocity

    def handle(body: pymunk.Body) -> Any:
        """What the accessors take for ``body``: its C handle."""
        return body._body

    def shape_handle(shape: pymunk.Shape) -> Any:
        """What :func:`set_surface_velocity` takes for ``shape``: its C handle."""
        return shape._shape

    def stepper(space: pymunk.Space) -> tuple[Callable[[Any, float], None], Any]:
        """(step, handle): ``step(handle, dt)`` steps ``space`` in C."""
        return lib.cpSpaceStep, space._space

except (ImportError, AttributeError):  # pragma: no cover - another pymunk release: the public API

    def get_position(body: pymunk.Body) -> Any:
        return body.position

    def get_velocity(body: pymunk.Body) -> Any:
        return body.velocity

    def set_velocity(body: pymunk.Body, v: tuple[float, float]) -> None:
        body.velocity = v

    def set_force(body: pymunk.Body, f: tuple[float, float]) -> None:
        body.force = f

    def get_angle(body: pymunk.Body) -> float:
        return body.angle

    def get_angular_velocity(body: pymunk.Body) -> float:
        return body.angular_velocity

    def set_surface_velocity(shape: pymunk.Shape, v: tuple[float, float]) -> None:
        shape.surface_velocity = v

    def handle(body: pymunk.Body) -> Any:
        """What the accessors take for ``body``: the body itself."""
        return body

    def shape_handle(shape: pymunk.Shape) -> Any:
        """What :func:`set_surface_velocity` takes for ``shape``: the shape itself."""
        return shape

    def stepper(space: pymunk.Space) -> tuple[Callable[[Any, float], None], Any]:
        """(step, handle): ``step(handle, dt)`` steps ``space`` (here with ``Space.step``)."""
        return (lambda _handle, dt: space.step(dt)), None
