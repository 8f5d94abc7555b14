"""Seta dynamics parameters: the tip's point mass and the damping ratios.

Units: µm, µN, µs, ng (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gecko_agents.params import SetaArray

__all__ = ["Damping", "DEFAULT_DAMPING", "seta_mass"]


@dataclass(frozen=True)
class Damping:
    """Damping ratios [-] (fractions of critical damping c = 2ζ√(k·m)).

    Attributes
    ----------
    seta : isotropic damping of the tip relative to the plate, on the seta's softest
        stiffness Ky; 1 = critical, so a free seta follows the plate without ringing and a
        tip moving with the plate feels none.
    normal : on the normal contact velocity, on the contact stiffness at zero load (2E*a0).
    tangential : on the tangential velocity of a sticking tip, on the stick stiffness.
    """

    seta: float = 1.0
    normal: float = 0.1
    tangential: float = 0.5

    def __post_init__(self):
        for name in ("seta", "normal", "tangential"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"Damping.{name} = {v!r} must be finite and ≥ 0")


DEFAULT_DAMPING = Damping()
"""Critical seta damping, light normal and moderate tangential contact damping."""


def seta_mass(params: SetaArray) -> float:
    """Tip point mass [ng]: the sphere plus the cantilever rod's effective share 33/140.

    33/140 is Rayleigh's effective mass of a cantilever loaded at its tip (Timoshenko, Vibration
    Problems in Engineering, §1.10): the rod's kinetic energy when it swings in its first mode.
    """
    rho, R = params.seta.density, params.contact.R
    rod = math.pi * params.seta.r**2 * params.seta.L * rho
    return 4.0 / 3.0 * math.pi * R**3 * rho + 33.0 / 140.0 * rod
