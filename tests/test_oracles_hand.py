"""Oracles that do not trust the code under test: numbers worked out by hand from the textbook
formulas, a force against the finite-difference derivative of its energy, a rod against the
elastica of a cantilever, and the paper's friction law run in the agent model against the
quasi-static solver.

Units: µm, µN, MPa (= µN/µm²), pJ (= µN·µm).

Hand arithmetic follows Johnson, *Contact Mechanics* (Cambridge, 1985), §7.2 (Mindlin 1949,
J Appl Mech 16:259): a circular contact of radius a between two elastic bodies sticks with the
tangential stiffness k_t = 8G*·a, where G_i = E_i/(2(1 + ν_i)) and
G* = ((2 − ν1)/G1 + (2 − ν2)/G2)⁻¹ (the same mixing as LAMMPS's granular
``mix_stiffnessG``: 1/(2(2 − ν1)(1 + ν1)/E1 + 2(2 − ν2)(1 + ν2)/E2)).
"""

import math
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from gecko_agents import protocol
from gecko_agents import quasistatic as qs
from gecko_agents.contact import JKRSphere, ShearedJKRSphere, mindlin_stiffness
from gecko_agents.history import STATE_SLIP, STATE_STICK
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY, PAPER_TABLE1, Contact
from gecko_agents.physics import beam
from gecko_agents.physics.friction import combined_shear_modulus, stick_stiffness

# ---- G* and k_t by hand --------------------------------------------------------------------

# Paper materials (Table 1): seta E1 = 1.413 MPa, ν1 = 0.3; glass floor E2 = 55 000 MPa,
# ν2 = 0.25.
#   G1 = 1.413/(2·1.3) = 0.543461538… MPa, (2 − 0.3)/G1 = 1.7·2.6/1.413 = 3.128096249…
#   G2 = 55000/(2·1.25) = 22000 MPa,        (2 − 0.25)/G2 = 1.75/22000 = 7.954545…e-5
#   G* = 1/(3.128096249 + 0.0000795455) = 0.319675129 MPa
G_STAR_PAPER = 0.3196751287877961
# JKR's zero-load radius a0 = (9πwR²/(2E*))^(1/3) (Johnson, Kendall & Roberts 1971, the
# radius under load P = 0; a³ = (3R/4E*)·6πwR) with
#   w = 2√(γ1γ2) = 2√(0.04·0.17) = 0.164924225 µN/µm, R = 4 µm,
#   E* = 1/((1 − 0.09)/1.413 + (1 − 0.0625)/55000) = 1.552706157 MPa
#   a0³ = 9π·0.164924225·16/(2·1.552706157) = 24.02578277 µm³, a0 = 2.885531693 µm
A0_PAPER = 2.885531692849332
#   k_t = 8·0.319675129·2.885531693 = 7.379461724 µN/µm
KT_PAPER = 7.379461724263019


@pytest.mark.parametrize(
    ("E1", "nu1", "E2", "nu2", "G_star"),
    [
        # G1 = 2/(2·1.25) = 0.8, G2 = 3/(2·1.5) = 1; 1.75/0.8 + 1.5/1 = 3.6875 → G* = 16/59
        (2.0, 0.25, 3.0, 0.5, 16.0 / 59.0),
        # equal bodies, ν = 0: G = E/2, G* = 1/(2·2/(E/2)) = E/8
        (8.0, 0.0, 8.0, 0.0, 1.0),
        (1.413, 0.3, 55_000.0, 0.25, G_STAR_PAPER),
    ],
)
def test_combined_shear_modulus_by_hand(E1, nu1, E2, nu2, G_star):
    # Exact arithmetic in doubles: the only error is rounding (a few ulp).
    assert combined_shear_modulus(E1, nu1, E2, nu2) == pytest.approx(G_star, rel=1e-14)
    # Swapping the bodies changes nothing.
    assert combined_shear_modulus(E2, nu2, E1, nu1) == pytest.approx(G_star, rel=1e-14)


def test_stick_stiffness_by_hand():
    # 8·(16/59)·0.5 = 64/59 µN/µm; the paper's contact at a = 1.5 µm: 8·0.319675129·1.5.
    assert stick_stiffness(0.5, 16.0 / 59.0) == pytest.approx(64.0 / 59.0, rel=1e-15)
    assert stick_stiffness(1.5, G_STAR_PAPER) == pytest.approx(3.8361015454535528, rel=1e-15)
    # Contact refuses ν = 0.5: E2 = 2.8, ν2 = 0.4 gives G2 = 2.8/2.8 = 1, (2 − 0.4)/1 = 1.6,
    # G* = 1/(2.1875 + 1.6) = 80/303 and 8·(80/303)·0.5 = 320/303 µN/µm.
    c = Contact(E1=2.0, nu1=0.25, E2=2.8, nu2=0.4)
    assert mindlin_stiffness(c, 0.5) == pytest.approx(320.0 / 303.0, rel=1e-14)


def test_the_model_and_its_laws_stick_with_8_g_star_a0():
    """The stick spring every sphere law and the agent model use for the paper's materials."""
    c = PAPER_TABLE1.contact
    law = JKRSphere(c)
    assert law.a0 == pytest.approx(A0_PAPER, rel=1e-12)  # cube root: a few ulp
    assert law.tangential_stiffness == pytest.approx(KT_PAPER, rel=1e-12)
    sheared = ShearedJKRSphere(c, PAPER_TABLE1.friction)
    assert sheared.G_star == pytest.approx(G_STAR_PAPER, rel=1e-14)
    assert sheared.tangential_stiffness == pytest.approx(KT_PAPER, rel=1e-12)
    m = Model(PAPER_TABLE1.replace(**{"seta.L": 5.0, "array.count": 1}))
    assert m.k_t == pytest.approx(KT_PAPER, rel=1e-12)


@pytest.mark.parametrize("xi", [1e-4, -3e-4])
def test_sheared_tip_holds_minus_8_g_star_a_xi(xi):
    """A sticking sheared-JKR tip at a small tangential offset ξ: T = −8G*·a·ξ with the
    hand-computed G* and the radius the law reports (Mindlin's spring, Johnson 1985 §7.2)."""
    law = ShearedJKRSphere(PAPER_TABLE1.contact, PAPER_TABLE1.friction)
    z = law.R - 1.0  # pressed 1 µm, past the zero-load overlap a0²/(3R) = 0.69 µm
    P, T, _, a, xi_out, *_ = law.step_scalar(xi, z, 0.0, 0.0, 0.0, 0.0, law.constants)
    assert P > 0 and xi_out == xi  # it sticks (ξ far below the cap μ|P + 2Fc|/k_t)
    assert T == pytest.approx(-8.0 * G_STAR_PAPER * a * xi, rel=1e-12)


# ---- the rod seta: force = −∇energy, and the cantilever under a tip force ------------------

ROD_L, ROD_KA, ROD_KPHI = 5.0, 2.0, 0.7  # µm, µN/µm, µN·µm/rad²


@pytest.mark.parametrize("theta_deg", [30.0, 60.0])
def test_rod_force_is_minus_the_gradient_of_its_energy(theta_deg):
    """Central differences of E(d) at h = 1e-6 µm: truncation O(h²·E''') ~ 1e-12, rounding
    ~ ε·E/h ~ 1e-10 µN, so 1e-7 relative is ample and a wrong sign or factor fails by O(1)."""
    th = math.radians(theta_deg)
    rng = np.random.default_rng(4)
    rest = np.array(beam.rest_tip_offset(ROD_L, th))
    d = rest + rng.uniform(-2.0, 2.0, (40, 2))  # rotations up to ~±40°, stretch ±40 %
    F, _ = beam.rod_spring_force(d, ROD_L, ROD_KA, ROD_KPHI, th)
    h = 1e-6
    for axis in (0, 1):
        step = np.zeros(2)
        step[axis] = h
        _, Ep = beam.rod_spring_force(d + step, ROD_L, ROD_KA, ROD_KPHI, th)
        _, Em = beam.rod_spring_force(d - step, ROD_L, ROD_KA, ROD_KPHI, th)
        assert_allclose(F[:, axis], -(Ep - Em) / (2 * h), rtol=1e-7, atol=1e-9)
    # At rest: no force, no energy.
    F0, E0 = beam.rod_spring_force(rest[None, :], ROD_L, ROD_KA, ROD_KPHI, th)
    assert_allclose(F0, 0.0, atol=1e-15) and assert_allclose(E0, 0.0, atol=1e-28)


def _equilibrium(L, Ka, kphi, F, guess):
    """Tip position d of a horizontal rod seta (θ = 0, root at the origin) in equilibrium
    under a downward dead tip load F: rod_spring_force(d) + (0, −F) = 0 (Newton, with the
    Jacobian from central differences) to a step of 1e-14·L, where the residual is rounding."""

    def residual(d):
        Fs, _ = beam.rod_spring_force(d[None, :], L, Ka, kphi, 0.0)
        return Fs[0] + np.array([0.0, -F])

    d = np.array(guess, float)
    for _ in range(100):
        h = 1e-7 * L
        J = np.column_stack([(residual(d + e) - residual(d - e)) / (2 * h) for e in np.eye(2) * h])
        step = np.linalg.solve(J, residual(d))
        d = d - step
        if np.abs(step).max() < 1e-14 * L:
            assert np.abs(residual(d)).max() < 1e-9 * F
            return d
    raise AssertionError(f"no equilibrium found for F = {F}")


def _rod_tip_under_force(F, r, L, E, Ka):
    """Tip of a horizontal rod seta (θ = 0, root at the origin) in equilibrium under a
    downward tip force F: rod_spring_force(d) + (0, −F) = 0, solved for d."""
    kphi = beam.bending_stiffness(r, L, E) * L * L  # kφ = Kp·L² = 3EI/L
    return _equilibrium(L, Ka, kphi, F, [L, -F * L**3 / (3 * E * math.pi * r**4 / 4)])


def _elastica_deflection(F, L, EI):
    """Tip drop of an inextensible cantilever (the elastica) under a downward tip force F:
    θ' = κ, EI κ' = −F cos θ... written as EI θ'' = F cos θ (θ the slope below the
    horizontal), θ(0) = 0, θ'(L) = 0, found by shooting on κ(0) (Euler–Bernoulli, large
    rotation; e.g. Timoshenko & Gere, Theory of Elastic Stability, §2.7)."""

    def end_moment(k0):
        sol = solve_ivp(
            lambda s, y: [y[1], -F / EI * math.cos(y[0]), math.sin(y[0])],
            (0.0, L), [0.0, k0, 0.0], rtol=1e-12, atol=1e-14,
        )  # fmt: skip
        return sol.y[1, -1], sol.y[2, -1]

    k_small = F * L / EI  # curvature at the root of the linear cantilever, an upper bound
    k0 = brentq(lambda k: end_moment(k)[0], 0.0, 1.01 * k_small, xtol=1e-15)
    return end_moment(k0)[1]


def test_rod_cantilever_under_a_tip_force_is_the_elastica_to_first_order():
    """δ → FL³/(3EI) as F → 0 (the rod's kφ = Kp·L² is chosen for exactly that), and its
    difference from the elastica is of second order in the load parameter α = FL²/EI: halving
    α quarters the relative difference (the rigid rod on a root spring is a pseudo-rigid-body
    model, right only to first order at large rotation)."""
    r, L, E = 1.5, 20.0, 1.413
    EI = E * math.pi * r**4 / 4
    Ka = 1e2 * beam.axial_stiffness(r, L, E)  # stretches < 1e-5 L here, as the elastica: none
    rel = []
    for alpha in (0.2, 0.1, 0.05):
        F = alpha * EI / L**2
        x, y = _rod_tip_under_force(F, r, L, E, Ka)
        drop = -y
        linear = F * L**3 / (3 * EI)
        elastica = _elastica_deflection(F, L, EI)
        # Both are FL³/3EI to first order: their relative second-order terms are −(2/27)α²
        # for the rod (φ = (α/3)cos φ, drop = L sin φ) and about −0.11α² for the elastica,
        # so both lie within α²/5 of it (α = 0.2: 0.8 %) and a factor in kφ fails.
        assert drop == pytest.approx(linear, rel=alpha**2 / 5)
        assert elastica == pytest.approx(linear, rel=alpha**2 / 5)
        rel.append(abs(drop - elastica) / elastica)
        # The rod keeps its length (Ka stiff): the tip lies on the circle of radius L.
        assert math.hypot(x, y) == pytest.approx(L, rel=1e-5)
    # Second order: ratios 4 ± 10 % (the next term is O(α⁴)).
    assert rel[0] / rel[1] == pytest.approx(4.0, rel=0.1)
    assert rel[1] / rel[2] == pytest.approx(4.0, rel=0.1)


def test_rod_rotation_under_a_dead_tip_load_solves_its_moment_balance():
    """Large rotation, exact for the rod model itself: a horizontal rod on a rotary spring kφ
    and an axial spring Ka under a downward dead load F rotates by φ and stretches to ℓ with
    kφ·φ = F·ℓ·cos φ (moment balance about the root) and Ka(ℓ − L) = F·sin φ (along the rod).
    """
    L, kphi, Ka = 5.0, 0.7, 3.0
    for F in (0.05, 0.2, 0.6):
        phi = brentq(
            lambda p, F=F: kphi * p - F * (L + F * math.sin(p) / Ka) * math.cos(p),
            0.0, math.pi / 2, xtol=1e-15,
        )  # fmt: skip
        ell = L + F * math.sin(phi) / Ka
        d = _equilibrium(L, Ka, kphi, F, [L, -0.1 * L])
        assert math.atan2(-d[1], d[0]) == pytest.approx(phi, rel=1e-9)
        assert math.hypot(*d) == pytest.approx(ell, rel=1e-12)


# ---- eq 27 (μ·max(P, 0)) in the agent model ------------------------------------------------

STUBBY = PAPER_ARRAY.replace(**{"array.count": 20, "seta.L": 5.0, "floor.sigma": 0.3})  # linear
PAPER_FRICTION = {"friction.mu": 0.2, "friction.law": "paper"}


def test_paper_friction_agent_matches_quasistatic():
    """The paper's friction law (eq 27) run in the agent model (20 stubby linear setae, rough
    floor, μ = 0.2, pressed 1.5 µm) against the quasi-static solver on the same pads and plate
    path. The adhesive cap μ|P + 2Fc| or μ = 0 in either one would show: on this run the
    quasi-static retraction curves of the three laws differ by a median 16 µN (adhesive) and
    the tangential force by 1.6 µN (μ = 0), against the 0.7 µN and 0.1 µN the agent lags the
    paper-law curve by at 0.02 µm/µs (tests/test_model.py's rough-floor comparison)."""
    p = STUBBY.replace(**PAPER_FRICTION)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(p, record_setae=True)
        h = m.run(protocol.press_pull(1.5, speed=0.02), progress=False)
    sub = 10
    y = h["plate_y_um"]
    y_dense = np.interp(np.arange((len(y) - 1) * sub + 1) / sub, np.arange(len(y)), y)
    q = qs.solve(p, m.profile.pad_heights, y_dense, tangential_stiffness=m.k_t)
    # Dynamic lag at 0.02 µm/µs: 1.3 % on the peak here, 2 % allowed as in test_model.
    assert h.peak_pull_off == pytest.approx(q.pull_off, rel=0.02)
    turn = int(np.argmin(y))
    err = np.abs(h["force_normal_uN"] - q.force_normal[::sub])[turn:]
    # Retraction: the median step within 2 % of the peak (a release a step late is a jump).
    assert np.median(err) < 0.02 * q.pull_off
    # The shear the tips hold through their inclined setae, as large as the solver's (the
    # record's maximum, within 10 %: the agent's seta rings after each jump-in).
    Ft, Ft_qs = np.abs(h["force_tangential_uN"]).max(), np.abs(q.force_tangential).max()
    assert Ft_qs > 1.0 and Ft == pytest.approx(Ft_qs, rel=0.1)
    # Eq 27: a tip in tension holds no shear, so no tip is seen sticking with P < 0 (the
    # adhesive cap holds 424 of 448 sticking records in tension on this floor at 0.5 µm).
    P, state = h.setae["force_normal_uN"], h.setae["state"]
    assert not np.any((state == STATE_STICK) & (P < -1e-9))
    assert np.any(state == STATE_SLIP)


@pytest.mark.parametrize("kernel", ["numpy", "python"])
def test_sliding_dissipates_the_paper_coulomb_work(kernel):
    """One rod seta pressed 1.5 µm and dragged 8 µm under eq 27: a tip in tension holds no
    shear, so it slides from its jump-in on; once the jump-in has rung down (the second half of
    the drag) friction dissipates Σ μ·max(P, 0)·Δx, nothing more. The trapezoid over records
    5 steps apart at a steady P is exact to rounding; 0.2 % as the adhesive-law test in
    tests/test_model.py.

    dt is a quarter of the default: the jump-in snap (kinetic energy ~30 % of the contact's
    energy within a few steps) books its energy with a lag first order in dt (9 % of the run's
    energy scale at the default dt with records every step, 2 % at dt/4), which the suite's
    invariant check (conftest.py) would flag; the steady slide balances to 1e-4."""
    p = PAPER_TABLE1.replace(**{"mechanics": "rod", "seta.L": 5.0, **PAPER_FRICTION})
    dt = Model(p, numerics=Numerics(kernel=kernel)).dt / 4
    m = Model(p, record_setae=True, numerics=Numerics(kernel=kernel, record_every=20, dt=dt))
    h = m.run([protocol.PressTo(1.5, 0.05), protocol.Move(dx=8.0, speed=0.1)], progress=False)
    state = h.setae["state"][:, 0]
    k = np.arange(len(state) // 2, len(state) - 1)
    assert np.all(state[k] == STATE_SLIP), "the tip must slide steadily"
    x, P = h.setae["tip_x_um"][k, 0], h.setae["force_normal_uN"][k, 0]
    assert P.min() > 0  # pressed: eq 27's cap is μP here, not μ|P + 2Fc|
    cap = 0.2 * np.maximum(P, 0.0)
    coulomb = np.sum(0.5 * (cap[1:] + cap[:-1]) * np.diff(x))
    dissipated = h["energy_dissipated_pJ"][k[-1]] - h["energy_dissipated_pJ"][k[0]]
    assert x[-1] - x[0] > 3.0
    assert dissipated == pytest.approx(coulomb, rel=2e-3)
    # The adhesive cap μ|P + 2Fc| would dissipate (P + 2Fc)/P ≈ 20 times more here.
    Fc = p.contact.pull_off_force
    assert np.mean(P + 2 * Fc) / np.mean(P) > 10
