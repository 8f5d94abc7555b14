"""The quasi-static solver's equilibrium and release (eq 22–27 of Lin et al., Dynamic
Simulation and Parameter Analysis of Contact Mechanics for Mimicking Geckos' Foot Setae
Array, Crystals 12:282, 2022) against oracles built without it: the rod's equilibria found by a
bracketing root search on its own force law and JKR's eq 7 and 10, the friction cap of eq 27
written out, equal load sharing on a flat floor, and the state's bookkeeping counted anew.

Fast: every case is a handful of setae and plate positions."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gecko_agents import quasistatic as qs
from gecko_agents.history import STATE_FREE, STATE_SLIP, STATE_STICK
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import beam, jkr
from gecko_agents.quasistatic import rod as qs_rod
from gecko_agents.quasistatic import rod_equilibrium as req
from gecko_agents.quasistatic import state as qs_state

# A stubby seta (L = 5 µm) of the paper's array; ×10 stiffer, it holds Fc within ~L/3.
ROD = PAPER_ARRAY.replace(**{"seta.L": 5.0, "mechanics": "rod"})
STIFF = 10.0


def _rod_setup(**kw):
    return qs.RodSetup.from_params(ROD, stiffness_scale=STIFF, **kw)


def _held_tip_plate(rs, a):
    """c = h + R − Z [µm] at which a rod seta whose tip is held at its rest abscissa sits at
    contact radius a [µm]: the tip height y solves F_y(x0, y) = −P(a) (a root bracketed on the
    rod's force law, eq 7 for P), and c = y + δ(a) (eq 10, eq 22–23)."""
    x0, y0 = rs.rest
    P = jkr.force_from_radius(a, rs.R, rs.w, rs.E_star)

    def fy(y):
        return qs.rod_force(x0, y, rs.Ka, rs.k_phi, rs.L, rs.theta)[0][1] + P

    y = brentq(fy, y0 - 1.0, y0 + 1.0, xtol=1e-15, rtol=1e-15)
    return y + jkr.overlap_from_radius(a, rs.R, rs.w, rs.E_star)


def test_rod_tip_held_sideways_is_refused_past_its_fold():
    """A tip held at its anchor (rigid stick) at a plate height just short of its fold has two
    equilibria: the stable one (a above the fold) and the unstable one between a_c and the
    fold, where dP/dδ < −H_yy (the contact softer than the rod holds it). Newton started at
    either converges to it; only the stable one counts."""
    rs = _rod_setup()
    x0, _ = rs.rest
    a = np.linspace(rs.a_c * 1.0001, 1.2 * rs.a0, 801)
    c = np.array([_held_tip_plate(rs, ai) for ai in a])
    i = int(np.argmin(c))  # the fold: the plate's highest position that holds the tip
    assert 0 < i < a.size - 1
    c_at = c[i] + 1e-3
    a_u = brentq(lambda t: _held_tip_plate(rs, t) - c_at, a[0], a[i], xtol=1e-14)
    a_s = brentq(lambda t: _held_tip_plate(rs, t) - c_at, a[i], a[-1], xtol=1e-14)
    # The unstable side: the contact's stiffness dP/dδ below −H_yy there, above it on the other.
    y_u = c_at - jkr.overlap_from_radius(a_u, rs.R, rs.w, rs.E_star)
    y_s = c_at - jkr.overlap_from_radius(a_s, rs.R, rs.w, rs.E_star)
    hyy_u = qs.rod_force(x0, y_u, rs.Ka, rs.k_phi, rs.L, rs.theta)[1][2]
    hyy_s = qs.rod_force(x0, y_s, rs.Ka, rs.k_phi, rs.L, rs.theta)[1][2]
    assert jkr.contact_stiffness(a_u, rs.R, rs.w, rs.E_star) + hyy_u < 0
    assert jkr.contact_stiffness(a_s, rs.R, rs.w, rs.E_star) + hyy_s > 0
    one = np.ones(2)
    starts = np.array([a_u * (1 + 1e-3), a_s * (1 - 1e-3)])
    x, a_n, ok = req.rod_newton(rs, c_at * one, x0 * one, starts, anchor=x0 * one)
    # Both roots found to the residual tolerance 1e-10·Fc (measured |Δa| < 1e-11 µm).
    assert_allclose(a_n, [a_u, a_s], rtol=1e-9)
    assert_allclose(x, x0, rtol=0, atol=1e-12)
    assert ok.tolist() == [False, True]


def test_rod_tip_without_friction_holds_no_lateral_force():
    """Slide with no direction given: the frictionless tip (eq 25 with F_t = 0) slides until
    the rod pushes straight down on it, F_x = 0 and F_y = −P(a), checked on the rod's force
    law at y = c − δ(a)."""
    rs = _rod_setup()
    x0, y0 = rs.rest
    c = y0 + np.array([0.05, 0.2, 0.4])  # pressed tips: δ = c − y0 at first touch
    x, a, ok = req.rod_newton(rs, c, np.full(3, x0), np.full(3, rs.a0))
    assert ok.all()
    y = c - jkr.overlap_from_radius(a, rs.R, rs.w, rs.E_star)
    (Fx, Fy), _ = qs.rod_force(x, y, rs.Ka, rs.k_phi, rs.L, rs.theta)
    P = jkr.force_from_radius(a, rs.R, rs.w, rs.E_star)
    # The solve stops within 1e-10·Fc + 1e-12(|P| + |F_x|) of both residuals.
    tol = 1e-10 * rs.Fc + 1e-12 * np.abs(P)
    assert np.all(np.abs(Fx) <= 1.01 * tol) and np.all(np.abs(Fy + P) <= 1.01 * tol)
    assert np.all(np.diff(P) > 0)  # pressed deeper, pushed harder
    assert np.all(np.diff(x) > 0)  # and the tilted rod swings flatter


def test_setae_at_one_plate_height_reach_one_equilibrium_from_any_start():
    """Setae over the same floor height at one plate height (a scalar c and anchor for all)
    are one seta: from different starts on the stable branch they reach the same (x, a),
    that of the seta solved alone."""
    rs = _rod_setup(tangential_stiffness=2.0)
    x0, y0 = rs.rest
    c = y0 + 0.3
    starts_x = x0 + np.array([-0.3, 0.0, 0.2, 0.5])
    starts_a = rs.a0 * np.array([0.8, 1.0, 1.3, 1.6])
    x, a, ok = req.rod_newton(rs, c, starts_x, starts_a, anchor=x0)
    x1, a1, ok1 = req.rod_newton(rs, np.array([c]), np.array([x0]), np.array([rs.a0]), [x0])
    # Starts in whole micrometres (integer arrays) iterate in floating point all the same.
    xi, ai, oki = req.rod_newton(rs, c, np.array([2, 3]), np.array([3, 3]), anchor=x0)
    assert ok.all() and ok1.all() and oki.all()
    # All within the residual tolerance of one root (measured spread < 1e-12 µm).
    assert_allclose(np.r_[x, xi], x1[0], rtol=0, atol=1e-10)
    assert_allclose(np.r_[a, ai], a1[0], rtol=0, atol=1e-10)
    # The stick spring pulls the tip back toward its anchor: F_t = −k_t(x − x0) balances F_x.
    y = c - jkr.overlap_from_radius(a1, rs.R, rs.w, rs.E_star)
    (Fx, _), _ = qs.rod_force(x1, y, rs.Ka, rs.k_phi, rs.L, rs.theta)
    assert_allclose(Fx, rs.k_t * (x1 - x0), rtol=0, atol=1e-9 * rs.Fc)


def _cap_paper(P, mu):
    """The paper's friction cap, eq 27: F_μ = μ·F in compression, none in tension [µN]."""
    return mu * np.maximum(P, 0.0)


def test_rod_seta_under_the_papers_friction_slides_freely_in_tension():
    """Eq 27 for the rod: a tip sticks only within μ·max(P, 0) and slides at that cap, so a
    tip in tension carries no tangential force at all."""
    p = ROD.replace(**{"friction.law": "paper"})
    r = qs.press_pull(
        p, [0.0], 1.0, n_approach=60, n_retract=300, stiffness_scale=STIFF, record_setae=True
    )
    P, state = r.per_seta["force"][:, 0], r.per_seta["state"][:, 0]
    Ft, mu = r.force_tangential, p.friction.mu
    cap = _cap_paper(P, mu)
    stick, slip = state == STATE_STICK, state == STATE_SLIP
    # F_t is the rod's force at Newton's root, within its residual tolerance ~1e-10·Fc of the
    # cap (measured |F_t| ≤ 3e-11 µN on the tips in tension).
    tol = 1e-9 * p.contact.pull_off_force
    assert np.all(np.abs(Ft) <= cap + tol)
    assert_allclose(np.abs(Ft[slip]), cap[slip], rtol=0, atol=tol)
    tension = (P < 0) & (stick | slip)
    assert tension.sum() > 10 and np.all(np.abs(Ft[tension]) <= tol)
    assert np.any(stick & (P > 0)) and np.any(slip & (P > 0))
    assert math.isclose(r.pull_off, p.contact.pull_off_force, rel_tol=0.05)


# --- the linear seta (eq 16–27) ------------------------------------------------------------
LIN = PAPER_ARRAY  # the paper's seta: L = 20 µm at 60°, linear mechanics


def _linear_K(p, scale=1.0):
    """The seta's 2×2 stiffness K (eq 16–21) from Ka, Kp and θ [µN/µm]."""
    return beam.stiffness_matrix(
        p.axial_stiffness * scale, p.bending_stiffness * scale, p.seta.theta
    )


def _touchdown(p):
    """Plate height at which a resting tip touches h = 0: R + L sin θ (eq 22, y = 0) [µm]."""
    return p.contact.R + p.seta.L * math.sin(p.seta.theta)


def _cap(P, p):
    """Friction cap [µN] written out: μ·max(P, 0) (eq 27) or the adhesive μ|P + 2Fc|."""
    mu, Fc = p.friction.mu, p.contact.pull_off_force
    return mu * np.maximum(P, 0.0) if p.friction.law == "paper" else mu * np.abs(P + 2 * Fc)


def _check_linear_equilibria(p, r, h, k_t=math.inf):
    """Every step of a single linear seta against eq 22–27: the tip sits on JKR's branch
    (eq 7, 10); its spring deflection (x, D), D = h + R + L sin θ − δ − Z (eq 22–23), carries
    the contact force, K·(x, D) = (F_t, P); the contact's stick spring k_t holds the tip to its
    anchor u, F_t = k_t(u − x) (k_t = ∞: x = u); a sticking tip holds |F_t| ≤ cap, a sliding
    one F_t = ±cap (its anchor trailing it); a free tip carries nothing."""
    R, w, E = p.contact.jkr_args()
    K = _linear_K(p)
    Z, Ft = r.plate_y, r.force_tangential
    P, d, u = (r.per_seta[k][:, 0] for k in ("force", "overlap", "tip_dx"))
    state = r.per_seta["state"][:, 0]
    att = state != STATE_FREE
    a = jkr.radius_from_overlap(d[att], R, w, E)
    Fc = p.contact.pull_off_force
    # Tables inverted to ~1e-13 µm in a (Newton-polished): forces within 1e-9·Fc.
    assert_allclose(P[att], jkr.force_from_radius(a, R, w, E), rtol=0, atol=1e-9 * Fc)
    D = h + _touchdown(p) - d - Z
    x = u if math.isinf(k_t) else (Ft - K[0, 1] * D) / K[0, 0]
    assert_allclose(K[0, 1] * x[att] + K[1, 1] * D[att], P[att], rtol=0, atol=1e-9 * Fc)
    assert_allclose(K[0, 0] * x[att] + K[0, 1] * D[att], Ft[att], rtol=0, atol=1e-9 * Fc)
    if not math.isinf(k_t):
        assert_allclose(k_t * (u - x)[att], Ft[att], rtol=0, atol=1e-9 * Fc)
    _check_cap_and_free_tips(p, P, Ft, d, u, state, att, h, Z, Fc, rtol=1e-9, atol=1e-12)
    return state


def _check_cap_and_free_tips(p, P, Ft, d, u, state, att, h, Z, Fc, rtol, atol):
    """At every step: a sticking tip within its friction cap, a sliding one at it (to rtol,
    atol [µN]); a free tip carries nothing and hangs at rest, its overlap h + L sin θ + R − Z
    (eq 22); a tip that sticks from one step to the next keeps its anchor; friction opposes
    the slide."""
    cap = _cap(P, p)
    stick, slip = state == STATE_STICK, state == STATE_SLIP
    assert np.all(np.abs(Ft[stick]) <= cap[stick] * (1 + rtol) + atol)
    assert_allclose(np.abs(Ft[slip]), cap[slip], rtol=rtol, atol=atol)
    assert np.all(P[~att] == 0) and np.all(Ft[~att] == 0) and np.all(u[~att] == 0)
    assert_allclose(d[~att], (h + _touchdown(p) - Z)[~att], rtol=0, atol=1e-12)
    both = stick[1:] & stick[:-1]
    assert np.array_equal(u[1:][both], u[:-1][both])
    _check_friction_opposes_sliding(u, Ft, state, Fc)


def _check_friction_opposes_sliding(u, Ft, state, Fc):
    """Coulomb friction does negative work: where a tip slides from one step to the next, its
    anchor u moves against the floor's tangential force F_t on it (Δu·F_t ≤ 0)."""
    slid = (state[1:] == STATE_SLIP) & (state[:-1] != STATE_FREE)
    work = np.diff(u)[slid] * Ft[1:][slid]
    # Equilibria to ~1e-10·Fc: a tip sliding by a step's travel does work ≥ −1e-9·Fc·µm wrong.
    assert slid.sum() > 5 and np.all(work <= 1e-9 * Fc)


@pytest.mark.parametrize(
    ("mu", "law", "depth"), [(0.2, "adhesive", 1.0), (0.05, "adhesive", 3.0), (0.3, "paper", 3.0)]
)
def test_linear_seta_sits_on_eq22_27_at_every_step(mu, law, depth):
    p = LIN.replace(**{"friction.mu": mu, "friction.law": law})
    r = qs.press_pull(p, [0.2], depth, n_approach=40, n_retract=300, record_setae=True)
    state = _check_linear_equilibria(p, r, 0.2)
    # Pressed, a stuck tip pushes sideways with F_t/P = K_xy/K_yy (u = 0): under eq 27 it
    # slides at once where μ is below that; the adhesive cap μ|P + 2Fc| holds it near P = 0.
    K = _linear_K(p)
    assert np.any(state == STATE_STICK) == (law == "adhesive" or mu >= abs(K[0, 1] / K[1, 1]))
    assert np.any(state == STATE_SLIP)
    assert len(r.releases) == 1 and state[-1] == STATE_FREE
    fold_overlap = _check_release_at_the_fold(p, r, 0.2)
    # A stick spring k_t = 2Kxx in series with the seta: the same laws, the tip off its anchor.
    k_t = 2.0 * K[0, 0]
    rk = qs.press_pull(
        p, [0.2], depth, n_approach=40, n_retract=300, record_setae=True, tangential_stiffness=k_t
    )
    state_k = _check_linear_equilibria(p, rk, 0.2, k_t)
    assert np.any(state_k == STATE_SLIP) and state_k[-1] == STATE_FREE
    # The release overlap is δ at the fold of the branch the tip was on (the dense grid's
    # resolution: rtol 1e-4, as test_a_sliding_tip_lets_go_with_the_overlap_of_its_slide_fold).
    assert_allclose(r.releases[0][2], fold_overlap, rtol=1e-4)


def test_a_sliding_tip_lets_go_with_the_overlap_of_its_slide_fold():
    """A seta sliding on retraction lets go at the fold of its slide branch (eq 22–27 with
    F_t = σ·cap): the overlap it releases with is δ there, not that of the stick branch's
    fold, which it never reached."""
    p = LIN
    r = qs.press_pull(p, [0.2], 1.0, n_approach=40, n_retract=300, record_setae=True)
    ((i, _, d_rel),) = r.releases
    assert r.per_seta["state"][i - 1, 0] == STATE_SLIP
    assert_allclose(d_rel, _check_release_at_the_fold(p, r, 0.2), rtol=1e-4)


def _check_release_at_the_fold(p, r, h):
    """The tip lets go at the first plate step past the fold of the branch it was on: the
    highest plate Z(a) = h + R + L sin θ − δ(a) − D(a) over a on a dense grid (D from
    K·(u, D) = (F_t, P): slide F_t = σ·cap(P), or stick at its anchor u), and the recorded
    overlap is δ at that fold."""
    R, w, E = p.contact.jkr_args()
    K = _linear_K(p)
    ((i, _, d_rel),) = r.releases
    state, u = r.per_seta["state"][i - 1, 0], r.per_seta["tip_dx"][i - 1, 0]
    a = np.geomspace(jkr.snap_off_radius(R, w, E), jkr.zero_load_contact_radius(R, w, E), 200_001)
    P = jkr.force_from_radius(a, R, w, E)
    if state == STATE_SLIP:
        sigma = np.sign(r.force_tangential[i - 1])
        D = np.linalg.solve(K, np.stack([sigma * _cap(P, p), P]))[1]
    else:
        D = (P - K[0, 1] * u) / K[1, 1]
    Z = h + _touchdown(p) - jkr.overlap_from_radius(a, R, w, E) - D
    k = int(np.argmax(Z))
    assert 0 < k < a.size - 1  # a fold inside the branch
    # The grid's maximum is within ~1e-11 µm of the fold's plate height (Z is flat there).
    assert r.plate_y[i - 1] <= Z[k] + 1e-9 < r.plate_y[i]
    if state == STATE_SLIP:
        return jkr.overlap_from_radius(a[k], R, w, E)
    # δ at the grid's fold: within its spacing (5e-6 relative in a) of the exact one.
    assert_allclose(d_rel, jkr.overlap_from_radius(a[k], R, w, E), rtol=1e-4)
    return d_rel


@pytest.mark.parametrize("mechanics", ["linear", "rod"])
def test_setae_under_one_rigid_plate_do_not_interact(mechanics):
    """Under displacement control each seta's history depends on its own floor height only
    (eq 28's premise): setae solved together are each solved alone, and N setae on one height
    carry N times one seta's force."""
    p = LIN.replace(mechanics=mechanics, **{"seta.L": 5.0})
    h = np.array([0.3, -0.2, 0.05, 0.3, -0.45])
    Zt = _touchdown(p)
    Z = Zt + np.concatenate([np.linspace(0.6, -0.8, 29), np.linspace(-0.8, 2.0, 141)[1:]])
    together = qs.solve(p, h, Z, stiffness_scale=STIFF, record_setae=True)
    assert len(together.releases) == h.size
    for j, hj in enumerate(h):
        alone = qs.solve(p, [hj], Z, stiffness_scale=STIFF, record_setae=True)
        # The same elementwise operations (equal here; SIMD loops may round a batch apart).
        for k in ("force", "overlap", "tip_dx", "state"):
            assert_allclose(together.per_seta[k][:, j], alone.per_seta[k][:, 0], atol=1e-12)
        (i1, _, d1), *_ = [r for r in together.releases if r[1] == j]
        ((i2, _, d2),) = alone.releases
        assert i1 == i2 and math.isclose(d1, d2, abs_tol=1e-12)
    one = qs.solve(p, [0.3], Z, stiffness_scale=STIFF)
    F = together.per_seta["force"]
    assert_allclose(F[:, 0] + F[:, 3], 2 * one.force_normal, rtol=0, atol=1e-12)
    assert_allclose(together.force_normal, F.sum(axis=1), rtol=1e-12, atol=1e-12)
    n_att = (together.per_seta["state"] != STATE_FREE).sum(axis=1)
    assert np.array_equal(together.n_attached, n_att)


def test_jump_in_attaches_exactly_the_free_tips_that_touch():
    """State bookkeeping (eq 22: a free tip touches where h ≥ its gap, δ ≥ 0): counted anew."""
    rng = np.random.default_rng(4)
    st = qs_state.State(50)
    st.state[:] = rng.choice([STATE_FREE, STATE_STICK, STATE_SLIP], 50)
    st.state[:3] = STATE_FREE  # free tips that just touch (h = 0 in eq 22): they attach
    st.sigma[:] = np.where(st.state == STATE_SLIP, rng.choice([-1.0, 1.0], 50), 0.0)
    st.u[:] = np.where(st.state != STATE_FREE, rng.normal(size=50), 0.0)
    before = st.copy()
    delta = rng.normal(size=50)
    delta[:3] = 0.0  # touching exactly: contact
    jump, att = qs_state.jump_in(st, delta)
    was_free = before.state == STATE_FREE
    for j in range(50):
        touches = delta[j] >= 0.0
        assert jump[j] == (was_free[j] and touches)
        assert att[j] == (not was_free[j] or touches)
        if jump[j]:  # jumps in at rest, sticking
            assert (st.state[j], st.sigma[j], st.u[j]) == (STATE_STICK, 0.0, 0.0)
        else:  # untouched
            assert (st.state[j], st.sigma[j], st.u[j]) == (
                before.state[j],
                before.sigma[j],
                before.u[j],
            )
    assert jump[:3].all()
    # The copy kept the state as it was: an independent copy.
    assert np.array_equal(before.state == STATE_FREE, was_free) and jump.any()
    assert not np.array_equal(before.state, st.state)


@pytest.mark.parametrize("kind", ["linear", "rod"])
def test_states_split_and_joined_are_the_same_setae(kind):
    rng = np.random.default_rng(6)
    st = qs_state.State(7) if kind == "linear" else qs_rod.RodState(7)
    for k in vars(st):
        getattr(st, k)[:] = rng.integers(0, 3, 7) if k == "state" else rng.normal(size=7)
    parts = [qs_state.take_state(st, slice(0, 3)), qs_state.take_state(st, [3, 4, 5, 6])]
    back = qs_state.concat_states(parts)
    assert type(back) is type(st) and set(vars(back)) == set(vars(st))
    for k in vars(st):
        assert np.array_equal(getattr(back, k), getattr(st, k))
        assert getattr(back, k).dtype == getattr(st, k).dtype
    picked = qs_state.take_state(st, [5, 1])
    for k in vars(st):
        assert np.array_equal(getattr(picked, k), getattr(st, k)[[5, 1]])
    # Taken and copied states are copies: changing them leaves the original alone.
    cp = st.copy()
    for s in (picked, parts[0], cp):
        for k in vars(s):
            getattr(s, k)[:] = 9
    for k in vars(st):
        assert not np.any(getattr(st, k) == 9)
    assert all(np.array_equal(getattr(cp, k), np.full(7, 9)) for k in vars(st))


def _check_rod_equilibria(p, r, h, k_t=math.inf, scale=STIFF):
    """Every step of a single rod seta against its force law (:func:`rod_force`) and JKR's
    eq 7, 10: the tip at (x, y = h + R − Z − δ) from the root, the rod's force balanced by the
    contact's, F_rod = −(F_t, P); the tip held to its anchor x0 + u by the stick spring,
    F_t = k_t(x0 + u − x) (k_t = ∞: x = x0 + u); stick within the cap, slide at it."""
    rs = qs.RodSetup.from_params(p, stiffness_scale=scale, tangential_stiffness=k_t)
    R, w, E = p.contact.jkr_args()
    x0, _ = rs.rest
    Z, Ft = r.plate_y, r.force_tangential
    P, d, u = (r.per_seta[k][:, 0] for k in ("force", "overlap", "tip_dx"))
    state = r.per_seta["state"][:, 0]
    att = state != STATE_FREE
    Fc = p.contact.pull_off_force
    # Newton stops within 1e-10·Fc of both residuals: the forces balance within 1e-9·Fc.
    tol = 1e-9 * Fc
    a = jkr.radius_from_overlap(d[att], R, w, E)
    assert_allclose(P[att], jkr.force_from_radius(a, R, w, E), rtol=0, atol=tol)
    x = x0 + u if math.isinf(k_t) else x0 + u - Ft / k_t
    y = h + R - Z - d
    (Fx, Fy), _ = qs.rod_force(x[att], y[att], rs.Ka, rs.k_phi, rs.L, rs.theta)
    assert_allclose(-Fx, Ft[att], rtol=0, atol=tol)
    assert_allclose(-Fy, P[att], rtol=0, atol=tol)
    _check_cap_and_free_tips(p, P, Ft, d, u, state, att, h, Z, Fc, rtol=0.0, atol=tol)
    return state


@pytest.mark.parametrize("k_t", [math.inf, 2.0])
@pytest.mark.parametrize(("mu", "law"), [(0.1, "adhesive"), (0.3, "paper")])
def test_rod_seta_sits_in_equilibrium_at_every_step(mu, law, k_t):
    p = ROD.replace(**{"friction.mu": mu, "friction.law": law})
    r = qs.press_pull(
        p,
        [0.2],
        1.0,
        n_approach=40,
        n_retract=300,
        stiffness_scale=STIFF,
        tangential_stiffness=k_t,
        record_setae=True,
    )
    state = _check_rod_equilibria(p, r, 0.2, k_t)
    assert np.any(state == STATE_STICK) and np.any(state == STATE_SLIP)
    ((i, _, d_rel),) = r.releases
    assert state[i] == STATE_FREE and state[i - 1] != STATE_FREE
    # The release overlap is the tip's last equilibrium's (one plate step before the fold).
    assert d_rel == r.per_seta["overlap"][i - 1, 0]


@pytest.mark.parametrize(
    ("law", "k_t"), [("adhesive", math.inf), ("paper", math.inf), ("adhesive", 0.3)]
)
def test_branch_tables_fold_where_the_plate_height_peaks(law, k_t):
    """Each branch's fold a_fold is where its plate height Z(a) = −δ(a) − D(a) + const peaks
    (eq 22–25; D from K·(x, D) = (F_t, P) with F_t = σ·cap(P) sliding, or the tip held by
    k_t to its anchor when stuck), found on a dense grid; the table starts there, and
    inverting it gives back the radius of any plate height below the fold."""
    p = LIN.replace(**{"friction.law": law})
    br = qs.Branches.from_params(p, tangential_stiffness=k_t)
    R, w, E = p.contact.jkr_args()
    K = _linear_K(p)
    a = np.geomspace(jkr.snap_off_radius(R, w, E), jkr.zero_load_contact_radius(R, w, E), 400_001)
    P = jkr.force_from_radius(a, R, w, E)
    for name, sigma in (("stick", 0.0), ("slip+", 1.0), ("slip-", -1.0)):
        if name == "stick":  # anchor at rest: k_t(0 − x) = F_t in series with the seta
            Kt = K + np.diag([k_t, 0.0]) if not math.isinf(k_t) else None
            D = P / K[1, 1] if Kt is None else np.linalg.solve(Kt, np.stack([0 * P, P]))[1]
        else:
            D = np.linalg.solve(K, np.stack([sigma * _cap(P, p), P]))[1]
        G = -jkr.overlap_from_radius(a, R, w, E) - D
        k = int(np.argmax(G))
        assert 0 < k < a.size - 1
        # The grid's spacing is 2.7e-6 of a: the fold within it.
        assert_allclose(br.a_fold[name], a[k], rtol=1e-5)
        # The paper's soft seta deflects ~250 µm there: G to rounding of that.
        assert_allclose(br.G_grid[name][0], G[k], rtol=1e-11)
        # Round trip below the fold: the radius of a plate height is given back.
        pick = np.arange(k + 1000, a.size, 20_000)
        assert_allclose(br.invert(name, G[pick]), a[pick], rtol=1e-10)
        assert np.isnan(br.invert(name, G[k] + 1e-6))
    with pytest.raises(ValueError, match="compressed beyond"):
        br.invert("stick", br.G_grid["stick"][-1] - 1.0)


def test_bad_branch_setups_are_refused():
    with pytest.raises(ValueError, match="tangential_stiffness"):
        qs.Branches.from_params(LIN, tangential_stiffness=0.0)
    with pytest.raises(ValueError, match="stiffness_scale"):
        qs.Branches.from_params(LIN, stiffness_scale=0.0)
    with pytest.raises(ValueError, match="lateral"):
        qs.Branches.from_params(LIN, lateral="sideways")
    for bad in ({"tangential_stiffness": -1.0}, {"stiffness_scale": 0.0}, {"lateral": "x"}):
        with pytest.raises(ValueError, match=next(iter(bad))):
            qs.RodSetup.from_params(ROD, **bad)
    # μ·|K_xy/K_xx| ≥ 1: the sliding seta's normal stiffness Ky/(1 − qσμ) turns negative.
    q = abs(_linear_K(LIN)[0, 1] / _linear_K(LIN)[0, 0])
    qs.Branches.from_params(LIN.replace(**{"friction.mu": 0.99 / q}))
    with pytest.raises(ValueError, match="self-locks"):
        qs.Branches.from_params(LIN.replace(**{"friction.mu": 1.0 / q}))


def _branch_folds(p, lateral, scale):
    """max over a of G(a) = −δ(a) − D(a) [µm] for each slide direction σ (0: free sideways),
    D from K·(x, D) = (σ·cap(P), P) (eq 22–27), by a bounded scalar maximisation."""
    from scipy.optimize import minimize_scalar

    R, w, E = p.contact.jkr_args()
    K = _linear_K(p, scale)
    bounds = (jkr.snap_off_radius(R, w, E), jkr.zero_load_contact_radius(R, w, E))
    out = {}
    for sigma in (1.0, -1.0) if lateral == "coupled" else (0.0,):

        def G(a, sigma=sigma):
            P = jkr.force_from_radius(a, R, w, E)
            D = np.linalg.solve(K, np.array([sigma * _cap(P, p), P]))[1]
            return -jkr.overlap_from_radius(a, R, w, E) - D

        best = minimize_scalar(lambda a: -G(a), bounds=bounds, method="bounded")
        out[sigma] = -best.fun
    return out


@pytest.mark.parametrize("lateral", ["coupled", "free"])
def test_step_margins_agree_with_its_decisions(lateral):
    """The decision margins :class:`Blocks` splits on: a tip sticks exactly where the stick
    trial's cap − |F_t| ≥ 0 (within the cap's 1e-12 slack), slides the way its F_t points, and
    lets go exactly where its branch's fold margin is negative."""
    from gecko_agents.quasistatic import linear

    p = LIN.replace(**{"friction.mu": 0.1})
    br = qs.Branches.from_params(p, lateral, stiffness_scale=100.0)  # lets go within 5 µm
    h = np.random.default_rng(9).normal(0.0, 0.3, 60)
    st = qs_state.State(h.size)
    Zt = _touchdown(p)
    R, w, E = p.contact.jkr_args()
    # Every fold lies between JKR's under displacement control (a_c) and load control (a_lc).
    d_lo = jkr.snap_off_overlap(R, w, E)
    d_hi = jkr.overlap_from_radius(0.25 ** (1 / 3) * jkr.zero_load_contact_radius(R, w, E), R, w, E)
    seen = {"stick": 0, "slip": 0, "release": 0}
    g_fold = _branch_folds(p, lateral, 100.0)
    Zs = Zt + np.concatenate([np.linspace(0.5, -1.0, 16), np.linspace(-1.0, 6.0, 71)[1:]])
    for Z in Zs:
        was = st.state.copy()
        P, Ft, d, rel, rel_d, mg = linear.step(br, st, Z, h, margins=True)
        att = (was != STATE_FREE) | (d >= 0) | rel
        assert np.all(np.isnan(mg["fold"][~att])) and np.all(np.isfinite(mg["fold"][att]))
        # The fold margin: the plate rise left before the branch the tip would slide on (in
        # the direction its stick trial pushes) has no equilibrium.
        if lateral == "coupled":
            rise = np.where(mg["ft"] >= 0, g_fold[1.0], g_fold[-1.0])
        else:
            rise = g_fold[0.0]
        # The tables' fold and the maximiser's agree to ~1e-12 µm (Z is flat there).
        assert_allclose(mg["fold"][att], (rise - (Z - Zt - h))[att], rtol=0, atol=1e-9)
        assert np.array_equal(rel, att & (mg["fold"] < 0) & (st.state == STATE_FREE))
        assert np.all((rel_d[rel] > d_lo) & (rel_d[rel] < d_hi))
        seen["release"] += rel.sum()
        if lateral == "free":
            assert np.all(np.isnan(mg["stick"]))
            continue
        stick = st.state == STATE_STICK
        assert np.all(mg["stick"][stick] >= -1e-12 * np.abs(mg["ft"][stick]))
        slid = att & ~stick & ~rel
        assert np.all(mg["stick"][slid] < 0)
        assert np.array_equal(np.sign(Ft[slid]), np.where(mg["ft"][slid] >= 0, 1.0, -1.0))
        assert np.array_equal(st.sigma[slid], np.sign(Ft[slid]))
        seen["stick"] += stick.sum()
        seen["slip"] += slid.sum()
    assert st.state.max() == STATE_FREE and seen["release"] == h.size
    assert lateral == "free" or min(seen.values()) > 0


@pytest.mark.parametrize("k_t", [math.inf, 0.1])
def test_soft_rod_swings_upright_and_stretches_before_it_lets_go(k_t):
    """A long soft rod at a shallow angle (L = 40 µm at 20°) pulled off a flat floor swings
    nearly upright and stretches axially before the tip lets go: the plate then has risen
    from its deepest point by at most L(1 − sin θ) + Fc/Ka (upright, stretched by the largest
    tension Fc) + the press depth − δ(a_lc) (JKR's overlap at −Fc, eq 8–10), and it lets go
    within the retract travel, on a rigid or a soft stick spring k_t."""
    p = PAPER_ARRAY.replace(**{"seta.L": 40.0, "seta.theta_deg": 20.0, "mechanics": "rod"})
    depth = 0.5
    r = qs.press_pull(
        p, [0.0], depth, n_approach=40, n_retract=400, tangential_stiffness=k_t, record_setae=True
    )
    ((i, _, _),) = r.releases
    assert r.per_seta["state"][-1, 0] == STATE_FREE and i < r.plate_y.size
    R, w, E = p.contact.jkr_args()
    a_lc = 0.25 ** (1 / 3) * jkr.zero_load_contact_radius(R, w, E)
    L, th = p.seta.L, p.seta.theta
    bound = L * (1 - math.sin(th)) + p.contact.pull_off_force / p.axial_stiffness
    bound += depth - jkr.overlap_from_radius(a_lc, R, w, E)
    rise = r.plate_y[i - 1] - r.plate_y.min()
    step = r.plate_y[i] - r.plate_y[i - 1]
    # The rotary spring keeps the rod short of upright: measured 0.987 of the bound, sampled
    # one retract step (0.14 µm here) before the fold.
    assert 0.95 * bound - step < rise <= bound


def test_rod_tip_free_sideways_slides_without_friction():
    """Eq 25 for the rod (``lateral = "free"``): the tip carries no tangential force at any
    step; the rod pushes straight down on it (F_x = 0, F_y = −P)."""
    p = ROD
    r = qs.press_pull(
        p,
        [0.1],
        1.0,
        n_approach=40,
        n_retract=300,
        lateral="free",
        stiffness_scale=STIFF,
        record_setae=True,
    )
    state = _check_rod_equilibria(p.replace(**{"friction.mu": 0.0}), r, 0.1)
    assert np.all(r.force_tangential == 0.0)
    assert np.all(state[state != STATE_FREE] == STATE_SLIP) and np.any(state == STATE_SLIP)
    assert len(r.releases) == 1 and state[-1] == STATE_FREE


def test_a_tip_free_sideways_holds_up_to_its_fold_and_lets_go_just_past_it():
    """Pulled in small steps, a tip free sideways (eq 25) holds until the plate reaches its
    fold, where the fold margin is zero, and lets go just past it with the fold's overlap:
    the fold is the highest plate Z(a) = h + R + L sin θ − δ(a) − P(a)/Ky (eq 22–25), found
    here by a bounded scalar maximisation."""
    from scipy.optimize import minimize_scalar

    from gecko_agents.quasistatic import linear

    scale = 100.0
    p = LIN
    br = qs.Branches.from_params(p, "free", stiffness_scale=scale)
    R, w, E = p.contact.jkr_args()
    K = _linear_K(p, scale)
    Ky = K[1, 1] - K[0, 1] ** 2 / K[0, 0]  # eq 20

    def plate(a):
        P = jkr.force_from_radius(a, R, w, E)
        return _touchdown(p) - jkr.overlap_from_radius(a, R, w, E) - P / Ky

    a_c, a_lc = jkr.snap_off_radius(R, w, E), 0.63 * jkr.zero_load_contact_radius(R, w, E)
    best = minimize_scalar(
        lambda a: -plate(a), bounds=(a_c, a_lc), method="bounded", options={"xatol": 1e-12}
    )
    a_f, Z_f = best.x, -best.fun
    st, h = qs_state.State(1), np.zeros(1)
    Zt = _touchdown(p)
    for Z in np.concatenate([np.linspace(Zt + 0.2, Zt - 0.5, 8), np.linspace(Zt - 0.5, Z_f, 60)]):
        if Z < Z_f - 1e-6:
            linear.step(br, st, Z, h)
    assert st.state[0] == STATE_SLIP
    held = st.copy()
    # Z_f is good to ~1e-15 µm (flat there); 1e-9 µm either side is ~1e5 ulp of Z ≈ 20 µm.
    out = linear.step(br, st, Z_f - 1e-9, h, margins=True)
    assert not out[3][0] and st.state[0] == STATE_SLIP
    assert 0 < out[5]["fold"][0] < 2e-9
    out = linear.step(br, held, Z_f + 1e-9, h, margins=True)
    assert out[3][0] and held.state[0] == STATE_FREE
    assert -2e-9 < out[5]["fold"][0] < 0
    # The maximiser's radius is good to ~1e-8 relative (Z is flat there): δ to 4e-8.
    assert_allclose(out[4][0], jkr.overlap_from_radius(a_f, R, w, E), rtol=1e-7)
