"""The non-adhesive Hertz sphere tip: :class:`HertzSphere`."""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.contact.base import ContactLaw, mindlin_stiffness
from gecko_agents.physics import jkr

__all__ = ["HertzSphere"]

# Indices of HertzSphere.constants (k), what the scalar functions read.
K_R = 0  # tip radius R [µm]
K_FORCE = 1  # 4E*/(3R) [µN/µm³]: P = k[K_FORCE]·a³
K_ENERGY = 2  # 8E*/(15R²) [µN/µm⁴]: U = k[K_ENERGY]·a⁵


class HertzSphere(ContactLaw):
    """An elastic sphere on a flat without adhesion (Hertz 1882; paper eq 1–3; Johnson,
    Contact Mechanics, 1985, §4.2): a = √(Rδ), P = (4E*/3R)·a³ = (4/3)E*√R·δ^(3/2),
    U = (8/15)E*√R·δ^(5/2).

    The tip touches at δ = 0 and lets go when δ < 0; Fc = 0, so the adhesive friction cap
    μ|P + 2Fc| becomes Amontons' μP. The stick stiffness is Mindlin's at the radius the contact
    has under the load Fc_ref of the JKR law with the same materials (a Hertz contact has no
    zero-load radius), so that both laws share a time-step scale.

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (w is not used).
    """

    name = "hertz"

    def __init__(self, contact):
        R, w, E = contact.jkr_args()
        self.R, self.E_star = R, E
        self.pull_off_force = 0.0
        self.detach_overlap = 0.0
        self.jump_radius = 0.0
        a_ref = float(jkr.hertz_contact_radius(jkr.pull_off_force(R, w), R, E))
        self.a0 = a_ref
        self.tangential_stiffness = mindlin_stiffness(contact, a_ref)
        self.zero_load_stiffness = 2 * E * a_ref
        k = self.constants = np.zeros(3)
        k[K_R], k[K_FORCE], k[K_ENERGY] = R, 4.0 * E / (3.0 * R), 8.0 * E / (15.0 * R * R)

    def stiffest(self, load: float) -> float:
        return 2 * self.E_star * float(jkr.hertz_contact_radius(load, self.R, self.E_star))

    def stiffness(self, a, delta=None):
        """dP/dδ = 2E*a (Johnson, Contact Mechanics, 1985, eq 4.23 differentiated)."""
        return 2.0 * self.E_star * np.asarray(a, dtype=float)

    def radius(self, delta, a_prev=None, dt=0.0):
        return np.sqrt(np.maximum(delta, 0.0) * self.R)

    def force(self, a, delta=None):
        return (4.0 * self.E_star / (3.0 * self.R)) * a * a * a

    def energy(self, a, delta=None):
        return (8.0 * self.E_star / (15.0 * self.R * self.R)) * a**5

    @staticmethod
    def radius_scalar(delta, a_prev, dt, k):
        return math.sqrt(delta * k[K_R]) if delta > 0.0 else 0.0

    @staticmethod
    def force_scalar(a, delta, k):
        return k[K_FORCE] * a * a * a

    @staticmethod
    def energy_scalar(a, delta, k):
        return k[K_ENERGY] * a**5
