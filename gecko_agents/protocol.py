"""Plate trajectories: a protocol is a list of segments the backing plate runs through in order.

Units: µm, µs, µN; speeds in µm/µs (1 µm/µs = 1 m/s; the default 5e-3 µm/µs is 5 mm/s).
Every segment validates itself on construction and raises ``ValueError`` naming the field.

Each segment knows how it drives the plate: :meth:`Segment.velocity` gives the plate velocity
for the next step (or ``None`` when the segment is over), :meth:`Segment.estimated_duration`
an estimate of its length [µs] for progress bars, and :meth:`Segment.target` where it ends, if
it ends at a fixed point (the model may skip free travel towards it). They ask the model only what a
:class:`Plate` offers.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Protocol

from gecko_agents._stack import user_stacklevel
from gecko_agents.params.checks import check as _check

__all__ = [
    "PressLimitError",
    "Segment",
    "Plate",
    "Move",
    "PressTo",
    "Press",
    "Hold",
    "PullOff",
    "press_pull",
    "preload_pull",
    "drag_pull",
    "DEFAULT_SPEED",
]

DEFAULT_SPEED = 5e-3
"""Plate speed [µm/µs] at which the force history of the paper's seta is quasi-static."""


class Plate(Protocol):
    """What a segment may ask of the model driving the plate (all read-only)."""

    dt: float  # time step [µs]
    time: float  # simulated time [µs]
    plate_position: tuple  # (x, y) [µm]
    z_touch: float  # plate height at which a resting tip touches h = 0 [µm]
    plate_start: float  # plate height at the start of a run [µm]
    settle_time: float  # slowest period of a free seta [µs]
    pull_travel: float  # plate travel a pull-off typically needs [µm]
    n: int  # simulated setae
    deepest: float  # deepest plate height: root a seta length and a tip radius under h = 0 [µm]

    def normal_force(self) -> float: ...  # total normal contact force [µN]

    def n_attached(self) -> int: ...


class PressLimitError(RuntimeError):
    """A force-controlled press whose preload the setae cannot carry: the plate came down a
    seta length and a tip radius below the floor's mean plane first."""


class Segment:
    """A piece of a protocol. Subclasses are frozen dataclasses validated on construction."""

    skips_free_travel = False  # whether travel with every tip free may be skipped

    def velocity(self, plate: Plate, state: dict):
        """Plate velocity (vx, vy) [µm/µs] for the next step, or None when the segment is
        over. ``state`` starts as {"start": plate position, "t0": time} and is the segment's
        own scratch space."""
        raise NotImplementedError

    def estimated_duration(self, plate: Plate) -> float:
        """Estimated duration [µs] (for progress bars)."""
        raise NotImplementedError

    def longest_duration(self, plate: Plate) -> float:
        """The longest the segment can run [µs], for the cost check before a run starts; the
        estimate unless the segment ends on a measured condition (force control)."""
        return self.estimated_duration(plate)

    def check(self, plate: Plate) -> None:
        """Refuse (ValueError naming the field, value and range) what this plate cannot do;
        called for every segment before the run steps."""

    def target(self, plate: Plate, state: dict):
        """Fixed end point (x, y) [µm] of the plate, or None."""
        return None

    def time_left(self, plate: Plate, state: dict) -> float | None:
        """Time to a fixed end [µs], or None (the segment ends at a point or on a condition):
        the implicit step shortens its last step to it, so the segment lasts its duration."""
        return None


def _towards(plate: Plate, target, speed: float):
    """Velocity to move the plate to ``target`` at ``speed``, landing on it exactly."""
    px, py = plate.plate_position
    rx, ry = target[0] - px, target[1] - py
    dist = math.hypot(rx, ry)
    if dist <= 1e-12:
        return None
    if dist < speed * plate.dt:
        return rx / plate.dt, ry / plate.dt
    return rx / dist * speed, ry / dist * speed


@dataclass(frozen=True)
class Move(Segment):
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

    skips_free_travel = True

    def target(self, plate, state):
        return state["start"][0] + self.dx, state["start"][1] + self.dy

    def velocity(self, plate, state):
        return _towards(plate, self.target(plate, state), self.speed)

    def estimated_duration(self, plate):
        return math.hypot(self.dx, self.dy) / self.speed


@dataclass(frozen=True)
class PressTo(Segment):
    """Move straight down until the plate is ``depth`` [µm] below the height at which a resting
    tip touches the floor's mean plane (the same reference as the quasi-static solver)."""

    depth: float
    speed: float = DEFAULT_SPEED

    def __post_init__(self):
        _check(self, "depth", -math.inf, math.inf)
        _check(self, "speed", 0.0)

    skips_free_travel = True

    def target(self, plate, state):
        return state["start"][0], plate.z_touch - self.depth

    def velocity(self, plate, state):
        return _towards(plate, self.target(plate, state), self.speed)

    def estimated_duration(self, plate):
        return abs(plate.plate_start - (plate.z_touch - self.depth)) / self.speed

    def check(self, plate):
        # Deeper than the touch-down height puts the plate below the floor's mean plane;
        # higher than that above it leaves every tip a seta's reach away: neither measures.
        z, deepest = float(plate.z_touch), float(plate.z_touch - plate.deepest)
        if not -z <= self.depth <= deepest:
            raise ValueError(
                f"PressTo.depth = {self.depth!r} µm is outside the allowed range [{-z:.4g}, "
                f"{deepest:.4g}] µm: from the touch-down height R + L sin θ above touch-down to "
                "the plate a seta length and a tip radius below the floor's mean plane"
            )


@dataclass(frozen=True)
class Press(Segment):
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

    skips_free_travel = True

    def velocity(self, plate, state):
        # Servo on the force averaged over the seta's slowest period: a fresh contact's
        # ring-down can push the instantaneous force past the target before the static force
        # gets there.
        force = plate.normal_force()
        avg = state.setdefault("force_avg", force)
        avg += (force - avg) * min(1.0, plate.dt / plate.settle_time)
        state["force_avg"] = avg
        if avg >= self.preload:
            return None
        if plate.plate_position[1] <= plate.deepest:  # seta and tip wholly under h = 0
            raise PressLimitError(
                f"Press(preload={self.preload:.6g} µN) was not reached: the plate came down to "
                f"{plate.deepest:.4g} µm, a seta length and a tip radius below the floor's mean "
                f"plane, where its {plate.n} setae carried {avg:.4g} µN: lower the preload or "
                "simulate more setae"
            )
        frac = (self.preload - avg) / (self.band * self.preload)
        return 0.0, -self.speed * min(1.0, max(frac, 0.02))

    def estimated_duration(self, plate):
        return 2.0 / self.speed

    def longest_duration(self, plate):
        # At most the travel from the start down to the deepest plate height, where it stops
        # (rod setae folded flat let a plate pass the floor's mean plane in accepted runs).
        return max(float(plate.plate_start) - float(plate.deepest), 0.0) / self.speed


@dataclass(frozen=True)
class Hold(Segment):
    """Keep the plate still for ``duration`` [µs]."""

    duration: float

    def __post_init__(self):
        _check(self, "duration", 0.0)

    def velocity(self, plate, state):
        if plate.time - state["t0"] < self.duration - 1e-9 * plate.dt:
            return 0.0, 0.0
        return None

    def estimated_duration(self, plate):
        return self.duration

    def time_left(self, plate, state):
        return self.duration - (plate.time - state["t0"])


@dataclass(frozen=True)
class PullOff(Segment):
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

    def velocity(self, plate, state):
        px, py = plate.plate_position
        sx, sy = state["start"]
        travel = math.hypot(px - sx, py - sy)
        n_attached = plate.n_attached()
        if self.max_travel is not None and travel >= self.max_travel:
            if n_attached:
                warnings.warn(
                    f"PullOff stopped at max_travel = {self.max_travel} µm with "
                    f"{n_attached} setae still attached",
                    stacklevel=user_stacklevel(),
                )
            return None
        if not n_attached:
            free = state.get("all_free")
            if free is None:
                state["all_free"] = (px, py)
            elif math.hypot(px - free[0], py - free[1]) >= self.clearance:
                return None
        else:
            state["all_free"] = None
        ang = math.radians(self.angle_deg)
        return self.speed * math.cos(ang), self.speed * math.sin(ang)

    def estimated_duration(self, plate):
        return plate.pull_travel / self.speed

    def longest_duration(self, plate):
        """The travel that lifts the plate a pull-off's travel at ``angle_deg`` and then the
        clearance, at most ``max_travel``, over the speed [µs]."""
        travel = plate.pull_travel / math.sin(math.radians(self.angle_deg)) + self.clearance
        if self.max_travel is not None:
            travel = min(travel, self.max_travel)
        return travel / self.speed


def press_pull(depth: float, speed: float = DEFAULT_SPEED) -> list:
    """Displacement control: press to ``depth`` [µm] (see :class:`PressTo`), then pull off."""
    return [PressTo(depth, speed), PullOff(speed)]


def preload_pull(preload: float, speed: float = DEFAULT_SPEED) -> list:
    """Force control: press until the total normal force is ``preload`` [µN], then pull off."""
    return [Press(preload, speed), PullOff(speed)]


def drag_pull(
    preload: float, drag: float, angle_deg: float = 90.0, speed: float = DEFAULT_SPEED
) -> list:
    """Press to ``preload`` [µN], drag sideways by ``drag`` [µm] (positive = along the seta
    tilt, towards +x), then pull off along ``angle_deg`` [degrees from +x]."""
    steps: list[Segment] = [Press(preload, speed)]
    if drag != 0:
        steps.append(Move(dx=drag, speed=speed))
    return steps + [PullOff(speed, angle_deg)]
