"""Frictional adhesion: the critical angle of a limit curve (synthetic oracle) and a spatula
seta whose release force falls as the pull turns up past α*."""

import math
import warnings

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.limit_curve import critical_angle
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY


def test_critical_angle_of_a_synthetic_limit_line():
    shear = np.array([0.5, 1.0, 2.0, 3.0])
    alpha = 27.0
    adhesion = shear * math.tan(math.radians(alpha))
    # Releases in compression or with releasing shear are not on the adhesion limit.
    shear = np.append(shear, [1.0, -2.0])
    adhesion = np.append(adhesion, [-0.4, 1.0])
    assert critical_angle(shear, adhesion) == pytest.approx(alpha, abs=1e-9)


def test_critical_angle_least_squares_through_the_origin():
    # Points 20° and 40° off the shear axis at equal shear: slope (tan20 + tan40)/2.
    a = [math.tan(math.radians(20.0)), math.tan(math.radians(40.0))]
    expected = math.degrees(math.atan(0.5 * (a[0] + a[1])))
    assert critical_angle([1.0, 1.0], a) == pytest.approx(expected, abs=1e-9)


def test_critical_angle_nan_without_tension():
    assert math.isnan(critical_angle([1.0, 2.0], [-0.1, 0.0]))


SETA = PAPER_ARRAY.replace(
    **{"tip": "spatula", "mechanics": "rod", "floor.sigma": 0.0, "array.count": 1,
       "friction.mu": 10.0}
)  # fmt: skip


def _release_force(beta):
    """Largest force magnitude [µN] a gripping-dragged spatula seta holds in a pull at β [deg]
    from +x (the pull's angle from the gripping shear axis is 180° − β)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        h = Model(SETA, seed=1, record_every=1).run(
            protocol.drag_pull(0.2, -8.0, beta, speed=0.05), progress=False
        )
    px = h["plate_x_um"]
    k0 = int(np.flatnonzero(np.abs(px - (px[0] - 8.0)) < 1e-6)[0])
    return float(np.hypot(h["force_normal_uN"][k0:], h["force_tangential_uN"][k0:]).max())


def test_release_force_falls_as_the_pull_angle_rises_past_critical():
    """α* of this seta is ≈ 42° (scenario): pulls 60°, 90°, 120° from the shear axis."""
    forces = [_release_force(180.0 - a) for a in (60.0, 90.0, 120.0)]
    assert forces[0] > forces[1] > forces[2] > 0.0


def test_a_film_pushed_over_its_pad_holds_at_most_its_180_degree_peel_force():
    """Dragged +x past its lean (15 µm against a 10 µm lean), a spatula seta is pushed over its
    pad: the film holds it back with at most Kendall's 180° force w·b/(1 − cos 180°) = w·b/2
    (inextensible limit, an upper bound for the elastic film), so the tip slides along and the
    seta never flips (its root stays behind the tip, on −x)."""
    from gecko_agents.contact import contact_law

    law = contact_law(SETA)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        h = Model(SETA, seed=1, record_every=1, record_setae=True).run(
            protocol.drag_pull(0.2, 15.0, 90.0, speed=0.05), progress=False
        )
    px = h["plate_x_um"]
    drag = (px > px[0] + 1e-9) & (
        np.abs(h["plate_y_um"] - h["plate_y_um"][np.argmax(px > 0)]) < 1e-9
    )
    held_back = -h["force_tangential_uN"][drag]
    assert held_back.max() <= 1.001 * law.w * law.b / 2.0
    assert held_back.max() > 0.9 * law.w * law.b / 2.0  # the film does peel backwards
    assert np.all(h.setae["tip_x_um"][drag, 0] > px[drag])  # root still behind the tip
