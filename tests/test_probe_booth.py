"""The spherical probe on fibrils on an elastic half-space (Bettscheider et al. 2021's model,
:mod:`gecko_agents.physics.fibril_probe_halfspace`): its rigid-backing limit against the
independent-fibril closed form, a coupled cluster solved by hand, the half-space compliance by
quadrature, the continuum limit, and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gecko_agents.physics import fibril_probe
from gecko_agents.physics import fibril_probe_halfspace as hs

K, F_R = 0.451, 4.66  # µN/µm, µN: the probe study's pillar with its punch, Kendall's pull-off
E, NU, C_FIB = 1.413, 0.3, 1.5  # MPa, -, µm: the study's polyurethane and pillar radius


@pytest.mark.parametrize("probe_radius", [30.0, 100.0])
@pytest.mark.parametrize("preload", [0.05, 1.0, 30.0])
def test_rigid_backing_is_the_independent_fibril_closed_form(probe_radius, preload):
    """With no backing compliance the model is the closed form, to rounding (1e-12 allows the
    order of the sums and of the linear solves)."""
    x, y = hs.hex_lattice(4.0, 24.0)
    h = hs.parabolic_heights(x, y, probe_radius)
    res = hs.probe_test(h, np.eye(x.size) / K, F_R, preload)
    d_max = fibril_probe.depth_for_preload(preload, h, K)
    assert res.depth_max == pytest.approx(d_max, rel=1e-12, abs=1e-12)
    assert res.pull_off == pytest.approx(fibril_probe.probe_pull_off(h, K, F_R, d_max), rel=1e-12)


def test_stiff_backing_tends_to_the_rigid_limit():
    """C_b ∝ 1/E_b: at E_b = 1e6·E the pull-off differs from the rigid one by O(1e-6) (the
    tolerance 1e-4 allows a factor 100 on that first-order term)."""
    x, y = hs.hex_lattice(4.0, 20.0)
    h = hs.parabolic_heights(x, y, 60.0)
    rigid = hs.probe_test(h, np.eye(x.size) / K, F_R, 5.0).pull_off
    stiff = np.eye(x.size) / K + hs.halfspace_compliance(x, y, C_FIB, 1e6 * E, NU)
    assert hs.probe_test(h, stiff, F_R, 5.0).pull_off == pytest.approx(rigid, rel=1e-4)


def _cluster_by_hand(p, R, s, b):
    """A centre fibril and its six hexagonal neighbours at distance p, all attached, solved by
    symmetry: forces f0 (centre), f1 (each neighbour) at depth d obey
        s·f0 + 6b(p)·f1 = d,   b(p)·f0 + (s + 2b(p) + 2b(√3p) + b(2p))·f1 = d − p²/(2R)."""
    h1 = -(p * p) / (2.0 * R)
    M = np.array([[s, 6.0 * b(p)], [b(p), s + 2 * b(p) + 2 * b(math.sqrt(3) * p) + b(2 * p)]])
    a0, a1 = np.linalg.solve(M, [1.0, 1.0])  # f = a·d + c
    c0, c1 = np.linalg.solve(M, [0.0, h1])
    # the ring touches when the probe reaches its tips, lowered by the centre's force d/s
    d_touch = -h1 / (1.0 - b(p) / s)
    # pulling: the ring (lower, more stretched) lets go first; then the centre alone at F_r
    d_ring = (-F_R - c1) / a1
    assert a0 * d_ring + c0 > -F_R  # the centre holds when the ring goes
    tension_ring = -((a0 + 6 * a1) * d_ring + c0 + 6 * c1)
    return d_touch, max(tension_ring, F_R)


def test_seven_fibrils_coupled_by_the_half_space_by_hand():
    """The coupled case against its closed form: 7 fibrils (1e-9 allows the linear solves)."""
    p, R = 4.0, 100.0
    x, y = hs.hex_lattice(p, p)
    assert x.size == 7
    h = hs.parabolic_heights(x, y, R)
    s = 1.0 / K + 16.0 * (1 - NU**2) / (3 * math.pi**2 * E * C_FIB)

    def b(r):
        return (1 - NU**2) / (math.pi * E * r)

    d_touch, expected = _cluster_by_hand(p, R, s, b)
    res = hs.probe_test(h, np.eye(7) / K + hs.halfspace_compliance(x, y, C_FIB, E, NU), F_R, 50.0)
    assert res.attached_max == 7
    assert res.depth[0] == pytest.approx(d_touch, rel=1e-9)
    assert res.pull_off == pytest.approx(expected, rel=1e-9)
    rigid = hs.probe_test(h, np.eye(7) / K, F_R, 50.0).pull_off
    assert expected != pytest.approx(rigid, rel=1e-3)  # the coupling matters here


def _stepped(h, C, F_r, preload, step):
    """The test as the ``sphericalprobe`` code runs it: the probe moved in fixed steps; after
    each, attach every free tip the probe has reached (its root lowered by the attached
    fibrils' forces) until none is added, or release every fibril past F_r until none is."""
    att, d, force = np.zeros(h.size, bool), -h.max() - step, 0.0
    while force < preload:
        d += step
        while True:
            f = np.zeros(h.size)
            A = np.flatnonzero(att)
            f[A] = np.linalg.solve(C[np.ix_(A, A)], d + h[A]) if A.size else 0.0
            new = ~att & (d + h >= C @ f)
            if not new.any():
                break
            att |= new
        force = f.sum()
    best = 0.0
    while att.any():
        d -= step
        while att.any():
            A = np.flatnonzero(att)
            f = np.linalg.solve(C[np.ix_(A, A)], d + h[A])
            if not np.any(f < -F_r):
                best = max(best, -f.sum())
                break
            att[A[f < -F_r]] = False
    return best


def test_event_to_event_meets_the_stepped_test():
    """19 coupled fibrils: the stepped test meets the event-to-event pull-off; its largest
    sampled tension falls short by at most a step times the contact's stiffness
    (1e-2 µm × 19 × 0.45 µN/µm on ≈ 85 µN, 1e-3), so 2e-3."""
    x, y = hs.hex_lattice(4.0, 8.0)
    assert x.size == 19
    h = hs.parabolic_heights(x, y, 100.0)
    C = np.eye(x.size) / K + hs.halfspace_compliance(x, y, C_FIB, E, NU)
    exact = hs.probe_test(h, C, F_R, 20.0)
    assert exact.attached_max == 19
    assert _stepped(h, C, F_R, 20.0, 1e-2) == pytest.approx(exact.pull_off, rel=2e-3)


def test_self_compliance_is_the_mean_boussinesq_displacement_over_the_disc():
    """∫∫ dA dA'/|x − x'| over a disc of radius c is 16πc³/3, so the mean displacement under a
    uniformly loaded disc is 16(1 − ν²)F/(3π²Ec). Quadrature: about the point at radius s the
    inner integral is ∫ L(φ) dφ, L the distance to the rim, ∫ over φ of √(c² − s²sin²φ)
    (Gauss–Legendre, 1e-6 allows its error for a smooth integrand on 200×200 nodes)."""
    c = 1.7
    gs, ws = np.polynomial.legendre.leggauss(200)
    s = 0.5 * c * (gs + 1.0)
    phi = np.pi * (gs + 1.0)
    inner = np.pi * np.sqrt(c * c - np.outer(s**2, np.sin(phi) ** 2)) @ ws
    integral = 0.5 * c * np.sum(ws * 2.0 * np.pi * s * inner)
    assert integral == pytest.approx(16.0 * np.pi * c**3 / 3.0, rel=1e-6)
    C = hs.halfspace_compliance([0.0, 10.0], [0.0, 0.0], c, E, NU)
    mean = (1 - NU**2) / (np.pi * E) * integral / (np.pi * c * c) ** 2
    assert C[0, 0] == pytest.approx(mean, rel=1e-6)
    assert C[0, 1] == pytest.approx((1 - NU**2) / (np.pi * E * 10.0), rel=1e-15)


def test_discrete_lattice_tends_to_the_continuum_saturation():
    """A hexagonal lattice pressed past saturation tends to π·n·R·F_r²/k as the contact radius
    √(2R·F_r/k) holds more pitches: the excess (the rim's discreteness; 6.8 %, 2.9 %, 0.9 % at
    10, 20, 40 pitches) shrinks at each doubling, and is within 1.5 % at 40 pitches."""
    n = 2.0 / math.sqrt(3.0)  # pitch 1 µm, k = 1 µN/µm, F_r = 1 µN
    excess = []
    for radius_in_pitches in (10, 20, 40):
        R = radius_in_pitches**2 / 2.0
        x, y = hs.hex_lattice(1.0, 1.5 * radius_in_pitches)
        h = hs.parabolic_heights(x, y, R)
        sat = hs.saturation_pull_off_continuum(R, n, 1.0, 1.0)
        d_max = fibril_probe.depth_for_preload(3.0 * sat, h, 1.0)
        excess.append(fibril_probe.probe_pull_off(h, 1.0, 1.0, d_max) / sat - 1.0)
    assert excess[0] > excess[1] > excess[2] > 0.0
    assert excess[2] < 0.015
    sat = hs.saturation_pull_off_continuum(50.0, n, 0.3, 2.0)
    assert sat == pytest.approx(2 * np.pi * 50.0 * hs.effective_work_of_adhesion(n, 0.3, 2.0))


def test_lattices_have_their_density():
    """Fibrils per area of a large patch (0.5 % allows the patch's ragged rim)."""
    for lattice, n in ((hs.hex_lattice, 2 / math.sqrt(3)), (hs.square_lattice, 1.0)):
        x, _ = lattice(1.0, 60.0)
        assert x.size / (math.pi * 60.0**2) == pytest.approx(n, rel=0.005)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"preload": 0.0}, "preload"),
        ({"release_force": -1.0}, "release_force"),
        ({"compliance": np.eye(3)}, "2×2"),
        ({"compliance": np.array([[1.0, 0.1], [0.2, 1.0]])}, "symmetric"),
        ({"heights": [0.0, np.nan]}, "heights"),
    ],
)
def test_bad_input_is_refused(kwargs, match):
    args = {"heights": [0.0, -0.1], "compliance": np.eye(2), "release_force": 1.0, "preload": 1.0}
    with pytest.raises(ValueError, match=match):
        hs.probe_test(**(args | kwargs))


def test_bad_backing_is_refused():
    with pytest.raises(ValueError, match="poisson"):
        hs.halfspace_compliance([0.0, 5.0], [0.0, 0.0], 1.0, 1.0, 0.6)
    with pytest.raises(ValueError, match="overlap"):
        hs.halfspace_compliance([0.0, 1.0], [0.0, 0.0], 1.0, 1.0, 0.3)
    with pytest.raises(ValueError, match="overlap"):  # radius 2 µm: roots 3 µm < 2c apart
        hs.halfspace_compliance([0.0, 3.0], [0.0, 0.0], 2.0, 1.0, 0.3)
    with pytest.raises(ValueError, match="pitch"):
        hs.hex_lattice(0.0, 10.0)


@pytest.mark.slow
def test_a_compliant_backing_attaches_more_pillars_in_both_models():
    """The study's 11 pillars under a 100 µm probe pressed to 3 µN: on the rigid backing 7
    attach; the engine's elastic strip and the half-space model both let the probe sink deeper
    and attach 9, and their pull-offs agree within 3 %, which allows for their different
    backings (a plane-strain strip held by a handle against a half-space; 1.8 % measured)."""
    from gecko_agents.studies import probe_test

    engine, _ = probe_test.run_point("flat punch, elastic backing", 11, 100.0, 3.0)
    booth = probe_test.booth_point(100.0, engine["preload_reached_uN"], 11)
    assert booth["row_attached_rigid"] == 7
    assert engine["attached_max"] == booth["row_attached_halfspace"] == 9
    assert engine["pull_off_uN"] == pytest.approx(booth["row_halfspace_uN"], rel=0.03)


def test_a_release_that_overloads_its_neighbour_takes_it_along_by_hand():
    """Two fibrils, tips at h = (−0.05, −0.1) µm, coupled through the backing:
    C = [[1, 0.5], [0.5, 1]] µm/µN, F_r = 1 µN, pressed to 1 µN. By hand, with
    C⁻¹ = (4/3)[[1, −0.5], [−0.5, 1]]: pressing, the second tip reaches the probe where
    d − 0.1 − 0.5·(d − 0.05) = 0, d = 0.15 µm (the first carrying 0.1 µN); both then carry
    (4/3)d − 0.1 = 1 µN at d = 0.825 µm. Pulling, f = ((2/3)d, (2/3)d − 0.1): the second lets
    go at f₂ = −F_r, d = −1.35 µm, the pair holding 1.9 µN; alone, the first then carries
    (d − 0.05)/1 = −1.4 µN < −F_r and goes at the same depth. The path records each event."""
    res = hs.probe_test([-0.05, -0.1], [[1.0, 0.5], [0.5, 1.0]], 1.0, 1.0)
    assert res.pull_off == pytest.approx(1.9, rel=1e-12)
    assert res.depth_max == pytest.approx(0.825, rel=1e-12)
    assert res.attached_max == 2
    np.testing.assert_allclose(res.depth, [0.15, 0.825, -1.35, -1.35], rtol=1e-12)
    np.testing.assert_allclose(res.force, [0.1, 1.0, -1.9, 0.0], rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(res.attached, [1, 2, 2, 0])
    assert res.attached.dtype.kind == "i"


def test_a_cascade_stops_at_a_fibril_the_backing_does_not_load_by_hand():
    """The coupled pair of the test above, lowered by 0.5 µm (h = −0.55, −0.6 µm), beside a
    third fibril on its own (h₃ = −0.1 µm, no coupling), F_r = 1 µN, pressed to 3 µN. By hand:
    the third touches at d = 0.1, the first at 0.55 (the third carrying 0.45 µN), the second
    where d − 0.6 − 0.5(d − 0.55) = 0, d = 0.65 (0.55 + 0.1 µN); all three carry
    (d − 0.1) + (4/3)d − 0.7667 = 3 µN at d = 1.6571 µm. Pulling, the pair goes at
    d = −0.85 µm as before (its second at −F_r, its first then at −1.4 µN alone), the third
    holding d − 0.1 = −0.95 µN: 2.85 µN on the probe. The third alone lets go at d = −0.9 µm."""
    res = hs.probe_test([-0.55, -0.6, -0.1], [[1, 0.5, 0], [0.5, 1, 0], [0, 0, 1]], 1.0, 3.0)
    assert res.pull_off == pytest.approx(2.85, rel=1e-12)
    np.testing.assert_allclose(res.depth, [0.55, 0.65, 11.6 / 7, -0.85, -0.9, -0.9], rtol=1e-12)
    np.testing.assert_allclose(res.force, [0.45, 0.65, 3.0, -2.85, -1.0, 0.0], rtol=1e-12)
    np.testing.assert_array_equal(res.attached, [1, 2, 3, 3, 1, 0])


@pytest.mark.parametrize("release_force", [0.5, 3.0])
def test_one_fibril_pulls_off_at_its_release_force(release_force):
    """A single fibril (k = 2 µN/µm) holds the probe until its own release force; pressed
    too little to touch (its tip below the deepest press), it holds nothing."""
    assert hs.probe_test([0.0], [[0.5]], release_force, 1.0).pull_off == pytest.approx(
        release_force, rel=1e-12
    )
    assert fibril_probe.probe_pull_off([0.0], 2.0, release_force, 1.0) == pytest.approx(
        release_force, rel=1e-12
    )
    assert fibril_probe.probe_pull_off([-3.0], 2.0, release_force, 1.0) == 0.0


def test_weights_count_fibrils_as_repeats():
    """A weight w_i is w_i identical fibrils: integer weights give the closed forms of the
    heights repeated w_i times (depth for a preload, force while retracting, pull-off)."""
    h, w = np.array([0.0, -0.2, -0.5, -0.9]), np.array([2.0, 1.0, 3.0, 1.0])
    rep = np.repeat(h, w.astype(int))
    for preload in (0.3, 2.0, 9.0):
        d = fibril_probe.depth_for_preload(preload, h, K, weights=w)
        assert d == pytest.approx(fibril_probe.depth_for_preload(preload, rep, K), rel=1e-12)
        for at in (d, 0.5 * d, -0.3):
            assert fibril_probe.probe_force(at, h, K, d, weights=w) == pytest.approx(
                fibril_probe.probe_force(at, rep, K, d), rel=1e-12, abs=1e-15
            )
        assert fibril_probe.probe_pull_off(h, K, F_R, d, weights=w) == pytest.approx(
            fibril_probe.probe_pull_off(rep, K, F_R, d), rel=1e-12
        )


def test_ring_weights_fill_the_disc():
    """Rings of width Δr at their mid radii (i + ½)Δr hold 2πr·n·Δr fibrils each, and m of
    them the disc's n·π(mΔr)² exactly (the midpoint rule is exact for 2πr)."""
    n, dr, m = 0.07, 1.3, 12
    r = (np.arange(m) + 0.5) * dr
    wts = fibril_probe.ring_weights(r, n, dr)
    np.testing.assert_allclose(wts, 2.0 * np.pi * r * n * dr, rtol=1e-15)
    assert wts.sum() == pytest.approx(n * np.pi * (m * dr) ** 2, rel=1e-12)
    assert fibril_probe.ring_weights([-2.0], n, dr)[0] == pytest.approx(2 * np.pi * 2.0 * n * dr)


def test_effective_work_and_fibril_compliance_by_hand():
    """W_eff = n·F_r²/(2k): 0.2·3²/(2·0.5) = 1.8 µN/µm; a fibril's axial compliance
    L/(πc²E): 20/(π·1.5²·2) µm/µN."""
    assert hs.effective_work_of_adhesion(0.2, 0.5, 3.0) == pytest.approx(1.8, rel=1e-12)
    assert hs.fibril_compliance(20.0, 1.5, 2.0) == pytest.approx(
        20.0 / (math.pi * 1.5**2 * 2.0), rel=1e-12
    )


@pytest.mark.parametrize(
    ("call", "name"),  # the message starts with the name
    [
        (lambda: hs.hex_lattice(0.0, 10.0), "pitch = "),
        (lambda: hs.hex_lattice(1.0, -1.0), "extent = "),
        (lambda: hs.square_lattice(-1.0, 10.0), "pitch = "),
        (lambda: hs.square_lattice(1.0, 0.0), "extent = "),
        (lambda: hs.parabolic_heights([0.0], [0.0], 0.0), "probe_radius = "),
        (lambda: hs.fibril_compliance(0.0, 1.0, 1.0), "length = "),
        (lambda: hs.fibril_compliance(1.0, np.inf, 1.0), "radius = "),
        (lambda: hs.fibril_compliance(1.0, 1.0, -2.0), "modulus = "),
        (lambda: hs.halfspace_compliance([0.0], [0.0], 0.0, 1.0, 0.3), "radius = "),
        (lambda: hs.halfspace_compliance([0.0], [0.0], 1.0, np.nan, 0.3), "modulus = "),
        (lambda: hs.probe_test([0.0], [[1.0]], 0.0, 1.0), "release_force = "),
        (lambda: hs.probe_test([0.0], [[1.0]], 1.0, -1.0), "preload = "),
        (lambda: hs.probe_test([[0.0, -0.1]], np.eye(2), 1.0, 1.0), "heights must"),
        (lambda: hs.probe_test([0.0, -0.1], [[1.0, 0.0], [0.0, 0.0]], 1.0, 1.0), "compliance must"),
        (
            lambda: hs.probe_test([0.0, -0.1], [[1, 0.5], [0.5 + 5e-9, 1]], 1.0, 1.0),
            "compliance must",
        ),
    ],
)
def test_each_bad_value_is_refused_naming_it(call, name):
    with pytest.raises(ValueError, match="^" + name):
        call()


def test_the_limits_of_the_backing_are_accepted():
    """ν = 0 and ν = 0.5 (incompressible) are allowed, and fibrils just touching (roots 2c
    apart) do not overlap."""
    for nu in (0.0, 0.5):
        C = hs.halfspace_compliance([0.0, 5.0], [0.0, 0.0], 1.0, 1.0, nu)
        assert C[0, 1] == pytest.approx((1 - nu * nu) / (np.pi * 5.0), rel=1e-15)
    C = hs.halfspace_compliance([0.0, 2.0], [0.0, 0.0], 1.0, 1.0, 0.3)
    assert C[0, 1] == pytest.approx(0.91 / (2 * np.pi), rel=1e-15)


def test_fibril_closed_forms_by_hand():
    """Fibrils at h = (0, −0.2, −0.5, −0.9) µm with weights (2, 1, 3, 1), k = K:
    - pressed to P = 0.7K the first two carry it, K(2d + (d − 0.2)) = P: d = 0.3 µm;
    - retracting from d_max = 0.6 µm (three attached) to d = 0.1 µm the probe feels
      K(2·0.1 + (0.1 − 0.2) + 3(0.1 − 0.5)) = −1.1K;
    - the pull-off is the largest of the tensions just before each height lets go:
      6F_r − 1.3K (all three), 3F_r − 0.4K, 2F_r: here 6F_r − 1.3K."""
    h, w = np.array([0.0, -0.2, -0.5, -0.9]), np.array([2.0, 1.0, 3.0, 1.0])
    assert fibril_probe.depth_for_preload(0.7 * K, h, K, weights=w) == pytest.approx(0.3)
    assert fibril_probe.probe_force(0.1, h, K, 0.6, weights=w) == pytest.approx(-1.1 * K)
    assert fibril_probe.probe_pull_off(h, K, F_R, 0.6, weights=w) == pytest.approx(
        6 * F_R - 1.3 * K, rel=1e-12
    )


@pytest.mark.parametrize("lattice", [hs.square_lattice, hs.hex_lattice])
@pytest.mark.parametrize("pitch", [0.25, 0.5, 2.0])
def test_small_patches_counted_by_hand(lattice, pitch):
    """Within two pitches of the origin, rim included: the square lattice's 13 points
    (i² + j² ≤ 4) and the hexagonal lattice's 19 (the centre, 6 at p, 6 at √3p, 6 at 2p);
    within one pitch, 5 and 7; within three, 29 and 37 (12 at √7p, 6 at 3p). Every point is
    at most the extent from the origin."""
    counts = {
        hs.square_lattice: {3.0: 29, 2.0: 13, 1.0: 5},
        hs.hex_lattice: {3.0: 37, 2.0: 19, 1.0: 7},
    }
    for reach, count in counts[lattice].items():
        x, y = lattice(pitch, reach * pitch)
        assert x.size == count
        assert np.hypot(x, y).max() == pytest.approx(reach * pitch, rel=1e-12)
        assert len(set(zip(np.round(x / pitch, 9), np.round(y / pitch, 9), strict=True))) == x.size


def test_a_fibril_the_probe_reaches_only_at_the_preload_has_not_bonded():
    """Fibrils at h = (0, −0.5) µm, k = 2 µN/µm, pressed to P = 1 µN: the first alone carries
    it at d = P/k = 0.5 µm, exactly where the probe reaches the second's tip, which carries
    nothing there (u = d + h = 0) and so has not bonded: both models pull off at the first's
    F_r = 2 µN (bonded, the second would add its tension: 2F_r − k·0.5 = 3 µN), and retracting
    to d = −0.2 µm the probe feels the first alone, k·d = −0.4 µN."""
    h, k, F_r, P = [0.0, -0.5], 2.0, 2.0, 1.0
    d_max = fibril_probe.depth_for_preload(P, h, k)
    assert d_max == 0.5
    assert fibril_probe.probe_force(-0.2, h, k, d_max) == pytest.approx(-0.4, rel=1e-15)
    assert fibril_probe.probe_pull_off(h, k, F_r, d_max) == pytest.approx(F_r, rel=1e-15)
    res = hs.probe_test(h, np.eye(2) / k, F_r, P)
    assert (res.depth_max, res.attached_max) == (0.5, 1)
    assert res.pull_off == pytest.approx(F_r, rel=1e-15)


@pytest.mark.parametrize("shift", [-0.3, 0.6])
def test_only_the_relative_heights_matter(shift):
    """The depth is counted from first touch, so heights all shifted by c (a probe measured
    from another reference) give the same forces and attached counts, every depth shifted
    by −c: the three-fibril cascade by hand above, shifted both ways."""
    h, C = np.array([-0.55, -0.6, -0.1]), [[1, 0.5, 0], [0.5, 1, 0], [0, 0, 1]]
    ref, moved = hs.probe_test(h, C, 1.0, 3.0), hs.probe_test(h + shift, C, 1.0, 3.0)
    assert moved.pull_off == pytest.approx(ref.pull_off, rel=1e-12)
    np.testing.assert_allclose(moved.depth, ref.depth - shift, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(moved.force, ref.force, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(moved.attached, ref.attached)
    # three independent fibrils (k = 2 µN/µm): each lets go at its own depth −F_r/k − h
    rigid = hs.probe_test([0.0 + shift, -0.2 + shift, -0.5 + shift], np.eye(3) / 2, 1.0, 3.0)
    np.testing.assert_allclose(rigid.depth[-4:], np.array([0.0, -0.3, -0.5, -0.5]) - shift)
    np.testing.assert_array_equal(rigid.attached[-4:], [3, 2, 1, 0])


@pytest.mark.parametrize("scale", [1e-6, 1e6])
def test_forces_scale_out_of_the_model(scale):
    """A linear model with a fixed release force has no force scale of its own: forces (F_r,
    the preload) times λ and the compliance over λ give the same depths and attached counts
    and every force times λ (the three-fibril cascade by hand above at λ = 1e-6 and 1e6, where
    a tolerance not proportional to F_r would release the third fibril with the pair)."""
    h, C = [-0.55, -0.6, -0.1], np.array([[1, 0.5, 0], [0.5, 1, 0], [0, 0, 1]])
    ref, scaled = hs.probe_test(h, C, 1.0, 3.0), hs.probe_test(h, C / scale, scale, 3.0 * scale)
    assert scaled.pull_off == pytest.approx(scale * ref.pull_off, rel=1e-12)
    np.testing.assert_allclose(scaled.depth, ref.depth, rtol=1e-12)
    np.testing.assert_allclose(scaled.force, scale * ref.force, rtol=1e-12)
    np.testing.assert_array_equal(scaled.attached, ref.attached)


@pytest.mark.parametrize("scale", [1.0, 1e-6])
def test_rings_of_a_hexagonal_patch_touch_and_let_go_together(scale):
    """On a rigid backing the probe reaches a fibril at r from its apex at d = r²/(2R_p) and
    it lets go at d = r²/(2R_p) − F_r/k; the hexagonal lattice's rings (6 at p, 6 at √3p, 6
    at 2p, 12 at √7p, 6 at 3p) touch and let go each at one depth, every fibril of the ring
    at once, outermost first on the pull: one event per ring, the attached counts 1, 7, 13,
    19, 31 before the preload's event (37 attached) and 37, 31, 19, 13, 7, 1 as each ring
    goes. Lengths (pitch, R_p, compliance) times 1e-6 scale every depth by 1e-6: the tolerance
    that tells one ring from the next is the model's own length scale."""
    p, R = 2.0 * scale, 50.0 * scale
    x, y = hs.hex_lattice(p, 3.0 * p)
    h = hs.parabolic_heights(x, y, R)
    res = hs.probe_test(h, scale * np.eye(x.size) / K, F_R, 1e3)
    top = np.argmax(res.depth)
    ring = np.array([0.0, 1.0, 3.0, 4.0, 7.0, 9.0]) * p * p / (2.0 * R)
    np.testing.assert_allclose(res.depth[:top], ring[1:], rtol=1e-12)
    np.testing.assert_array_equal(res.attached[: top + 1], [1, 7, 13, 19, 31, 37])
    pull = res.depth[top + 1 :]
    np.testing.assert_allclose(pull[:-1], ring[::-1] - scale * F_R / K, rtol=1e-12)
    np.testing.assert_array_equal(res.attached[top + 1 :], [37, 31, 19, 13, 7, 1, 0])


def test_a_fibril_its_pressed_neighbours_sink_faster_than_the_probe_never_touches():
    """Two fibrils at h = 0 that a backing couples (C₁₂ = 0.3 µm/µN) both to a third at
    h = −0.01 µm (C₁₃ = C₂₃ = 0.7, a positive-definite C with unit diagonal): pressed at
    depth d they carry f = d/1.3 each and lower the third's root by 2·0.7·d/1.3 > d, faster
    than the probe descends, so the third never touches; pressed to 5 µN the pair sinks to
    d = 3.25 µm and pulls off at 2F_r, both letting go at d = −1.3F_r."""
    C = [[1.0, 0.3, 0.7], [0.3, 1.0, 0.7], [0.7, 0.7, 1.0]]
    res = hs.probe_test([0.0, 0.0, -0.01], C, 1.0, 5.0)
    assert res.attached_max == 2
    assert res.depth_max == pytest.approx(3.25, rel=1e-12)
    assert res.pull_off == pytest.approx(2.0, rel=1e-12)
    np.testing.assert_allclose(res.depth, [3.25, -1.3, -1.3], rtol=1e-12)


def test_a_fibril_its_neighbours_press_into_tension_is_held_by_them():
    """Three fibrils at h = 0 on the coupled backing above (C₁₂ = 0.3, C₁₃ = C₂₃ = 0.7):
    C⁻¹1 = (15/16, 15/16, −5/16), so pressing the pair pulls the third into tension,
    f₃ = −5d/16. Pressed to 1 µN (d = 0.64 µm, the third at −0.2 µN, below F_r = 1 µN), then
    pulled, the third is pushed back as the pair stretches; the pair lets go at f = −F_r,
    d = −16/15 µm, the probe holding (25/16)·(16/15) = 5/3 µN, and the third, alone at
    f₃ = d < −F_r, follows at once."""
    C = [[1.0, 0.3, 0.7], [0.3, 1.0, 0.7], [0.7, 0.7, 1.0]]
    res = hs.probe_test([0.0, 0.0, 0.0], C, 1.0, 1.0)
    assert res.attached_max == 3 and res.depth_max == pytest.approx(0.64, rel=1e-12)
    assert res.pull_off == pytest.approx(5.0 / 3.0, rel=1e-12)
    np.testing.assert_allclose(res.depth, [0.64, -16 / 15, -16 / 15], rtol=1e-12)
    np.testing.assert_allclose(res.force, [1.0, -5.0 / 3.0, 0.0], rtol=1e-12, atol=1e-15)
    np.testing.assert_array_equal(res.attached, [3, 3, 0])
