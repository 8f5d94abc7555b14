"""The stress singularity at the rim of a flat face bonded to a rigid floor: the eigenproblem of
an elastic wedge (Williams 1952, J Appl Mech 19:526; Bogy 1971, J Appl Mech 38:377).

Near the corner where a face of a compliant body meets the floor, plane strain holds and the
displacements go as u = r^λ·(f(θ), g(θ)) (radial, tangential), the stresses as r^(λ−1): a
corner is singular where the smallest root λ of the wedge's eigenproblem has 0 < λ < 1 (a
crack's λ = 1/2). The wedge of angle α lies between the floor, θ = 0, and its free face,
θ = α; the floor holds it bonded (u = 0, full friction) or lets it slide (u_θ = 0, no shear).

Solved here directly, not read from a table: with u = r^λ(f, g), Hooke's law in plane strain
and the two equilibrium equations, the state y = (f, g, S_θθ, S_rθ) (the traction on a ray
over r^(λ−1)) obeys a linear ODE y′ = M(λ, ν)·y (``_state_matrix``); the free face asks
the traction at θ = α to vanish for a nonzero start satisfying the floor's condition, a 2 × 2
determinant whose roots in λ are found by bracketing and Brent's method (scipy). Checks in
``tests/test_tips.py``: the bonded incompressible 90° corner has λ = 0.5946 (r^−0.405, the
exponent of Tang et al.'s 2005 fit, and the value the literature notes quote), 45° is not
singular (Aksak, Şahin & Sitti 2014, Beilstein J Nanotechnol 5:630, full friction, ν = 0.5),
a frictionless floor is not singular up to 90° (the same paper), and a 180° wedge on a
frictionless floor is the edge of a flat punch on a half-space, λ = 1/2 (Kendall's crack).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import expm
from scipy.optimize import brentq

__all__ = ["singularity_exponent", "NOT_SINGULAR"]

NOT_SINGULAR = 1.0
"""What :func:`singularity_exponent` returns for a corner with no root in (0, 1): bounded stress."""

_FLOORS = ("bonded", "frictionless")


def _state_matrix(lam: float, nu: float) -> np.ndarray:
    """M of y′ = M·y for y = (f, g, S_θθ, S_rθ), shear modulus 1 (the eigenvalues do not
    depend on it). From ε_rr = λf, ε_θθ = f + g′, γ_rθ = f′ + (λ − 1)g (over r^(λ−1)),
    S_θθ = 2(1−ν)/(1−2ν)·(ε_θθ + ν/(1−ν)·ε_rr) written for g′ (finite at ν = 1/2),
    S_rθ = γ_rθ, S_rr − S_θθ = 2(ε_rr − ε_θθ), and equilibrium
    λS_rr + S_rθ′ − S_θθ = 0, (λ + 1)S_rθ + S_θθ′ = 0."""
    c = (1.0 - 2.0 * nu) / (2.0 * (1.0 - nu))  # 1/(Λ + 2μ) at μ = 1
    b = nu / (1.0 - nu)  # Λ/(Λ + 2μ)
    # g′ = c·S − (bλ + 1)f ; f′ = T − (λ − 1)g
    gp = np.array([-(b * lam + 1.0), 0.0, c, 0.0])
    fp = np.array([0.0, -(lam - 1.0), 0.0, 1.0])
    # S_rr = S + 2(λf − f − g′) ; S_rθ′ = S − λ·S_rr ; S′ = −(λ + 1)T
    srr = np.array([2.0 * (lam - 1.0), 0.0, 1.0, 0.0]) - 2.0 * gp
    tp = np.array([0.0, 0.0, 1.0, 0.0]) - lam * srr
    sp = np.array([0.0, 0.0, 0.0, -(lam + 1.0)])
    return np.vstack([fp, gp, sp, tp])


def _determinant(lam: float, alpha: float, nu: float, floor: str) -> float:
    """det of the free face's tractions over the two starts the floor allows."""
    P = expm(_state_matrix(lam, nu) * alpha)
    start = (2, 3) if floor == "bonded" else (0, 2)  # free (S, T) or free (f, S)
    return float(np.linalg.det(P[np.ix_((2, 3), start)]))


def singularity_exponent(angle_deg, nu: float = 0.5, floor: str = "bonded") -> float:
    """Smallest root λ in (0, 1) of the corner's eigenproblem (module docstring) [-]: the
    stress near the rim goes as r^(λ−1); :data:`NOT_SINGULAR` (1.0) where there is none.

    Roots where the determinant changes sign only: the oscillating (complex) roots a
    compressible wedge has near 180° and a double root (the bonded half-plane at ν = 1/2,
    λ = 1/2) are not found; rim angles of a tip (up to 135°) have simple real roots.

    Parameters
    ----------
    angle_deg : wedge (rim) angle α between the floor and the free face [degrees], in
        (0, 180]; 90 is a flat-ended cylinder's corner.
    nu : Poisson's ratio ν of the body [-], in [0, 0.5].
    floor : ``"bonded"`` (full friction: the face cannot move on the floor) or
        ``"frictionless"`` (it slides, no shear).
    """
    if not 0.0 < angle_deg <= 180.0:
        raise ValueError(f"angle_deg = {angle_deg!r} is outside the allowed range (0, 180]")
    if not 0.0 <= nu <= 0.5:
        raise ValueError(f"nu = {nu!r} is outside the allowed range [0, 0.5]")
    if floor not in _FLOORS:
        raise ValueError(f"floor = {floor!r} must be one of {_FLOORS}")
    alpha = math.radians(angle_deg)
    grid = np.linspace(1e-3, 1.0 - 1e-9, 400)
    det = np.array([_determinant(x, alpha, nu, floor) for x in grid])
    for i in np.flatnonzero(np.sign(det[:-1]) * np.sign(det[1:]) < 0):
        return float(
            brentq(_determinant, grid[i], grid[i + 1], args=(alpha, nu, floor), xtol=1e-13)
        )
    return NOT_SINGULAR
