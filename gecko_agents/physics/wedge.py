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
determinant, analytic in λ. Its roots are real or come in complex pairs λ = ξ ± iη; an
obtuse bonded corner of a compressible body has complex ones (120°, ν = 0.1: 0.800 ± 0.133i;
the bonded half-plane, 180°, is the crack on a rigid floor, λ = ½ ± i·ln(3 − 4ν)/(2π),
Williams 1959, Bull Seismol Soc Am 49:199, as restated in Suo's notes *Interfacial
Fracture*, Harvard ES 247, read at studylib.net), and the stress then goes as r^(ξ−1) times
an oscillation in ln r (Sinclair 2004, Appl Mech Rev, doi 10.1115/1.1767846, abstract read:
"power singularities with both real and complex exponents"). Real roots are found by
bracketing and Brent's method, complex ones by the secant method from starts across the
strip 0 < Re λ < 1 (scipy). Checks in ``tests/test_tips.py`` and
``tests/test_wedge_roots.py``: the bonded incompressible 90° corner has λ = 0.5946 (r^−0.405,
the exponent of Tang et al.'s 2005 fit, and the value the literature notes quote), 45° is not
singular (Aksak, Şahin & Sitti 2014, Beilstein J Nanotechnol 5:630, full friction, ν = 0.5),
a frictionless floor is not singular up to 90° (the same paper), and a 180° wedge on a
frictionless floor is the edge of a flat punch on a half-space, λ = 1/2 (Kendall's crack).
"""

from __future__ import annotations

import functools
import math
import warnings

import numpy as np
from scipy.linalg import expm
from scipy.optimize import brentq, newton

__all__ = ["corner_eigenvalue", "singularity_exponent", "NOT_SINGULAR"]

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


def _determinant(lam, alpha: float, nu: float, floor: str):
    """det of the free face's tractions over the two starts the floor allows: a float for a
    real λ, a complex number for a complex one."""
    P = expm(_state_matrix(lam, nu) * alpha)
    start = (2, 3) if floor == "bonded" else (0, 2)  # free (S, T) or free (f, S)
    det = np.linalg.det(P[np.ix_((2, 3), start)])
    return complex(det) if np.iscomplexobj(det) else float(det)


# Starts of the complex search across the strip 0 < Re λ < 1 (the roots found so far lie at
# |Im λ| < 0.3: the rigid-floor crack's ln(3)/(2π) = 0.175 is the largest at ν = 0).
_STARTS = [complex(x, y) for x in np.linspace(0.05, 0.95, 7) for y in (0.1, 0.4)]
_IMAG = 1e-7  # |Im λ| below which a root is taken as real [-]


def _complex_roots(alpha: float, nu: float, floor: str) -> list[complex]:
    """Roots of the determinant in 0 < Re λ < 1 reached by the secant method from
    :data:`_STARTS` (scipy.optimize.newton on the complex determinant), each checked: a
    residual below 1e-9 of the determinant at its start (a thin wedge's determinant is
    nearly constant, where the secant method stops at its start)."""
    args = (alpha, nu, floor)
    found = []
    for z0 in _STARTS:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            try:
                z = newton(_determinant, z0, args=args, tol=1e-13, maxiter=100, disp=False)
            except (OverflowError, ValueError, ZeroDivisionError):
                continue
        z = complex(z)
        if not (1e-3 < z.real < 1.0 - 1e-6) or not math.isfinite(abs(z)):  # λ = 1: bounded
            continue
        if abs(_determinant(z, *args)) <= 1e-9 * abs(_determinant(z0, *args)):
            found.append(complex(z.real, abs(z.imag)))
    return found


@functools.lru_cache(maxsize=256)
def _eigenvalue(angle_deg: float, nu: float, floor: str) -> complex:
    alpha = math.radians(angle_deg)
    grid = np.linspace(1e-3, 1.0 - 1e-9, 400)
    det = np.array([_determinant(x, alpha, nu, floor) for x in grid])
    real = None
    for i in np.flatnonzero(np.sign(det[:-1]) * np.sign(det[1:]) < 0):
        real = complex(
            brentq(_determinant, grid[i], grid[i + 1], args=(alpha, nu, floor), xtol=1e-13)
        )
        break
    # Complex pairs, and real double roots (no sign change) where no real root was bracketed.
    others = [z for z in _complex_roots(alpha, nu, floor) if z.imag > _IMAG or real is None]
    roots = ([real] if real is not None else []) + others
    if not roots:
        return complex(NOT_SINGULAR)
    root = min(roots, key=lambda z: (z.real, z.imag))
    return complex(root.real, 0.0) if root.imag <= _IMAG else root


def _check(angle_deg, nu, floor) -> None:
    if not 0.0 < angle_deg <= 180.0:
        raise ValueError(f"angle_deg = {angle_deg!r} is outside the allowed range (0, 180]")
    if not 0.0 <= nu <= 0.5:
        raise ValueError(f"nu = {nu!r} is outside the allowed range [0, 0.5]")
    if floor not in _FLOORS:
        raise ValueError(f"floor = {floor!r} must be one of {_FLOORS}")


def corner_eigenvalue(angle_deg, nu: float = 0.5, floor: str = "bonded") -> complex:
    """The root λ of the corner's eigenproblem (module docstring) with the smallest real
    part in (0, 1), real or one of a complex pair (the one with Im λ ≥ 0) [-]: the
    displacements near the rim go as r^λ, the stresses' magnitude as r^(Re λ − 1);
    ``complex(NOT_SINGULAR)`` where there is none (bounded stress).

    Parameters are those of :func:`singularity_exponent`.
    """
    _check(angle_deg, nu, floor)
    return _eigenvalue(float(angle_deg), float(nu), floor)


def singularity_exponent(angle_deg, nu: float = 0.5, floor: str = "bonded") -> float:
    """Re λ of :func:`corner_eigenvalue` [-]: the stress near the rim goes as r^(Re λ − 1)
    (times an oscillation in ln r where λ is complex); :data:`NOT_SINGULAR` (1.0) where no
    root lies in (0, 1).

    Parameters
    ----------
    angle_deg : wedge (rim) angle α between the floor and the free face [degrees], in
        (0, 180]; 90 is a flat-ended cylinder's corner.
    nu : Poisson's ratio ν of the body [-], in [0, 0.5].
    floor : ``"bonded"`` (full friction: the face cannot move on the floor) or
        ``"frictionless"`` (it slides, no shear).
    """
    return corner_eigenvalue(angle_deg, nu, floor).real
