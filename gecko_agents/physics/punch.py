"""Adhesion of a flat-ended cylindrical punch on an elastic half-space (the flat-tipped pillar).

Plain vectorized functions valid in any consistent unit set (µm, µN, MPa = µN/µm², µN/µm for
the work of adhesion in gecko_agents). Sign convention as in :mod:`gecko_agents.physics.jkr`:
overlap δ > 0 pressed in, normal force P > 0 compressive, P < 0 adhesive.

A rigid flat punch of radius a pressed a depth δ into a half-space of effective modulus E*
carries P = 2E*aδ whatever the sign of δ while its whole face stays bonded (Sneddon 1965, Int J
Eng Sci 3:47, the flat-ended cylinder).
The traction under it is singular at the edge, p(r) = P/(2πa√(a² − r²)), so the edge is a crack
tip; its energy release rate G = P²/(8πa³E*) reaches the work of adhesion w at Kendall's
pull-off P = −√(8πE*wa³) (Kendall 1971, J Phys D 4:1186). The face being flat, the
contact radius cannot shrink stably: G at fixed δ, E*δ²/(2πa), grows as a falls, so the punch
lets go at once under load or displacement control.

A punch whose face carries a moment M as well (the pillar's end turned by a lateral load or a
misaligned floor) is :func:`tilted_punch_pressure` to :func:`lateral_load_moment`: the edge on
the side the moment lifts opens first, and the pull-off falls linearly with the moment. What is
derived here and what is cited is said in each function; ``tests/test_punch_tilt.py`` checks
every step against an independent numerical integral.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "punch_stiffness",
    "punch_force",
    "punch_energy",
    "kendall_pull_off",
    "kendall_detach_overlap",
    "edge_release_rate",
    "punch_rotation_stiffness",
    "tilted_punch_pressure",
    "plane_punch_pressure",
    "edge_stress_intensity",
    "tilted_pull_off",
    "tilt_pull_off",
    "lateral_load_moment",
]


def punch_stiffness(a, E_star):
    """Normal stiffness of a bonded flat punch dP/dδ = 2E*a (Sneddon 1965, Int J Eng Sci 3:47)
    [force/length].

    Parameters
    ----------
    a : punch radius [length]. E_star : effective modulus E* [force/length²].
    """
    return 2.0 * np.multiply(E_star, a)


def punch_force(delta, a, E_star):
    """Normal force P = 2E*aδ of a bonded flat punch at overlap δ [force] (positive compressive;
    δ < 0 pulls on the bond).

    Parameters
    ----------
    delta : overlap δ [length]. a : punch radius [length]. E_star : E* [force/length²].
    """
    return punch_stiffness(a, E_star) * delta


def punch_energy(delta, a, E_star):
    """Elastic energy of a bonded flat punch U = E*aδ² = ∫P dδ from δ = 0 [force·length].

    Parameters
    ----------
    delta : overlap δ [length]. a : punch radius [length]. E_star : E* [force/length²].
    """
    return np.multiply(E_star, a) * np.square(delta)


def kendall_pull_off(a, w, E_star):
    """Pull-off force magnitude of a flat punch F = √(8πE*wa³) (Kendall 1971, J Phys D 4:1186,
    [force].

    Parameters
    ----------
    a : punch radius [length]. w : work of adhesion [force/length]. E_star : E*
    [force/length²].
    """
    return np.sqrt(8.0 * np.pi * np.multiply(E_star, w) * np.power(a, 3))


def kendall_detach_overlap(a, w, E_star):
    """Overlap at which a flat punch lets go, δ = −F/(2E*a) = −√(2πwa/E*) [length] (Kendall's
    pull-off :func:`kendall_pull_off` on Sneddon's stiffness :func:`punch_stiffness`).

    Parameters
    ----------
    a : punch radius [length]. w : work of adhesion [force/length]. E_star : E*
    [force/length²].
    """
    return -np.sqrt(2.0 * np.pi * np.multiply(w, a) / E_star)


def edge_release_rate(P, a, E_star):
    """Energy release rate at the punch edge G = P²/(8πa³E*) [force/length] (the edge
    singularity p ∝ 1/√(a² − r²) as a mode-I crack, Kendall 1971; G = w is the pull-off).

    Parameters
    ----------
    P : normal force [force]. a : punch radius [length]. E_star : E* [force/length²].
    """
    return np.square(P) / (8.0 * np.pi * np.power(a, 3) * E_star)


def punch_rotation_stiffness(a, E_star):
    """Rotational stiffness of a bonded flat punch k_r = M/α = 4E*a³/3 [force·length/rad]
    (M the moment on the face, α its small tilt).

    Derived here, not read in a text: the pressure of :func:`tilted_punch_pressure`'s moment
    term, p = 3Mx/(2πa³√(a² − r²)), put into Boussinesq's surface displacement
    u(x) = (1/πE*)∫∫p(ξ)/|x − ξ| dA gives u = αx over the face with α = 3M/(4E*a³), a face that
    stays flat and turns rigidly; ``tests/test_punch_tilt.py`` evaluates that integral
    numerically at points across the face (its oracle). The result is the classical rocking
    stiffness of a rigid circular footing (Johnson, Contact Mechanics, 1985, ch. 5, was not
    read here; the numerical integral is the check relied on).

    Parameters
    ----------
    a : punch radius [length]. E_star : effective modulus E* [force/length²].
    """
    return 4.0 / 3.0 * np.multiply(E_star, np.power(a, 3))


def tilted_punch_pressure(r, theta, P, M, a):
    """Pressure under a bonded flat punch carrying a normal force P and a moment M
    [force/length²], compressive positive:
    p(r, θ) = P/(2πa√(a² − r²)) + 3M·r·cosθ/(2πa³√(a² − r²)).

    The first term is Sneddon's (1965, Int J Eng Sci 3:47; :func:`edge_release_rate`), the
    second the tilted face's (the field whose Boussinesq displacement is a rigid rotation,
    :func:`punch_rotation_stiffness`). They integrate to ∫p dA = P and ∫p·r·cosθ dA = M (the
    moment turns the face about the y axis, pressing harder at θ = 0); both are checked by
    numerical quadrature in ``tests/test_punch_tilt.py``. Linear superposition of the two holds
    while the whole face stays in contact.

    Parameters
    ----------
    r : radius from the face's centre, 0 ≤ r < a [length]. theta : azimuth from the direction
    the moment presses [rad]. P : normal force (> 0 compressive) [force]. M : moment [force·length].
    a : punch radius [length].
    """
    root = np.sqrt(np.square(a) - np.square(r))
    return (P + 3.0 * M * np.multiply(r, np.cos(theta)) / np.square(a)) / (2.0 * np.pi * a * root)


def plane_punch_pressure(x, a, P):
    """Pressure under a rigid flat punch of half-width a pressed into a half-space in plane
    strain by a force P per length [force/length²], compressive positive:
    p(x) = P/(π√(a² − x²)) for |x| < a, the classical plane punch problem (Johnson 1985,
    Contact Mechanics, ch. 2, line loading of a half-space; derived from the singular
    integral equation of the symmetric load in Wikiversity's "Introduction to
    Elasticity/Flat punch indentation"): the edge singularity of
    :func:`tilted_punch_pressure` on a strip. The oracle of load sharing through a thick
    backing layer (``tests/test_layer.py``).

    Parameters
    ----------
    x : abscissa from the face's centre, |x| < a [length]. a : half-width [length].
    P : normal force per length (> 0 compressive) [force/length].
    """
    return P / (np.pi * np.sqrt(np.square(a) - np.square(x)))


def edge_stress_intensity(P, M, a, theta=np.pi):
    """Opening stress-intensity factor at the punch edge K_I(θ) = −(P + 3M·cosθ/a)/(2a√(πa))
    [force/length^1.5] (> 0 where the edge is pulled open).

    Derived: near the edge, a − r = s ≪ a, :func:`tilted_punch_pressure` is
    p ≈ (P + 3M·cosθ/a)/(2πa·√(2as)); the tensile traction −p = K_I/√(2πs) of a mode-I crack
    tip gives K_I. With the release rate G = K_I²/(2E*) of Kendall's edge crack
    (:func:`edge_release_rate` is this at M = 0), the edge where the moment lifts (θ = π for
    M > 0) opens first. Checked against the pressure's own limit −p·√(2πs) and, averaged
    round the edge, against the compliance release rate of Sneddon's stiffness and
    :func:`punch_rotation_stiffness` (``tests/test_punch_tilt.py``).

    Parameters
    ----------
    P : normal force (> 0 compressive) [force]. M : moment [force·length]. a : punch radius
    [length]. theta : azimuth [rad]; default π, the edge a positive M opens.
    """
    return -(P + 3.0 * M * np.cos(theta) / a) / (2.0 * a * np.sqrt(np.pi * a))


def tilted_pull_off(a, w, E_star, M):
    """Pull-off force of a flat punch carrying a moment M: F = √(8πE*wa³) − 3|M|/a [force].

    Derived: Griffith at the most opened edge, K_I(π)²/(2E*) = w with
    :func:`edge_stress_intensity`, gives −P = √(8πE*wa³) − 3|M|/a: Kendall's pull-off
    (:func:`kendall_pull_off`, Kendall 1971, J Phys D 4:1186) exactly at M = 0, falling
    linearly with the moment. The edge crack, once it runs, is taken to run through the face as
    in the aligned punch (Kendall's instability); that is an assumption of this estimate, not a
    result. F ≤ 0 (|M| ≥ aF_K/3) means the edge opens before the punch is pulled at all: the
    full-contact solution no longer holds there, and this function returns the negative number
    rather than a guess at the partial contact.

    Parameters
    ----------
    a : punch radius [length]. w : work of adhesion [force/length]. E_star : E*
    [force/length²]. M : moment on the face [force·length].
    """
    return kendall_pull_off(a, w, E_star) - 3.0 * np.abs(M) / a


def tilt_pull_off(a, w, E_star, alpha):
    """Pull-off force of a flat punch whose face is held bonded at a tilt α to the floor [force]:
    :func:`tilted_pull_off` at M = k_r·α (:func:`punch_rotation_stiffness`), that is
    F = √(8πE*wa³) − 4E*a²|α|, zero at |α| = √(πw/(2E*a)). Derived here from the two.

    Parameters
    ----------
    a : punch radius [length]. w : work of adhesion [force/length]. E_star : E*
    [force/length²]. alpha : tilt of the face against the floor [rad].
    """
    return tilted_pull_off(a, w, E_star, punch_rotation_stiffness(a, E_star) * alpha)


def lateral_load_moment(Q, L, EI, k_r):
    """Moment on the bonded face of a pillar (root clamped, length L) under a lateral force Q
    at its end, the face's turn resisted by a rotary spring k_r [force·length]:
    M = (QL/2)/(1 + EI/(k_r·L)).

    Derived here from the Euler–Bernoulli cantilever: integrating EI·w″ = bending moment from
    the clamped root gives the end slope QL²/(2EI) under an end force Q and ML/(EI) under an
    end moment M; the face's turn QL²/(2EI) − ML/(EI) equals M/k_r. (No text was read for
    these two elementary slopes; ``tests/test_punch_tilt.py`` checks the rigid-face limit
    against the model's bar-chain elastica.) A rigidly held face
    (k_r → ∞, the elastica's clamp) carries QL/2, the guided cantilever's end moment. Axial
    load's effect on bending (beam-column) is left out: it is small while |P| ≪ π²EI/L².

    Parameters
    ----------
    Q : lateral force at the end [force]. L : pillar length [length]. EI : bending stiffness
    [force·length²]. k_r : the face's rotational stiffness [force·length/rad]
    (:func:`punch_rotation_stiffness`; ``np.inf`` for a rigid clamp).
    """
    return 0.5 * np.multiply(Q, L) / (1.0 + np.divide(EI, np.multiply(k_r, L)))
