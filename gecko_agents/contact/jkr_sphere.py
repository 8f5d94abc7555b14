"""The elastic JKR sphere tip (paper eq 1–15): :class:`JKRSphere`."""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.contact.base import ContactLaw, branch_radius, mindlin_stiffness
from gecko_agents.physics import jkr

__all__ = ["JKRSphere"]

# Indices of JKRSphere.constants (k), what the scalar functions read.
K_R = 0  # tip radius R [µm]
K_AC = 1  # snap-off radius a_c [µm]
K_HERTZ = 2  # 4E*/(3R) [µN/µm³] (eq 7's first term over a³)
K_ADHESION = 3  # 8πwE* [µN²/µm³] (eq 7's second term is √(k[K_ADHESION]·a³))
K_W = 4  # work of adhesion w [µN/µm]
K_E = 5  # effective modulus E* [MPa]
K_U_JUMP = 6  # U(a_jump) [pJ], from the scalar energy itself: the energy is 0 at attachment


class JKRSphere(ContactLaw):
    """An elastic sphere of radius R on a flat, JKR adhesion (paper eq 1–15; Johnson, Kendall &
    Roberts 1971, Proc R Soc A 324:301).

    The tip attaches at δ = 0 (no long-range force: it jumps in to P = −(8/9)Fc), follows the
    stable branch P(a) = 4E*a³/(3R) − √(8πwE*a³) (eq 7), δ(a) = a²/R − √(2πwa/E*) (eq 10), and
    lets go past δc = −(3/4)(π²w²R/E*²)^(1/3) where the branch ends (displacement control). A
    tip on a soft seta leaves its equilibrium earlier, at the fold of the spring–contact
    system; the model finds that dynamically.

    Where it lets go follows ``contact.detachment``: ``"fold"`` past δc (above), ``"delta_s"``
    past the paper's δs = −0.21·a0²/R (eq 8), ``"load_control"`` past the overlap where
    P = −Fc on the branch, δ_lc = −a_lc²/(3R) with a_lc = (9πwR²/(8E*))^(1/3) (Johnson 1985,
    §5.5). Radius, force and energy depend on δ alone (the branch).

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R [µm], moduli [MPa], w [µN/µm]).
    """

    name = "sphere"

    def __init__(self, contact):
        R, w, E = contact.jkr_args()
        self.R, self.w, self.E_star = R, w, E
        self.pull_off_force = float(jkr.pull_off_force(R, w))
        self.ac = float(jkr.snap_off_radius(R, w, E))
        a0 = float(jkr.zero_load_contact_radius(R, w, E))
        a_lc = (9.0 * math.pi * w * R * R / (8.0 * E)) ** (1.0 / 3.0)
        self.detach_overlap = {
            "fold": float(jkr.snap_off_overlap(R, w, E)),
            "delta_s": -0.21 * a0 * a0 / R,
            "load_control": -(a_lc * a_lc) / (3.0 * R),
        }[getattr(contact, "detachment", "fold")]
        # U(a_jump) = 0: the radius where δ = 0 on the branch.
        self.jump_radius = float(np.cbrt((math.sqrt(2 * math.pi * w / E) * R) ** 2))
        self.a0 = a0
        self.tangential_stiffness = mindlin_stiffness(contact, a0)
        self.zero_load_stiffness = 2 * E * a0
        k = self.constants = np.zeros(7)
        k[K_R], k[K_AC], k[K_W], k[K_E] = R, self.ac, w, E
        k[K_HERTZ], k[K_ADHESION] = 4.0 * E / (3.0 * R), 8.0 * math.pi * w * E
        k[K_U_JUMP] = JKRSphere.energy_scalar(self.jump_radius, 0.0, k)

    def stiffest(self, load: float) -> float:
        a = float(jkr.contact_radius_from_force(load, self.R, self.w, self.E_star))
        return 2 * self.E_star * a

    def stiffness(self, a, delta=None):
        """dP/dδ along the branch, (dP/da)/(dδ/da) of eq 7 and 10
        (:func:`jkr.contact_stiffness`): 2E*a in the Hertz limit, 0 at the load-controlled
        pull-off, negative below it."""
        return jkr.contact_stiffness(a, self.R, self.w, self.E_star)

    def radius(self, delta, a_prev=None, dt=0.0):
        """:func:`jkr.radius_from_overlap` (Ferrari's closed form + one Newton step), written
        with fewer temporaries for the hot path; the previous radius does not matter."""
        ac = self.ac
        d = delta * (self.R / (ac * ac))
        np.maximum(d, -3.0, out=d)
        disc = d * d
        disc *= d
        disc *= 1.0 / 27.0
        disc += 1.0
        np.sqrt(disc, out=disc)
        disc += 1.0
        A = np.cbrt(disc, out=disc)
        Bp = d / (3.0 * A)
        den = A * A
        den += d * (1.0 / 3.0)  # A·Bp = d/3
        den += Bp * Bp
        m = np.divide(2.0, den, out=den)
        inner = np.divide(2.0, m, out=Bp)
        np.sqrt(inner, out=inner)
        inner *= 4.0
        inner -= 2.0 * m
        np.maximum(inner, 0.0, out=inner)
        np.sqrt(inner, out=inner)
        m *= 2.0
        u = np.sqrt(m, out=m)
        u += inner
        u *= 0.5
        # One Newton step on u⁴ − 4u − d where 4u³ − 4 > 1e-3 (as jkr.radius_from_overlap).
        u2 = u * u
        f = u2 * u2
        f -= 4.0 * u
        f -= d
        fp = np.multiply(u2, u, out=u2)
        fp -= 1.0
        fp *= 4.0
        if fp.min() > 1e-3:
            f /= fp
            u -= f
        else:
            safe = fp > 1e-3
            u = np.where(safe, u - f / np.where(safe, fp, 1.0), u)
        np.maximum(u, 1.0, out=u)
        u *= u
        u *= ac
        return u

    def force(self, a, delta=None):
        """:func:`jkr.force_from_radius` (eq 7)."""
        a3 = a * a
        a3 *= a
        root = np.multiply(a3, 8.0 * math.pi * self.w * self.E_star)
        np.sqrt(root, out=root)
        a3 *= 4.0 * self.E_star / (3.0 * self.R)
        a3 -= root
        return a3

    def energy(self, a, delta=None):
        """:func:`jkr.contact_energy`: U(a) − U(a_jump), dU/dδ = P."""
        return jkr.contact_energy(a, self.R, self.w, self.E_star)

    @staticmethod
    def radius_scalar(delta, a_prev, dt, k):
        return branch_radius(delta, k[K_R], k[K_AC])

    @staticmethod
    def force_scalar(a, delta, k):
        a3 = a * a * a
        return a3 * k[K_HERTZ] - math.sqrt(a3 * k[K_ADHESION])

    @staticmethod
    def energy_scalar(a, delta, k):
        R, w, E = k[K_R], k[K_W], k[K_E]
        A = 4.0 * E / (3.0 * R)
        B = math.sqrt(8.0 * math.pi * w * E)
        C = math.sqrt(2.0 * math.pi * w / E)
        U = (
            2.0 * A * a**5 / (5.0 * R)
            - (A * C / 7.0 + 4.0 * B / (7.0 * R)) * a**3.5
            + math.pi * w * a * a
        )
        return U - k[K_U_JUMP]
