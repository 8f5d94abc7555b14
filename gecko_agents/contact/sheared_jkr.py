"""The JKR sphere whose adhesion feels the shear it carries (Savkoor & Briggs 1977):
:class:`ShearedJKRSphere`."""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.contact.base import (
    K_ATTACH_FILM,
    K_ATTACH_RADIUS,
    ContactLaw,
    branch_radius,
    mindlin_stiffness,
)
from gecko_agents.physics import jkr
from gecko_agents.physics._util import register_jitables
from gecko_agents.physics.friction import combined_shear_modulus, friction_cap, stick_stiffness

__all__ = ["ShearedJKRSphere"]


try:  # called from the compiled per-seta loop, so compiled too
    from numba import njit as _njit

    register_jitables()
except ImportError:  # pragma: no cover

    def _njit(**kwargs):
        return lambda f: f


# Indices of ShearedJKRSphere.constants (k), what the scalar functions read; k[K_ATTACH_RADIUS]
# and k[K_ATTACH_FILM] are the radius and the (unused) film length the kernels give a tip on
# attachment, as for every tangential law (:mod:`.base`).
K_R = 0  # tip radius R [µm]
K_AC = 1  # JKR's snap-off radius a_c [µm]
K_W = 2  # work of adhesion w [µN/µm]
K_E = 3  # effective modulus E* [MPa]
K_G = 4  # combined shear modulus G* [MPa]
K_MU = 6  # friction coefficient μ [-]
K_PAPER = 7  # 1.0: the paper's friction cap μ·max(P, 0), 0.0: the adhesive μ|P + 2Fc|
K_FC = 8  # pull-off force Fc [µN]


@_njit(cache=True)
def _fold_radius(c2, k):
    """Radius [µm] at the end of the stable branch at fixed δ and ξ, where dδ/da = 0:
    8πw·a³ − 4c2·a² − π²w²R²/E* = 0 with c2 = 4G*ξ² [µN] (Newton from the right, where the
    cubic is convex and increasing; a_c, JKR's snap-off radius, at ξ = 0)."""
    R, w, E = k[K_R], k[K_W], k[K_E]
    C = (math.pi * w * R) ** 2 / E
    a = c2 / (2.0 * math.pi * w) + k[K_AC]  # the cubic is ≥ 0 here (module docstring)
    for _ in range(100):
        h = (8.0 * math.pi * w * a - 4.0 * c2) * a * a - C
        dh = (24.0 * math.pi * w * a - 8.0 * c2) * a
        step = h / dh
        a -= step
        if step <= 1e-15 * a:
            break
    return a


@_njit(cache=True)
def _gap(a, delta, c2, k):
    """g(a) = a²/R − √((2πwa − c2)/E*) − δ [µm] and g'(a): zero on the branch at (δ, ξ)."""
    R, w, E = k[K_R], k[K_W], k[K_E]
    q = (2.0 * math.pi * w * a - c2) / E
    r = math.sqrt(q) if q > 0.0 else 0.0
    g = a * a / R - r - delta
    dg = 2.0 * a / R - (math.pi * w / E / r if r > 0.0 else math.inf)
    return g, dg


@_njit(cache=True)
def _radius(delta, xi, k):
    """Contact radius [µm] on the stable branch at overlap δ and tangential displacement ξ [µm]
    (:func:`gecko_agents.physics.savkoor_briggs.overlap_from_radius` inverted); 0 where none exists
    (past
    the fold). g(a) is convex, so Newton from JKR's radius at δ (where g ≥ 0, right of the
    fold whenever the contact exists) falls monotonically onto the largest root."""
    c2 = 4.0 * k[K_G] * xi * xi
    a_fold = _fold_radius(c2, k)
    g, _ = _gap(a_fold, delta, c2, k)
    if g > 0.0:
        return 0.0
    a = max(branch_radius(delta, k[K_R], k[K_AC]), a_fold)
    for _ in range(200):
        g, dg = _gap(a, delta, c2, k)
        if g <= 0.0 or dg <= 0.0:
            break
        step = g / dg
        a -= step
        if step <= 1e-15 * a:
            break
    return max(a, a_fold)


@_njit(cache=True)
def _state_energy(a, delta, xi, k):
    """:func:`gecko_agents.physics.savkoor_briggs.energy` [pJ] of radius a at (δ, ξ)."""
    R, w, E, G = k[K_R], k[K_W], k[K_E], k[K_G]
    e = delta - a * a / R
    U = 8.0 * E * a**5 / (15.0 * R * R) + 4.0 * E * a**3 / (3.0 * R) * e + E * a * e * e
    return U - math.pi * a * a * w + 4.0 * G * a * xi * xi


@_njit(cache=True)
def _normal_force(a, delta, k):
    """:func:`gecko_agents.physics.savkoor_briggs.force_from_state` [µN]."""
    R, E = k[K_R], k[K_E]
    return 4.0 * E * a**3 / (3.0 * R) + 2.0 * E * a * (delta - a * a / R)


@_njit(cache=True)
def _cap(P, k):
    """Coulomb cap [µN]: :func:`gecko_agents.physics.friction.friction_cap`, μ|P + 2Fc|
    (adhesive, Thornton 1991) or μ·max(P, 0) (paper, eq 27)."""
    return friction_cap(P, k[K_FC], k[K_MU], k[K_PAPER] > 0.0)


@_njit(cache=True)
def _holds(delta, s, k):
    """(radius [µm], 1.0 if a contact at tangential displacement s ≥ 0 holds within the cap)."""
    a = _radius(delta, s, k)
    if a <= 0.0:
        return a, 0.0
    held = stick_stiffness(a, k[K_G]) * s <= _cap(_normal_force(a, delta, k), k)
    return a, (1.0 if held else 0.0)


class ShearedJKRSphere(ContactLaw):
    """The JKR sphere (paper eq 1–15) with its adhesion coupled to the shear it carries:
    ``contact.shear_coupling = "savkoor_briggs"``.

    The tip's stick spring is the contact's own Mindlin stiffness k_t = 8G*·a at its current
    radius, and the contact radius solves Griffith's balance with both release rates,
    G_I + G_II = w (Savkoor & Briggs 1977, Proc R Soc A 356:103), at the tip's overlap δ and
    tangential displacement ξ from its stick anchor: δ = a²/R − √((2πwa − 4G*ξ²)/E*)
    (:mod:`gecko_agents.physics.savkoor_briggs`, the closed forms this law is tested against). Shear
    shrinks the contact and lowers the tension it holds; the tip lets go where the branch at
    its (δ, ξ) ends, which a sheared tip reaches at a smaller pull, or sheared alone.

    Every step, at the tip's position: the tip first tries to stick (ξ = x_tip − anchor); if
    the contact then exceeds the Coulomb cap (μ|P + 2Fc|, Thornton 1991, or the paper's
    μ·max(P, 0), eq 27) or no contact can hold that ξ, the anchor slides to the largest ξ that
    holds (bisection), dissipating the work of the shear held there (at the cap: the Coulomb
    work cap·|Δξ|, as the sphere's stick spring). If that boundary is the end of the branch
    (the contact fails below its cap) a tip off the floor (δ ≤ 0) lets go, its stored energy
    dissipated; a pressed one slides there (:meth:`step_scalar`).

    With ξ = 0 the branch is JKR's; the law then follows :class:`JKRSphere`'s ``"fold"``
    detachment. Energy U = 8E*a⁵/(15R²) + P1·e + E*a·e² − πa²w + 4G*·a·ξ² [pJ]
    (e = δ − a²/R, P1 = 4E*a³/(3R)), from which P = ∂U/∂δ and the tangential force ∂U/∂ξ follow;
    the radius minimises it at fixed (δ, ξ), so the contact is elastic: a step at a fixed tip
    position dissipates only the work of a slip.

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R [µm], moduli [MPa], w [µN/µm]).
    friction : :class:`gecko_agents.params.Friction` (μ, law).
    """

    name = "sphere"
    tangential = True
    damp_sliding = False  # as JKRSphere: a sliding tip is held by its Coulomb cap alone
    label = "tip = 'sphere' with contact.shear_coupling = 'savkoor_briggs'"

    def __init__(self, contact, friction):
        R, w, E = contact.jkr_args()
        G = float(combined_shear_modulus(contact.E1, contact.nu1, contact.E2, contact.nu2))
        self.R, self.w, self.E_star, self.G_star = R, w, E, G
        self.pull_off_force = float(jkr.pull_off_force(R, w))
        self.ac = float(jkr.snap_off_radius(R, w, E))
        self.a0 = float(jkr.zero_load_contact_radius(R, w, E))
        self.detach_overlap = float(jkr.snap_off_overlap(R, w, E))
        self.jump_radius = float(np.cbrt((math.sqrt(2 * math.pi * w / E) * R) ** 2))
        # What the kernels give a tip on attachment: its radius at δ = 0 (no film).
        self.ell0, self.s_attach = self.jump_radius, 0.0
        # As the sphere's: the stick spring at a0 sets the tangential damping and the time
        # step (a pressed contact is stiffer, 8G*·a, as its normal stiffness 2E*·a is).
        self.tangential_stiffness = mindlin_stiffness(contact, self.a0)
        self.zero_load_stiffness = 2 * E * self.a0
        mu, paper = friction.mu, 1.0 if friction.law == "paper" else 0.0
        k = self.constants = np.zeros(K_ATTACH_FILM + 1)  # indices 9–11 unused
        k[K_R], k[K_AC], k[K_W], k[K_E], k[K_G] = R, self.ac, w, E, G
        k[K_ATTACH_RADIUS], k[K_ATTACH_FILM] = self.jump_radius, 0.0
        k[K_MU], k[K_PAPER], k[K_FC] = mu, paper, self.pull_off_force

    def stiffest(self, load: float) -> float:
        a = float(jkr.contact_radius_from_force(load, self.R, self.w, self.E_star))
        return 2 * self.E_star * a

    def stiffness(self, a, delta):
        """dP/dδ of the unsheared JKR branch at radius a (:func:`jkr.contact_stiffness`, eq 7
        and 10): the normal stiffness the shear coupling starts from."""
        return jkr.contact_stiffness(a, self.R, self.w, self.E_star)

    def energy(self, a, delta):
        raise NotImplementedError("ShearedJKRSphere stores its energy in the state (state.uc)")

    @staticmethod
    def step_scalar(dx, z, a_prev, xi_prev, u_prev, xa, k):
        """One step of the contact at the tip's offset dx from its attachment point and height
        z of its centre above the floor [µm], from state (a_prev [µm], xi_prev the tip's
        tangential displacement at the end of the previous step [µm], u_prev the energy stored
        then [pJ], xa the stick anchor − attachment point [µm]; the kernels keep ξ and U in the
        film's pre-tension and length slots, 0 on attachment). Returns (P, T, shift, a, ξ, U,
        xa, U, dissipation, slid) as :meth:`SpatulaTip.step_scalar`: P [µN] > 0 compressive,
        T [µN] along +x on the tip, shift 0 (the attachment point stays), a = 0 when the tip
        lets go, U then what the contact stored when its force last acted, which the kernels
        dissipate (as for :class:`JKRSphere`).

        Past the cap, or where no contact holds the trial ξ, the anchor slides to the largest
        ξ that holds (bisection from the last ξ, which held): at the cap, or at the end of the
        branch. A tip whose branch ends there lets go if it no longer overlaps the floor
        (δ ≤ 0); pressed into it (δ > 0) it keeps its contact and slides at the shear the
        branch's end holds (shear has peeled the adhesive contact as far as it goes; Johnson
        1997 has it drop to the Hertz area then, which is not modelled). A slip dissipates the
        work of the shear it held, 8G*·a·|ξ| times the slip."""
        delta = k[K_R] - z
        xi = dx - xa
        s = abs(xi)
        a, ok = _holds(delta, s, k)
        coulomb = 0.0
        slid = 0.0
        if ok == 0.0:  # over the cap, or no contact holds this ξ: the largest ξ that holds
            released = _radius(delta, 0.0, k) <= 0.0  # past the fold even without shear
            if not released:
                lo, hi = 0.0, s
                last = abs(xi_prev)  # held last step: the first boundary lies beyond it
                if xi_prev * xi > 0.0 and last < s and _holds(delta, last, k)[1] > 0.0:
                    lo = last
                for _ in range(60):
                    mid = 0.5 * (lo + hi)
                    if _holds(delta, mid, k)[1] > 0.0:
                        lo = mid
                    else:
                        hi = mid
                # The branch ends below the cap: a tip off the floor lets go.
                released = delta <= 0.0 and _radius(delta, hi, k) <= 0.0
            if released:  # what the contact stored when its force last acted is dissipated
                return 0.0, 0.0, 0.0, 0.0, 0.0, u_prev, xa, u_prev, 0.0, 0.0
            a = _radius(delta, lo, k)
            coulomb = stick_stiffness(a, k[K_G]) * lo * (s - lo)
            xi = math.copysign(lo, xi)
            xa = dx - xi
            slid = 1.0
        P = _normal_force(a, delta, k)
        T = -stick_stiffness(a, k[K_G]) * xi
        # Elastic: the radius follows (δ, ξ) on the branch, so a step dissipates only the
        # work of a slip (the stick spring's release at fixed position, to first order).
        U = _state_energy(a, delta, xi, k)
        return P, T, 0.0, a, xi, U, xa, U, coulomb, slid
