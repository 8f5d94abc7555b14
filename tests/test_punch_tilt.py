"""The flat punch under a moment (a tilted pillar end): its pressure, edge stress intensity,
rotational stiffness and pull-off (:mod:`gecko_agents.physics.punch`) against independent
numerical integrals, the aligned limit (Kendall 1971) and the model's own elastica."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from gecko_agents.physics import punch
from gecko_agents.physics.elastica import Elastica

A, W, E_STAR = 1.5, 0.04, 2.0  # µm, µN/µm, MPa
P, M = -1.3, 0.7  # µN (tensile), µN·µm


def test_zero_moment_recovers_kendall_exactly():
    F_K = punch.kendall_pull_off(A, W, E_STAR)
    assert punch.tilted_pull_off(A, W, E_STAR, 0.0) == F_K
    assert punch.tilt_pull_off(A, W, E_STAR, 0.0) == F_K
    # K²/(2E*) at M = 0 is Kendall's edge release rate (rounding only)
    K = punch.edge_stress_intensity(-F_K, 0.0, A)
    assert K**2 / (2 * E_STAR) == pytest.approx(punch.edge_release_rate(F_K, A, E_STAR), 1e-12)
    assert K**2 / (2 * E_STAR) == pytest.approx(W, rel=1e-12)


def _disk_integral(f):
    """∫∫ f(r, θ) r dr dθ over the face, with r = a·sin β removing the edge's 1/√(a² − r²)."""

    def inner(theta):
        def g(beta):
            r = A * math.sin(beta)
            return f(r, theta) * r * A * math.cos(beta)

        return integrate.quad(g, 0.0, math.pi / 2, epsabs=1e-13, epsrel=1e-12)[0]

    return integrate.quad(inner, 0.0, 2 * math.pi, epsabs=1e-13, epsrel=1e-12)[0]


def test_pressure_integrates_to_the_force_and_the_moment():
    def p(r, t):
        return punch.tilted_punch_pressure(r, t, P, M, A)

    # quadrature of a smooth integrand after the substitution: error far below 1e-9
    assert _disk_integral(p) == pytest.approx(P, rel=1e-9)
    assert _disk_integral(lambda r, t: p(r, t) * r * math.cos(t)) == pytest.approx(M, rel=1e-9)
    assert _disk_integral(lambda r, t: p(r, t) * r * math.sin(t)) == pytest.approx(0, abs=1e-9)


@pytest.mark.parametrize("theta", [0.0, 1.0, math.pi / 2, 2.5, math.pi])
def test_edge_K_is_the_limit_of_the_pressure_field(theta):
    # −p·√(2πs) at s = a − r → 0; at s = 1e-7·a each term of the field differs from its limit
    # by O(s/a) relative (√(a² − r²) = √(2as)·(1 − s/4a + …), r = a − s): 1e-6 of the larger
    # term's scale allows that (the two terms nearly cancel at θ = 0) and rounding.
    s = 1e-7 * A
    limit = -punch.tilted_punch_pressure(A - s, theta, P, M, A) * math.sqrt(2 * math.pi * s)
    K = punch.edge_stress_intensity(P, M, A, theta)
    scale = (abs(P) + 3 * abs(M) / A) / (2 * A * math.sqrt(math.pi * A))
    assert limit == pytest.approx(K, rel=0, abs=1e-6 * scale)


def test_mean_edge_release_rate_is_the_compliance_release_rate():
    """Averaged round the edge, K²/(2E*) is the energy the face's compliances release per unit
    area as its radius shrinks at fixed P and M: U* = P²/(2k_n) + M²/(2k_r), G = −∂U*/∂A with
    Sneddon's k_n = 2E*a and k_r = 4E*a³/3 — an energy oracle independent of the K formula."""

    def U(a):
        k_n, k_r = punch.punch_stiffness(a, E_STAR), punch.punch_rotation_stiffness(a, E_STAR)
        return P**2 / (2 * k_n) + M**2 / (2 * k_r)

    h = 1e-5  # central difference: O(h²) ≈ 1e-10 relative
    G_compliance = -(U(A + h) - U(A - h)) / (2 * h) / (2 * math.pi * A)
    mean = integrate.quad(
        lambda t: punch.edge_stress_intensity(P, M, A, t) ** 2 / (2 * E_STAR), 0, 2 * math.pi
    )[0] / (2 * math.pi)
    assert mean == pytest.approx(G_compliance, rel=1e-8)  # FD error ~1e-10, quad ~1e-14


def _boussinesq_displacement(x0, y0):
    """u(x0, y0) = (1/πE*)∫∫ p dA/|x − ξ| over the face, in polar coordinates about the field
    point (ds·dψ: the 1/|x − ξ| cancels); the edge's 1/√(s_max − s) is quad's 'alg' weight."""
    xy2 = x0 * x0 + y0 * y0

    def along(psi):
        c, sn = math.cos(psi), math.sin(psi)
        b = x0 * c + y0 * sn
        root = math.sqrt(b * b + A * A - xy2)
        s_max, s_other = root - b, root + b  # a² − ρ² = (s_max − s)(s + s_other)

        def f(s):
            x = x0 + s * c
            return (P + 3 * M * x / A**2) / (2 * math.pi * A * math.sqrt(s + s_other))

        return integrate.quad(f, 0.0, s_max, weight="alg", wvar=(0.0, -0.5), epsabs=1e-13)[0]

    return integrate.quad(along, 0.0, 2 * math.pi, epsabs=1e-13, epsrel=1e-11, limit=200)[0] / (
        math.pi * E_STAR
    )


@pytest.mark.parametrize("x0, y0", [(0.0, 0.0), (0.7, 0.0), (-1.1, 0.4), (0.3, -1.2)])
def test_boussinesq_displacement_of_the_pressure_is_a_rigid_tilted_face(x0, y0):
    # The pressure field makes the surface under the face flat and turned: u = δ + α·x with
    # Sneddon's δ = P/(2E*a) and α = M/k_r. The quadrature's error is ≲ 1e-9 relative.
    alpha = M / punch.punch_rotation_stiffness(A, E_STAR)
    expected = P / punch.punch_stiffness(A, E_STAR) + alpha * x0
    assert _boussinesq_displacement(x0, y0) == pytest.approx(expected, rel=1e-7, abs=1e-10)


def test_pull_off_falls_with_moment_and_tilt_and_vanishes_where_stated():
    F_K = punch.kendall_pull_off(A, W, E_STAR)
    Ms = np.linspace(0.0, A * F_K / 3, 9)
    F = punch.tilted_pull_off(A, W, E_STAR, Ms)
    assert np.all(np.diff(F) < 0) and F[-1] == pytest.approx(0.0, abs=1e-12)
    assert np.array_equal(F, punch.tilted_pull_off(A, W, E_STAR, -Ms))  # either edge
    alpha0 = math.sqrt(math.pi * W / (2 * E_STAR * A))  # the tilt that leaves no pull-off
    alphas = np.linspace(0.0, alpha0, 9)
    Fa = punch.tilt_pull_off(A, W, E_STAR, alphas)
    assert np.all(np.diff(Fa) < 0) and Fa[-1] == pytest.approx(0.0, abs=1e-12)
    # at the pull-off the most opened edge meets Griffith: K²/(2E*) = w (rounding only)
    K = punch.edge_stress_intensity(-F[3], Ms[3], A)
    assert K**2 / (2 * E_STAR) == pytest.approx(W, rel=1e-12)


def test_lateral_load_moment_limits():
    Q, L, EI = 0.2, 15.0, 3.0
    assert punch.lateral_load_moment(Q, L, EI, np.inf) == pytest.approx(Q * L / 2, rel=1e-15)
    assert punch.lateral_load_moment(Q, L, EI, 1e-12) == pytest.approx(0.0, abs=1e-9)
    k_r = EI / L  # face as stiff as the pillar: the moment is halved
    assert punch.lateral_load_moment(Q, L, EI, k_r) == pytest.approx(Q * L / 4, rel=1e-15)


@pytest.mark.parametrize("links", [16, 32])
def test_elastica_clamped_face_carries_the_guided_cantilever_moment(links):
    """The model's pillar (bar-chain elastica, its bonded face clamped rigidly) pushed sideways
    carries the face moment QL/2 of :func:`punch.lateral_load_moment` at k_r → ∞."""
    L = 15.0
    e = Elastica(1, L, 1.5, 1.413, math.pi / 2, links=links)
    d0 = e.rest_end()[None, :]
    e.solve(d0, True)  # the face bonds at rest: the clamp holds that direction
    e.solve(d0 + [[0.01, 0.0]], True)
    Q = e.lam[0, 0]  # lateral force on the chain's end [µN]
    M_face = e.face_moment()[0]
    # 1e-3 allows the crooked rest shape (imperfection 1e-3·L) and the chain's geometric
    # nonlinearity at u/L = 7e-4 (measured 9e-5 off at 16 and 32 links)
    assert M_face == pytest.approx(punch.lateral_load_moment(Q, L, 1.0, np.inf), rel=1e-3)


def test_study_elastica_points_meet_the_closed_form_for_small_pushes():
    """The pillar-designs study's elastica (face clamped, pushed sideways with no axial force)
    against F_K − 3|M|/a with the guided cantilever's M = QL/2."""
    from gecko_agents.studies import pillar_designs as pd

    rows = pd.tilt_rows([5.0], n=3)
    a, w, E = pd.BASE.contact.jkr_args()
    EI = pd.BASE.contact.E1 * math.pi * pd.R_PILLAR**4 / 4.0
    r = next(r for r in rows if r["source"] == "elastica")  # the smaller push, u/L = 0.10
    M = punch.lateral_load_moment(r["lateral_uN"], 15.0, EI, np.inf)
    # 0.5 % allows the large-deflection drop of the end moment at u/L = 0.10 (0.64 % in M,
    # measured 0.07 % in the pull-off)
    assert r["pull_off_uN"] == pytest.approx(punch.tilted_pull_off(a, w, E, M), rel=5e-3)
    tilt = [r["pull_off_uN"] for r in rows if r["load"] == "tilt"]
    assert tilt[0] == punch.kendall_pull_off(a, w, E) and tilt[-1] == pytest.approx(0, abs=1e-12)


@pytest.mark.slow
def test_edge_log_observes_without_changing_the_run():
    """The pillar-designs study's EdgeLog chain gives the plain elastica's history bit for bit,
    and what it logs while the punch is pulled is the closed form's moment share."""
    from gecko_agents import protocol
    from gecko_agents.model import Model
    from gecko_agents.studies import pillar_designs as pd

    p = pd.params_for("flat_punch", 5.0, "flat").replace(**{"array.count": 1})
    proto = protocol.press_pull(0.01 * p.seta.L, speed=pd.SPEED)
    plain = Model(p, n_sim=1, seed=0).run(proto, progress=False)
    m = Model(p, n_sim=1, seed=0)
    log = m.physics.chain = pd.EdgeLog.of(p, 1)
    a, w, E = p.contact.jkr_args()
    log.edge_a, log.edge_FK = a, float(punch.kendall_pull_off(a, w, E))
    seen = m.run(proto, progress=False)
    for key in ("force_normal_uN", "n_attached"):
        assert np.array_equal(plain[key], seen[key])
    # straight pull of a nearly straight column: the face moment is a small share of F_K
    assert 0.0 <= log.pull_share < 1e-2
    assert log.press_peak < 1.0  # the edge stays closed while pressed below buckling
