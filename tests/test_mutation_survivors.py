"""Tests that kill the mutants of the physics modules that survived the suite (tools/mutation.sh),
each against an oracle of its own: a compliance written out, a finite-difference stiffness, a
clipped branch, the crack law's step written out.

mutmut 3.8 on physics/{jkr,beam,friction,savkoor_briggs} and contact/{jkr_sphere,hertz,
rate_jkr,base}: 1675 mutants, 1469 killed and 29 timeouts by the suite, 177 survivors; these
tests kill 85 of them (each applied with ``mutmut apply`` and this file run against it). The
92 left change no physics:
- 18 ``np.asarray(x, dtype=float)`` → default dtype: every caller passes floats;
- 12 ``out=`` buffers dropped in JKRSphere.radius and 4 ``zip(strict=)`` flags: same values;
- 25 in the Newton step that polishes Ferrari's root (jkr.radius_from_overlap, JKRSphere.radius,
  base.branch_radius): the closed form alone is within 4e-15 of eq 10 from δc to 5 µm, so the
  step only guards rounding;
- boundaries of measure zero (``>`` ↔ ``>=`` at δ = δc, δ = 0, g = 0, G = w, a = a_eq,
  disc = 0, dG = 0, step = 0.1a), an unused default ``dt``, an extra constants slot, the
  ``getattr`` default of ``detachment`` (a Contact always has one), a_eq's initial value when no
  branch exists (never read), K_U_JUMP computed at another δ (the sphere's energy_scalar does
  not read δ), the Δφ wrap shifted by 2π, the text of an error message;
- RateJKRSphere.radius_scalar's clip of an opening step to a_eq (mutmut_105/106): the linearly
  implicit step did not pass a_eq in any state tried; not shown equivalent.
mutmut skips decorated functions (friction.stick_stiffness, friction.friction_cap,
base.branch_radius are @jitable): their mutants were planted by hand (8G*a → 4G*a, 2Fc → Fc,
max(P, 0) → |P|, (2 − ν) → (2 + ν), the clip and scale of branch_radius) and are killed by
tests/test_oracles_hand.py and tests/test_quasistatic.py, except the Newton polish above."""

import dataclasses
import math

import numpy as np
import pytest

from gecko_agents.contact import HertzSphere, JKRSphere
from gecko_agents.params import PAPER_TABLE1
from gecko_agents.physics import beam, jkr


def test_deflection_ratio_is_the_written_out_compliance_for_any_direction_and_forces():
    """K = Ka·n nᵀ + Kp·t tᵀ with n ⟂ t unit vectors, so K⁻¹ = n nᵀ/Ka + t tᵀ/Kp: a force F
    along the unit vector e moves the tip by F·(n(n·e)/Ka + t(t·e)/Kp). The direction need
    not be normalised and forces may be an array (one ratio each)."""
    Ka, Kp, th, L = 0.5, 0.002, math.radians(30.0), 20.0
    n = np.array([math.cos(th), -math.sin(th)])
    t = np.array([math.sin(th), math.cos(th)])
    for direction in ((0.0, 3.0), (2.0, -1.0), (-0.3, 0.4)):
        e = np.asarray(direction) / math.hypot(*direction)
        forces = np.array([1e-3, 0.02, 1.5])
        per_force = np.linalg.norm(n * (n @ e) / Ka + t * (t @ e) / Kp)
        got = beam.deflection_ratio(forces, Ka, Kp, th, L, direction=direction)
        assert got.shape == forces.shape
        np.testing.assert_allclose(got, forces * per_force / L, rtol=1e-12)


C = PAPER_TABLE1.contact
R, W, E = C.jkr_args()


def test_hertz_law_scales_are_hertz_closed_forms():
    """The Hertz tip's reference radius is Hertz's under the JKR law's Fc = 1.5πRw,
    a = (3R·Fc/(4E*))^(1/3); its damping and time-step stiffnesses are dP/dδ = 2E*·a of
    P = (4/3)E*√R·δ^(3/2) (checked by central differences at the matching overlap a²/R);
    it touches with zero radius."""
    law = HertzSphere(C)
    Fc = 1.5 * math.pi * R * W
    a_ref = (3 * R * Fc / (4 * E)) ** (1 / 3)
    assert law.a0 == pytest.approx(a_ref, rel=1e-12)
    assert law.jump_radius == 0.0 and law.pull_off_force == 0.0

    def dP_ddelta(delta, h=1e-7):
        return (jkr.hertz_force(delta + h, R, E) - jkr.hertz_force(delta - h, R, E)) / (2 * h)

    assert law.zero_load_stiffness == pytest.approx(dP_ddelta(a_ref**2 / R), rel=1e-6)
    for load in (0.3, 3.0, 30.0):
        a = (3 * R * load / (4 * E)) ** (1 / 3)
        assert law.stiffest(load) == pytest.approx(dP_ddelta(a * a / R), rel=1e-6)


def test_jkr_law_radius_is_clipped_at_the_end_of_the_branch():
    """Below δc no contact exists; the law's vectorized radius, like
    :func:`jkr.radius_from_overlap`, returns the radius at δc, a_c = (πwR²/(8E*))^(1/3)."""
    law = JKRSphere(C)
    dc = -0.75 * (math.pi**2 * W**2 * R / E**2) ** (1 / 3)
    a_c = (math.pi * W * R * R / (8 * E)) ** (1 / 3)
    d = np.array([1.5 * dc, 3.0 * dc, dc])
    np.testing.assert_allclose(law.radius(d.copy()), a_c, rtol=1e-7)
    np.testing.assert_allclose(jkr.radius_from_overlap(d, R, W, E), a_c, rtol=1e-7)


def test_linear_spring_force_is_minus_k_u_and_its_energy_the_quadratic_form():
    """F = −K·u (eq 20–21's 2×2 K, K symmetric) and E = ½uᵀKu, with F = −∇E (central
    differences, exact for a quadratic up to rounding)."""
    K = beam.stiffness_matrix(0.5, 0.002, math.radians(60.0))
    u = np.random.default_rng(7).uniform(-2.0, 2.0, (25, 2))
    F, energy = beam.linear_spring_force(u, K)
    np.testing.assert_allclose(F, -(u @ K.T), rtol=1e-13, atol=1e-16)
    np.testing.assert_allclose(energy, 0.5 * np.einsum("ni,ij,nj->n", u, K, u), rtol=1e-13)
    h = 1e-6
    for axis in (0, 1):
        e = np.zeros(2)
        e[axis] = h
        _, Ep = beam.linear_spring_force(u + e, K)
        _, Em = beam.linear_spring_force(u - e, K)
        np.testing.assert_allclose(F[:, axis], -(Ep - Em) / (2 * h), rtol=1e-7, atol=1e-12)


@pytest.mark.parametrize("v_close", [math.inf, 0.5])
def test_rate_law_closes_its_edge_onto_the_jkr_branch_when_pressed(v_close):
    """A crack-kinetics tip pressed to δ > 0 from a radius below JKR's there (G < w, the edge
    closing): at an infinite closing speed it takes the equilibrium radius at once; at a finite
    one it grows by dt·v_close·((w − G)/w)^(1/n), never past equilibrium (Maugis 2000 ch 5,
    the law's docstring)."""
    from gecko_agents.contact import RateJKRSphere

    law = RateJKRSphere(dataclasses.replace(C, crack_speed=0.05, crack_closing_speed=v_close))
    delta = 0.4
    a_eq = float(jkr.radius_from_overlap(delta, R, W, E))
    a_prev, dt = 0.6 * a_eq, 0.01
    a_new = law.radius_scalar(delta, a_prev, dt, law.constants)
    assert law.radius(np.array([delta]), np.array([a_prev]), dt)[0] == a_new
    if math.isinf(v_close):
        assert a_new == pytest.approx(a_eq, rel=1e-12)
    else:
        g = a_prev**2 / R - delta
        G = E * g * g / (2 * math.pi * a_prev)
        expected = a_prev + dt * v_close * ((W - G) / W) ** (1 / law.n_exp)
        assert G < W and expected < a_eq
        assert a_new == pytest.approx(expected, rel=1e-12)


def _rate_law(v_close=math.inf):
    from gecko_agents.contact import RateJKRSphere

    return RateJKRSphere(dataclasses.replace(C, crack_speed=0.05, crack_closing_speed=v_close))


@pytest.mark.parametrize("side", [-1.0, 1.0])
def test_rate_law_opens_exactly_where_g_exceeds_w(side):
    """At radius a the edge is in equilibrium (G = w) at δ_eq = a²/R − √(2πwa/E*) (eq 10);
    pulled 0.1 % of that gap further (G > w) it opens and the radius falls, pressed as much
    (G < w) it closes at the closing speed: a + dt·v_close·((w − G)/w)^(1/n)."""
    law = _rate_law(0.5)
    a, dt = 2.0, 0.01
    gap = math.sqrt(2 * math.pi * W * a / E)
    delta = a * a / R - gap * (1 + side * 1e-3)  # side −1: pressed, +1: pulled
    a_new = law.radius_scalar(delta, a, dt, law.constants)
    if side > 0:
        assert a_new < a
    else:
        G = E * (a * a / R - delta) ** 2 / (2 * math.pi * a)
        closing = a + dt * 0.5 * ((W - G) / W) ** (1 / law.n_exp)
        assert a < closing < float(jkr.radius_from_overlap(delta, R, W, E))
        assert a_new == pytest.approx(closing, rel=1e-12)


def test_rate_law_opening_step_is_linearly_implicit_euler():
    """An opening edge takes one Newton step of backward Euler on ȧ = −v*·((G − w)/w)^(1/n):
    a_new = a − dt·v*·x^(1/n)/(1 + dt·v*·(1/n)·x^(1/n − 1)·G'(a)/w), x = (G − w)/w, with
    G(a) = E*(a²/R − δ)²/(2πa) and G'(a) here by central differences (Maugis 2000 ch 5; the
    law's docstring)."""
    law = _rate_law()
    a, delta, dt = 2.0, -0.2, 0.05
    inv_n = 1.0 / law.n_exp

    def G(x):
        return E * (x * x / R - delta) ** 2 / (2 * math.pi * x)

    h = 1e-6
    dG = (G(a + h) - G(a - h)) / (2 * h)
    x = (G(a) - W) / W
    assert x > 0 and dG > 0
    v = law.v_star
    expected = a - dt * v * x**inv_n / (1 + dt * v * inv_n * x ** (inv_n - 1) * dG / W)
    assert a - expected < 0.1 * a  # a resolved step, not a snap-off
    assert law.radius_scalar(delta, a, dt, law.constants) == pytest.approx(expected, rel=1e-9)


def test_rate_law_snaps_off_on_an_unresolved_step_and_runs_free_below_delta_c():
    """A step that would shrink the radius by more than 10 % is a snap-off (a = 0); below δc
    (no equilibrium radius) a resolved opening step is not clipped to any branch: it is the
    same linearly implicit Euler step (law's docstring)."""
    law = _rate_law()
    inv_n, v = 1.0 / law.n_exp, law.v_star
    # Small and pulled hard (δ < −3a²/R: G'(a) < 0, an explicit step, the edge running away):
    a, delta, dt = 0.3, -0.5, 10.0
    g = a * a / R - delta
    x = (E * g * g / (2 * math.pi * a) - W) / W
    assert 3 * a * a / R + delta < 0 and dt * v * x**inv_n > 0.1 * a
    assert law.radius_scalar(delta, a, dt, law.constants) == 0.0
    assert law.radius_scalar(delta, a, 1e-4 * dt, law.constants) > 0.9 * a  # resolved: no
    a, delta, dt = 0.8, 1.5 * law.delta_c, 1e-4  # below δc: no branch radius exists
    g = a * a / R - delta
    G = E * g * g / (2 * math.pi * a)
    dG = E * g * (3 * a * a / R + delta) / (2 * math.pi * a * a)  # d/da of G, by hand
    x = (G - W) / W
    step = dt * v * x**inv_n
    if dG > 0:
        step /= 1 + dt * v * inv_n * x ** (inv_n - 1) * dG / W
    assert 0 < step < 0.1 * a
    assert law.radius_scalar(delta, a, dt, law.constants) == pytest.approx(a - step, rel=1e-12)


def test_rate_law_closes_at_once_when_its_edge_is_compressed_and_never_past_equilibrium():
    """g = a²/R − δ ≤ 0 (edge in compression) closes onto the branch at once, at any closing
    speed; a closing step that would pass the equilibrium radius stops on it."""
    law = _rate_law(0.5)
    a_prev, delta = 1.0, 0.5  # g = 0.25 − 0.5 < 0
    a_eq = float(jkr.radius_from_overlap(delta, R, W, E))
    assert law.radius_scalar(delta, a_prev, 1e-3, law.constants) == pytest.approx(a_eq, rel=1e-12)
    a_prev, delta = 1.5, 0.4  # g > 0 but G < w: a slow closing, here over a long step
    a_eq = float(jkr.radius_from_overlap(delta, R, W, E))
    assert law.radius_scalar(delta, a_prev, 1e4, law.constants) == pytest.approx(a_eq, rel=1e-12)


def test_rate_law_constants_and_attachment_energy():
    """Its release radius is 1 % of a0 and its backstop detachment 20·δc (law docstring);
    the energy of a JKR tip is zero where it attaches (a_j at δ = 0)."""
    law = _rate_law()
    a0 = (4.5 * math.pi * W * R * R / E) ** (1 / 3)
    dc = -0.75 * (math.pi**2 * W**2 * R / E**2) ** (1 / 3)
    assert law.release_radius == pytest.approx(0.01 * a0, rel=1e-12)
    assert law.detach_overlap == pytest.approx(20.0 * dc, rel=1e-12)
    for tip in (JKRSphere(C), law):
        e = tip.energy(np.array([tip.jump_radius]), np.array([0.0]))
        assert e == pytest.approx(0.0, abs=1e-12)
        e = tip.energy_scalar(tip.jump_radius, 0.0, tip.constants)  # the kernels' form
        assert e == pytest.approx(0.0, abs=1e-12)


def test_rod_rotation_is_wrapped_to_the_shorter_way_round():
    """A rod tip carried past the half turn (here 210° from rest, counter-clockwise) is a
    rotation of −150°: E = ½kφ(150°)² (Δφ wrapped into (−π, π])."""
    th, L, kphi = math.radians(60.0), 5.0, 0.7
    ang = -th + math.radians(210.0)
    d = np.array([[L * math.cos(ang), L * math.sin(ang)]])
    _, energy = beam.rod_spring_force(d, L, 2.0, kphi, th)
    assert energy[0] == pytest.approx(0.5 * kphi * math.radians(150.0) ** 2, rel=1e-12)
