"""Friction at the tip: Mindlin's stick spring and the Coulomb cap on the tangential force.

The one home of each formula. They take scalars or numpy arrays (any consistent units; µm, µN,
MPa in gecko_agents) and numba compiles :func:`stick_stiffness` and :func:`friction_cap` into its
per-seta loops, so the vectorized model, the compiled and interpreted loops, the contact laws
and the quasi-static solvers all call the same lines.

Symbols: P normal force [force] (> 0 compressive, < 0 in adhesion), Fc the load-controlled
pull-off force [force] (> 0), μ friction coefficient [-], a contact radius [length], G* the
combined shear modulus [force/length²].

References: R. D. Mindlin, J Appl Mech 16:259 (1949); K. L. Johnson, *Contact Mechanics*
(Cambridge, 1985), §7.2; C. Thornton, J Phys D 24:1942 (1991).
"""

from __future__ import annotations

import numpy as np

from gecko_agents.physics._util import jitable

__all__ = ["combined_shear_modulus", "stick_stiffness", "friction_cap", "friction_cap_slope"]


def combined_shear_modulus(E1, nu1, E2, nu2):
    """G* = ((2 − ν1)/G1 + (2 − ν2)/G2)⁻¹ with G = E/(2(1 + ν)) [force/length²] (Mindlin
    1949; Johnson, Contact Mechanics, 1985, §7.2).

    Parameters
    ----------
    E1, E2 : Young's moduli [force/length²]. nu1, nu2 : Poisson's ratios [-].
    """
    G1, G2 = E1 / (2 * (1 + nu1)), E2 / (2 * (1 + nu2))
    return 1.0 / ((2 - nu1) / G1 + (2 - nu2) / G2)


@jitable
def stick_stiffness(a, G_star):
    """Tangential stiffness k_t = 8G*·a of a sticking circular contact [force/length]
    (Mindlin 1949; Johnson, Contact Mechanics, 1985, §7.2).

    Parameters
    ----------
    a : contact radius [length] (float or array). G_star : combined shear modulus
        [force/length²] (:func:`combined_shear_modulus`).
    """
    return 8.0 * G_star * a


@jitable
def friction_cap(P, Fc, mu, paper):
    """Largest tangential force a contact holds before it slides [force]: μ|P + 2Fc| (the
    adhesive cap, Thornton 1991: a JKR contact holds shear in tension too, down to P = −2Fc)
    or, with ``paper``, Amontons' μ·max(P, 0) (the paper's eq 27).

    Parameters
    ----------
    P : normal force [force] (float or array), > 0 compressive. Fc : pull-off force [force],
        ≥ 0 (0 for a contact without adhesion: the cap is then μ|P|). mu : friction coefficient
        [-]. paper : bool, the paper's cap instead of the adhesive one.
    """
    if paper:
        return mu * np.maximum(P, 0.0)
    return mu * abs(P + 2.0 * Fc)


def friction_cap_slope(P, Fc, mu, paper):
    """d(:func:`friction_cap`)/dP [-]: μ·sign(P + 2Fc), or μ where P > 0 else 0 (``paper``).

    Parameters as :func:`friction_cap`.
    """
    if paper:
        return mu * (P > 0)
    return mu * np.sign(P + 2.0 * Fc)
