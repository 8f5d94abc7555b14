"""Tip compliance of a seta whose shaft is a circular arc (rest curvature), clamped at its root:
the curved counterpart of the straight rod's eq 16–21 (:mod:`gecko_agents.physics.beam`).

By Castigliano's theorem (the complementary energy of a linear elastic rod,
U = ∫ M²/(2EI) + N²/(2EA) ds; Young & Budynas 2002, Roark's Formulas for Stress and Strain,
7th ed., McGraw-Hill, ch. 9, curved beams) its tip compliance under a tip force F is
C_ij = ∫₀ᴸ [m_i(s) m_j(s)/EI + t_i(s) t_j(s)/EA] ds, where the moment of a
unit tip force along axis j at arc length s is m(s) = (−(y_t − y(s)), x_t − x(s)) (the z part
of (r_t − r)×F) and the axial force is its projection on the tangent t(s). Shear compliance is
neglected (slender rods, L ≫ r). Straight (no turn) it is exactly the rod of eq 16–21:
1/K_p = L³/(3EI) across the shaft and 1/K_a = L/(EA) along it. Curved, no direction loads the
shaft purely axially, so no direction is as stiff as a straight shaft loaded along its axis.

Geometry (x along the backing towards the lean, y up, the root at the origin): the shaft's
chord leans at θ below the backing, as the straight rod's n = (cos θ, −sin θ); its tangent
turns uniformly by ``turn`` from root to tip, symmetric about the chord (tangent angle
−θ − turn/2 at the root, −θ + turn/2 at the tip; turn > 0 turns it anticlockwise). The arc
length is L, the chord L·sinc(turn/2).

Units: lengths µm, EI µN·µm², EA µN; compliance µm/µN (stiffness µN/µm = N/m).
"""

from __future__ import annotations

import numpy as np

__all__ = ["arc_points", "curved_rod_compliance"]

_NODES = 64
"""Gauss–Legendre points along the shaft: the integrands are smooth (trigonometric in s), so 64
points integrate them to machine precision for any turn up to a full circle."""


def arc_points(L: float, theta: float, turn: float, s) -> tuple[np.ndarray, np.ndarray]:
    """Positions (x, y) [µm] at arc lengths ``s`` [µm] of the shaft (module docstring):
    x + iy = s·sinc(κs/2)·exp(i(φ₀ + κs/2)), κ = turn/L, φ₀ = −θ − turn/2 (exact for an arc,
    the straight rod at turn = 0).

    Parameters
    ----------
    L : arc length [µm]. theta : chord angle below the backing [rad]. turn : total turn of the
        tangent [rad]. s : arc lengths [µm].
    """
    s = np.asarray(s, dtype=float)
    kappa, phi0 = turn / L, -theta - 0.5 * turn
    chord = s * np.sinc(kappa * s / (2.0 * np.pi))  # numpy's sinc is sin(πx)/(πx)
    angle = phi0 + 0.5 * kappa * s
    return chord * np.cos(angle), chord * np.sin(angle)


def curved_rod_compliance(L: float, EI: float, EA: float, theta: float, turn: float) -> np.ndarray:
    """The 2×2 tip compliance [µm/µN] of a clamped circular-arc shaft (module docstring).

    Parameters
    ----------
    L : arc length [µm], > 0. EI : bending stiffness [µN·µm²], > 0. EA : axial stiffness
        [µN], > 0. theta : chord angle below the backing [rad]. turn : total turn of the
        tangent from root to tip [rad], |turn| < 2π.
    """
    for name, value in (("L", L), ("EI", EI), ("EA", EA)):
        if not value > 0:
            raise ValueError(f"curved_rod_compliance: {name} = {value!r} must be > 0")
    if not abs(turn) < 2.0 * np.pi:
        raise ValueError(f"curved_rod_compliance: turn = {turn!r} rad must lie in (−2π, 2π)")
    u, w = np.polynomial.legendre.leggauss(_NODES)
    s, ds = 0.5 * L * (u + 1.0), 0.5 * L * w
    x, y = arc_points(L, theta, turn, s)
    xt, yt = arc_points(L, theta, turn, np.array([L]))
    m = np.stack([-(yt - y), xt - x])  # moment of a unit tip force along x, y
    phi = -theta - 0.5 * turn + turn * s / L
    t = np.stack([np.cos(phi), np.sin(phi)])  # axial force of a unit tip force along x, y
    return (m * ds) @ m.T / EI + (t * ds) @ t.T / EA
