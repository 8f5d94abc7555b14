"""The linear seta's equilibrium branches (eq 22–27), tabulated over the JKR contact radius.

A seta is a linear spring (the 2×2 beam stiffness K of eq 16–21) on a JKR tip (eq 7, 10).
For each lateral state (stick, slide either way, or free) the plate height holding a seta
at contact radius a is its floor height plus a fixed shift plus a branch function G_b(a);
:class:`Branches` tabulates G_b once and inverts it, and :func:`release_radius` gives the fold
where the tip lets go. Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from gecko_agents.params import SetaArray
from gecko_agents.physics import beam, jkr
from gecko_agents.physics.friction import friction_cap, friction_cap_slope
from gecko_agents.quasistatic.heights import plate_start_height


def release_radius(k, R, w, E_star):
    """Contact radius at which a tip on a spring of stiffness k lets go [µm].

    The spring–contact equilibrium folds where dP/dδ = −k (:func:`jkr.contact_stiffness`);
    between a_c (k → ∞, displacement control) and 0.63 a0 (k → 0, load control).

    Parameters
    ----------
    k : effective normal stiffness of the mount [µN/µm], > 0.
    R [µm], w [µN/µm], E_star [MPa].
    """
    if not k > 0:
        raise ValueError(f"mount stiffness k = {k!r} must be > 0 [µN/µm]")
    ac = jkr.snap_off_radius(R, w, E_star)
    a_lc = 0.25 ** (1 / 3) * jkr.zero_load_contact_radius(R, w, E_star)

    def g(a):  # δ' + P'/k, sign change between a_c (P'<0, δ'=0) and a_lc (P'=0, δ'>0)
        return jkr.overlap_slope(a, R, w, E_star) + jkr.force_slope(a, R, w, E_star) / k

    return brentq(g, ac * (1 + 1e-13), a_lc, xtol=1e-15 * ac, rtol=1e-15, maxiter=200)


@dataclass(frozen=True)
class Branches:
    """The equilibrium branches of one seta type, tabulated over the contact radius a.

    For branch b the plate height that holds a seta of floor height h at contact radius a is
    Z = h + R + L sin θ + shift + G_b(a), with G_b(a) = −δ(a) − D_b(a) and D_b the spring
    deflection: P/K_yy (stick), (P − qσ·cap(P))/Ky (slide in direction σ = ±1), P/Ky (free).
    Each G_b decreases for a above its fold a_fold[b]; inverting that part is the solve.
    """

    R: float
    w: float
    E_star: float
    Fc: float
    L: float
    theta: float
    Kxx: float
    Kxy: float
    Kyy: float
    Ky: float
    r_t: float
    Kyy_stick: float
    mu: float
    law: str
    lateral: str
    a_grid: dict = field(repr=False)
    G_grid: dict = field(repr=False)
    a_fold: dict = field(repr=False)

    @classmethod
    def from_params(
        cls,
        params: SetaArray,
        lateral: str = "coupled",
        stiffness_scale: float = 1.0,
        tangential_stiffness: float = math.inf,
        n_grid: int = 16384,
    ) -> Branches:
        """Build the branch tables for ``params``.

        ``stiffness_scale`` multiplies Ka and Kp (1e6 ≈ rigid setae: the Fuller–Tabor limit).
        ``tangential_stiffness`` k_t [µN/µm] is the stick spring of the contact (∞: a sticking
        tip does not move, as in eq 26–27). A sticking tip then sits on a lateral spring k_t to
        its anchor, which softens the stick branch to K_yy − K_xy²/(K_xx + k_t).
        """
        if not tangential_stiffness > 0:
            raise ValueError(f"tangential_stiffness = {tangential_stiffness!r} must be > 0")
        if lateral not in ("coupled", "free"):
            raise ValueError(f"lateral = {lateral!r} must be 'coupled' or 'free'")
        if not stiffness_scale > 0:
            raise ValueError(f"stiffness_scale = {stiffness_scale!r} must be > 0")
        R, w, Es = params.contact.jkr_args()
        K = beam.stiffness_matrix(
            params.axial_stiffness * stiffness_scale,
            params.bending_stiffness * stiffness_scale,
            params.seta.theta,
        )
        Kxx, Kxy, Kyy = float(K[0, 0]), float(K[0, 1]), float(K[1, 1])
        Ky = Kyy - Kxy * Kxy / Kxx  # Schur complement = eq 20
        r_t = (
            1.0
            if math.isinf(tangential_stiffness)
            else (tangential_stiffness / (Kxx + tangential_stiffness))
        )
        Kyy_stick = Kyy - Kxy * Kxy * (1.0 - r_t) / Kxx
        mu = params.friction.mu if lateral == "coupled" else 0.0
        self = cls(
            R,
            w,
            Es,
            params.contact.pull_off_force,
            params.seta.L,
            params.seta.theta,
            Kxx,
            Kxy,
            Kyy,
            Ky,
            r_t,
            Kyy_stick,
            mu,
            params.friction.law,
            lateral,
            {},
            {},
            {},
        )
        a0 = jkr.zero_load_contact_radius(R, w, Es)
        for name in ["free"] if lateral == "free" else ["stick", "slip+", "slip-"]:
            a_f = release_radius(self._mount_stiffness(name, params.seta.theta_deg), R, w, Es)
            a = np.geomspace(a_f, max(40.0 * a0, 4.0 * a_f), n_grid)
            self.a_fold[name] = a_f
            self.a_grid[name] = a
            self.G_grid[name] = self.G(name, a)
        return self

    def _mount_stiffness(self, name, theta_deg) -> float:
        """Effective normal stiffness of the seta on branch ``name`` near its fold [µN/µm]."""
        if name == "stick":
            return self.Kyy_stick
        if name == "free":
            return self.Ky
        q = self.Kxy / self.Kxx
        sigma = 1.0 if name == "slip+" else -1.0
        # Near the fold P < 0; the adhesive cap grows with P there, the paper's is 0.
        dcap = self.mu if self.law == "adhesive" else 0.0
        factor = 1.0 - q * sigma * dcap
        if factor <= 0:
            raise ValueError(
                f"friction self-locks: μ = {self.mu} with θ = {theta_deg}° makes "
                "the sliding seta's normal stiffness negative; lower friction.mu"
            )
        return self.Ky / factor

    @property
    def touchdown(self) -> float:
        """Plate height [µm] at which a resting tip touches h = 0: R + L sin θ
        (:func:`gecko_agents.physics.beam.touchdown_height`)."""
        return float(beam.touchdown_height(self.L, self.theta, self.R))

    def cap(self, P):
        """Tangential force cap [µN] for normal force(s) P [µN] (as :meth:`Friction.cap`)."""
        return friction_cap(P, self.Fc, self.mu, self.law == "paper")

    def deflection(self, name, P):
        """Spring deflection D_b (tip minus rest, downward positive) for force P [µm]."""
        if name == "stick":
            return P / self.Kyy_stick
        if name == "free":
            return P / self.Ky
        sigma = 1.0 if name == "slip+" else -1.0
        return (P - self.Kxy / self.Kxx * sigma * self.cap(P)) / self.Ky

    def G(self, name, a):
        """G_b(a) = −δ(a) − D_b(P(a)) [µm]."""
        P = jkr.force_from_radius(a, self.R, self.w, self.E_star)
        return -jkr.overlap_from_radius(a, self.R, self.w, self.E_star) - self.deflection(name, P)

    def _G_dG(self, name, a):
        """G_b(a) [µm] and dG_b/da [-] together, sharing √a."""
        # jkr.branch_terms written out in the order of operations these tables were built
        # with (another order moves the inverted radii in their last bit); tests/test_formulas.py
        # pins it to jkr.branch_terms.
        R, w, Es = self.R, self.w, self.E_star
        k1, k2 = math.sqrt(8.0 * math.pi * w * Es), math.sqrt(2.0 * math.pi * w / Es)
        sa = np.sqrt(a)
        a2 = a * a
        P = (4.0 * Es / (3.0 * R)) * a2 * a - k1 * (a * sa)  # eq 7
        dP = (4.0 * Es / R) * a2 - (1.5 * k1) * sa
        G = k2 * sa - a2 / R  # −δ, eq 10
        dG = (0.5 * k2) / sa - (2.0 / R) * a
        if name == "stick":
            G -= P / self.Kyy_stick
            dG -= dP / self.Kyy_stick
        elif name == "free":
            G -= P / self.Ky
            dG -= dP / self.Ky
        else:
            q = self.Kxy / self.Kxx * (1.0 if name == "slip+" else -1.0)
            G -= (P - q * self.cap(P)) / self.Ky
            dcap = friction_cap_slope(P, self.Fc, self.mu, self.law == "paper")
            dG -= (1.0 - q * dcap) / self.Ky * dP
        return G, dG

    def invert(self, name, target):
        """Contact radius on branch b with G_b(a) = target, NaN where none exists [µm]."""
        a_tab, G_tab = self.a_grid[name], self.G_grid[name]
        target = np.asarray(target, dtype=float)
        if np.any(target < G_tab[-1]):
            raise ValueError(
                "a seta is compressed beyond the tabulated range "
                f"(G = {target.min():.3g} µm); the plate went implausibly deep"
            )
        a = np.interp(target, G_tab[::-1], a_tab[::-1])
        a_f = self.a_fold[name]
        for _ in range(2):  # Newton polish of the interpolated start; G' < 0 above the fold
            G, slope = self._G_dG(name, a)
            ok = slope < 0
            if ok.all():
                a = np.maximum(a - (G - target) / slope, a_f)
            else:
                a = np.where(ok, np.maximum(a - (G - target) / np.where(ok, slope, -1.0), a_f), a)
        return np.where(target <= G_tab[0], a, np.nan)


def retract_travel(params: SetaArray, br: Branches, heights, Z_from: float) -> float:
    """Plate travel up from Z_from [µm] after which every seta has surely let go [µm].

    Back past the start height, plus the stretch of the softest branch holding Fc.
    """
    k_soft = min(br.Ky / (1 + abs(br.Kxy / br.Kxx) * br.mu), br.Kyy)
    return (
        plate_start_height(params, heights, 0.0)
        - Z_from
        + 1.5 * params.contact.pull_off_force / k_soft
        + 20 * abs(params.contact.snap_off_overlap)
    )
