"""Plate trajectories: a protocol is a list of segments the backing plate runs through in order.

Units: µm, µs, µN; speeds in µm/µs (1 µm/µs = 1 m/s; the default 5e-3 µm/µs is 5 mm/s).
Every segment validates itself on construction and raises ``ValueError`` naming the field.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .params import _check

__all__ = ["Move", "PressTo", "Press", "Hold", "PullOff", "press_pull", "preload_pull",
           "drag_pull", "DEFAULT_SPEED"]

DEFAULT_SPEED = 5e-3
"""Plate speed [µm/µs] at which the force history of the paper's seta is quasi-static."""


@dataclass(frozen=True)
class Move:
    """Move the plate by (dx, dy) [µm] at ``speed`` [µm/µs]."""

    dx: float = 0.0
    dy: float = 0.0
    speed: float = DEFAULT_SPEED

    def __post_init__(self):
        _check(self, "dx", -math.inf, math.inf)
        _check(self, "dy", -math.inf, math.inf)
        _check(self, "speed", 0.0)
        if self.dx == 0 and self.dy == 0:
            raise ValueError("Move needs a non-zero displacement (dx, dy)")


@dataclass(frozen=True)
class PressTo:
    """Move straight down until the plate is ``depth`` [µm] below the height at which a resting
    tip touches the floor's mean plane (the same reference as the quasi-static solver)."""

    depth: float
    speed: float = DEFAULT_SPEED

    def __post_init__(self):
        _check(self, "depth", -math.inf, math.inf)
        _check(self, "speed", 0.0)


@dataclass(frozen=True)
class Press:
    """Force control: move down until the total normal contact force reaches ``preload`` [µN].

    A velocity servo on the force averaged over the seta's slowest period (a fresh contact's
    ring-down must not end the press): full ``speed`` far from the target, slowing linearly
    within the last ``band`` (fraction of the preload); it stops once the average reaches it.
    """

    preload: float
    speed: float = DEFAULT_SPEED
    band: float = 0.2

    def __post_init__(self):
        _check(self, "preload", 0.0)
        _check(self, "speed", 0.0)
        _check(self, "band", 0.0, 1.0, hi_open=False)


@dataclass(frozen=True)
class Hold:
    """Keep the plate still for ``duration`` [µs]."""

    duration: float

    def __post_init__(self):
        _check(self, "duration", 0.0)


@dataclass(frozen=True)
class PullOff:
    """Move away at ``speed`` [µm/µs] along ``angle_deg`` (90 = straight up, measured from +x,
    the direction the setae lean towards) until every tip has let go and the plate has moved a
    further ``clearance`` [µm]; gives up after ``max_travel`` [µm] (None: no limit)."""

    speed: float = DEFAULT_SPEED
    angle_deg: float = 90.0
    clearance: float = 1.0
    max_travel: float | None = None

    def __post_init__(self):
        _check(self, "speed", 0.0)
        _check(self, "angle_deg", 0.0, 180.0)
        _check(self, "clearance", 0.0, lo_open=False)
        if self.max_travel is not None:
            _check(self, "max_travel", 0.0)


def press_pull(depth: float, speed: float = DEFAULT_SPEED) -> list:
    """Displacement control: press to ``depth`` [µm] (see :class:`PressTo`), then pull off."""
    return [PressTo(depth, speed), PullOff(speed)]


def preload_pull(preload: float, speed: float = DEFAULT_SPEED) -> list:
    """Force control: press until the total normal force is ``preload`` [µN], then pull off."""
    return [Press(preload, speed), PullOff(speed)]


def drag_pull(preload: float, drag: float, angle_deg: float = 90.0,
              speed: float = DEFAULT_SPEED) -> list:
    """Press to ``preload`` [µN], drag sideways by ``drag`` [µm] (positive = along the seta
    tilt, towards +x), then pull off along ``angle_deg`` [degrees from +x]."""
    steps = [Press(preload, speed)]
    if drag != 0:
        steps.append(Move(dx=drag, speed=speed))
    return steps + [PullOff(speed, angle_deg)]
