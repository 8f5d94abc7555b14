"""Buckling loads of a straight column that bends and shears: Euler's, Engesser's, and the
clamped–pinned column with shear, solved here.

Plain functions in any consistent unit set (µm, µN, MPa in gecko_agents). End conditions, the
column's root clamped: ``"free"`` (the tip free to move sideways and turn), ``"pinned"`` (the
tip held sideways, free to turn) and ``"clamped"`` (held sideways and flat: a bonded flat face).

Shear enters as Engesser assumed (Engesser 1891; Timoshenko & Gere, Theory of Elastic
Stability, 2nd ed., 1961, §2.16): the shear force is the load's component across the column's
deflected axis, V = dM/dx, and the clamp holds the cross-section, not the axis. For the free
and clamped columns (no lateral reaction) this gives Engesser's P = P_E/(1 + P_E/(κGA)); for
the pinned one the reaction at the tip shears the clamp's section and the condition, derived
here, becomes tan(kL) = kL(1 − P/(κGA)) with k² = P/(EI(1 − P/(κGA))), lower than Engesser's
formula by 2.8 % at L/r = 6 (for ν = 0.3, κ = 0.886) and by 0.16 % at L/r = 30.
"""

from __future__ import annotations

import math

from scipy.optimize import brentq

__all__ = ["EULER_FACTORS", "euler_load", "engesser_load", "shear_column_load"]

EULER_FACTORS = {"free": math.pi**2 / 4.0, "pinned": 20.1907, "clamped": 4.0 * math.pi**2}
"""P_E·L²/EI of a column clamped at its root (Timoshenko & Gere 1961, ch. 2); the pinned
factor is (4.4934)², the first root of tan x = x, squared (2.0457π²)."""


def euler_load(EI, L, case):
    """Euler's buckling load P_E = c·EI/L² [force] (:data:`EULER_FACTORS`).

    Parameters
    ----------
    EI : bending stiffness [force·length²]. L : length [length]. case : end condition.
    """
    return EULER_FACTORS[case] * EI / L**2


def engesser_load(EI, kGA, L, case):
    """Engesser's load P_E/(1 + P_E/(κGA)) [force] (module docstring).

    Parameters
    ----------
    EI : bending stiffness [force·length²]. kGA : shear stiffness κGA [force].
    L : length [length]. case : end condition.
    """
    P_E = euler_load(EI, L, case)
    return P_E / (1.0 + P_E / kGA)


def shear_column_load(EI, kGA, L, case):
    """Critical load of the column with shear [force]: Engesser's formula for ``"free"`` and
    ``"clamped"``, the root of tan(kL) = kL(1 − P/(κGA)) for ``"pinned"`` (module docstring;
    κGA = inf gives Euler's).

    Derived: with M = Pw + R(L − x) (R the tip's lateral reaction), EI·w_b″ = −M, the shear
    slope w_s′ = V/(κGA), V = dM/dx = Pw′ − R, the deflection w = w_b + w_s obeys
    (1 − q)w″ + (Pw + R(L − x))/EI = 0, q = P/(κGA); w(0) = 0, w_b′(0) = 0 (the clamped
    section) and w(L) = 0 give the condition.

    Parameters
    ----------
    EI : bending stiffness [force·length²]. kGA : shear stiffness κGA [force].
    L : length [length]. case : end condition.
    """
    if case != "pinned" or math.isinf(kGA):
        return engesser_load(EI, kGA, L, case)

    def condition(P):
        q = P / kGA
        x = L * math.sqrt(P / (EI * (1.0 - q)))
        return math.sin(x) - x * (1.0 - q) * math.cos(x)

    hi = engesser_load(EI, kGA, L, case)  # the root lies below Engesser's formula
    return brentq(condition, 0.2 * hi, hi, xtol=1e-14 * hi)
