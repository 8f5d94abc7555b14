"""The free parameters of a fit: names, bounds, start points and the unit box the fit runs in.

A free parameter is a dotted name of a :class:`~gecko_agents.params.SetaArray` field (as
:meth:`SetaArray.replace` takes) or a pseudo-parameter (:data:`PSEUDO_PARAMETERS`), with
(low, high) bounds in its own unit. The fit moves in the unit box u ∈ [0, 1]ᵏ, mapped to each
parameter linearly or, for bounds spanning a decade or more, logarithmically.
"""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.params import SetaArray

PSEUDO_PARAMETERS = ("seta.stiffness_scale",)
"""Free parameters that are not fields of :class:`SetaArray`: ``seta.stiffness_scale``
multiplies the seta's axial and bending stiffness (Ka, Kp of eq 17, 19) and nothing else."""


def apply_free(base: SetaArray, names, values) -> tuple[SetaArray, float]:
    """Parameters with the free values set, and the seta stiffness scale."""
    scale, over = 1.0, {}
    for n, v in zip(names, values, strict=True):
        if n == "seta.stiffness_scale":
            scale = float(v)
        else:
            over[n] = float(v)
    return base.replace(**over), scale


def base_value(base: SetaArray, name: str) -> float:
    """The value of free parameter ``name`` in ``base`` (its unit)."""
    if name == "seta.stiffness_scale":
        return 1.0
    part, _, attr = name.partition(".")
    if name == "contact.w":
        return base.contact.work_of_adhesion
    return float(getattr(getattr(base, part), attr) if attr else getattr(base, part))


def check_free(base: SetaArray, free) -> tuple[list, np.ndarray, np.ndarray]:
    """Names, low and high bounds of ``free`` (name → (low, high)); ValueError naming the
    problem if a name is unknown, a bound is not a number or excludes the base value."""
    if not isinstance(free, dict) or not free:
        raise ValueError("free must map at least one dotted parameter name to (low, high)")
    names, lo, hi = [], [], []
    for name, b in free.items():
        if name not in PSEUDO_PARAMETERS:
            try:
                if "." not in name:
                    raise ValueError(name)
                base.replace(**{name: base_value(base, name)})
            except (ValueError, AttributeError, TypeError):
                raise ValueError(
                    f"unknown parameter name {name!r} in free (dotted names of "
                    f"SetaArray fields, e.g. 'contact.w', or one of "
                    f"{PSEUDO_PARAMETERS})"
                ) from None
        try:
            low, high = (float(v) for v in b)
        except (TypeError, ValueError):
            raise ValueError(f"free[{name!r}] = {b!r} must be a (low, high) pair") from None
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise ValueError(f"free[{name!r}] = ({low}, {high}): need finite low < high")
        start = base_value(base, name)
        if not low <= start <= high:
            raise ValueError(
                f"bounds of {name!r} ({low}, {high}) exclude its start value "
                f"{start} in the base parameters; widen them or set the base"
            )
        for v in (low, high):  # both ends must be valid parameter values
            try:
                apply_free(base, [name], [v])
            except ValueError as exc:
                raise ValueError(f"bound {v} of {name!r} is not allowed: {exc}") from None
        names.append(name)
        lo.append(low)
        hi.append(high)
    return names, np.array(lo), np.array(hi)


def starts(k: int, n_starts: int) -> list[np.ndarray]:
    """Starts in the unit box: all-low and all-high corners (2 % inside), the centre, then
    alternating corners."""
    pts = [np.full(k, 0.02), np.full(k, 0.98), np.full(k, 0.5)]
    for i in range(max(0, n_starts - 3)):
        pts.append(
            np.array([0.02 if (i >> j) & 1 == 0 else 0.98 for j in range(k)])
            if k > 1
            else np.array([0.25 + 0.5 * (i % 2)])
        )
    return pts[:n_starts]


class UnitBox:
    """The map from the fit's unit box u ∈ [0, 1]ᵏ to the parameters between bounds lo, hi.

    A parameter with 0 < lo and hi ≥ 10·lo is mapped logarithmically (its steps are
    relative), any other linearly. ``tlo``, ``tspan``: the (log or linear) interval.
    """

    def __init__(self, lo: np.ndarray, hi: np.ndarray):
        self.lo, self.hi = lo, hi
        self.logs = (lo > 0) & (hi >= 10 * lo)
        self.tlo = np.where(self.logs, np.log(np.where(self.logs, lo, 1.0)), lo)
        thi = np.where(self.logs, np.log(np.where(self.logs, hi, 1.0)), hi)
        self.tspan = thi - self.tlo

    def to_param(self, u) -> np.ndarray:
        """Parameter values at unit-box point u."""
        t = self.tlo + self.tspan * np.asarray(u, dtype=float)
        return np.where(self.logs, np.exp(t), t)

    def dparam_du(self, values) -> np.ndarray:
        """d(parameter)/du at parameter ``values``."""
        return np.where(self.logs, values * self.tspan, self.tspan)
