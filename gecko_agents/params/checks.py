"""Range checks of parameters: one function that refuses a value naming the class, field,
value and allowed interval, and the physical ranges the parameter classes of
:mod:`gecko_agents.params` allow.

Units: µm, µN, µs, ng (MPa for moduli, J/m² = µN/µm for surface energies).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "check",
    "MODULUS_RANGE",
    "LENGTH_RANGE",
    "SURFACE_ENERGY_MAX",
    "DENSITY_RANGE",
    "COUNT_MAX",
    "ROUGHNESS_MAX",
    "FRICTION_MAX",
]


def check(
    obj: object,
    name: str,
    lo: float,
    hi: float = math.inf,
    *,
    lo_open: bool = True,
    hi_open: bool = True,
    integer: bool = False,
) -> None:
    """Raise ValueError unless ``getattr(obj, name)`` is a finite number in the interval.

    numpy scalars are accepted and stored as the Python number they hold (``np.int64(5)`` →
    ``5``), so parameters stay JSON-serialisable. ``integer=True`` accepts only integers
    (Python or numpy, not bool): ``5.0`` or ``1e12`` is refused rather than truncated.
    """
    value = getattr(obj, name)
    kind = type(obj).__name__
    interval = f"{'(' if lo_open else '['}{lo}, {hi}{')' if hi_open else ']'}"
    if isinstance(value, np.generic) and not isinstance(value, np.bool_):
        value = value.item()
        object.__setattr__(obj, name, value)
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise ValueError(f"{kind}.{name} = {value!r} must be a number in {interval}")
    if integer and not isinstance(value, int):
        raise ValueError(f"{kind}.{name} = {value!r} must be an integer in {interval}")
    ok = math.isfinite(value) or (hi == math.inf and value == math.inf and not hi_open)
    below = value < lo or (lo_open and value == lo)
    above = value > hi or (hi_open and value == hi)
    if not ok or below or above:
        raise ValueError(f"{kind}.{name} = {value!r} is outside the allowed range {interval}")


# Physical ranges of the parameters ---------------------------------------------------------
# Wide enough for any material or geometry the model could be asked about, narrow enough that
# a typo (a modulus in Pa instead of MPa, a count of 1e12) is refused before it divides by
# zero, takes a time step of 1e-150 µs or allocates terabytes.
MODULUS_RANGE = (1e-6, 1e7)
"""Young's moduli [MPa]: 1 Pa (softer than the softest hydrogels, ~10 Pa) to 10 TPa (above
diamond, 1.2 TPa)."""
LENGTH_RANGE = (1e-3, 1e5)
"""Tip radius, seta radius and length, pitch [µm]: 1 nm (below it continuum contact mechanics
does not apply) to 10 cm (a whole robot foot)."""
SURFACE_ENERGY_MAX = 10.0
"""Surface energies γ [J/m² = µN/µm]: polymers 0.02–0.05, metals up to ~3 (tungsten);
w = 2√(γ1γ2) ≤ 2·SURFACE_ENERGY_MAX."""
DENSITY_RANGE = (1e-5, 3e-2)
"""Density [ng/µm³]: 10 kg/m³ (aerogels) to 30 000 kg/m³ (above osmium, 22 590 kg/m³)."""
COUNT_MAX = 10**9
"""Setae in the physical array [-]: a tokay gecko has ~6.5·10⁶ (Autumn et al. 2000, Nature
405:681), the paper's array 10⁷; 10⁹ leaves two decades while keeping the quasi-static solver's
per-seta arrays (8 bytes each) in memory."""
ROUGHNESS_MAX = 1e4
"""RMS height and correlation length of the floor [µm]: up to 1 cm."""
FRICTION_MAX = 10.0
"""Friction coefficient [-]: elastomers on clean glass reach ~3–5 (Roberts & Thomas 1975);
10 leaves margin."""
