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
