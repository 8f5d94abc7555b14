"""An interface with a strength: the pull-off stress of a flat contact whose interface holds at
most a cohesive stress σ₀ (flaw tolerance, "contact splitting").

Plain vectorized functions in any consistent unit set (µm, µN, MPa = µN/µm², µN/µm for the
work of adhesion in gecko_agents). Stresses are tensile positive here (a pull-off stress is the
tensile force at pull-off over the contact's area).

A flat contact of radius a on a stiff floor lets go either by a crack (Kendall's edge crack,
Kendall 1971, J Phys D 4:1186: mean stress √(8E*w/(πa)), falling as a^(−1/2)) or, once that
mean stress would exceed what the interface can hold, uniformly at σ₀: below a size the
contact is flaw tolerant and splitting it into smaller contacts stops paying (Hui, Glassmaker,
Tang & Jagota 2004, J R Soc Interface 1:35; Gao & Yao 2004, PNAS 101:7851). The one number
that decides which is Tang, Hui & Glassmaker's (2005, J R Soc Interface 2:505)

    χ = σ₀²·a·(1 − ν²)/(2πE·w) = σ₀²·a/(2πE*·w)         (E* = E/(1 − ν²) on a rigid floor),

flaw insensitive for χ ≲ 1, flaw sensitive for χ ≫ 1. Tang et al. fit their cohesive-zone
finite elements of a compliant cylinder bonded (full friction) to a rigid flat by
σ_c = σ₀·min(1, 0.83χ^(−0.4)), the exponent 0.4 being the bonded 90° corner's stress
singularity (:mod:`gecko_agents.physics.wedge`: r^(λ−1), λ = 0.5946 for an incompressible
wedge), not a crack's 0.5. Their Table 1 (read at
https://pmc.ncbi.nlm.nih.gov/articles/PMC1618499/table/tbl1) gives the rows that
``tests/test_flaw_tolerance.py`` reproduces; the same χ and fit are restated by Aksak, Şahin &
Sitti 2014 (Beilstein J Nanotechnol 5:630), whose χ = 33.6 for PDMS (E = 1.42 MPa, ν = 0.5,
w = 25 mJ/m², σ₀ = 1 MPa, a = 10 µm) is a further hand check.

A flat punch whose edge carries a flaw lets go by Kendall's edge crack; with an interface
of strength σ₀ that crack has a cohesive (Dugdale) zone, a band c < r < a of the face held
at σ₀ while the punch's edge opens by less than h₀ = w/σ₀. Its pull-off is Maugis's (1992,
J Colloid Interface Sci 150:243) Dugdale solution with the sphere's Hertz terms dropped (a
flat face has no profile) and the zone's outer end fixed at the punch's edge (derived in
:func:`dugdale_punch_strength`; his eqs 6.17 and the load and penetration beside it are read
in the ContactMechanics code, ``PyCo/ReferenceSolutions/MaugisDugdale.py``). It runs from
σ₀πa² (the whole face at σ₀, a ≤ 0.540·a_cr) to Kendall's force (a ≫ a_cr) and lies below
both: 13.4 % below min(Kendall, σ₀πa²) at a = a_cr, where that simple form has its kink.

Written as the release rate of a crack in the package's convention (Kendall's punch
G = P²/(8πa³E*), :func:`gecko_agents.physics.punch.edge_release_rate`), Griffith's penny crack of
radius c inside a bonded face under a uniform stress σ has G = 2σ²c/(πE*) (the crack in an
infinite body, K = 2σ√(c/π), with one side rigid), so it runs at σ = √(πE*w/(2c)).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from gecko_agents.physics import punch

__all__ = [
    "TANG_PREFACTOR",
    "TANG_EXPONENT",
    "flaw_parameter",
    "strength_ratio",
    "tang_strength",
    "kendall_strength",
    "flaw_tolerant_radius",
    "penny_crack_strength",
    "UNIFORM_CHI",
    "dugdale_punch_strength",
    "punch_pull_off",
]

TANG_PREFACTOR = 0.83
"""B in σ_c/σ₀ = B·χ^(−0.4) (Tang, Hui & Glassmaker 2005, J R Soc Interface 2:505)."""
TANG_EXPONENT = 0.4
"""The exponent of their fit, the bonded 90° corner's singularity 1 − λ ≈ 0.405 rounded."""


def flaw_parameter(a, sigma0, E_star, w):
    """Tang's flaw parameter χ = σ₀²·a/(2πE*·w) [-] (Tang, Hui & Glassmaker 2005, J R Soc
    Interface 2:505, with E* = E/(1 − ν²) of the contact on a rigid floor): the contact's size
    over the length on which the cohesive stress σ₀ acts.

    Parameters
    ----------
    a : contact radius [µm]. sigma0 : cohesive strength σ₀ [MPa]. E_star : E* [MPa].
    w : work of adhesion [µN/µm].
    """
    return np.square(sigma0) * np.asarray(a, float) / (2.0 * np.pi * np.multiply(E_star, w))


def strength_ratio(chi, exponent=TANG_EXPONENT, prefactor=TANG_PREFACTOR):
    """Φ = σ_c/σ₀ = min(1, B·χ^(−α)) [-]: Tang et al.'s (2005) fit of a bonded cylinder's
    pull-off stress (B = 0.83, α = 0.4). Aksak, Şahin & Sitti (2014, Beilstein J Nanotechnol
    5:630, eq 2a) use the same form at the rim of a mushroom tip, α from the rim's corner
    singularity (:func:`gecko_agents.physics.wedge.singularity_exponent`); Φ = 1 where χ ≤
    B^(1/α), the flaw-insensitive regime.

    Parameters
    ----------
    chi : flaw parameter χ [-]. exponent : α [-]. prefactor : B [-].
    """
    chi = np.asarray(chi, float)
    with np.errstate(divide="ignore"):
        return np.minimum(1.0, prefactor * np.power(chi, -exponent))


def tang_strength(a, sigma0, E_star, w):
    """Pull-off stress of a compliant flat-ended cylinder bonded to a rigid flat,
    σ_c = σ₀·min(1, 0.83χ^(−0.4)) [MPa] (Tang, Hui & Glassmaker 2005, J R Soc Interface 2:505;
    χ :func:`flaw_parameter`).

    Parameters
    ----------
    a : cylinder radius [µm]. sigma0 : σ₀ [MPa]. E_star : E* [MPa]. w : work of adhesion
    [µN/µm].
    """
    return sigma0 * strength_ratio(flaw_parameter(a, sigma0, E_star, w))


def kendall_strength(a, w, E_star):
    """Mean tensile stress at Kendall's pull-off of a flat punch, √(8E*w/(πa)) [MPa]
    (:func:`gecko_agents.physics.punch.kendall_pull_off` over πa²; Kendall 1971, J Phys D
    4:1186). In Tang's variable it is σ₀·(2/π)·χ^(−1/2).

    Parameters
    ----------
    a : punch radius [µm]. w : work of adhesion [µN/µm]. E_star : E* [MPa].
    """
    return np.sqrt(8.0 * np.multiply(E_star, w) / (np.pi * np.asarray(a, float)))


def flaw_tolerant_radius(sigma0, E_star, w):
    """Radius below which a flat contact is flaw tolerant, a_cr = 8E*w/(πσ₀²) [µm]: where
    Kendall's pull-off stress (:func:`kendall_strength`) reaches σ₀, χ = 4/π² ≈ 0.41. Smaller
    contacts pull off at σ₀ whatever their size, so splitting one below a_cr gains nothing.

    Derived here from Kendall's law and the cut-off at σ₀ (the criterion of Gao & Yao 2004,
    PNAS 101:7851, and of Hui et al. 2004, J R Soc Interface 1:35, who give χ ≲ 1; only their
    abstracts were read). Tang's own boundary, χ = 1, lies at 2πE*w/σ₀² = (π²/4)·a_cr.

    Parameters
    ----------
    sigma0 : σ₀ [MPa]. E_star : E* [MPa]. w : work of adhesion [µN/µm].
    """
    return 8.0 * np.multiply(E_star, w) / (np.pi * np.square(sigma0))


def penny_crack_strength(c, w, E_star, sigma0=math.inf):
    """Uniform tensile stress at which a penny-shaped interface crack of radius c runs,
    min(σ₀, √(πE*w/(2c))) [MPa]: Griffith's balance G = w with G = 2σ²c/(πE*) (the module
    docstring), bounded by the interface's strength σ₀. c = 0 (no defect) gives σ₀, uniform
    detachment.

    Parameters
    ----------
    c : crack (defect) radius [µm], ≥ 0. w : work of adhesion [µN/µm]. E_star : E* [MPa].
    sigma0 : cohesive strength σ₀ [MPa]; inf (default) leaves Griffith's stress unbounded.
    """
    c = np.asarray(c, float)
    with np.errstate(divide="ignore"):
        griffith = np.sqrt(np.pi * np.multiply(E_star, w) / (2.0 * c))
    return np.minimum(sigma0, griffith)


UNIFORM_CHI = 1.0 / (8.0 * (math.pi / 2.0 - 1.0))
"""χ = 0.2190 below which the Dugdale punch lets go with its whole face at σ₀
(:func:`dugdale_punch_strength`): a = π/(16(1 − 2/π))·a_cr = 0.540·a_cr."""


def _edge_opening(phi: float) -> float:
    """G = √(1 − t²)·arccos t − (1 − t) at t = cos φ, φ·sin φ − 2sin²(φ/2): the Dugdale
    punch's edge opening over 4σ₀a/(πE*) at bonded radius c = a·cos φ
    (:func:`dugdale_punch_strength`; in φ, free of the cancellation near t = 1)."""
    return phi * math.sin(phi) - 2.0 * math.sin(0.5 * phi) ** 2


def _dugdale_ratio(chi: float) -> float:
    if chi <= UNIFORM_CHI:
        return 1.0
    target = 1.0 / (8.0 * chi)
    phi = brentq(lambda x: _edge_opening(x) - target, 0.0, math.pi / 2, xtol=1e-300, rtol=1e-15)
    return (2.0 * phi + math.sin(2.0 * phi)) / math.pi  # (2/π)(arccos t + t√(1 − t²))


def dugdale_punch_strength(a, sigma0, E_star, w):
    """Mean tensile stress at pull-off of a rigid flat punch of radius a on a half-space whose
    interface holds at most σ₀ up to an opening h₀ = w/σ₀ (Dugdale), detaching from its
    edge inward [MPa]: σ₀·Φ(χ), Φ = (2/π)(arccos t + t√(1 − t²)), t = c/a the bonded radius
    where the edge's opening reaches h₀, G(t) = √(1 − t²)·arccos t − (1 − t) = 1/(8χ);
    Φ = 1 for χ ≤ :data:`UNIFORM_CHI` (G(0) = π/2 − 1: the whole face at σ₀ before the edge
    opens h₀). χ is Tang's :func:`flaw_parameter`.

    Maugis (1992, J Colloid Interface Sci 150:243) solves the sphere: bonded over r < c, σ₀ over
    c < r < m, with P = P_Hertz − 2σ₀[m²·arccos(c/m) + c√(m² − c²)], δ = c²/R − (2σ₀/E*)√(m² − c²)
    and, for the gap at m, the Hertz term plus (4σ₀c/(πE*))[√(s² − 1)·arcsec s − s + 1],
    s = m/c (his eq 6.17 in dimensional form). A flat face drops the Hertz terms and its zone
    ends at its edge, m = a; the gap there reaching h₀ is the condition above, and the load
    2σ₀[a²·arccos t + a²t√(1 − t²)] is Φ·σ₀πa². Large χ gives Kendall's √(8πE*wa³)
    (t → 1, a − c = πE*w/(4σ₀²)), χ → UNIFORM_CHI gives σ₀πa²; below both everywhere.

    Parameters
    ----------
    a : punch radius [µm]. sigma0 : cohesive strength σ₀ [MPa], > 0. E_star : E* [MPa].
    w : work of adhesion [µN/µm].
    """
    chi = np.asarray(flaw_parameter(a, sigma0, E_star, w), float)
    ratio = np.vectorize(_dugdale_ratio, otypes=[float])(chi)
    return sigma0 * (ratio if ratio.ndim else float(ratio))


def punch_pull_off(a, w, E_star, sigma0=math.inf):
    """Pull-off force of a flat punch with a flawed edge whose interface has the strength σ₀
    [µN]: the Dugdale punch, πa²·:func:`dugdale_punch_strength`, between σ₀πa² (small
    punches) and Kendall's √(8πE*wa³) (large ones;
    :func:`gecko_agents.physics.punch.kendall_pull_off`), and below both. σ₀ = inf returns
    Kendall's exactly.

    The sharp, bonded 90° corner (an edge with no flaw) holds more: Tang's stress
    (:func:`tang_strength`) is 1.30·χ^0.1 times Kendall's where both fall with size, the
    corner being less singular than a crack, so the flawed edge is the weaker.

    Parameters
    ----------
    a : punch radius [µm]. w : work of adhesion [µN/µm]. E_star : E* [MPa].
    sigma0 : cohesive strength σ₀ [MPa].
    """
    if math.isinf(sigma0):
        return punch.kendall_pull_off(a, w, E_star)
    return np.pi * np.square(a) * dugdale_punch_strength(a, sigma0, E_star, w)
