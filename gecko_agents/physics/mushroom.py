"""How a mushroom (flanged) tip lets go: from its rim (edge mode) or from its centre, whichever
needs less tension.

Plain functions in the package's units (µm, µN, MPa, µN/µm). The flange is a thin disc of
radius a_t on a stalk of radius a ≤ a_t, its face bonded to a stiff floor. Aksak, Şahin & Sitti
(2014, Beilstein J Nanotechnol 5:630, eq 2; the equations printed in the text of their patent
US 2015/0368519, read in the Pap2Pat corpus) find by cohesive-zone finite elements that
detachment starts

* at the rim, Φ = B_e(βχ)^(−α), α the rim corner's singularity (βχ = χ at the flange's radius,
  :func:`gecko_agents.physics.flaw_tolerance.flaw_parameter`), where the rim is singular:
  edge angle θ > 45° on a full-friction floor at ν = 1/2
  (:func:`gecko_agents.physics.wedge.singularity_exponent`), or where a step or rounding at
  the rim (a flaw) restores an edge crack;
* at the centre, Φ = B_c(βχ)^(−1/2) + Γ_c, where the rim is not singular: the stress peaks in
  the middle of the face and a crack opens there (seen by Varenberg & Gorb 2008, Murphy et al.
  2009, as they report).

Their B_e, B_c and Γ_c(β) are given only in figures, so this module does not use them. It
takes instead the laws with no fitted constant but Tang's: the edge of a flawed rim is
Kendall's crack with a cohesive zone at σ₀, Maugis's Dugdale punch
(:func:`gecko_agents.physics.flaw_tolerance.punch_pull_off`, the flat punch's law); a
sharp, singular rim follows Tang et al.'s form with the rim's own exponent
α = 1 − λ and Tang's B = 0.83 (Tang, Hui & Glassmaker 2005, J R Soc Interface 2:505; at 90°
and ν = 1/2, α = 0.405, Tang's fit), an assumption at other angles; the centre lets go by
Griffith's penny crack from a central defect of radius c, bounded by σ₀, under a stress taken
uniform over the flange (:func:`gecko_agents.physics.flaw_tolerance.penny_crack_strength`).
The uniform stress is an upper bound: Aksak et al.'s lower bound Γ_c is 0.85 at β = 1.1–1.2
and 0.74 at β = 1.3 for θ = 45° (the stalk concentrates stress at the centre), which this
module does not reproduce.
"""

from __future__ import annotations

import math

from gecko_agents.physics import flaw_tolerance as ft
from gecko_agents.physics.wedge import NOT_SINGULAR, singularity_exponent

__all__ = ["MODES", "edge_pull_off", "centre_pull_off", "pull_offs"]

MODES = ("edge", "centre")
"""Where a mushroom tip's detachment starts: at its rim or at its centre."""


def edge_pull_off(a_t, w, E_star, sigma0, rim="flawed", rim_angle_deg=90.0, nu=0.5) -> float:
    """Tension [µN] at which a crack runs in from the flange's rim (module docstring).

    ``rim = "flawed"``: Kendall's edge crack with a cohesive zone at σ₀ (the Dugdale punch,
    at most σ₀πa_t²), the flat punch's law.
    ``rim = "sharp"``: σ₀πa_t²·min(1, 0.83·χ^(−(1 − λ))) with λ the bonded rim's
    :func:`~gecko_agents.physics.wedge.singularity_exponent` (the real part of a complex
    root: an obtuse rim of a compressible tip); ``inf`` where the rim is not singular (no
    edge mode) or σ₀ is unbounded.

    Parameters
    ----------
    a_t : flange radius [µm]. w : work of adhesion [µN/µm]. E_star : E* [MPa].
    sigma0 : cohesive strength σ₀ [MPa]. rim : ``"flawed"`` or ``"sharp"``.
    rim_angle_deg : edge angle θ of a sharp rim [degrees]. nu : Poisson's ratio of the tip [-].
    """
    if rim == "flawed":
        return float(ft.punch_pull_off(a_t, w, E_star, sigma0))
    lam = singularity_exponent(rim_angle_deg, nu, "bonded")
    if lam >= NOT_SINGULAR or math.isinf(sigma0):
        return math.inf
    chi = ft.flaw_parameter(a_t, sigma0, E_star, w)
    return float(math.pi * a_t * a_t * sigma0 * ft.strength_ratio(chi, exponent=1.0 - lam))


def centre_pull_off(a_t, c, w, E_star, sigma0) -> float:
    """Tension [µN] at which the face lets go from its centre: Griffith's penny crack from a
    defect of radius c bounded by σ₀ (uniform detachment at σ₀ for c = 0), over the flange's
    area πa_t² (:func:`gecko_agents.physics.flaw_tolerance.penny_crack_strength`); ``inf``
    for c = 0 and σ₀ = inf.

    Parameters
    ----------
    a_t : flange radius [µm]. c : defect radius [µm], ≥ 0. w : work of adhesion [µN/µm].
    E_star : E* [MPa]. sigma0 : cohesive strength σ₀ [MPa].
    """
    return float(math.pi * a_t * a_t * ft.penny_crack_strength(c, w, E_star, sigma0))


def pull_offs(a_t, c, w, E_star, sigma0, rim="flawed", rim_angle_deg=90.0, nu=0.5) -> dict:
    """Both modes' tensions [µN], ``{"edge": …, "centre": …}`` (:func:`edge_pull_off`,
    :func:`centre_pull_off`); the tip lets go by the smaller (the edge on a tie)."""
    return {
        "edge": edge_pull_off(a_t, w, E_star, sigma0, rim, rim_angle_deg, nu),
        "centre": centre_pull_off(a_t, c, w, E_star, sigma0),
    }
