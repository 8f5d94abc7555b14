"""The branched seta: N spatula films sharing the seta's load, :class:`SpatulaeTip`, and the
closed form of their steady peel, :func:`peel_force` and :func:`seta_pull_off`.

Units: µm, µN, MPa, µN/µm (= J/m²), pJ (:mod:`gecko_agents.contact`).
"""

from __future__ import annotations

import numpy as np

from gecko_agents.contact.spatula import (
    K_B,
    K_FC,
    K_FILM,
    K_HERTZ_P,
    K_HERTZ_U,
    K_KT,
    SpatulaTip,
)
from gecko_agents.physics import jkr

__all__ = ["SpatulaeTip", "attached_fraction", "peel_force", "seta_pull_off"]

# The constants that add over N films in parallel (each film's own, times N): the films'
# total width N·b, stiffness N·E_f·h·b, 90° peel force N·w·b, and the tip bodies' Hertz
# constants and stick spring. Everything per width (w, the strains, g) is unchanged.
EXTENSIVE = (K_B, K_FILM, K_FC, K_HERTZ_P, K_HERTZ_U, K_KT)


def peel_force(phi, w: float, b: float, E_f: float, h: float, pretension: float = 0.0):
    """Steady peel force [µN] of one film of width b [µm], thickness h [µm], modulus E_f
    [MPa] and work of adhesion w [µN/µm] at peel angle φ [rad] from the floor, with a locked
    pre-tension P0 [µN] of the attached film: the root F of Chen, Wu & Gao's energy balance
    F(1 − cos φ) + (F − P0)²/(2E_f·h·b) = w·b (2009, J R Soc Interface 6:529, eq 2.4 per
    width; P0 = 0 is Kendall 1975, J Phys D 8:1449, eq 4), the root that is positive.

    With K = E_f·h·b and c = 1 − cos φ the balance is the quadratic
    F² + 2(cK − P0)F + P0² − 2K·w·b = 0; its larger root is returned (inextensible limit
    K → ∞: w·b/(1 − cos φ))."""
    phi = np.asarray(phi, dtype=float)
    K = E_f * h * b
    c = 1.0 - np.cos(phi)
    B = c * K - pretension
    C = pretension * pretension - 2.0 * K * w * b
    root = np.sqrt(B * B - C)
    # −B + √(B² − C), written as −C/(B + √(B² − C)) where B > 0 (no cancellation for stiff films)
    return np.where(B > 0.0, -C / np.where(B > 0.0, B + root, 1.0), root - B)


def seta_pull_off(count: int, phi, w: float, b: float, E_f: float, h: float):
    """Pull-off of a branched seta whose ``count`` identical spatulae share the load equally
    and peel together at angle φ [rad]: (normal, shear) components of N·F_peel [µN]
    (:func:`peel_force`, no pre-tension), normal = N·F·sin φ, shear = N·F·cos φ. The oracle of
    :class:`SpatulaeTip`; Tian et al. (2006, PNAS 103:19320) read a spatula's pull as its
    normal (adhesion) and lateral (friction) parts the same way."""
    F = count * peel_force(phi, w, b, E_f, h)
    return F * np.sin(phi), F * np.cos(phi)


class SpatulaeTip(SpatulaTip):
    """N identical spatula films on rigid branches that share the seta's load equally: each
    is the package's film (:class:`gecko_agents.contact.SpatulaTip`: Kendall's peel with the
    pad's pre-tension, the tip body's Hertz compression and friction), and all N hang from the
    seta's tip and lie in one state, so the law is the film's with every extensive constant
    times N (``EXTENSIVE``) and the state's pre-tension P0 the N films' total.

    Why this is exact: the film's energy release rate per width g (Kendall 1975, J Phys D
    8:1449, eq 4; Chen, Wu & Gao 2009, J R Soc Interface 6:529) depends on the force per width
    F/b, the strain F/(E_f·h·b) and the pre-strain P0/(E_f·h·b) alone, which N films carrying
    N·F, N·P0 over the width N·b share; the pad's friction cap (∝ w·b), the surface energy, the
    tip bodies' Hertz compression and stick spring are sums over the N films. So the N films
    peel, slide and let go as one film does, with N times its forces and energies: the closed
    form :func:`seta_pull_off`. N = 1 is the ``"spatula"`` tip, constant for constant.

    The branches' compliance is left out (rigid branches): for equal sharing it sets the
    travel to pull-off, not the force, since the steady peel force depends on the angle alone
    and a spring in series changes neither (Kendall 1975).

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (the spatula body's radius R [µm], E* [MPa],
        w [µN/µm]).
    spatula : :class:`gecko_agents.params.Spatula` (one film: b, h, length [µm], E_f [MPa]).
    spatulae : :class:`gecko_agents.params.spatulae.Spatulae` (N).
    friction : :class:`gecko_agents.params.Friction` (μ, law).
    """

    name = "spatulae"

    def __init__(self, contact, spatula, spatulae, friction):
        super().__init__(contact, spatula, friction)
        self.single = SpatulaTip(contact, spatula, friction)
        n = float(spatulae.count)
        self.count = int(spatulae.count)
        for i in EXTENSIVE:
            self.constants[i] = n * self.single.constants[i]
        one = self.single
        self.K = n * one.K
        self.pull_off_force = n * one.pull_off_force
        self.tip_stiffness = n * one.tip_stiffness
        self.tangential_stiffness = n * one.tangential_stiffness
        self.zero_load_stiffness = n * one.zero_load_stiffness

    def stiffest(self, load: float) -> float:
        """N tip bodies sharing a compressive load [µN]: N times one body's Hertz stiffness at
        load/N [µN/µm]."""
        n = float(self.count)
        return n * 2 * self.E_star * float(jkr.hertz_contact_radius(load / n, self.R, self.E_star))

    def stiffness(self, a, delta):
        """N times one film's normal stiffness bound (:meth:`SpatulaTip.stiffness`) [µN/µm]."""
        return self.count * self.single.stiffness(a, delta)

    def jacobian(self, dx, delta, s0, xa, ell=None, p0=None):
        """N times one film's tangent (:meth:`SpatulaTip.jacobian`) at the state of one film:
        the pre-tension per film P0/N [µN]."""
        n = float(self.count)
        one = self.single.jacobian(dx, delta, s0, xa, ell, None if p0 is None else p0 / n)
        return tuple(n * k for k in one)


def attached_fraction(ell, ell0: float) -> np.ndarray:
    """Fraction of the spatulae's pad length still attached, ℓ/ℓ0 [-] (state ``a`` of the
    film law over its length at first contact), 0 for a free tip (NaN in a history)."""
    f = np.asarray(ell, dtype=float) / ell0
    return np.where(np.isfinite(f), np.clip(f, 0.0, 1.0), 0.0)
