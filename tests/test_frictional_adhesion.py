"""Frictional adhesion: a spatula seta whose release force falls as the pull turns up past α*,
a tip pushed over its pad, and the study's plate-speed check (its numbers, from
:mod:`gecko_agents.analysis.convergence`). The analyses themselves are tested against
synthetic histories in ``test_analysis.py``."""

import math

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.analysis.drag import drag_span
from gecko_agents.analysis.pull import release_point
from gecko_agents.history import STATE_STICK
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY

SETA = PAPER_ARRAY.replace(
    **{"tip": "spatula", "mechanics": "rod", "floor.sigma": 0.0, "array.count": 1,
       "friction.mu": 10.0}
)  # fmt: skip


def _release_force(beta):
    """The force [µN] at the release point (the largest force held in tension) of a
    gripping-dragged spatula seta pulled at β [deg] from +x (the pull's angle from the gripping
    shear axis is 180° − β), the plate at the quasi-static speed."""
    h = Model(SETA, seed=1, numerics=Numerics(record_every=1)).run(
        protocol.drag_pull(0.2, -8.0, beta, speed=protocol.DEFAULT_SPEED), progress=False
    )
    release = release_point(h)
    assert release.in_tension
    return release.force


def test_release_force_falls_as_the_pull_angle_rises_past_critical():
    """α* of this seta is ≈ 40° (scenario): pulls 60°, 90°, 120° from the shear axis."""
    forces = [_release_force(180.0 - a) for a in (60.0, 90.0, 120.0)]
    assert forces[0] > forces[1] > forces[2] > 0.0


def _push_over_the_pad(mu):
    """A spatula seta pressed to 0.2 µN and dragged +x 15 µm, past its 10 µm lean: (law,
    history, mask of the drag's rows)."""
    from gecko_agents.contact import contact_law

    p = SETA.replace(**{"friction.mu": mu})
    h = Model(p, seed=1, record_setae=True, numerics=Numerics(record_every=1)).run(
        protocol.drag_pull(0.2, 15.0, 90.0, speed=0.05), progress=False
    )
    start, end = drag_span(h)
    drag = np.zeros(len(h), dtype=bool)
    drag[start + 1 : end + 1] = True  # the records of the plate moving along the floor
    return contact_law(p), h, drag


def _hertz(law, delta):
    """Hertz compression (4/3)E*√R·δ^(3/2) [µN] of the tip body (Johnson 1985, eq 4.22)."""
    return 4.0 / 3.0 * law.E_star * math.sqrt(law.R) * np.maximum(delta, 0.0) ** 1.5


def test_a_pushed_tip_slides_at_its_own_friction_plus_its_pads():
    """At the paper's μ = 0.2 a seta pushed over its pad slides: the tip body at its Coulomb
    cap μ·P_c and the pad, which the film (pulled back at ≤ w·b/2, its 180° peel force) drags
    along, at its adhesive cap μ·2Fc (ℓ = ℓ0: no peel). Held back, once steady:
    μ(P_c + 2Fc), P_c the Hertz compression at the recorded overlap. The seta does not flip."""
    law, h, drag = _push_over_the_pad(0.2)
    held_back = -h["force_tangential_uN"][drag]
    Pc = _hertz(law, h.setae["overlap_um"][drag, 0])
    steady = slice(-200, None)  # the last 10 µs of the drag
    expected = 0.2 * (Pc[steady] + 2.0 * law.w * law.b)
    np.testing.assert_allclose(held_back[steady], expected, rtol=1e-6)
    assert np.all(held_back <= 0.2 * Pc + law.w * law.b / 2.0 + 1e-9)
    assert np.all(h.setae["tip_x_um"][drag, 0] > h["plate_x_um"][drag])  # root behind the tip


def test_a_pressed_tip_sticks_and_its_seta_flips_over_it():
    """At μ = 10 the pressed tip body's cap μ·P_c (≥ 5 µN) is far above what the seta pushes
    with (< 1 µN): the tip sticks all along (it creeps < 0.3 µm over a 15 µm drag, on its stick
    spring: ≈ |ΔT|/k_t) and the seta rotates over it until its root has passed the tip (a
    releasing drag flips it, as a gecko seta's)."""
    law, h, drag = _push_over_the_pad(10.0)
    held_back = -h["force_tangential_uN"][drag]
    Pc = _hertz(law, h.setae["overlap_um"][drag, 0])
    assert np.all(np.abs(held_back) < 0.2 * 10.0 * Pc)
    assert np.all(h.setae["state"][drag, 0] == STATE_STICK)
    tip_x = h.setae["tip_x_um"][drag, 0]
    assert np.ptp(tip_x) < 0.3
    px = h["plate_x_um"][drag]
    assert tip_x[0] > px[0] and tip_x[-1] < px[-1]  # the root has passed over the tip


def _convergence_rows(releasing, undamped_releasing):
    """Synthetic rows of the study's plate-speed check: speeds 0.04, 0.02, 0.01 µm/µs with the
    given releasing pull-offs [µN], then one undamped row at 0.04."""
    speeds = (0.04, 0.02, 0.01)
    rows = [
        {"tip": "spatula", "speed_um_per_us": v, "contact_damping": True, "gripping_uN": 1.0,
         "releasing_uN": r, "gripping_over_releasing": 1.0 / r, "pressed_to_uN": 0.2,
         "max_kinetic_to_elastic_gripping": 0.1, "max_kinetic_to_elastic_releasing": 0.1}
        for v, r in zip(speeds, releasing, strict=True)
    ]  # fmt: skip
    undamped = dict(rows[0], contact_damping=False, releasing_uN=undamped_releasing)
    return rows + [dict(undamped, gripping_over_releasing=1.0 / undamped_releasing)]


@pytest.fixture
def study():
    from gecko_agents.studies import frictional_adhesion

    return frictional_adhesion


def test_convergence_numbers_of_an_error_linear_in_the_speed(study):
    """0.5 + 2v: equal slopes (2 µN per µm/µs), order 1, limit 0.5 µN; the undamped run
    0.518 µN is 0.4 % from the slowest damped one (0.52) against 11.5 % for the damped runs'
    change: the dashpots' share."""
    conv = study.convergence_summary(_convergence_rows([0.58, 0.54, 0.52], 0.518))
    rel = conv["releasing"]
    np.testing.assert_allclose(rel["slopes"], [2.0, 2.0], rtol=1e-9)
    assert rel["first_order"]
    assert rel["order"] == pytest.approx(1.0, abs=1e-6)
    assert rel["limit"] == pytest.approx(0.5, abs=1e-12)
    assert rel["change"] == pytest.approx(0.58 / 0.52 - 1.0)
    assert conv["gripping"]["change"] == 0.0
    assert conv["undamped"]["gap"] == pytest.approx(0.518 / 0.52 - 1.0)
    assert conv["undamped"]["dashpot_dominated"]
    assert conv["sphere_range"] is None


def test_convergence_numbers_of_an_error_quadratic_in_the_speed(study):
    """0.5 + 400v²: slopes 24 and 12 (×2 apart): not first order, observed order 2."""
    conv = study.convergence_summary(
        _convergence_rows([0.5 + 400 * v**2 for v in (0.04, 0.02, 0.01)], 0.5)
    )
    rel = conv["releasing"]
    np.testing.assert_allclose(rel["slopes"], [24.0, 12.0], rtol=1e-9)
    assert not rel["first_order"]
    assert rel["order"] == pytest.approx(2.0, abs=1e-6)
    assert rel["limit_at_order"] == pytest.approx(0.5, abs=1e-9)


def test_an_undamped_run_as_far_off_as_the_damped_ones_is_not_the_dashpots(study):
    conv = study.convergence_summary(_convergence_rows([0.58, 0.54, 0.52], 0.58))
    assert conv["undamped"]["gap"] == pytest.approx(conv["releasing"]["change"])
    assert not conv["undamped"]["dashpot_dominated"]
