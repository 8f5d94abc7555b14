"""The derivatives the implicit step linearises with, against central differences of the
functions they differentiate: each law's contact stiffness dP/dδ and the friction cap's slope
dF_cap/dP. A wrong Jacobian leaves a converged run converging, only slower and with other
errors, so these are pinned here, at the law."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gecko_agents import contact
from gecko_agents.params import PAPER_TABLE1, TIPS
from gecko_agents.physics import friction

H = 1e-6  # central-difference step [µm] (truncation ~ h² P''' ≈ 1e-12 of these forces)


def _branch_laws():
    """Laws whose radius follows the overlap (equilibrium): dP/dδ along the branch."""
    laws = [
        contact.JKRSphere(PAPER_TABLE1.contact),
        contact.HertzSphere(PAPER_TABLE1.contact),
    ]
    for tip in ("flat_punch", "mushroom"):
        assert tip in TIPS
        p = PAPER_TABLE1.replace(tip=tip)
        laws.append(contact.contact_law(p))
    return laws


@pytest.mark.parametrize("law", _branch_laws(), ids=lambda law: type(law).__name__)
def test_contact_stiffness_is_the_branch_derivative_of_the_force(law):
    """stiffness(a(δ), δ) = d/dδ P(a(δ), δ) along the law's own branch, over compression and
    (adhesive laws) tension down to near where the tip lets go."""
    lo = max(law.detach_overlap, -1.0) if np.isfinite(law.detach_overlap) else 0.0
    d = np.linspace(0.9 * lo + 1e-3 if lo < 0 else 1e-2, 1.5, 61)

    def P(x):
        return law.force(law.radius(x.copy(), x.copy(), 0.0), x)

    dP = (P(d + H) - P(d - H)) / (2 * H)
    k = law.stiffness(law.radius(d.copy(), d.copy(), 0.0), d)
    # measured: largest difference 5.7e-10 of the largest dP/dδ (JKR), 2e-10 (the others)
    assert_allclose(k, dP, rtol=1e-6, atol=1e-6 * float(np.max(np.abs(dP))))


def test_crack_kinetics_stiffness_is_the_force_derivative_at_a_fixed_radius():
    """With crack kinetics the radius is a state: within a step the edge does not move, so the
    stiffness is ∂P/∂δ at fixed a (Barquins & Maugis 1981's P(a, δ))."""
    law = contact.RateJKRSphere(PAPER_TABLE1.replace(**{"contact.crack_speed": 0.5}).contact)
    a = np.linspace(0.2, 1.5, 14) * law.a0
    d = np.linspace(-0.5, 1.0, 14)
    dP = (law.force(a, d + H) - law.force(a, d - H)) / (2 * H)
    assert_allclose(law.stiffness(a, d), dP, rtol=1e-7)


@pytest.mark.parametrize("paper", [False, True])
@pytest.mark.parametrize("Fc", [0.0, 1.5])
def test_friction_cap_slope_is_the_derivative_of_the_cap(paper, Fc):
    """dF_cap/dP of both caps (μ|P + 2Fc|, the paper's μ·max(P, 0)) by central differences,
    away from their kinks (P = −2Fc, P = 0)."""
    mu = 0.7
    P = np.concatenate([np.linspace(-8.0, -0.3, 20), np.linspace(0.3, 8.0, 20)])
    P = P[np.abs(P + 2.0 * Fc) > 0.1]
    h = 1e-4

    def cap(x):
        return friction.friction_cap(x, Fc, mu, paper)

    slope = friction.friction_cap_slope(P, Fc, mu, paper)
    assert_allclose(slope, (cap(P + h) - cap(P - h)) / (2 * h), rtol=1e-9, atol=1e-12)
    assert np.any(slope == 0.0) == paper  # Amontons' cap is flat in tension


@pytest.mark.parametrize("n", [0.5, 1.0])
def test_an_opening_crack_step_is_one_linearised_backward_euler_step(n):
    """An opening edge of the crack-kinetics law moves by one Newton step of backward Euler on
    da/dt = −f(a) = −v*·((G(a) − w)/w)^{1/n}, G = E*(a²/R − δ)²/(2πa) (Greenwood & Johnson
    1981, Phil Mag A 43:697; the law's docstring): a₁ = a₀ − dt·f(a₀)/(1 + dt·f′(a₀)), with
    f′ by central differences here."""
    p = PAPER_TABLE1.replace(**{"contact.crack_speed": 0.5, "contact.crack_exponent": n})
    law = contact.RateJKRSphere(p.contact)
    R, w, E = law.R, law.w, law.E_star
    a0 = 1.2
    delta = a0 * a0 / R - np.sqrt(1.1 * w * 2 * np.pi * a0 / E)  # G(a0) = 1.1 w

    def f(a):
        G = E * (a * a / R - delta) ** 2 / (2 * np.pi * a)
        return law.v_star * ((G - w) / w) ** (1.0 / n)

    h = 1e-6
    fp = (f(a0 + h) - f(a0 - h)) / (2 * h)
    dt = 0.5 / fp  # dt·f′ = 0.5: the step is a third shorter than the explicit one
    expected = a0 - dt * f(a0) / (1.0 + dt * fp)
    # below δc (no branch radius clips the step), dG/da > 0 (the Newton factor acts), and a
    # step the law resolves (under a tenth of the radius)
    assert delta < law.delta_c and 3 * a0 * a0 / R + delta > 0 and 0 < a0 - expected < 0.1 * a0
    assert law.radius_scalar(delta, a0, dt, law.constants) == pytest.approx(expected, rel=1e-8)
