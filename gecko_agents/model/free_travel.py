"""The free approach skipped: while nothing can touch, the plate and its tips move rigidly to
where the first sensor would reach the floor (:meth:`gecko_agents.model.Model.skip_free_travel`).

Units: µm, µs (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["skip_free_travel", "translate"]


def skip_free_travel(world, vp, omega: float, dt: float, target=None) -> float:
    """Move the plate and tips of ``world`` rigidly along the plate velocity ``vp`` [µm/µs]
    while nothing can touch; returns the travel [µm] (0 if nothing was moved).

    Only when every tip rests relative to the plate: deflection below 1e-3 of the lag
    v/ω of a seta dragged at the plate speed (ω [rad/µs] its slowest free frequency),
    relative velocity below 1e-3 of the plate speed (a free seta then just follows the
    plate, wherever it is). The plate stops where the first sensor circle would reach the
    floor, and a few steps (of ``dt`` [µs]) before ``target`` (x, y) [µm] if given.
    """
    vx, vy = vp
    speed = math.hypot(vx, vy)
    if speed == 0.0:
        return 0.0
    world.read()
    px, py, tvx, tvy = world.state.pv
    pp = world.plate.position
    tol_u, tol_v = 1e-3 * speed / omega, 1e-3 * speed
    if (
        np.abs(px - pp.x - world.rest_dx).max() > tol_u
        or np.abs(py - pp.y - world.rest_dy).max() > tol_u
        or np.abs(tvx - vx).max() > tol_v
        or np.abs(tvy - vy).max() > tol_v
    ):
        return 0.0
    reach = world.sensor_radius + 2.0 * speed * dt
    if world.pads:
        gap = float(np.min(py - world.h)) - reach
    else:
        gap = float(np.min(py)) - world.floor_top() - reach
    travel = math.inf if vy >= 0 else gap * speed / -vy
    if target is not None:
        travel = min(travel, math.hypot(target[0] - pp.x, target[1] - pp.y) - 3.0 * speed * dt)
    if not travel > 20.0 * speed * dt:
        return 0.0
    translate(world, vx / speed * travel, vy / speed * travel, px, py)
    return travel


def translate(world, sx: float, sy: float, px, py) -> None:
    """Move the plate of ``world`` by (sx, sy) [µm] and put the tips at (px + sx, py + sy)."""
    pp = world.plate.position
    world.plate.position = (pp.x + sx, pp.y + sy)
    for body, x, y in zip(world.tips, px.tolist(), py.tolist(), strict=True):
        body.position = (x + sx, y + sy)
