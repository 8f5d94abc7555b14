"""JKR functions against closed-form oracles (Johnson et al. 1971; Maugis 2000)."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gecko_agents.physics import jkr

R, W, ES = 4.0, 0.08, 1.553  # µm, µN/µm, MPa (the Fig 5 reading)
FC = 1.5 * np.pi * R * W


def test_effective_modulus_and_work_of_adhesion():
    # Rigid floor: E* = E1/(1-ν1²); identical bodies: E* = E/(2(1-ν²)).
    assert_allclose(jkr.effective_modulus(1.0, 0.3, np.inf, 0.25), 1.0 / 0.91)
    assert_allclose(jkr.effective_modulus(2.0, 0.5, 2.0, 0.5), 2.0 / (2 * 0.75))
    assert_allclose(jkr.work_of_adhesion(0.04, 0.17), 2 * np.sqrt(0.04 * 0.17))
    assert_allclose(jkr.work_of_adhesion(0.04, 0.04), 0.08)


def test_pull_off_force_closed_form_and_independent_of_modulus():
    assert_allclose(jkr.pull_off_force(R, W), 1.5 * np.pi * R * W)
    # Minimum of eq 7 over a, found numerically, equals −Fc for any E*.
    for es in (0.1, 1.0, 10.0):
        a = np.linspace(1e-4, 5, 400_001)
        assert_allclose(jkr.force_from_radius(a, R, W, es).min(), -FC, rtol=1e-8)


def test_special_points():
    a0 = jkr.zero_load_contact_radius(R, W, ES)
    assert_allclose(jkr.force_from_radius(a0, R, W, ES), 0.0, atol=1e-12)
    assert_allclose(jkr.overlap_from_radius(a0, R, W, ES), a0**2 / (3 * R))
    # Load-controlled pull-off: a = 0.63 a0 and P = −Fc.
    a_lc = jkr.contact_radius_from_force(-FC, R, W, ES)
    # Eq 8 at P = −Fc takes √ of 6πwRP + (3πwR)², zero but for rounding (~1e-16 of (3πwR)²),
    # which the root lifts to ~1e-8 of 3πwR: measured exact here, allowed 1e-7.
    assert_allclose(a_lc / a0, 0.25 ** (1 / 3), rtol=1e-7)
    assert abs(a_lc / a0 - 0.63) < 0.001
    # Displacement-controlled end: δc, a = 0.303 a0, P = −5/9 Fc; δc is the minimum of eq 10.
    ac = jkr.snap_off_radius(R, W, ES)
    assert abs(ac / a0 - 0.303) < 0.001
    dc = jkr.snap_off_overlap(R, W, ES)
    a = np.linspace(1e-5, 3, 300_001)
    assert_allclose(jkr.overlap_from_radius(a, R, W, ES).min(), dc, rtol=1e-8)
    assert_allclose(jkr.overlap_from_radius(ac, R, W, ES), dc, rtol=1e-12)
    assert_allclose(jkr.force_from_radius(ac, R, W, ES), -5 / 9 * FC, rtol=1e-12)
    assert_allclose(jkr.force_from_overlap(dc, R, W, ES), -5 / 9 * FC, rtol=1e-9)
    # Jump-in at zero overlap: P = −8/9 Fc.
    assert_allclose(jkr.force_from_overlap(0.0, R, W, ES), -8 / 9 * FC, rtol=1e-10)
    # δc = −0.275 a0²/R (docs/physics.md, "JKR contact of a sphere tip").
    assert_allclose(dc * R / a0**2, -0.75 * (np.pi**2 * W**2 * R / ES**2) ** (1 / 3) * R / a0**2)
    assert abs(dc * R / a0**2 + 0.275) < 0.001


def test_round_trips():
    a = np.geomspace(0.01, 50, 2001)
    P = jkr.force_from_radius(a, R, W, ES)
    stable = a >= jkr.contact_radius_from_force(-FC, R, W, ES)
    assert_allclose(jkr.contact_radius_from_force(P[stable], R, W, ES), a[stable], rtol=1e-10)
    ac = jkr.snap_off_radius(R, W, ES)
    a = ac * np.geomspace(1.001, 1e3, 2001)
    d = jkr.overlap_from_radius(a, R, W, ES)
    assert_allclose(jkr.radius_from_overlap(d, R, W, ES), a, rtol=1e-10)


def test_force_from_overlap_accuracy_on_whole_branch():
    ac = jkr.snap_off_radius(R, W, ES)
    a = ac * np.concatenate([1 + np.geomspace(1e-8, 1e-2, 500), np.geomspace(1.01, 1e4, 5000)])
    d = jkr.overlap_from_radius(a, R, W, ES)
    P = jkr.force_from_radius(a, R, W, ES)
    err = np.abs(jkr.force_from_overlap(d, R, W, ES) - P) / np.maximum(FC, np.abs(P))
    # dP/dδ → ∞ at δc, so within a/ac − 1 < 1e-4 a rounding of δ alone moves P by ~√eps:
    # there the bound is the problem's conditioning, elsewhere 1e-9.
    near = a / ac - 1 < 1e-4
    assert err[~near].max() < 1e-9
    assert err[near].max() < 1e-7
    # Along the branch P falls from −5/9 Fc at δc to −Fc at the load-control point, then rises.
    d_lc = jkr.overlap_from_radius(
        0.25 ** (1 / 3) * jkr.zero_load_contact_radius(R, W, ES), R, W, ES
    )
    x = np.linspace(jkr.snap_off_overlap(R, W, ES), d_lc, 1001)
    assert np.all(np.diff(jkr.force_from_overlap(x, R, W, ES)) < 0)
    assert_allclose(jkr.force_from_overlap(d_lc, R, W, ES), -FC, rtol=1e-9)
    x = np.linspace(d_lc, 3.0, 10_001)[1:]
    assert np.all(np.diff(jkr.force_from_overlap(x, R, W, ES)) > 0)


def test_hertz_limit_as_adhesion_vanishes():
    d = np.linspace(0.01, 1.0, 50)
    for w in (1e-6, 1e-9):
        P = jkr.force_from_overlap(d, R, w, ES)
        # At a fixed overlap the √w terms of eq 7 and eq 10 cancel (the Hertz force's change
        # with the shifted radius, 2√(2πwE*a³), is the adhesive term √(8πwE*a³)), so P departs
        # from Hertz at first order in w: measured 3.1e3·w at the smallest overlap (0.01 µm).
        assert_allclose(P, jkr.hertz_force(d, R, ES), rtol=4e3 * w)
    P = np.linspace(0.1, 10, 20)
    assert_allclose(jkr.hertz_overlap(P, R, ES), (3 * R * P / (4 * ES)) ** (2 / 3) / R)
    # Pressure integrates to the load (eq 3).
    r = np.linspace(0, jkr.hertz_contact_radius(2.0, R, ES), 200_001)
    total = np.trapezoid(2 * np.pi * r * jkr.hertz_pressure(r, 2.0, R, ES), r)
    # The trapezoid rule on √(1 − r²/a²), whose slope is infinite at r = a: error ∝ N^(−3/2),
    # 1.1e-8 for N = 2·10⁵ (measured 9.9e-9).
    assert_allclose(total, 2.0, rtol=3e-8)


def test_scaling_laws():
    dc = jkr.snap_off_overlap(R, W, ES)
    assert_allclose(jkr.snap_off_overlap(R, 8 * W, ES), dc * 4)  # ∝ w^(2/3)
    assert_allclose(jkr.snap_off_overlap(R, W, 8 * ES), dc / 4)  # ∝ E*^(-2/3)
    assert_allclose(jkr.snap_off_overlap(8 * R, W, ES), dc * 2)  # ∝ R^(1/3)
    # At fixed load, a ∝ E*^(-1/3) exactly: a³ = (3R/(4E*))(P + 3πwR + √(6πwRP + (3πwR)²))
    # (eq 8) and the bracket is free of E*, so only rounding separates the two sides.
    assert_allclose(
        jkr.contact_radius_from_force(1.0, R, W, 8 * ES),
        jkr.contact_radius_from_force(1.0, R, W, ES) / 2,
        rtol=1e-13,
    )
    a1 = jkr.zero_load_contact_radius(R, W, ES)
    assert_allclose(jkr.zero_load_contact_radius(R, W, 1000 * ES), a1 / 10)


def test_dimensionless_forms_match_dimensional():
    a = np.linspace(0.05, 5, 100)
    a_s = jkr.dimensionless_radius(a, R, W, ES)
    assert_allclose(
        jkr.dimensionless_force_from_radius(a_s),
        jkr.dimensionless_force(jkr.force_from_radius(a, R, W, ES), R, W),
        rtol=1e-10,
        atol=1e-12,
    )
    assert_allclose(
        jkr.dimensionless_overlap_from_radius(a_s),
        jkr.dimensionless_overlap(jkr.overlap_from_radius(a, R, W, ES), R, W, ES),
        rtol=1e-10,
        atol=1e-12,
    )
    # Dimensionless pull-off is −1.5 (eq 11 with Fc = 1.5πRw).
    assert_allclose(jkr.dimensionless_force(-FC, R, W), -1.5)


def test_contact_stiffness_signs():
    a0 = jkr.zero_load_contact_radius(R, W, ES)
    a_lc = 0.25 ** (1 / 3) * a0
    assert abs(jkr.contact_stiffness(a_lc, R, W, ES)) < 1e-9
    assert jkr.contact_stiffness(0.5 * a0, R, W, ES) < 0
    # Hertz limit 2E*a for large a, with its adhesive correction: expanding eq 7 and eq 10,
    # dP/dδ = 2E*a·(1 − (1/3)(a0/a)^(3/2) + O((a0/a)³)) (a0³ = 9πwR²/(2E*)): −3.33e-4 at 100 a0,
    # the next term ~1e-6.
    k = jkr.contact_stiffness(100 * a0, R, W, ES) / (2 * ES * 100 * a0)
    assert_allclose(k - 1.0, -(1 / 3) * 100 ** (-1.5), atol=2e-6)
    # Numerical derivative of the inverted curve.
    d = np.array([0.0, 0.2, 1.0])
    h = 1e-6
    f = jkr.force_from_overlap
    num = (f(d + h, R, W, ES) - f(d - h, R, W, ES)) / (2 * h)
    ana = jkr.contact_stiffness(jkr.radius_from_overlap(d, R, W, ES), R, W, ES)
    # Central difference: h²·P‴/6 ~ 1e-12 plus rounding ~1e-16·|P|/h ~ 1e-10 (measured
    # 7e-11–2.4e-10).
    assert_allclose(num, ana, rtol=1e-8)


def test_load_below_pull_off_is_refused():
    with pytest.raises(ValueError, match="pull-off"):
        jkr.contact_radius_from_force(-1.1 * FC, R, W, ES)


def test_contact_energy_is_the_integral_of_force():
    d = np.linspace(jkr.snap_off_overlap(R, W, ES), 2.0, 200_001)
    P = jkr.force_from_overlap(d, R, W, ES)
    a = jkr.radius_from_overlap(d, R, W, ES)
    U = jkr.contact_energy(a, R, W, ES)
    num = np.concatenate([[0], np.cumsum(0.5 * (P[1:] + P[:-1]) * np.diff(d))])
    assert_allclose(U, num - np.interp(0.0, d, num), atol=1e-6 * FC * abs(d[0]))
    assert abs(jkr.contact_energy(jkr.radius_from_overlap(0.0, R, W, ES), R, W, ES)) < 1e-12
