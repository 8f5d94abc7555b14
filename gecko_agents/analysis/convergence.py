"""Convergence in the plate speed: is a result quasi-static, and what is its v → 0 limit?

A quasi-static result must not depend on the plate speed v. A time-stepped model's result
``f(v) = f₀ + C·vᵖ + …`` approaches its quasi-static limit f₀ as the plate slows; a contact
dashpot, whose force is ∝ v, gives order p = 1. From runs at several speeds this module
returns numbers, not verdicts in prose: the changes per unit of speed between successive speeds
(equal for p = 1), the observed order p from three speeds (Roache 1994, J Fluids Eng
116:405, the grid-convergence form with the speed as the step) and the extrapolated limit f₀
(Richardson 1911, Phil Trans R Soc A 210:307; Richardson & Gaunt 1927, Phil Trans R Soc A
226:299).

Units: speeds in µm/µs; the values in any unit (here µN); slopes in value units per µm/µs.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

__all__ = [
    "SpeedConvergence",
    "successive_slopes",
    "is_first_order",
    "observed_order",
    "richardson_limit",
    "speed_convergence",
]

FIRST_ORDER_SPREAD = 0.5
"""Largest relative spread of the successive slopes, max|s|/min|s| − 1, called first order."""


def successive_slopes(speeds, values) -> np.ndarray:
    """(f_i − f_{i+1}) / (v_i − v_{i+1}) between successive speeds, in the order given.

    Parameters
    ----------
    speeds : plate speeds [µm/µs], distinct (usually from fastest to slowest).
    values : the result at each speed (same length).
    """
    pairs = itertools.pairwise(zip(speeds, values, strict=True))
    return np.array([(f0 - f1) / (v0 - v1) for (v0, f0), (v1, f1) in pairs])


def is_first_order(slopes, spread: float = FIRST_ORDER_SPREAD) -> bool:
    """Whether the successive slopes say f is linear in v: all non-zero, of one sign, and the
    largest |slope| at most (1 + ``spread``) × the smallest. False with fewer than two slopes
    (two speeds cannot tell an order)."""
    s = np.abs(np.asarray(slopes, dtype=float))
    signs = np.sign(slopes)
    if len(s) < 2 or not np.all(s > 0) or not np.all(signs == signs[0]):
        return False
    return bool(s.max() <= (1.0 + spread) * s.min())


def observed_order(speeds, values) -> float:
    """Order p of f(v) = f₀ + C·vᵖ through the three slowest speeds (Roache 1994).

    Solves (f₁ − f₂)/(f₂ − f₃) = (v₁ᵖ − v₂ᵖ)/(v₂ᵖ − v₃ᵖ) for p in [0.01, 20] (v₁ > v₂ > v₃;
    with a constant speed ratio r it is p = ln[(f₁ − f₂)/(f₂ − f₃)]/ln r). NaN with fewer than
    three speeds, or if the differences change sign (not monotone: no power law fits) or no
    p in that range fits.
    """
    order = np.argsort(np.asarray(speeds, dtype=float))[::-1]
    if len(order) < 3:
        return math.nan
    (v1, v2, v3), (f1, f2, f3) = (np.asarray(x, dtype=float)[order[-3:]] for x in (speeds, values))
    if f2 == f3 or (f1 - f2) / (f2 - f3) <= 0:
        return math.nan
    target = (f1 - f2) / (f2 - f3)

    def mismatch(p):
        return (v1**p - v2**p) / (v2**p - v3**p) - target

    lo, hi = 0.01, 20.0
    if mismatch(lo) * mismatch(hi) > 0:
        return math.nan
    return float(brentq(mismatch, lo, hi, xtol=1e-12))


def richardson_limit(speeds, values, order: float = 1.0) -> float:
    """Richardson extrapolation to v → 0 from the two slowest speeds, for an error ∝ vᵖ:
    f₀ = f₂ + (f₂ − f₁)/((v₁/v₂)ᵖ − 1), v₁ > v₂ (Richardson 1911). NaN if fewer than two
    speeds or the order is not finite."""
    order_idx = np.argsort(np.asarray(speeds, dtype=float))[::-1]
    if len(order_idx) < 2 or not math.isfinite(order):
        return math.nan
    (v1, v2), (f1, f2) = (np.asarray(x, dtype=float)[order_idx[-2:]] for x in (speeds, values))
    return float(f2 + (f2 - f1) / ((v1 / v2) ** order - 1.0))


@dataclass(frozen=True)
class SpeedConvergence:
    """What a series of runs at several plate speeds says (:func:`speed_convergence`).

    Attributes
    ----------
    speeds : plate speeds [µm/µs], as given.
    values : the result at each speed.
    slopes : :func:`successive_slopes` [value per µm/µs], len(speeds) − 1.
    first_order : :func:`is_first_order` of the slopes.
    order : :func:`observed_order` from the three slowest speeds (NaN if undetermined).
    limit : :func:`richardson_limit` with order 1 (a dashpot's force ∝ v).
    limit_at_order : :func:`richardson_limit` with the observed order (NaN if none).
    change : relative change (f_fastest/f_slowest − 1) [-].
    """

    speeds: tuple
    values: tuple
    slopes: np.ndarray
    first_order: bool
    order: float
    limit: float
    limit_at_order: float
    change: float


def speed_convergence(speeds, values, spread: float = FIRST_ORDER_SPREAD) -> SpeedConvergence:
    """Slopes, first-order test, observed order and extrapolated limits of a result against the
    plate speed (module docstring).

    Parameters
    ----------
    speeds : plate speeds [µm/µs], distinct, from fastest to slowest.
    values : the result at each speed (same length).
    spread : tolerance of :func:`is_first_order`.
    """
    speeds, values = tuple(float(v) for v in speeds), tuple(float(f) for f in values)
    if len(speeds) != len(values) or len(speeds) < 2:
        raise ValueError(f"need ≥ 2 speeds and one value each, got {len(speeds)}/{len(values)}")
    slopes = successive_slopes(speeds, values)
    order = observed_order(speeds, values)
    return SpeedConvergence(
        speeds=speeds,
        values=values,
        slopes=slopes,
        first_order=is_first_order(slopes, spread),
        order=order,
        limit=richardson_limit(speeds, values, 1.0),
        limit_at_order=richardson_limit(speeds, values, order),
        change=values[0] / values[-1] - 1.0,
    )
