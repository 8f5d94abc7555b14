"""Vertical pillars that buckle: the bar-chain elastica (``mechanics = "elastica"``) against
Euler's loads, statically and in the time-stepped model."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import columns
from gecko_agents.physics.elastica import Elastica, shear_coefficient

E1 = PAPER_ARRAY.contact.E1
R_SETA = 2.0
# Euler's critical loads over EI/L² (Timoshenko & Gere 1961, ch. 2): clamped–free,
# clamped–pinned (the tip held laterally, free to turn), clamped–clamped (held and flat).
EULER = {"free": math.pi**2 / 4, "pinned": 2.046 * math.pi**2, "clamped": 4 * math.pi**2}


def _euler(case, L):
    return EULER[case] * E1 * math.pi * R_SETA**4 / 4 / L**2


def test_chain_at_rest_carries_nothing_and_matches_the_straight_beam():
    el = Elastica(3, 20.0, 1.5, E1, math.radians(60.0), imperfection=0.0)
    d = np.tile(el.rest_end(), (3, 1))
    F, U = el.solve(d, False)
    assert np.abs(F).max() < 1e-12 and np.abs(U).max() < 1e-20
    # small tip displacement: Timoshenko's cantilever across, 1/(L³/(3EI) + L/(κGA)), Ka along
    # (eq 17–19)
    n = np.array([math.cos(math.radians(60)), -math.sin(math.radians(60))])
    t = np.array([-n[1], n[0]])
    eps = 1e-5
    F, _ = el.solve(d + eps * np.array([n, t, -t]), False)
    EI = E1 * math.pi * 1.5**4 / 4
    assert -F[0] @ n / eps == pytest.approx(E1 * math.pi * 1.5**2 / 20.0, rel=1e-4)
    # 16 links: Hencky's chain is the beam to O(1/n²); shear softens it by 1.2 % at L/r = 13
    kGA = shear_coefficient(0.3) * E1 / 2.6 * math.pi * 1.5**2
    assert -F[1] @ t / eps == pytest.approx(1 / (20.0**3 / (3 * EI) + 20.0 / kGA), rel=0.005)


@pytest.mark.parametrize(
    "case, tip_spring, pinned, below",
    [("free", 0.0, False, 0.004), ("pinned", 0.0, True, 0.009), ("clamped", 2.0, True, 0.014)],
)
def test_chain_linear_stability_converges_on_euler(case, tip_spring, pinned, below):
    """The chain's own critical load (smallest eigenvalue of its bending stiffness over its
    geometric stiffness P·ℓ per link, the tip's lateral constraint Σψ = 0 where pinned) for
    16 links lies just below Euler's, and 4× closer with 32 links (1/n² convergence); without
    shear the chain's stiffness is the joint springs' own tridiagonal matrix."""
    from scipy.linalg import eigh, null_space

    def critical(n):
        el = Elastica(1, 1.0, 1.0, 1.0, math.pi / 2, links=n, imperfection=0.0, shear=False)
        k = el.k.copy()
        K = np.diag(k[:-1] + np.append(k[1:-1], tip_spring * el.EI / el.ell))
        K -= np.diag(k[1:-1], 1) + np.diag(k[1:-1], -1)
        assert np.allclose(el.B[1 if tip_spring else 0], K, rtol=1e-13, atol=1e-12 * k[0])
        G = el.ell * np.eye(n)
        if pinned:
            Z = null_space(np.ones((1, n)))
            K, G = Z.T @ K @ Z, Z.T @ G @ Z
        return eigh(K, G, eigvals_only=True)[0] / (EULER[case] * el.EI)

    e16, e32 = 1 - critical(16), 1 - critical(32)
    assert 0 < e16 < below
    assert e32 == pytest.approx(e16 / 4, rel=0.15)


def _chain_critical(case, L_over_r, links=16):
    """Critical load of the chain with shear about its straight shape (its bending and shear
    stiffness B over the geometric stiffness P·ℓ per link) and the shear column's closed form."""
    from scipy.linalg import eigh, null_space

    el = Elastica(1, float(L_over_r), 1.0, 1.0, math.pi / 2, links=links, imperfection=0.0)
    K, G = el.B[1 if case == "clamped" else 0], el.ell * np.eye(links)
    if case != "free":
        Z = null_space(np.ones((1, links)))
        K, G = Z.T @ K @ Z, Z.T @ G @ Z
    exact = columns.shear_column_load(el.EI, el.kGA, el.L, case)
    return eigh(K, G, eigvals_only=True)[0], exact, el


@pytest.mark.parametrize("L_over_r", [6, 10, 30, 40])
@pytest.mark.parametrize("case", ["free", "pinned", "clamped"])
def test_chain_with_shear_buckles_at_the_shear_columns_load(case, L_over_r):
    """With shear (ν = 0.3) the chain meets the shear column's load (Engesser's formula for the
    free and clamped columns, tan kL = kL(1 − P/κGA) for the pinned one) within 1.3 % at 16
    links (as the chain without shear meets Euler's), 4× closer at 32; at L/r = 6 that is
    4.8 %, 31 % and 45 % below Euler's. Engesser's formula itself is met within 3 % at L/r = 6
    except by the pinned column, whose exact load lies 2.8 % below it. At L/r ≥ 30 the shear
    column's load is Euler's within 2 % except the clamped column's, which shear lowers by
    3.2 % (L/r = 30) and 1.8 % (40)."""
    P16, exact, el = _chain_critical(case, L_over_r)
    P32 = _chain_critical(case, L_over_r, 32)[0]
    assert -0.013 < P16 / exact - 1 < 0
    assert P32 / exact - 1 == pytest.approx((P16 / exact - 1) / 4, rel=0.2, abs=2e-4)
    engesser = columns.engesser_load(el.EI, el.kGA, el.L, case)
    euler = columns.euler_load(el.EI, el.L, case)
    if L_over_r == 6:
        assert P16 == pytest.approx(engesser, rel=0.035 if case == "pinned" else 0.03)
    if L_over_r >= 30:
        assert exact == pytest.approx(euler, rel=0.033 if case == "clamped" else 0.02)


def test_chain_force_is_the_gradient_of_its_energy():
    el = Elastica(1, 30.0, 2.0, E1, math.pi / 2, imperfection=1e-3)
    d0 = el.rest_end() + np.array([0.8, 1.5])  # bent well past small deflection
    F, U = el.solve(d0[None], True)
    h = 1e-4  # central difference: O(h²) ≈ 1e-9 relative; smaller h meets Newton's tolerance
    for k in range(2):
        e = np.zeros(2)
        e[k] = h
        up = el.solve((d0 + e)[None], True)[1][0]
        dn = el.solve((d0 - e)[None], True)[1][0]
        el.solve(d0[None], True)
        assert -(up - dn) / (2 * h) == pytest.approx(F[0, k], rel=1e-5, abs=1e-9)


def _pressed_load(case, el):
    """The shear column's load (:func:`columns.shear_column_load`) for a column shortened by
    ε = P/(EA) before it buckles: the chain's joint springs are per unstretched link and its
    lever arms shorten, so P(1 − P/EA) = P_cr (module docstring of physics.elastica)."""
    lin = columns.shear_column_load(el.EI, el.kGA, el.L, case)
    EA = el.Ka * el.L
    return EA * (1.0 - math.sqrt(1.0 - 4.0 * lin / EA)) / 2.0


@pytest.mark.parametrize(
    "case, L",
    [("free", 12.0), ("pinned", 12.0), ("free", 60.0), ("pinned", 60.0), ("clamped", 60.0),
     ("free", 80.0), ("pinned", 80.0), ("clamped", 80.0)],
)  # fmt: skip
def test_static_chain_buckles_at_the_shear_columns_load(case, L):
    """Pressed to 1.6 times the buckling shortening with the tip free sideways ("free": the
    lateral force kept at 0), held sideways ("pinned") or held sideways and flat ("clamped"):
    the largest force is the shear column's load of the shortened column within 2 % (16 links:
    −0.1 %…−1.3 %). At L/r = 6 (L = 12 µm) the clamped–free pillar settles 2.0 % above
    Engesser's formula and 2.8 % below Euler's; the clamped–clamped one, shortened by 20 %
    before it buckles, is left out (a strain the elastica's linear springs do not describe)."""
    el = Elastica(1, L, R_SETA, E1, math.pi / 2, imperfection=1e-4)
    d0 = el.rest_end()
    ref = _pressed_load(case, el)
    x, peak = d0[0], 0.0
    for u in np.linspace(0.0, 1.6 * ref / el.Ka, 500):
        for _ in range(30 if case == "free" else 1):
            F = el.solve(np.array([[x, d0[1] + u]]), case == "clamped")[0]
            if case != "free" or abs(F[0, 0]) < 1e-13:
                break
            kept = el.phi, el.stretch, el.lam
            kx = (el.solve(np.array([[x + 1e-7, d0[1] + u]]), False)[0][0, 0] - F[0, 0]) / 1e-7
            el.phi, el.stretch, el.lam = kept
            x -= F[0, 0] / kx
        peak = max(peak, -F[0, 1])
    assert peak == pytest.approx(ref, rel=0.02)


@pytest.mark.slow
@pytest.mark.parametrize("L", [60.0, 80.0])
@pytest.mark.parametrize(
    "case, tip, mu",
    [("free", "hertz", 0.0), ("pinned", "hertz", 5.0), ("clamped", "flat_punch", 5.0)],
)
def test_pillar_buckles_at_euler_in_the_model(case, tip, mu, L):
    """A vertical pillar pressed past its critical load and held: a frictionless sphere
    (clamped–free), a stuck sphere (clamped–pinned) and a stuck flat punch (clamped–clamped)
    settle on the shear column's load of the shortened column within 2 % (:func:`_pressed_load`).
    The peak during the press overshoots it by a rate effect (the bending mode grows slowly near
    the bifurcation), not counted here."""
    ref = _pressed_load(case, Elastica(1, L, R_SETA, E1, math.pi / 2))
    p = PAPER_ARRAY.replace(
        **{"seta.theta_deg": 90.0, "seta.r": R_SETA, "seta.L": L, "mechanics": "elastica",
           "tip": tip, "friction.mu": mu, "array.count": 1, "floor.sigma": 0.0,
           "contact.R": 2.0}
    )  # fmt: skip
    m = Model(p, n_sim=1, seed=0)
    depth = 2.5 * ref / p.axial_stiffness + 0.05  # past the contact's own compression
    # A free tip has to swing sideways: its bending mode is slow (period ~ 400 µs here).
    hold = 1500.0 if case == "free" else 300.0
    h = m.run([protocol.PressTo(depth, 0.001), protocol.Hold(hold)], progress=False)
    assert h["force_normal_uN"][-1] == pytest.approx(ref, rel=0.02)


@pytest.mark.slow
def test_stubby_pillar_settles_below_euler_in_the_model():
    """A vertical pillar with L/r = 6 (r = 5 µm, L = 30 µm, E = 2 MPa, frictionless sphere
    tip: clamped–free) pressed past buckling and held settles below Euler's π²EI/(4L²) as shear
    lowers it, within 3 % of Engesser's formula (2 % above it: the 1.6 % shortening before it
    buckles, :func:`_pressed_load`)."""
    p = PAPER_ARRAY.replace(
        **{"seta.theta_deg": 90.0, "seta.r": 5.0, "seta.L": 30.0, "contact.E1": 2.0,
           "mechanics": "elastica", "tip": "hertz", "friction.mu": 0.0, "array.count": 1,
           "floor.sigma": 0.0, "contact.R": 5.0}
    )  # fmt: skip
    el = Elastica.of(p, 1)
    euler = columns.euler_load(el.EI, 30.0, "free")
    engesser = columns.engesser_load(el.EI, el.kGA, 30.0, "free")
    depth = 2.5 * euler / p.axial_stiffness + 0.1
    h = Model(p, n_sim=1, seed=0).run([protocol.PressTo(depth, 0.002), protocol.Hold(1500.0)],
                                      progress=False)  # fmt: skip
    settled = h["force_normal_uN"][-1]
    assert settled < euler
    assert settled == pytest.approx(engesser, rel=0.03)


def test_elastica_is_refused_where_it_is_not_modelled():
    from gecko_agents import quasistatic as qs

    p = PAPER_ARRAY.replace(
        **{"seta.theta_deg": 90.0, "mechanics": "elastica", "array.count": 1, "floor.sigma": 0.0}
    )
    with pytest.raises(ValueError, match="mechanics = 'elastica' runs in the time-stepped Model"):
        qs.press_pull(p, np.zeros(1), 0.2)
    with pytest.raises(ValueError, match="kernel='python': mechanics='elastica' runs on kernel"):
        Model(p, n_sim=1, seed=0, numerics=Numerics(kernel="python"))
    with pytest.raises(ValueError, match=r"links = 2 is outside the allowed range \[14, 200\]"):
        p.replace(**{"seta.links": 2})


def test_chain_of_params_carries_their_imperfection():
    """:meth:`Elastica.of` builds the chain the parameters name: its crooked rest shape (tip
    offset ≈ imperfection·L) is the one built by hand from the same values."""
    p = PAPER_ARRAY.replace(**{"seta.imperfection": 0.02})
    s = p.seta
    hand = Elastica(2, s.L, s.r, p.contact.E1, s.theta, s.links, 0.02)
    np.testing.assert_allclose(Elastica.of(p, 2).rest_end(), hand.rest_end(), rtol=1e-15)


def _bent_chains(n):
    el = Elastica(n, 30.0, 2.0, E1, math.pi / 2, imperfection=1e-3)
    d = el.rest_end() + np.array([[0.8, 1.5], [-0.4, 0.6], [0.2, -0.9]])[:n]
    return el, d


def test_each_chain_has_its_own_energy_and_force():
    """Three setae bent three ways: each carries the force and energy of a chain solved
    alone (the solve is per seta; 1e-9 allows Newton's tolerance)."""
    el, d = _bent_chains(3)
    F, U = el.solve(d, [True, False, True])
    assert F.shape == (3, 2) and U.shape == (3,)
    for i, held in enumerate((True, False, True)):
        one, _ = _bent_chains(1)
        F1, U1 = one.solve(d[i : i + 1], held)
        np.testing.assert_allclose(F[i], F1[0], rtol=1e-9, atol=1e-12)
        assert U[i] == pytest.approx(U1[0], rel=1e-9)


def test_nodes_are_the_solved_chain():
    """The joints drawn are the chain solved: from the root, n links of ℓ + s/n (the axial
    stretch s spread over the links), ending at the tip the solve put there (1e-9 µm:
    Newton's tolerance)."""
    el, d = _bent_chains(3)
    el.solve(d, False)
    root = np.array([[1.0, 2.0], [-3.0, 0.5], [0.0, 0.0]])
    nodes = el.nodes(root)
    assert nodes.shape == (3, el.n + 1, 2)
    np.testing.assert_allclose(nodes[:, 0], root, rtol=0, atol=1e-15)
    np.testing.assert_allclose(nodes[:, -1] - root, d, rtol=0, atol=1e-9)
    links = np.linalg.norm(np.diff(nodes, axis=1), axis=2)
    expected = np.broadcast_to((el.ell + el.stretch / el.n)[:, None], links.shape)
    np.testing.assert_allclose(links, expected, rtol=1e-12)


def test_peek_answers_as_a_solve_and_leaves_the_chain_as_it_was():
    """A peek at other positions returns what a solve there returns and restores the chain
    (angles, stretch, multipliers, held tips, clamps); at the last solve's own positions it
    returns that solve's answer."""
    el, d = _bent_chains(2)
    F0, U0 = el.solve(d, [True, False])
    kept = (el.phi.copy(), el.stretch.copy(), el.lam.copy(), el.held.copy(), el.clamp.copy())
    d2 = d + np.array([[0.05, -0.1], [0.1, 0.02]])
    Fp, Up = el.peek(d2)
    for before, now in zip(kept, (el.phi, el.stretch, el.lam, el.held, el.clamp), strict=True):
        np.testing.assert_array_equal(before, now)
    twin, _ = _bent_chains(2)
    twin.solve(d, [True, False])
    Fs, Us = twin.solve(d2, [True, False])
    np.testing.assert_allclose(Fp, Fs, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(Up, Us, rtol=1e-9)
    F1, U1 = el.peek(d.copy())
    np.testing.assert_array_equal(F1, F0)
    np.testing.assert_array_equal(U1, U0)


def test_a_released_tip_lets_go_of_its_clamp_energy():
    """Tips held and then let go at the same positions: the solve books as released the held
    chain's energy over the free chain's relaxed at the same end (the massless chain's jump),
    for the released tip only; nothing for a tip that stays held or was never held."""
    el, d = _bent_chains(3)
    el.solve(np.tile(el.rest_end(), (3, 1)), [True, True, False])  # the faces bond at rest
    _, U_held = el.solve(d, [True, True, False])
    free, _ = _bent_chains(3)
    free.solve(d, [False, False, False])
    _, U_free = free.solve(d, [False, False, False])
    el.solve(d, [False, True, False])
    assert el.released > 0
    assert el.released == pytest.approx(U_held[0] - U_free[0], rel=1e-6)
    el.solve(d, [False, True, False])
    assert el.released == 0.0
