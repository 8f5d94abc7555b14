"""Pillar designs: the flat-punch tip, vertical pillars and the spherical-probe test, against
their closed forms (Sneddon 1965; Kendall 1971; the independent-fibril probe model)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.analysis.pull import pull_off
from gecko_agents.contact import FlatPunch, contact_law
from gecko_agents.floor.probe import probe_heights, probe_profile
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY, Contact
from gecko_agents.physics import fibril_probe, punch

PILLAR = PAPER_ARRAY.replace(
    **{"seta.theta_deg": 90.0, "tip": "flat_punch", "array.count": 1, "floor.sigma": 0.0}
)


def _run(params, proto, n=1):
    return Model(params, n_sim=n, seed=0).run(proto, progress=False)


# --- closed forms, by hand ------------------------------------------------------------------
def test_punch_closed_forms_by_hand():
    # E* = 2 MPa, a = 1.5 µm, w = 0.04 µN/µm: F = √(8π·2·0.04·1.5³) = √(6.7858…) µN
    assert punch.kendall_pull_off(1.5, 0.04, 2.0) == pytest.approx(2.6049645, rel=1e-7)
    assert punch.punch_stiffness(1.5, 2.0) == 6.0  # 2E*a
    # δ_detach = −F/(2E*a) = −√(2π·0.04·1.5/2)
    assert punch.kendall_detach_overlap(1.5, 0.04, 2.0) == pytest.approx(-0.43416, rel=1e-4)
    # Griffith at the edge: G(F) = w exactly at Kendall's pull-off
    F = punch.kendall_pull_off(1.5, 0.04, 2.0)
    assert punch.edge_release_rate(F, 1.5, 2.0) == pytest.approx(0.04, rel=1e-12)


def test_flat_punch_law_forms_agree_and_energy_is_the_force_integral():
    law = FlatPunch(Contact(R=2.0))
    k = law.constants
    d = np.linspace(law.detach_overlap, 0.3, 41)
    a = law.radius(d)
    assert np.all(a == 2.0)
    P = law.force(a, d)
    assert np.allclose(P, [law.force_scalar(2.0, x, k) for x in d], rtol=0, atol=1e-14)
    assert np.allclose(law.energy(a, d), [law.energy_scalar(2.0, x, k) for x in d], atol=1e-14)
    h = 1e-6  # central difference, error O(h²) on a quadratic: exact to rounding
    dU = (law.energy(a, d + h) - law.energy(a, d - h)) / (2 * h)
    assert np.allclose(dU, P, rtol=1e-7, atol=1e-9)
    assert law.force(a[:1], np.array([law.detach_overlap]))[0] == pytest.approx(
        -law.pull_off_force, rel=1e-12
    )


def test_flat_punch_bonds_at_first_touch_with_its_whole_face():
    """A flat face has no jump-in: it bonds where it touches (δ = 0) over its whole radius,
    carrying no force there, and its zero-load stiffness is Sneddon's 2E*a."""
    c = Contact(R=2.0)
    law = FlatPunch(c)
    assert law.attach_overlap == 0.0
    assert law.jump_radius == law.a0 == 2.0
    assert law.force_scalar(law.jump_radius, law.attach_overlap, law.constants) == 0.0
    _, _, E = c.jkr_args()
    assert law.zero_load_stiffness == pytest.approx(2.0 * E * 2.0, rel=1e-15)


def test_tip_is_chosen_by_name_and_sphere_options_are_refused():
    assert isinstance(contact_law(PILLAR), FlatPunch)
    for key, value in (
        ("contact.crack_speed", 1.0),
        ("contact.shear_coupling", "savkoor_briggs"),
        ("contact.detachment", "delta_s"),
    ):
        with pytest.raises(ValueError, match="flat_punch"):
            PILLAR.replace(**{key: value})


def test_vertical_pillar_is_allowed_and_beyond_is_refused():
    assert PILLAR.seta.theta_deg == 90.0
    with pytest.raises(
        ValueError, match=r"theta_deg = 90.5 is outside the allowed range \(0.0, 90.0\]"
    ):
        PILLAR.replace(**{"seta.theta_deg": 90.5})


# --- agent single pillar against Kendall and Sneddon ------------------------------------
@pytest.fixture(scope="module")
def pillar_history():
    return _run(PILLAR, protocol.press_pull(0.2, speed=0.005))


def test_single_pillar_pull_off_is_kendall(pillar_history):
    c = PILLAR.contact
    F = float(punch.kendall_pull_off(c.R, c.work_of_adhesion, c.E_star))
    # A slow pull (0.005 µm/µs, ~10⁴ steps through the tension branch): the tip lags its
    # quasi-static place by v·(damping time), far below 1 %.
    assert pull_off(pillar_history).adhesion == pytest.approx(F, rel=0.01)


def test_single_pillar_stiffness_is_seta_and_sneddon_in_series(pillar_history):
    h = pillar_history
    c = PILLAR.contact
    k = 1.0 / (1.0 / PILLAR.axial_stiffness + 1.0 / float(punch.punch_stiffness(c.R, c.E_star)))
    P, y = h["force_normal_uN"], h["plate_y_um"]
    # The retraction's tension branch, between 20 % and 80 % of the pull-off (away from the
    # touch-down ringing and the release): a straight line of slope k.
    Fc = pull_off(h).adhesion
    i0 = int(np.argmax(P))
    sel = np.arange(i0, pull_off(h).index)
    sel = sel[(-P[sel] > 0.2 * Fc) & (-P[sel] < 0.8 * Fc)]
    slope = np.polyfit(y[sel], P[sel], 1)[0]
    assert -slope == pytest.approx(k, rel=0.01)


@pytest.mark.parametrize("tip", ["flat_punch", "sphere"])
def test_theta_to_90_is_continuous(tip):
    out = []
    for theta in (89.9, 90.0):
        p = PILLAR.replace(**{"seta.theta_deg": theta, "tip": tip, "mechanics": "rod"})
        out.append(pull_off(_run(p, protocol.press_pull(0.2, speed=0.01))).adhesion)
    assert out[0] == pytest.approx(out[1], rel=0.005)


# --- the spherical probe --------------------------------------------------------------------
def test_probe_profile_is_the_circle():
    prof = probe_profile(50.0, -30.0, 30.0, centre=0.0)
    assert prof.y.max() == pytest.approx(0.0, abs=1e-12)
    # a chord of length s sags s²/(8R cos³α) below the circle at slope α
    xm = 0.5 * (prof.x[1:] + prof.x[:-1])
    gap = probe_heights(xm, 50.0) - np.interp(xm, prof.x, prof.y)
    cos_a = np.sqrt(1.0 - (xm / 50.0) ** 2)
    assert np.all(gap <= 1.0001e-4 / cos_a**3)
    assert np.all(gap >= 0.0)
    assert probe_heights(np.array([30.0]), 50.0)[0] == pytest.approx(40.0 - 50.0)


def test_independent_fibril_oracle_against_brute_force():
    rng = np.random.default_rng(1)
    h = -np.sort(rng.uniform(0, 1.0, 9))
    k, Fr = 0.7, 0.3
    d_max = fibril_probe.depth_for_preload(2.0, h, k)
    assert np.sum(k * np.clip(d_max + h, 0, None)) == pytest.approx(2.0, rel=1e-12)
    # retract in fine steps, releasing every fibril past −Fr/k: the largest tension
    att = d_max + h > 0
    best = 0.0
    for d in np.linspace(d_max, -Fr / k - 2.0, 200_001):
        att &= d + h >= -Fr / k
        best = max(best, -float(np.sum(k * (d + h[att]))))
    assert fibril_probe.probe_pull_off(h, k, Fr, d_max) == pytest.approx(best, rel=1e-4)


def test_ring_weights_make_the_area_of_a_disc():
    r = np.arange(0.5, 100.0, 1.0)  # rings 1 µm wide out to 100 µm, density 1/µm²
    assert fibril_probe.ring_weights(r, 1.0, 1.0).sum() == pytest.approx(math.pi * 100**2)


_STEEP = pytest.mark.xfail(
    strict=True,
    reason="+4.2 % at faces of R = 2 µm, recorded every step: the outer pillars sit at "
    "23.6° on the 20 µm probe (friction angle 26.6°): their contact force tilts with the "
    "probe's normal while the closed form keeps it vertical (docs/physics.md: 1.7 % at 15°)",
)


@pytest.mark.slow
@pytest.mark.parametrize("probe_radius", [20.0, 60.0])
@pytest.mark.parametrize("preload", [0.05, 0.3, 2.0])
def test_probe_test_matches_independent_fibrils(probe_radius, preload, request):
    """Where the models coincide — vertical pillars with flat punches (linear in compression
    and tension, a fixed pull-off each) on a rigid backing, the tips stuck by friction — the
    time-stepped probe test gives the closed form's pull-off within 1 % (recorded every step,
    so the peak is not sampled: measured −0.01 to +0.61 %, faces of R = 2 µm)."""
    if probe_radius == 20.0 and preload == 2.0:
        request.applymarker(_STEEP)
    n = 5
    p = PILLAR.replace(
        **{"array.count": n, "floor.kind": "probe", "floor.probe_radius": probe_radius,
           "friction.mu": 0.5, "contact.R": 2.0}
    )  # fmt: skip  # faces of R = 4 µm would overlap at 4 µm pitch: R = pitch/2
    m = Model(p, n_sim=n, seed=0, numerics=Numerics(record_every=1))
    h = m.run(protocol.preload_pull(preload, speed=0.04), progress=False)
    c = p.contact
    k = 1.0 / (1.0 / p.axial_stiffness + 1.0 / float(punch.punch_stiffness(c.R, c.E_star)))
    x = m.world.rest_dx
    heights = probe_heights(x, probe_radius, 0.5 * (x.min() + x.max()))
    # the press stops on the first step past the preload: the oracle gets the force reached
    reached = max(preload, float(h["force_normal_uN"].max()))  # records may miss the last step
    d_max = fibril_probe.depth_for_preload(reached, heights, k)
    Fr = float(punch.kendall_pull_off(c.R, c.work_of_adhesion, c.E_star))
    expected = fibril_probe.probe_pull_off(heights, k, Fr, d_max)
    assert pull_off(h).adhesion == pytest.approx(expected, rel=0.01)
