"""The quasi-static solver against oracles derived independently of it."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gecko_agents import quasistatic as qs
from gecko_agents.history import STATE_FREE, STATE_SLIP, STATE_STICK
from gecko_agents.params import PAPER_ARRAY, PAPER_TABLE1
from gecko_agents.physics import beam, jkr

P1 = PAPER_TABLE1
RWE = P1.contact.jkr_args()
FC = P1.contact.pull_off_force


def test_release_radius_limits_and_definition():
    a_c = jkr.snap_off_radius(*RWE)
    a_lc = 0.25 ** (1 / 3) * jkr.zero_load_contact_radius(*RWE)
    assert_allclose(qs.release_radius(1e9, *RWE), a_c, rtol=1e-5)
    assert_allclose(qs.release_radius(1e-9, *RWE), a_lc, rtol=1e-6)
    for k in (0.01, 0.5, 5.0):
        a = qs.release_radius(k, *RWE)
        assert_allclose(jkr.contact_stiffness(a, *RWE), -k, rtol=1e-8)
    with pytest.raises(ValueError, match="k = "):
        qs.release_radius(0.0, *RWE)


def _plate_of_radius(a, h, k):
    """Plate height holding a seta of normal stiffness k at contact radius a (eq 22–25)."""
    R, w, E = RWE
    return (
        h
        + R
        + P1.seta.L * np.sin(P1.seta.theta)
        - jkr.overlap_from_radius(a, R, w, E)
        - jkr.force_from_radius(a, R, w, E) / k
    )


@pytest.mark.parametrize("scale", [1.0, 300.0])
def test_single_seta_free_lateral_releases_at_the_fold_of_eq25(scale):
    # Oracle: Z(a) on a dense grid (no branch tables, no Newton); release where Z is maximal.
    p = P1
    ky = p.Ky * scale
    a = np.linspace(jkr.snap_off_radius(*RWE), 3.0, 2_000_001)
    Z = _plate_of_radius(a, 0.0, ky)
    Z_rel, a_rel = Z.max(), a[np.argmax(Z)]
    r = qs.press_pull(
        p, [0.0], 0.5, lateral="free", stiffness_scale=scale, n_retract=20_000, record_setae=True
    )
    ((i, j, d_rel),) = r.releases
    assert r.plate_y[i - 1] <= Z_rel + 1e-9 < r.plate_y[i]
    assert_allclose(d_rel, jkr.overlap_from_radius(a_rel, *RWE), rtol=1e-4)
    # Every attached step sits on the oracle curve: Z(a) at the solver's overlap.
    att = r.per_seta["state"][:, 0] != 0
    aa = jkr.radius_from_overlap(r.per_seta["overlap"][att, 0], *RWE)
    assert_allclose(_plate_of_radius(aa, 0.0, ky), r.plate_y[att], atol=1e-8)
    # The largest tension on this branch is the load-controlled Fc (it passes a = 0.63 a0).
    assert_allclose(r.pull_off, FC, rtol=1e-3)


def test_jump_in_soft_and_rigid():
    Ztouch = P1.contact.R + P1.seta.L * np.sin(P1.seta.theta)
    Zs = np.array([Ztouch + 0.1, Ztouch - 1e-12])
    soft = qs.single_seta(P1, Zs, lateral="free")
    # A soft seta cannot resist the adhesive pull: it snaps to zero load (δ ≈ a0²/(3R)).
    a0 = jkr.zero_load_contact_radius(*RWE)
    assert soft.force_normal[0] == 0.0
    assert_allclose(soft.per_seta["overlap"][1, 0], a0**2 / (3 * P1.contact.R), rtol=0.01)
    rigid = qs.single_seta(P1, Zs, lateral="free", stiffness_scale=1e7)
    assert_allclose(rigid.force_normal[1], -8 / 9 * FC, rtol=1e-4)


def test_rigid_setae_array_is_fuller_tabor():
    """Infinitely stiff setae: each tip is a JKR asperity at a fixed overlap (Fuller–Tabor)."""
    rng = np.random.default_rng(5)
    h = 0.3 * rng.standard_normal(400)
    r = qs.press_pull(
        P1, h, 0.4, lateral="free", stiffness_scale=1e7, n_approach=400, n_retract=4000
    )
    Zc = P1.contact.R + P1.seta.L * np.sin(P1.seta.theta)
    dc = jkr.snap_off_overlap(*RWE)
    touched = np.zeros(h.size, bool)
    attached = np.zeros(h.size, bool)
    expect = []
    for Z in r.plate_y:
        d = h + Zc - Z
        touched |= d >= 0
        attached = np.where(attached, d >= dc, d >= 0)
        expect.append(jkr.force_from_overlap(d[attached], *RWE).sum())
    expect = np.array(expect)
    assert_allclose(r.force_normal, expect, atol=2e-3 * np.abs(expect).max())


def test_flat_floor_equal_sharing_pulls_off_at_n_fc():
    n = 7
    r = qs.press_pull(P1, np.zeros(n), 0.5, lateral="free", n_retract=20_000)
    assert_allclose(r.pull_off, n * FC, rtol=1e-3)
    assert len(r.releases) == n and len({i for i, _, _ in r.releases}) == 1
    # Coupled friction changes the branch, not the cap on tension: still n·Fc at most.
    rc = qs.press_pull(P1, np.zeros(n), 0.5, n_retract=20_000)
    assert rc.pull_off <= n * FC * (1 + 1e-9) and rc.pull_off > 0.9 * n * FC


def test_no_friction_coupled_equals_free():
    p = PAPER_ARRAY.replace(**{"friction.mu": 0.0})
    h = np.random.default_rng(2).standard_normal(300)
    a = qs.press_pull(p, h, 1.0)
    b = qs.press_pull(p, h, 1.0, lateral="free")
    assert_allclose(a.force_normal, b.force_normal, rtol=1e-9, atol=1e-9)


@pytest.mark.parametrize("law", ["adhesive", "paper"])
def test_friction_invariants_on_every_step(law):
    p = PAPER_ARRAY.replace(**{"friction.law": law})
    h = 0.5 * np.random.default_rng(3).standard_normal(200)
    br = qs.Branches.from_params(p)
    r = qs.press_pull(p, h, 1.5, record_setae=True)
    P, state, u = r.per_seta["force"], r.per_seta["state"], r.per_seta["tip_dx"]
    # Tangential force recomputed from the spring: K·(p − p0) with p − p0 = (u, −D).
    dy = np.where(state == STATE_STICK, (P - br.Kxy * u) / br.Kyy, 0.0)
    Ft = br.Kxx * u + br.Kxy * dy
    stick = state == STATE_STICK
    # The cap written out (not the solver's br.cap): μ·max(P, 0) (eq 27) or μ|P + 2Fc|.
    mu = p.friction.mu
    cap = mu * np.maximum(P, 0.0) if law == "paper" else mu * np.abs(P + 2 * FC)
    assert np.all(np.abs(Ft[stick]) <= cap[stick] * (1 + 1e-9) + 1e-12)
    # The solver's own cap is that law.
    assert_allclose(np.abs(br.cap(P)), cap, rtol=1e-12, atol=1e-15)
    # A sticking tip does not move sideways between two sticking steps.
    both = stick[1:] & stick[:-1]
    assert_allclose(u[1:][both], u[:-1][both], atol=1e-12)
    assert np.any(state == STATE_SLIP)
    if law == "paper":  # eq 27: no friction without compression, so a tip in tension slides
        assert np.all(P[stick] >= 0)
    else:  # the adhesive cap μ|P + 2Fc| lets tips in tension stick
        assert np.any(stick & (P < 0))
    assert np.all(P[state == STATE_FREE] == 0)
    # Tension never exceeds Fc per seta nor n_attached·Fc in total.
    assert P.min() >= -FC * (1 + 1e-9)
    assert np.all(-r.force_normal <= r.n_attached * FC * (1 + 1e-9))


@pytest.mark.slow
def test_representative_blocks_converge_to_brute_force():
    h = np.random.default_rng(11).standard_normal(10_000)
    brute = qs.press_pull(PAPER_ARRAY, h, 1.0)
    hs = np.sort(h)
    errs = []
    for per_block in (20, 5):
        hr = hs.reshape(-1, per_block).mean(axis=1)
        rep = qs.solve(PAPER_ARRAY, hr, brute.plate_y, weights=np.full(hr.size, per_block))
        errs.append(
            np.abs(rep.force_normal - brute.force_normal).max() / np.abs(brute.force_normal).max()
        )
    assert errs[1] < errs[0] and errs[1] < 0.03
    # With the sample, blocks crossing a jump-in, stick/slide or release boundary are split
    # there: even blocks of 1000 setae give the curve of all 10⁴ to ~1e-9 of its peak.
    peak = np.abs(brute.force_normal).max()
    for per_block in (20, 1000):
        hr = hs.reshape(-1, per_block).mean(axis=1)
        rep = qs.solve(
            PAPER_ARRAY, hr, brute.plate_y, weights=np.full(hr.size, per_block), sample=hs
        )
        assert np.abs(rep.force_normal - brute.force_normal).max() < 1e-7 * peak
        assert rep.weights.sum() == h.size and rep.weights.size > hr.size  # it split
        assert_allclose(rep.n_attached, brute.n_attached, atol=1e-9)
    # The helper itself: block means of the sorted sample, weights summing to N.
    hr, w = qs.representative_heights(1000, 1.0, np.random.default_rng(0), 100)
    assert w.sum() == 1000 and np.all(np.diff(hr) >= 0)
    assert_allclose(
        np.sum(hr * w) / 1000, np.mean(1.0 * np.random.default_rng(0).standard_normal(1000))
    )
    hr2, w2, sample = qs.representative_heights(
        1000, 1.0, np.random.default_rng(0), 100, return_sample=True
    )
    np.testing.assert_array_equal(hr2, hr)
    np.testing.assert_array_equal(w2, w)
    np.testing.assert_array_equal(sample, np.sort(np.random.default_rng(0).standard_normal(1000)))


@pytest.mark.slow
@pytest.mark.parametrize("control", ["displacement", "force"])
def test_split_blocks_match_every_seta_under_both_controls(control):
    """press_pull / preload_pull on 40 blocks with the sample = the same on all 2000 setae."""
    hr, w, sample = qs.representative_heights(
        2000, 1.0, np.random.default_rng(5), 40, return_sample=True
    )
    if control == "displacement":
        brute = qs.press_pull(PAPER_ARRAY, sample, 1.0, n_retract=1000)
        rep = qs.press_pull(PAPER_ARRAY, hr, 1.0, weights=w, sample=sample, n_retract=1000)
    else:
        brute = qs.preload_pull(PAPER_ARRAY, sample, 400.0)
        rep = qs.preload_pull(PAPER_ARRAY, hr, 400.0, weights=w, sample=sample)
    # (force control: the turning point is bisected to 1e-9 of the preload)
    tol = 1e-12 if control == "displacement" else 1e-6
    assert_allclose(rep.plate_y, brute.plate_y, rtol=0, atol=tol)
    peak = np.abs(brute.force_normal).max()
    assert np.abs(rep.force_normal - brute.force_normal).max() < 1e-7 * peak
    assert np.abs(rep.force_tangential - brute.force_tangential).max() < 1e-7 * peak
    assert_allclose(rep.pull_off, brute.pull_off, rtol=1e-8)


def test_sample_refuses_blocks_that_do_not_match_it():
    hr, w, sample = qs.representative_heights(
        100, 1.0, np.random.default_rng(1), 10, return_sample=True
    )
    Z = [30.0, 20.0]
    with pytest.raises(ValueError, match="sorted"):
        qs.solve(PAPER_ARRAY, hr, Z, weights=w, sample=sample[::-1])
    with pytest.raises(ValueError, match="whole numbers"):
        qs.solve(PAPER_ARRAY, hr, Z, weights=w * 0.5, sample=sample)
    with pytest.raises(ValueError, match="means"):
        qs.solve(PAPER_ARRAY, hr + 0.1, Z, weights=w, sample=sample)
    with pytest.raises(ValueError, match="record_setae"):
        qs.solve(PAPER_ARRAY, hr, Z, weights=w, sample=sample, record_setae=True)


@pytest.mark.slow
def test_preload_is_hit_and_pull_off_saturates():
    h = np.random.default_rng(4).standard_normal(300)
    pulls = []
    for pre in (5.0, 40.0, 150.0, 400.0):
        r = qs.preload_pull(PAPER_ARRAY, h, pre)
        assert_allclose(r.preload, pre, rtol=1e-6)
        pulls.append(r.pull_off)
    assert np.all(np.diff(pulls) >= -1e-9)
    # Saturation: the last increase is much smaller than the first; and never above N·Fc.
    assert pulls[3] - pulls[2] < 0.2 * (pulls[1] - pulls[0])
    assert pulls[-1] <= h.size * FC


def test_bad_input():
    with pytest.raises(ValueError, match="depth"):
        qs.press_pull(P1, [0.0], -1.0)
    with pytest.raises(ValueError, match="preload"):
        qs.preload_pull(P1, [0.0], 0.0)
    with pytest.raises(ValueError, match="lateral"):
        qs.solve(P1, [0.0], [30.0], lateral="sideways")
    with pytest.raises(ValueError, match="self-locks"):
        qs.Branches.from_params(P1.replace(**{"seta.theta_deg": 85.0, "friction.mu": 2.0}))


# --- rod mechanics -------------------------------------------------------------------------
# A stubby seta (L = 5 µm) of the paper's array so the agent runs take about a second.
ROD = PAPER_ARRAY.replace(**{"seta.L": 5.0, "mechanics": "rod"})


def test_rod_force_is_the_gradient_of_its_energy_and_reduces_to_eq20_21_at_rest():
    p = ROD
    Ka, Kp, L, th = p.axial_stiffness, p.bending_stiffness, p.seta.L, p.seta.theta
    kphi = Kp * L * L

    def energy(x, y):
        dphi = np.arctan2(y, x) + th
        return 0.5 * Ka * (np.hypot(x, y) - L) ** 2 + 0.5 * kphi * dphi**2

    rng = np.random.default_rng(0)
    x = L * np.cos(th) + rng.uniform(-2, 2, 20)
    y = -L * np.sin(th) + rng.uniform(-2, 2, 20)
    (Fx, Fy), (Hxx, Hxy, Hyy) = qs.rod_force(x, y, Ka, kphi, L, th)
    e = 1e-5
    assert_allclose(Fx, -(energy(x + e, y) - energy(x - e, y)) / (2 * e), rtol=1e-6, atol=1e-9)
    assert_allclose(Fy, -(energy(x, y + e) - energy(x, y - e)) / (2 * e), rtol=1e-6, atol=1e-9)
    (Fx1, _), _ = qs.rod_force(x + e, y, Ka, kphi, L, th)
    (Fx0, _), _ = qs.rod_force(x - e, y, Ka, kphi, L, th)
    (Fx2, Fy2), _ = qs.rod_force(x, y + e, Ka, kphi, L, th)
    (Fx3, Fy3), _ = qs.rod_force(x, y - e, Ka, kphi, L, th)
    assert_allclose(Hxx, -(Fx1 - Fx0) / (2 * e), rtol=1e-6, atol=1e-8)
    assert_allclose(Hxy, -(Fx2 - Fx3) / (2 * e), rtol=1e-6, atol=1e-8)
    assert_allclose(Hyy, -(Fy2 - Fy3) / (2 * e), rtol=1e-6, atol=1e-8)
    # At rest the tangent stiffness is the paper's 2×2 K (eq 16–21).
    _, H = qs.rod_force(np.array([L * np.cos(th)]), np.array([-L * np.sin(th)]), Ka, kphi, L, th)
    K = beam.stiffness_matrix(Ka, Kp, th)
    assert_allclose(np.ravel(H), [K[0, 0], K[0, 1], K[1, 1]], rtol=1e-12)


def test_rod_and_linear_agree_for_small_deflections():
    # Setae 10⁴ × stiffer: holding Fc deflects a tip by < 1 % of L, where rod = linear.
    scale = 1e4
    p = ROD.replace(**{"seta.L": 20.0})
    assert p.contact.pull_off_force / (p.Ky * scale) < 0.01 * p.seta.L
    h = 0.2 * np.random.default_rng(8).standard_normal(30)
    lin = qs.press_pull(
        p.replace(mechanics="linear"), h, 0.5, stiffness_scale=scale, n_retract=3000
    )
    rod = qs.solve(p, h, lin.plate_y, stiffness_scale=scale)
    peak = np.abs(lin.force_normal).max()
    # Away from the steps where a tip lets go (a fold a hair earlier or later moves a release
    # by one step, and the tip's whole force with it) the curves agree within 1 %.
    near = np.zeros(lin.plate_y.size, bool)
    for i, _, _ in lin.releases + rod.releases:
        near[max(i - 1, 0) : i + 2] = True
    diff = np.abs(rod.force_normal - lin.force_normal)
    assert diff[~near].max() < 0.01 * peak
    assert diff.max() < 0.01 * peak + p.contact.pull_off_force
    assert_allclose(rod.pull_off, lin.pull_off, rtol=3e-3)
    assert np.abs(rod.force_tangential - lin.force_tangential)[~near].max() < 0.01 * peak
    # The same tips let go, at the same step or the next.
    assert sorted(j for _, j, _ in rod.releases) == sorted(j for _, j, _ in lin.releases)
    steps = dict((j, i) for i, j, _ in lin.releases)
    assert all(abs(i - steps[j]) <= 1 for i, j, _ in rod.releases)


def _agent(params, n_sim, speed):
    from gecko_agents import protocol
    from gecko_agents.model import Model

    m = Model(params, n_sim=n_sim, seed=1)
    return m, m.run(protocol.press_pull(0.5, speed=speed), progress=False)


@pytest.mark.parametrize(("n", "sigma"), [(1, 0.0), (40, 0.3)])
def test_rod_quasistatic_matches_the_agent_rod(n, sigma):
    """The agent model (pymunk, damped dynamics at a slow pull) is an independent oracle."""
    p = ROD.replace(**{"array.count": n, "floor.sigma": sigma})
    m, h = _agent(p, n, 0.005)
    heights = m.profile.pad_heights
    q = qs.press_pull(p, heights, 0.5, n_retract=2000, tangential_stiffness=m.k_t)
    assert_allclose(q.pull_off, h.peak_pull_off, rtol=0.01)
    # Release: plate height above touch-down at which the last tip let go (the agent's tip
    # crosses δc a little after leaving its fold; the quasi-static one leaves at the fold).
    z_agent = h.detachments["plate_y_um"].max() - m.z_touch
    z_qs = q.plate_y[max(i for i, _, _ in q.releases)] - m.z_touch
    assert_allclose(z_qs, z_agent, rtol=0.02)
    assert len(q.releases) == len(h.detachments["seta"])
    if n > 1:  # rough floor: unequal load sharing keeps the pull-off below N·Fc
        assert q.pull_off < 0.95 * n * p.contact.pull_off_force


@pytest.mark.parametrize("mechanics", ["linear", "rod"])
def test_shared_approach_equals_one_preload_pull_per_preload(mechanics):
    p = PAPER_ARRAY.replace(
        mechanics=mechanics, **{"array.count": 400, "seta.L": 5.0, "floor.sigma": 0.5}
    )
    h, w = qs.quantile_heights(400, 0.5, 16)
    pre = [2000.0, 6.0, 200.0, 40.0]
    many = qs.preload_pulls(p, h, pre, weights=w, retract_steps=100)
    for P, m in zip(pre, many, strict=True):
        one = qs.preload_pull(p, h, P, weights=w, retract_steps=100)
        assert_allclose(m.plate_y, one.plate_y, rtol=0, atol=1e-6)
        scale = np.abs(one.force_normal).max()
        assert_allclose(m.force_normal, one.force_normal, rtol=0, atol=1e-6 * scale)
        assert [r[:2] for r in m.releases] == [r[:2] for r in one.releases]


@pytest.mark.parametrize("law", ["paper", "adhesive"])
def test_long_approach_steps_of_a_pressed_array_land_where_the_short_ones_do(law):
    # A deep press of soft setae on a rough floor: once every seta is attached and pressed,
    # steps of up to 32 dz that change no contact state give the same turning points and
    # retracts as dz steps (a stuck tip depends on its anchor and the plate height only, a
    # sliding one on the plate height only), in far fewer approach steps.
    p = PAPER_ARRAY.replace(**{"array.count": 400, "floor.sigma": 1.0, "friction.law": law})
    h, w = qs.representative_heights(400, 1.0, np.random.default_rng(2), 20)
    pre = [3.0, 100.0, 400.0]
    short = qs.preload_pulls(p, h, pre, weights=w, retract_steps=100)
    long = qs.preload_pulls(p, h, pre, weights=w, retract_steps=100, approach_stride=32)
    for s, g in zip(short, long, strict=True):
        i, j = s.turn_index, g.turn_index
        assert g.plate_y[j] == pytest.approx(s.plate_y[i], rel=0, abs=1e-9)
        assert g.preload == pytest.approx(s.preload, rel=1e-9)
        # the retracts: the same plate heights, forces and releases
        assert_allclose(g.plate_y[j:], s.plate_y[i:], rtol=0, atol=1e-9)
        scale = np.abs(s.force_normal).max()
        assert_allclose(g.force_normal[j:], s.force_normal[i:], rtol=0, atol=1e-9 * scale)
        assert [(k - j, m) for k, m, _ in g.releases] == [(k - i, m) for k, m, _ in s.releases]
        assert g.n_attached.max() == s.n_attached.max()
    if law == "paper":  # the paper's sliding setae press deep (adhesive friction: stiff, short)
        assert long[-1].turn_index < short[-1].turn_index / 4
    with pytest.raises(ValueError, match="approach_stride"):
        qs.preload_pulls(p, h, pre, weights=w, approach_stride=0)


@pytest.mark.parametrize("law", ["paper", "adhesive"])
def test_long_retract_moves_keep_every_release_and_the_sampled_pull_off(law):
    # Between state changes each seta's force is monotone in the plate height, so moves of up
    # to 32 grid steps where nothing changes skip only points inside monotone stretches: the
    # sampled pull-off, every release (seta, plate height, overlap) and the attached counts
    # are those of single steps, from a small fraction of the records.
    p = PAPER_ARRAY.replace(**{"array.count": 400, "floor.sigma": 1.0, "friction.law": law})
    h, w = qs.representative_heights(400, 1.0, np.random.default_rng(2), 20)
    pre = [3.0, 60.0]
    one = qs.preload_pulls(p, h, pre, weights=w, retract_steps=100)
    far = qs.preload_pulls(p, h, pre, weights=w, retract_steps=100, retract_stride=32)
    for s, g in zip(one, far, strict=True):
        assert g.pull_off == pytest.approx(s.pull_off, rel=1e-12)
        assert g.n_attached.max() == s.n_attached.max()
        rel_g = np.array([(g.plate_y[k], m, d) for k, m, d in g.releases])
        rel_s = np.array([(s.plate_y[k], m, d) for k, m, d in s.releases])
        assert_allclose(rel_g, rel_s, rtol=1e-12, atol=0)
        assert np.isin(g.plate_y, s.plate_y).all()  # grid points, a subset
    retract_records = [[len(r.plate_y) - r.turn_index for r in rs] for rs in (one, far)]
    assert sum(retract_records[1]) < 0.6 * sum(retract_records[0]), retract_records
    with pytest.raises(ValueError, match="retract_stride"):
        qs.preload_pulls(p, h, pre, weights=w, retract_stride=1.5)


def test_quantile_heights_are_the_conditional_means_of_equal_probability_slices():
    h, w, z = qs.quantile_heights(10**7, 2.0, 64, return_edges=True)
    assert_allclose(w, 10**7 / 64)
    assert np.all((h > 2.0 * z[:-1]) & (h < 2.0 * z[1:]))
    # Oracle: sorted means of a large independent draw, in 64 equal groups.
    s = np.sort(np.random.default_rng(3).standard_normal(64 * 20_000)) * 2.0
    assert_allclose(h, s.reshape(64, -1).mean(axis=1), atol=0.02)
    assert_allclose(np.sum(w * h) / np.sum(w), 0.0, atol=1e-12)
    assert qs.quantile_heights(5, 0.0, 8)[0].tolist() == [0.0]


def test_moving_front_makes_the_pull_off_continuous_and_peak_refinement_exact():
    # Stepping the preload finely: with the front the pull-off varies smoothly; a plain grid
    # of the same blocks jumps as whole blocks enter contact.
    p = PAPER_ARRAY.replace(**{"array.count": 400, "seta.L": 5.0, "floor.sigma": 0.5})
    h, w, z = qs.quantile_heights(400, 0.5, 8, return_edges=True)
    pre = np.geomspace(2.0, 200.0, 25)
    g = (0.5, z)
    smooth = [r.pull_off for r in qs.preload_pulls(p, h, pre, weights=w, gaussian=g)]
    plain = [r.pull_off for r in qs.preload_pulls(p, h, pre, weights=w)]
    # A whole block (50 setae ≈ 10 % of the pull-off) enters contact somewhere in this range.
    assert np.max(np.abs(np.diff(plain, 2))) > 0.05 * np.mean(plain)
    assert np.max(np.abs(np.diff(smooth, 2))) < 0.005 * np.mean(smooth)
    # The refined peak is at least the sampled one, and no setae let go before it.
    r0, r1 = (
        qs.preload_pulls(p, h, [22.0], weights=w, gaussian=(0.5, z), refine_peak=f)[0]
        for f in (False, True)
    )
    assert r1.pull_off >= r0.pull_off
    i = int(np.argmin(r1.force_normal))
    assert all(k > i for k, _, _ in r1.releases if k >= r1.turn_index)
