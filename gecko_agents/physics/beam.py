"""Stiffness of one inclined seta: a cantilever rod (paper eq 16–21).

Plain vectorized functions, valid in any consistent unit set (µm, MPa → µN/µm in gecko_agents).
``r`` is the rod **radius** (the paper's text says diameter, its formulas need the radius:
docs/physics.md, "Typos and readings"). θ is the angle between the seta and the backing plate,
in radians.

The seta axis points from root to tip along n = (cos θ, −sin θ) (x along the plate, y up).
Ka acts along n, Kp across it; the tip's 2×2 stiffness is K = Ka·n nᵀ + Kp·t tᵀ.
Eq 20 and eq 21 are the inverse diagonal compliances of that matrix: the stiffness felt when
a force acts along y (or x) and the tip is free to move in the other direction.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "axial_stiffness",
    "bending_stiffness",
    "longitudinal_stiffness",
    "transverse_stiffness",
    "stiffness_matrix",
    "deflection_ratio",
    "rest_tip_offset",
    "touchdown_height",
]


def axial_stiffness(r, L, E):
    """Axial stiffness Ka = πr²E/L (eq 17) [force/length].

    Parameters
    ----------
    r : rod radius [length]. L : rod length [length]. E : Young's modulus [force/length²].
    """
    return np.pi * np.square(r) * E / L


def bending_stiffness(r, L, E):
    """Tip bending stiffness of a cantilever Kp = 3EI/L³ = 3πr⁴E/(4L³) (eq 18–19) [force/length].

    Parameters
    ----------
    r : rod radius [length]. L : rod length [length]. E : Young's modulus [force/length²].
    """
    return 3.0 * np.pi * np.power(r, 4) * E / (4.0 * np.power(L, 3))


def longitudinal_stiffness(Ka, Kp, theta):
    """Stiffness normal to the plate Ky = KpKa/(Kp sin²θ + Ka cos²θ) (eq 20) [force/length].

    Parameters
    ----------
    Ka, Kp : axial and bending stiffness [force/length]. theta : seta angle to the plate [rad].
    """
    s2, c2 = np.sin(theta) ** 2, np.cos(theta) ** 2
    return Kp * Ka / (Kp * s2 + Ka * c2)


def transverse_stiffness(Ka, Kp, theta):
    """Stiffness along the plate Kx = KpKa/(Kp cos²θ + Ka sin²θ) (eq 21) [force/length].

    Parameters
    ----------
    Ka, Kp : axial and bending stiffness [force/length]. theta : seta angle to the plate [rad].
    """
    s2, c2 = np.sin(theta) ** 2, np.cos(theta) ** 2
    return Kp * Ka / (Kp * c2 + Ka * s2)


def stiffness_matrix(Ka, Kp, theta):
    """Tip stiffness matrix K = Ka·n nᵀ + Kp·t tᵀ [force/length], n = (cos θ, −sin θ).

    Returns ``[[Kxx, Kxy], [Kxy, Kyy]]``; the spring force on the tip is −K·(tip − rest).
    Its inverse diagonal gives eq 21 (1/C_xx) and eq 20 (1/C_yy).
    """
    c, s = np.cos(theta), np.sin(theta)
    kxx = Ka * c * c + Kp * s * s
    kyy = Ka * s * s + Kp * c * c
    kxy = -(Ka - Kp) * c * s
    return np.array([[kxx, kxy], [kxy, kyy]])


def deflection_ratio(force, Ka, Kp, theta, L, direction=(0.0, 1.0)):
    """How far a tip force takes the seta, relative to its length, under the linear model [-].

    ``|K⁻¹·F| / L`` for a force of magnitude ``force`` along ``direction`` (default: normal to
    the plate). The linear beam model (eq 16–21) is a small-deflection theory: values above
    ~0.1 mean it is outside its validity (docs/physics.md, "Seta mechanics": the paper's seta
    needs 9–27 L to hold Fc).

    Parameters
    ----------
    force : tip force magnitude [force]. Ka, Kp [force/length]. theta [rad]. L [length].
    direction : 2-vector, need not be normalised.
    """
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    K = stiffness_matrix(Ka, Kp, theta)
    disp = np.linalg.solve(K, d) * np.asarray(force, dtype=float)[..., None]
    return np.linalg.norm(disp, axis=-1) / L


def rest_tip_offset(L, theta):
    """Resting tip position relative to the seta's root: (L cos θ, −L sin θ) [length].

    The unloaded seta is the straight rod of eq 16–21 leaning from its root on the backing
    plate towards +x and down to the floor, at the angle θ to the plate (x along the plate,
    y up): the rest direction n = (cos θ, −sin θ) of :func:`stiffness_matrix`. ``L = 1`` gives
    n itself. A resting tip of radius R touches the floor's mean plane y = 0 when the plate is
    at height R + L sin θ (the touch-down height of the pressing displacement d).

    Parameters
    ----------
    L : seta length [length]. theta : seta angle to the plate [rad]. Arrays broadcast.

    Returns
    -------
    (dx, dy) : the offsets along x (> 0) and y (< 0 for 0 < θ < π) [length].
    """
    return L * np.cos(theta), -L * np.sin(theta)


def touchdown_height(L, theta, R):
    """Plate height at which a resting tip of radius R touches the floor's mean plane y = 0:
    R + L sin θ [length] (the resting tip centre sits :func:`rest_tip_offset` below its root,
    which the plate carries, and touches y = 0 at y = R). The reference of the pressing
    displacement d = R + L sin θ − plate height.

    Parameters
    ----------
    L : seta length [length]. theta : seta angle to the plate [rad]. R : tip radius [length].
    Arrays broadcast.
    """
    return R - rest_tip_offset(L, theta)[1]


def linear_spring_force(u, K):
    """Force on the tip of a linear seta and its elastic energy (eq 20–21): F = −K·u, E = ½u·K·u.

    Parameters
    ----------
    u : tip displacements from rest, shape (N, 2) [length]. K : the 2×2 stiffness of
    :func:`stiffness_matrix` [force/length].

    Returns
    -------
    F (N, 2) [force], energy (N,) [force·length].
    """
    Fx, Fy, energy = _linear_parts(u[:, 0], u[:, 1], K)
    return np.column_stack([Fx, Fy]), energy


def linear_spring_energy(ux, uy, K):
    """The elastic energy (N,) [force·length] of :func:`linear_spring_force` alone (the same
    arithmetic), from the tip displacements' components ``ux``, ``uy`` (N,) [length]."""
    return _linear_parts(ux, uy, K)[2]


def _linear_parts(ux, uy, K):
    """F = −K·u by component and E = ½u·K·u = −½u·F (eq 20–21), written out (no BLAS call
    per record); ``ux``, ``uy`` [length], ``K`` [force/length]."""
    Fx = -(ux * K[0, 0] + uy * K[0, 1])
    Fy = -(ux * K[1, 0] + uy * K[1, 1])
    return Fx, Fy, -0.5 * (ux * Fx + uy * Fy)


def rod_spring_force(d, L, Ka, k_phi, theta):
    """Force on the tip of a seta modelled as a rigid rod on a rotary spring plus an axial
    spring, and its elastic energy (large rotation; docs/physics.md, "Rod mechanics").

    With ℓ = |d| the rod length, Δφ its rotation from rest (angle −θ to +x), e = d/ℓ and
    e⊥ = (−e_y, e_x): F = −Ka(ℓ − L)·e − (kφ·Δφ/ℓ)·e⊥, E = ½Ka(ℓ − L)² + ½kφ·Δφ². With
    kφ = Kp·L² this has eq 20–21's stiffness at small deflection.

    Parameters
    ----------
    d : root-to-tip vectors, shape (N, 2) [length]. L : rest length [length]. Ka : axial
    stiffness (eq 17) [force/length]. k_phi : rotary stiffness Kp·L² [force·length/rad²].
    theta : rest angle to the plate [rad].

    Returns
    -------
    F (N, 2) [force], energy (N,) [force·length].
    """
    ell, dphi = _rod_coordinates(d[:, 0], d[:, 1], theta)
    e = d / ell[:, None]
    e_perp = np.column_stack([-e[:, 1], e[:, 0]])
    F = (-Ka * (ell - L))[:, None] * e - (k_phi * dphi / ell)[:, None] * e_perp
    return F, _rod_energy(ell, dphi, L, Ka, k_phi)


def rod_spring_energy(dx, dy, L, Ka, k_phi, theta):
    """The elastic energy (N,) [force·length] of :func:`rod_spring_force` alone (the same
    arithmetic), from the root-to-tip vectors' components ``dx``, ``dy`` (N,) [length]; the
    other parameters as there."""
    ell, dphi = _rod_coordinates(dx, dy, theta)
    return _rod_energy(ell, dphi, L, Ka, k_phi)


def _rod_coordinates(dx, dy, theta):
    """The rod's length ℓ = |d| [length] and rotation from rest Δφ ∈ [−π, π) [rad]
    (:func:`rod_spring_force`)."""
    ell = np.hypot(dx, dy)
    dphi = np.arctan2(dy, dx) + theta
    dphi = (dphi + math.pi) % (2 * math.pi) - math.pi
    return ell, dphi


def _rod_energy(ell, dphi, L, Ka, k_phi):
    """E = ½Ka(ℓ − L)² + ½kφ·Δφ² [force·length] (:func:`rod_spring_force`)."""
    return 0.5 * Ka * (ell - L) ** 2 + 0.5 * k_phi * dphi**2
