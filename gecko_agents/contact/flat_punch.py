"""The flat-ended (punch) tip of a pillar: :class:`FlatPunch`."""

from __future__ import annotations

import numpy as np

from gecko_agents.contact.base import ContactLaw, mindlin_stiffness
from gecko_agents.physics import flaw_tolerance, punch

__all__ = ["FlatPunch"]

# Indices of FlatPunch.constants (k), what the scalar functions read.
K_A = 0  # punch radius a [µm]
K_STIFFNESS = 1  # Sneddon's 2E*a [µN/µm]: P = k[K_STIFFNESS]·δ
K_HALF_STIFFNESS = 2  # E*a [µN/µm]: U = k[K_HALF_STIFFNESS]·δ²


class FlatPunch(ContactLaw):
    """A flat-ended cylindrical tip of radius a = ``contact.R`` whose face stays parallel to the
    floor: Sneddon's stiffness P = 2E*aδ while bonded, Kendall's pull-off
    P = −√(8πE*wa³) (:mod:`gecko_agents.physics.punch`; Sneddon 1965, Int J Eng Sci 3:47;
    Kendall 1971, J Phys D 4:1186).

    The tip attaches when its face reaches the floor (δ = 0, the bond forms with no force: a
    flat face has no long-range jump-in), carries U = E*aδ² and lets go past
    δ_detach = −√(2πwa/E*), where the edge crack runs through the whole face (it is unstable
    under load and displacement control alike, so every ``contact.detachment`` rule other
    than the sphere's ``"delta_s"`` gives this point). The contact radius is a throughout:
    the face is either bonded or off.

    Geometry: the tip node sits R above the punch face (the tip is drawn as a rigid end cap
    of radius R), so the overlap is δ = R − (y − h) as for the sphere and the touch-down
    height keeps its form. On a continuous (non-pad) floor the face is taken parallel to the
    floor at the nearest point (a punch on a curved probe of radius ≫ a).

    The face does not tilt: a punch whose pillar end rotates opens at one edge first and lets
    go earlier (:func:`gecko_agents.physics.punch.tilted_pull_off`, F = F_K − 3|M|/a, not yet
    used here); this law is the aligned limit.

    An interface of finite strength ``contact.sigma0`` = σ₀ gives Kendall's edge crack a
    cohesive (Dugdale) zone: the face lets go at Maugis's Dugdale punch's force, σ₀πa² for
    a ≤ 0.540·a_cr and below both that and Kendall's above (flaw tolerance:
    :func:`gecko_agents.physics.flaw_tolerance.punch_pull_off`; Maugis 1992, J Colloid
    Interface Sci 150:243), at δ = −F/(2E*a), the same Sneddon stiffness (the zone's own
    compliance is not modelled). σ₀ = inf (default) is Kendall's law exactly.

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R = punch radius [µm], moduli [MPa],
        w [µN/µm], sigma0 [MPa]).
    """

    name = "flat_punch"
    label = "tip = 'flat_punch'"
    flat_face = True
    # A punch lets go at its full pull-off force (a sphere at its fold, at 5/9 of Fc): the
    # seta's unbalanced force accelerates the tip F·dt/m in the release step, and the record's
    # half-step kinetic energy ½m·v·(v + F·dt/m) is off by O(F²dt²/m) on that one record (2.2 %
    # of the run's energy for five pillars of L = 15 µm pulled at 0.05 µm/µs; the next record
    # balances again).
    energy_tolerance_factor = 2.0

    def __init__(self, contact):
        a, w, E = contact.jkr_args()
        self.R = self.a = a
        self.w, self.E_star = w, E
        self.sigma0 = float(contact.sigma0)
        self.set_pull_off(float(flaw_tolerance.punch_pull_off(a, w, E, self.sigma0)))
        # A face moment moves the detachment (gecko_agents.model.face_opening) where asked:
        # the edge lets go at 3|M|/a − P = edge_force [µN].
        self.edge_opening = bool(contact.edge_opening)
        self.edge_force = self.pull_off_force
        self.attach_overlap = 0.0
        self.jump_radius = a
        self.a0 = a
        self.tangential_stiffness = mindlin_stiffness(contact, a)
        self.zero_load_stiffness = float(punch.punch_stiffness(a, E))
        k = self.constants = np.zeros(3)
        k[K_A], k[K_STIFFNESS], k[K_HALF_STIFFNESS] = a, 2.0 * E * a, E * a

    def set_pull_off(self, force: float) -> None:
        """Let the face go at the tension ``force`` [µN], at δ = −F/(2E*a) on Sneddon's
        stiffness; Kendall's own force keeps Kendall's closed-form overlap
        (:func:`gecko_agents.physics.punch.kendall_detach_overlap`)."""
        a, w, E = self.a, self.w, self.E_star
        self.pull_off_force = force
        if force == float(punch.kendall_pull_off(a, w, E)):
            self.detach_overlap = float(punch.kendall_detach_overlap(a, w, E))
        else:
            self.detach_overlap = -force / float(punch.punch_stiffness(a, E))

    def stiffest(self, load: float) -> float:
        return self.zero_load_stiffness

    def stiffness(self, a, delta=None):
        """dP/dδ = 2E*a (Sneddon 1965), the same at every overlap while bonded."""
        return np.full(np.shape(a), self.zero_load_stiffness)

    def radius(self, delta, a_prev=None, dt=0.0):
        return np.full(np.shape(delta), self.a)

    def force(self, a, delta):
        return punch.punch_force(delta, self.a, self.E_star)

    def energy(self, a, delta):
        return punch.punch_energy(delta, self.a, self.E_star)

    @staticmethod
    def radius_scalar(delta, a_prev, dt, k):
        return k[K_A]

    @staticmethod
    def force_scalar(a, delta, k):
        return k[K_STIFFNESS] * delta

    @staticmethod
    def energy_scalar(a, delta, k):
        return k[K_HALF_STIFFNESS] * delta * delta
