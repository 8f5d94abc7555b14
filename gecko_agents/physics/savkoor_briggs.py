"""JKR contact of a sphere under a tangential load: the Savkoor–Briggs coupling of shear and
adhesion.

Plain vectorized numpy functions, the oracles of :class:`gecko_agents.contact.ShearedJKRSphere`
(any consistent units; µm, µN, MPa, µN/µm in gecko_agents). Symbols as
:mod:`gecko_agents.physics.jkr`
plus: T tangential force [force], ξ tangential displacement of the tip from its stick anchor
[length], G* the combined shear modulus of Mindlin's stick stiffness [force/length²]
(:func:`gecko_agents.physics.friction.combined_shear_modulus`).

Physics. A sticking circular contact of radius a under T holds the tangential field of a bonded
punch, stiffness k_t = 8G*·a (Mindlin 1949, J Appl Mech 16:259;
:func:`gecko_agents.physics.friction.stick_stiffness`). Its energy ½T²/k_t at fixed T
(= 4G*·a·ξ² at fixed ξ) grows as the contact shrinks, so shear adds a mode-II release rate
G_II = T²/(32πG*a³) at the contact edge to JKR's mode-I G_I = (P1 − P)²/(8πE*a³)
(P1 = 4E*a³/(3R), the Hertz load of radius a). Griffith's balance G_I + G_II = w on a brittle
interface (toughness w in every mode) gives Savkoor & Briggs' contact (1977, Proc R Soc A
356:103):

    P1 = P + 3πwR + √(6πwRP + (3πwR)² − E*T²/(4G*)),   a³ = 3R·P1/(4E*),

and, at fixed displacements δ and ξ (the model's: a seta holds its tip by a spring, as Popov,
Lyashenko & Filippov 2017, R Soc Open Sci 4:161010, treat the tangential displacement), δ = a²/R −
√((2πwa − 4G*ξ²)/E*), the paper's eq 10 with w → w − 2G*ξ²/(πa). Under load control the contact
comes off where the root vanishes: P = −Fc + E*T²/(24πwRG*), no tension at all once T ≥
4Fc·√(G*/E*).

What it leaves out. Savkoor & Briggs' rubber-on-glass contacts shrank under shear less than this
predicts; Johnson (1997, Proc R Soc A 453:163) and Papangelo et al. (2019, Phys Rev E 99:053005)
describe the difference with an interface toughness that rises with the mode mixity, and a sliding
contact keeps its JKR area (Vorvolakos & Chaudhury 2003, Langmuir 19:6778; Menga, Carbone & Dini
2018, J Mech Phys Solids 112:145, as corrected in its corrigendum). This brittle coupling is the
strongest effect shear can have on the contact; no coupling (the paper's JKR) the weakest. The stick
force 8G*·a·ξ is taken as path-independent: a bonded contact that grows under shear would carry
nothing on its newly bonded ring, and that history is not followed.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "force_from_state",
    "overlap_from_radius",
    "radius_from_loads",
    "pull_off_force",
    "shear_to_free",
    "energy",
]


def force_from_state(a, overlap, R, E_star):
    """Normal force P = 4E*a³/(3R) + 2E*a(δ − a²/R) [force] (> 0 compressive) of a contact of
    radius a at overlap δ: Hertz's load of radius a plus a flat punch of radius a (Johnson,
    Kendall & Roberts 1971; Maugis 2000, ch. 5)."""
    a = np.asarray(a, dtype=float)
    return 4.0 * E_star * a**3 / (3.0 * R) + 2.0 * E_star * a * (overlap - a * a / R)


def overlap_from_radius(a, xi, R, w, E_star, G_star):
    """Overlap δ = a²/R − √((2πwa − 4G*ξ²)/E*) [length] of the equilibrium contact of radius a
    at tangential displacement ξ (Griffith: G_I + G_II = w at fixed δ and ξ); NaN where the
    root is negative (no contact of that radius can hold that shear)."""
    a = np.asarray(a, dtype=float)
    q = (2.0 * np.pi * w * a - 4.0 * G_star * np.asarray(xi, dtype=float) ** 2) / E_star
    return np.where(q >= 0.0, a * a / R - np.sqrt(np.maximum(q, 0.0)), np.nan)


def radius_from_loads(P, T, R, w, E_star, G_star):
    """Contact radius a [length] on the stable branch under normal load P and tangential load T
    (Savkoor & Briggs 1977): a³ = 3R·P1/(4E*) with P1 = P + 3πwR + √(6πwRP + (3πwR)² −
    E*T²/(4G*)); NaN past the pull-off (negative root). T = 0 is the paper's eq 8."""
    P = np.asarray(P, dtype=float)
    T = np.asarray(T, dtype=float)
    disc = 6.0 * np.pi * w * R * P + (3.0 * np.pi * w * R) ** 2 - E_star * T * T / (4 * G_star)
    P1 = P + 3.0 * np.pi * w * R + np.sqrt(np.maximum(disc, 0.0))
    return np.where(disc >= 0.0, np.cbrt(3.0 * R * P1 / (4.0 * E_star)), np.nan)


def pull_off_force(T, R, w, E_star, G_star):
    """Load-controlled pull-off force magnitude under a tangential load T [force]:
    Fc(T) = Fc − E*T²/(24πwRG*), Fc = 1.5πwR, where the root of :func:`radius_from_loads`
    vanishes (Savkoor & Briggs 1977); 0 once T ≥ 4Fc·√(G*/E*), where the contact needs a
    compression of E*T²/(24πwRG*) − Fc to hold (this function reports no tension, not that
    load)."""
    T = np.asarray(T, dtype=float)
    Fc = 1.5 * np.pi * w * R
    return np.maximum(Fc - E_star * T * T / (24.0 * np.pi * w * R * G_star), 0.0)


def shear_to_free(R, w, E_star, G_star):
    """The tangential load 4Fc·√(G*/E*) [force] at which a contact holds no tension."""
    return 4.0 * 1.5 * np.pi * w * R * np.sqrt(G_star / E_star)


def energy(a, overlap, xi, R, w, E_star, G_star):
    """Energy of a contact of radius a at overlap δ and tangential displacement ξ [energy]:
    elastic (Hertz's load of radius a plus the flat punch, Maugis 2000, ch. 5)
    8E*a⁵/(15R²) + P1·e + E*a·e² (e = δ − a²/R), surface −πa²w and stick 4G*·a·ξ². Its
    derivatives are the forces, ∂U/∂δ = P and ∂U/∂ξ = 8G*·a·ξ, and ∂U/∂a = 0 is the
    equilibrium of :func:`overlap_from_radius`."""
    a = np.asarray(a, dtype=float)
    e = overlap - a * a / R
    elastic = 8.0 * E_star * a**5 / (15.0 * R * R) + 4.0 * E_star * a**3 / (3.0 * R) * e
    elastic = elastic + E_star * a * e * e
    return elastic - np.pi * a * a * w + 4.0 * G_star * a * np.asarray(xi, dtype=float) ** 2
