"""Each formula with one home (physics.friction, physics.beam.touchdown_height, the JKR slopes of
physics.jkr) against its closed form in numbers worked by hand, and every caller against the home:
the friction cap, Mindlin's stick stiffness, the touch-down height R + L sin θ, dP/da and dδ/da;
plus the named indices of the contact laws' constants."""

from __future__ import annotations

import math

import extras
import numpy as np
import pytest

from gecko_agents import quasistatic as qs
from gecko_agents.contact import (
    SpatulaTip,
    contact_law,
    hertz,
    jkr_sphere,
    mindlin_stiffness,
    rate_jkr,
    sheared_jkr,
    spatula,
)
from gecko_agents.contact.base import K_ATTACH_FILM, K_ATTACH_RADIUS
from gecko_agents.model.world import World
from gecko_agents.params import PAPER_ARRAY, PAPER_TABLE1, Friction, presets
from gecko_agents.physics import beam, jkr
from gecko_agents.physics.friction import (
    combined_shear_modulus,
    friction_cap,
    friction_cap_slope,
    stick_stiffness,
)
from gecko_agents.quasistatic.branches import Branches
from gecko_agents.quasistatic.heights import touchdown
from gecko_agents.render import touchdown_height

# --- Coulomb cap μ|P + 2Fc| (Thornton 1991) / μ·max(P, 0) (paper eq 27) ----------------------


@pytest.mark.parametrize(
    ("P", "Fc", "mu", "paper", "expected"),
    [
        (1.5, 2.0, 0.2, False, 1.1),  # 0.2·|1.5 + 4|
        (-3.0, 1.0, 0.2, False, 0.2),  # in tension: 0.2·|−3 + 2|
        (-5.0, 1.0, 0.2, False, 0.6),  # past −2Fc the magnitude counts: 0.2·|−5 + 2|
        (2.0, 0.0, 0.5, False, 1.0),  # no adhesion: Amontons' μ·P
        (1.5, 2.0, 0.2, True, 0.3),  # paper: 0.2·1.5
        (-1.0, 2.0, 0.2, True, 0.0),  # paper: no load, no friction
    ],
)
def test_friction_cap_by_hand(P, Fc, mu, paper, expected):
    assert friction_cap(P, Fc, mu, paper) == pytest.approx(expected, rel=1e-15)
    law = "paper" if paper else "adhesive"
    assert Friction(mu=mu, law=law).cap(P, Fc) == pytest.approx(expected, rel=1e-15)


def test_friction_cap_on_arrays_and_its_slope():
    P = np.array([-5.0, -3.0, 0.0, 1.5])
    assert np.allclose(friction_cap(P, 1.0, 0.2, False), [0.6, 0.2, 0.4, 0.7], rtol=1e-15)
    assert np.allclose(friction_cap(P, 1.0, 0.2, True), [0.0, 0.0, 0.0, 0.3], rtol=1e-15)
    assert np.array_equal(friction_cap_slope(P, 1.0, 0.2, False), [-0.2, -0.2, 0.2, 0.2])
    assert np.array_equal(friction_cap_slope(P, 1.0, 0.2, True), [0.0, 0.0, 0.0, 0.2])


def test_every_friction_cap_is_the_home():
    """The quasi-static solvers, the sheared JKR sphere and the spatula's pad cap call it."""
    P = np.array([-4.0, -1.0, 0.5, 3.0])
    for law in ("adhesive", "paper"):
        p = PAPER_TABLE1.replace(**{"friction.law": law, "friction.mu": 0.3})
        Fc = p.contact.pull_off_force
        expected = friction_cap(P, Fc, 0.3, law == "paper")
        assert np.array_equal(Branches.from_params(p).cap(P), expected)
        assert np.array_equal(qs.RodSetup.from_params(p).cap(P), expected)
        sheared = contact_law(p.replace(**{"contact.shear_coupling": "savkoor_briggs"}))
        assert [sheared_jkr._cap(x, sheared.constants) for x in P] == list(expected)
        # The spatula's pad: the cap of an unloaded contact, μ·2Fc (adhesive) or 0 (paper),
        # times the fraction ℓ/ℓ0 of the pad still attached (Fc = w·b).
        tip = SpatulaTip(p.contact, p.spatula, p.friction)
        half = 0.5 * tip.ell0
        pad = 0.0 if law == "paper" else 0.3 * 2.0 * p.contact.jkr_args()[1] * p.spatula.b * 0.5
        assert spatula._friction_cap(0.0, half, tip.constants) == pytest.approx(pad, rel=1e-15)


def test_friction_cap_compiles():
    numba = extras.require("fast")

    @numba.njit
    def caps(P):
        return friction_cap(P, 2.0, 0.2, False), friction_cap(P, 2.0, 0.2, True)

    assert caps(1.5) == pytest.approx((1.1, 0.3), rel=1e-15)


# --- Mindlin's stick stiffness k_t = 8G*·a (Mindlin 1949; Johnson 1985 §7.2) ----------------


def test_mindlin_stiffness_by_hand():
    """Table 1's materials: G1 = 1.413/(2·1.3) MPa, G2 = 55 000/(2·1.25) MPa;
    G* = (1.7/G1 + 1.75/G2)⁻¹ = 0.319675 MPa; at a = 2 µm, k_t = 16·G* = 5.114802 µN/µm."""
    c = PAPER_TABLE1.contact
    G = combined_shear_modulus(c.E1, c.nu1, c.E2, c.nu2)
    assert G == pytest.approx(0.3196751287877961, rel=1e-13)
    assert stick_stiffness(2.0, G) == pytest.approx(5.114802060604737, rel=1e-13)
    assert mindlin_stiffness(c, 2.0) == pytest.approx(5.114802060604737, rel=1e-13)
    assert np.allclose(stick_stiffness(np.array([1.0, 2.0]), 0.5), [4.0, 8.0], rtol=1e-15)


def test_sheared_sphere_stick_force_is_mindlins():
    """The sheared JKR sphere's tangential force is −8G*·a·ξ at the radius it reports."""
    p = PAPER_TABLE1.replace(**{"contact.shear_coupling": "savkoor_briggs"})
    law = contact_law(p)
    k = law.constants
    xi = 0.01
    P, T, _, a, xi_out, *_ = law.step_scalar(xi, law.R - 0.05, law.a0, 0.0, 0.0, 0.0, k)
    assert xi_out == xi
    assert T == pytest.approx(-8.0 * law.G_star * a * xi, rel=1e-15)


# --- touch-down height R + L sin θ ----------------------------------------------------------


def test_touchdown_height_by_hand():
    """Table 1: R = 4 µm, L = 20 µm, θ = 30°: 4 + 20·½ = 14 µm; the array (θ = 60°):
    4 + 20·(√3/2) = 21.320508 µm."""
    assert beam.touchdown_height(20.0, math.radians(30.0), 4.0) == pytest.approx(14.0, rel=1e-15)
    for p, expected in ((PAPER_TABLE1, 14.0), (PAPER_ARRAY, 21.32050807568877)):
        assert touchdown_height(p) == pytest.approx(expected, rel=1e-15)
        assert touchdown(p) == pytest.approx(expected, rel=1e-15)
        assert Branches.from_params(p).touchdown == pytest.approx(expected, rel=1e-15)


def test_world_touches_down_at_the_home_height():
    p = PAPER_TABLE1
    from gecko_agents.model import Model

    m = Model(p, n_sim=1)
    assert isinstance(m.world, World)
    assert m.z_touch == beam.touchdown_height(p.seta.L, p.seta.theta, p.contact.R)


# --- JKR slopes (eq 7 and eq 10 differentiated) ----------------------------------------------

# R = 1, E* = 1, w = 1/(2π): √(8πwE*) = 2 and √(2πw/E*) = 1, so every term is a round number.
R1, E1, W1 = 1.0, 1.0, 1.0 / (2.0 * math.pi)


def test_jkr_slopes_by_hand():
    """a = 1: P = 4/3 − 2 = −2/3, dP/da = 4 − 3 = 1, δ = 1 − 1 = 0, dδ/da = 2 − ½ = 3/2.
    a = 4: P = 256/3 − 16, dP/da = 64 − 6 = 58, δ = 16 − 2 = 14, dδ/da = 8 − ¼ = 7.75."""
    for a, terms in ((1.0, (-2.0 / 3.0, 1.0, 0.0, 1.5)), (4.0, (256 / 3 - 16, 58.0, 14.0, 7.75))):
        assert jkr.branch_terms(a, R1, W1, E1) == pytest.approx(terms, rel=1e-14, abs=1e-14)
        assert jkr.force_slope(a, R1, W1, E1) == pytest.approx(terms[1], rel=1e-14)
        assert jkr.overlap_slope(a, R1, W1, E1) == pytest.approx(terms[3], rel=1e-14)
        assert jkr.contact_stiffness(a, R1, W1, E1) == pytest.approx(terms[1] / terms[3])


def test_jkr_slopes_vanish_where_the_closed_forms_say():
    """dP/da = 0 at the load-controlled pull-off a = 4^(−1/3)·a0; dδ/da = 0 at a_c."""
    R, w, E = PAPER_TABLE1.contact.jkr_args()
    a0 = jkr.zero_load_contact_radius(R, w, E)
    scale = 4.0 * E * a0 * a0 / R
    assert abs(jkr.force_slope(4 ** (-1 / 3) * a0, R, w, E)) < 1e-12 * scale
    assert abs(jkr.overlap_slope(jkr.snap_off_radius(R, w, E), R, w, E)) < 1e-12


def test_branch_tables_follow_the_jkr_terms():
    """Branches._G_dG writes jkr.branch_terms out in its own order of operations (so the tables
    stay bit-identical); pinned here: G = −δ − D(P), dG/da = −δ' − D'·P' on every branch."""
    p = PAPER_TABLE1
    br = Branches.from_params(p)
    assert isinstance(br, Branches)
    a = np.linspace(1.01, 3.0, 50) * jkr.snap_off_radius(*p.contact.jkr_args())
    P, dP, d, dd = jkr.branch_terms(a, br.R, br.w, br.E_star)
    for name, K in (("stick", br.Kyy_stick), ("free", br.Ky)):
        G, dG = br._G_dG(name, a)
        np.testing.assert_allclose(G, -d - P / K, rtol=1e-12)
        np.testing.assert_allclose(dG, -dd - dP / K, rtol=1e-12)
    for name in ("slip+", "slip-"):
        G, dG = br._G_dG(name, a)
        np.testing.assert_allclose(G, -d - br.deflection(name, P), rtol=1e-12)


# --- named indices of the laws' constants ----------------------------------------------------


def test_named_constants_hold_what_their_names_say():
    c = PAPER_TABLE1.contact
    R, w, E = c.jkr_args()
    k = contact_law(PAPER_TABLE1.replace(tip="hertz")).constants
    assert (k[hertz.K_R], k[hertz.K_FORCE]) == (R, 4.0 * E / (3.0 * R))
    k = contact_law(PAPER_TABLE1).constants
    assert (k[jkr_sphere.K_R], k[jkr_sphere.K_W], k[jkr_sphere.K_E]) == (R, w, E)
    assert k[jkr_sphere.K_AC] == jkr.snap_off_radius(R, w, E)
    law = contact_law(PAPER_TABLE1.replace(**{"contact.crack_speed": 0.5}))
    k = law.constants
    assert (k[rate_jkr.K_V_OPEN], k[rate_jkr.K_DELTA_C]) == (0.5, law.delta_c)
    law = contact_law(PAPER_TABLE1.replace(**{"contact.shear_coupling": "savkoor_briggs"}))
    k = law.constants
    assert (k[sheared_jkr.K_G], k[sheared_jkr.K_FC]) == (law.G_star, law.pull_off_force)
    assert (k[sheared_jkr.K_MU], k[sheared_jkr.K_PAPER]) == (0.2, 0.0)
    law = contact_law(PAPER_TABLE1.replace(tip="spatula"))
    k = law.constants
    assert (k[spatula.K_FILM], k[spatula.K_KT]) == (law.K, law.tip_stiffness)
    assert (k[spatula.K_B], k[spatula.K_H], k[spatula.K_FC]) == (law.b, law.h, w * law.b)


@pytest.mark.parametrize("coupling", ["spatula", "savkoor_briggs"])
def test_tangential_laws_fill_the_attachment_slots(coupling):
    """The loop starts an attached tip at k[K_ATTACH_RADIUS], k[K_ATTACH_FILM]; the numpy step at
    the law's ell0, s_attach: they must agree."""
    if coupling == "spatula":
        law = contact_law(PAPER_TABLE1.replace(tip="spatula"))
    else:
        law = contact_law(PAPER_TABLE1.replace(**{"contact.shear_coupling": coupling}))
    assert law.constants[K_ATTACH_RADIUS] == law.ell0
    assert law.constants[K_ATTACH_FILM] == law.s_attach


def test_presets_are_the_params_api():
    from gecko_agents.params import PAPER_FIG5_READING

    assert presets.PAPER_FIG5_READING is PAPER_FIG5_READING
    assert presets.PAPER_ARRAY is PAPER_ARRAY
