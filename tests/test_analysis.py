"""The analyses of :mod:`gecko_agents.analysis`, each against a hand-built history or series whose
answer is known by construction (no model run, no copy of the code under test)."""

import math

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.analysis import convergence as cv
from gecko_agents.analysis.drag import drag_of, drag_span, lean_after_drag, let_go_in_drag
from gecko_agents.analysis.limit_curve import critical_angle, force_angle, limit_adhesion
from gecko_agents.analysis.pull import (
    pull_off,
    pull_off_index,
    pull_start,
    release_index,
    release_point,
)
from gecko_agents.analysis.ratio import gripping_over_releasing
from gecko_agents.history import SCALAR_COLUMNS, History
from gecko_agents.params import PAPER_ARRAY

# A load–drag–pull by hand, one row per record: press (rows 0–4, the plate comes down to
# y = 6), a −3 µm drag (rows 4–10, x from 0 to −3 in 0.5 µm steps), a 90° pull (rows 11–19).
PRESS_Y = [10.0, 9.0, 8.0, 7.0, 6.0]
DRAG_X = [-0.5, -1.0, -1.5, -2.0, -2.5, -3.0]
PULL_Y = [6.5, 7.0, 7.5, 8.0, 8.5, 9.0, 9.5, 10.0, 10.5]
# Normal force (> 0 compression): the press to 0.5, the drag at 0.5, the pull through tension.
NORMAL = [0.0, 0.0, 0.1, 0.3, 0.5] + [0.5] * 6 + [0.2, -0.5, -1.2, -1.8, -2.0, -1.0, 0.0, 0.0, 0.0]
SHEAR = [0.0] * 5 + [0.5, 1.0, 1.5, 2.0, 2.5, 3.0] + [3.0, 3.0, 3.0, 3.0, 1.0, 0.5, 0.0, 0.0, 0.0]
# Row 14: the largest |F| in tension, √(1.8² + 3²) = 3.499 µN (row 15: √(2² + 1²) = 2.236 µN).
# Row 15: the largest adhesion, 2 µN, with 1 µN of shear.
# Row 4: the first record of the press's largest force (0.5 µN, held through the drag).


def _history(drag=-3.0, attached=None, keep=None, setae=None, geometry=None):
    x = [0.0] * 5 + [math.copysign(abs(v), drag) for v in DRAG_X] + [drag] * len(PULL_Y)
    y = PRESS_Y + [6.0] * 6 + PULL_Y
    n = len(x)
    scalars = {c: np.zeros(n) for c in SCALAR_COLUMNS}
    scalars.update(
        time_us=np.arange(n, dtype=float),
        plate_x_um=np.array(x),
        plate_y_um=np.array(y),
        force_normal_uN=np.array(NORMAL),
        force_tangential_uN=np.array(SHEAR),
        n_attached=np.array(attached if attached is not None else [0, 0] + [1] * 15 + [0] * 3),
    )
    rows = np.arange(n) if keep is None else np.asarray(keep)
    scalars = {c: v[rows] for c, v in scalars.items()}
    meta = {"protocol": [repr(s) for s in protocol.drag_pull(0.5, drag, 90.0)]}
    return History(PAPER_ARRAY, 1, scalars, setae or {}, geometry or {}, {}, meta)


# --- drag -------------------------------------------------------------------------------


def test_drag_is_read_from_the_protocol():
    assert drag_of(_history()) == -3.0
    assert drag_of(_history(drag=2.5)) == 2.5
    h = _history()
    h.meta["protocol"] = [repr(s) for s in protocol.preload_pull(0.5)]
    assert drag_of(h) == 0.0


def test_drag_span_starts_before_the_plate_moves_and_ends_on_arrival():
    h = _history()
    assert drag_span(h, -3.0) == (4, 10)
    assert drag_span(h) == (4, 10)  # the drag from the protocol
    assert pull_start(h) == 10


def test_drag_span_when_the_arrival_was_not_recorded():
    # Every other record kept (record_every = 2, odd rows): row 10, the arrival, is gone; the
    # drag starts at row 3 (kept index 1) and ends at the last kept record on the drag's line
    # (y = 6), row 9 (kept index 4).
    h = _history(keep=list(range(1, 20, 2)))
    start, end = drag_span(h)
    assert (start, end) == (1, 4)
    assert h["plate_x_um"][end] == -2.5 and h["plate_y_um"][end + 1] > 6.0


def test_without_a_drag_the_pull_starts_at_the_press_peak():
    h = _history()
    h.meta["protocol"] = [repr(s) for s in protocol.preload_pull(0.5)]
    assert drag_span(h) == (4, 4)  # the first record of the largest normal force


def test_let_go_in_drag_is_the_travel_at_the_first_drop():
    held = _history()
    assert math.isnan(let_go_in_drag(held))
    # The tip lets go between rows 7 and 8 (x = −1.5 → −2.0): 2 µm of drag.
    lost = _history(attached=[0, 0] + [1] * 6 + [0, 1] + [1] * 7 + [0] * 3)
    assert let_go_in_drag(lost) == pytest.approx(2.0)
    # A drop after the drag (in the pull) is not a let-go in the drag.
    assert math.isnan(let_go_in_drag(_history(attached=[0, 0] + [1] * 10 + [0] * 8)))


def _lean_history(tip_dx):
    """The tip at (root x + tip_dx, root y − 5√3) at the drag's end (row 10), root offsets
    (−10, 0.5) from the plate."""
    n = 20
    tip_x, tip_y = np.zeros((n, 1)), np.zeros((n, 1))
    root_x, root_y = -3.0 - 10.0, 6.0 + 0.5
    tip_x[10, 0], tip_y[10, 0] = root_x + tip_dx, root_y - 5.0 * math.sqrt(3.0)
    geometry = {"root_dx_um": np.array([-10.0]), "root_dy_um": np.array([0.5])}
    return _history(setae={"tip_x_um": tip_x, "tip_y_um": tip_y}, geometry=geometry)


def test_lean_after_drag_is_the_seta_angle_from_minus_x():
    assert lean_after_drag(_lean_history(5.0)) == pytest.approx(60.0, abs=1e-12)
    assert lean_after_drag(_lean_history(-5.0)) == pytest.approx(120.0, abs=1e-12)  # flipped


# --- pull -------------------------------------------------------------------------------


def test_release_point_is_the_largest_force_held_in_tension():
    r = release_point(_history())
    assert (r.index, r.adhesion, r.shear) == (14, 1.8, 3.0)
    assert r.force == pytest.approx(math.hypot(1.8, 3.0)) and r.in_tension


def test_pull_off_is_the_largest_adhesion_of_the_pull():
    p = pull_off(_history())
    assert (p.index, p.adhesion, p.shear) == (15, 2.0, 1.0)


def test_a_compression_larger_than_any_tension_is_no_release():
    # A pushed-over seta: its pull starts at 5 µN of compression, then holds 0.3 µN of tension.
    adhesion, shear = np.array([-5.0, -1.0, 0.2, 0.3, 0.1]), np.array([0.0, 0.0, 0.1, 0.0, 0.0])
    assert release_index(adhesion, shear) == 3  # |F| 0.3 beats √(0.2² + 0.1²) = 0.224
    assert pull_off_index(adhesion) == 3


def test_a_pull_without_tension():
    adhesion, shear = np.array([-0.5, -2.0, -0.1]), np.array([1.0, 0.0, 0.0])
    assert release_index(adhesion, shear) == 1  # the largest force, in compression
    h = _history()
    h.scalars["force_normal_uN"] = np.abs(h["force_normal_uN"])  # never in tension
    assert not release_point(h).in_tension
    assert pull_off(h).adhesion == 0.0


def test_tension_before_the_drag_ends_is_not_the_pull():
    # A larger tension in the drag (row 6) does not count: the pull starts at the drag's end.
    h = _history()
    h.scalars["force_normal_uN"] = h["force_normal_uN"].copy()
    h.scalars["force_normal_uN"][6] = -9.0
    assert pull_off(h).adhesion == 2.0 and release_point(h).index == 14


# --- limit curve ------------------------------------------------------------------------


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


def test_limit_line_and_force_angle_round_trip():
    shear = np.array([-1.0, 0.0, 0.5, 2.0])
    allowed = limit_adhesion(shear, 30.0)
    np.testing.assert_allclose(allowed, [0.0, 0.0, 0.5 / math.sqrt(3), 2.0 / math.sqrt(3)])
    assert critical_angle(shear[2:], allowed[2:]) == pytest.approx(30.0, abs=1e-12)
    assert force_angle(allowed[3], shear[3]) == pytest.approx(30.0, abs=1e-12)
    assert force_angle(1.0, 0.0) == 90.0 and force_angle(1.0, -1.0) == pytest.approx(135.0)


# --- ratio ------------------------------------------------------------------------------


def test_gripping_over_releasing():
    assert gripping_over_releasing(3.0, 1.5) == 2.0
    assert gripping_over_releasing(0.0, 1.5) == 0.0
    assert math.isnan(gripping_over_releasing(3.0, 0.0))
    assert math.isnan(gripping_over_releasing(3.0, math.nan))


# --- convergence ------------------------------------------------------------------------

SPEEDS = (0.04, 0.02, 0.01)


def test_linear_in_the_speed_is_first_order_and_extrapolates_exactly():
    f = [0.5 + 2.0 * v for v in SPEEDS]
    c = cv.speed_convergence(SPEEDS, f)
    np.testing.assert_allclose(c.slopes, [2.0, 2.0], rtol=1e-12)
    assert c.first_order
    assert c.order == pytest.approx(1.0, abs=1e-9)
    assert c.limit == pytest.approx(0.5, abs=1e-12)
    assert c.limit_at_order == pytest.approx(0.5, abs=1e-9)
    assert c.change == pytest.approx(0.58 / 0.52 - 1.0)


def test_quadratic_in_the_speed_is_second_order():
    f = [0.5 + 400.0 * v**2 for v in SPEEDS]
    c = cv.speed_convergence(SPEEDS, f)
    np.testing.assert_allclose(c.slopes, [24.0, 12.0], rtol=1e-9)  # 400·(v₁ + v₂)
    assert not c.first_order
    assert c.order == pytest.approx(2.0, abs=1e-9)
    assert c.limit_at_order == pytest.approx(0.5, abs=1e-9)
    assert c.limit != pytest.approx(0.5, abs=1e-3)  # order 1 is the wrong extrapolation here


def test_order_with_unequal_speed_ratios():
    speeds = (0.05, 0.02, 0.01, 0.005, 0.0025)  # the study's: ratios 2.5, 2, 2, 2
    for p in (0.5, 1.0, 1.5, 3.0):
        f = [1.2 - 7.0 * v**p for v in speeds]
        assert cv.observed_order(speeds, f) == pytest.approx(p, abs=1e-8)
        assert cv.richardson_limit(speeds, f, p) == pytest.approx(1.2, abs=1e-12)
    # Only the three slowest speeds count: a different law at the fastest does not matter.
    speeds = (0.08, 0.04, 0.02, 0.01)
    assert cv.observed_order(speeds, [9.0, 0.04**2, 0.02**2, 0.01**2]) == pytest.approx(2.0)
    f = [1.2 + v**2 for v in (0.01, 0.005, 0.0025)]
    assert cv.observed_order((0.0025, 0.01, 0.005), [f[2], f[0], f[1]]) == pytest.approx(2.0)


def test_a_decreasing_series_is_first_order_too():
    f = [0.5 - 3.0 * v for v in SPEEDS]
    c = cv.speed_convergence(SPEEDS, f)
    assert c.first_order and c.limit == pytest.approx(0.5)


def test_what_cannot_be_told():
    # Two speeds: no order, no first-order claim, but a first-order extrapolation.
    c = cv.speed_convergence((0.02, 0.01), [0.54, 0.52])
    assert math.isnan(c.order) and not c.first_order and c.limit == pytest.approx(0.5)
    # Not monotone: no power law.
    c = cv.speed_convergence(SPEEDS, [0.5, 0.6, 0.5])
    assert math.isnan(c.order) and not c.first_order and math.isnan(c.limit_at_order)
    # Constant: slopes 0, no order.
    c = cv.speed_convergence(SPEEDS, [0.5, 0.5, 0.5])
    assert not c.first_order and math.isnan(c.order) and c.change == 0.0
    with pytest.raises(ValueError):
        cv.speed_convergence((0.01,), [0.5])
