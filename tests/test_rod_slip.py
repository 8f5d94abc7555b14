"""A quasi-static rod seta pressed until its lateral equilibrium folds slips along the floor and
stays attached: it never lets go while its contact is compressed. The end of the slip is
checked against an independent path search (scipy's brentq on the normal equilibrium at each
tip position and on the friction balance along the path)."""

import importlib
import math

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gecko_agents import quasistatic as qs
from gecko_agents.history import STATE_SLIP, STATE_STICK
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import jkr
from gecko_agents.quasistatic import rod as qs_rod
from gecko_agents.quasistatic.rod_equilibrium import rod_force

# A short, steep rod: pressed by 0.7 L its tip is pushed outward beyond the friction cone.
STEEP = PAPER_ARRAY.replace(
    **{
        "seta.L": 10.0,
        "seta.theta_deg": 75.0,
        "mechanics": "rod",
        "array.count": 2,
        "floor.sigma": 0.1,
        "friction.mu": 0.2,
    }
)


def _normal_radius(rs, c, x):
    """Contact radius a [µm] of the JKR tip held at abscissa x [µm], from brentq on the normal
    balance F_rod,y(x, c − δ(a)) + P(a) = 0 over the stable branch a > a_c."""
    args = (rs.R, rs.w, rs.E_star)

    def balance(a):
        y = c - jkr.overlap_from_radius(a, *args)
        return rod_force(x, y, rs.Ka, rs.k_phi, rs.L, rs.theta)[0][1] + jkr.force_from_radius(
            a, *args
        )

    return brentq(balance, rs.a_c * (1 + 1e-9), 3 * rs.R, xtol=1e-14, rtol=1e-15)


def _drive(rs, c, x, sigma):
    """The rod's lateral push along the slip direction −σ less the friction cap [µN]."""
    args = (rs.R, rs.w, rs.E_star)
    a = _normal_radius(rs, c, x)
    y = c - jkr.overlap_from_radius(a, *args)
    push = -sigma * rod_force(x, y, rs.Ka, rs.k_phi, rs.L, rs.theta)[0][0]
    return push - rs.cap(jkr.force_from_radius(a, *args))


def test_a_pressed_tip_slips_to_the_first_point_where_friction_holds_it():
    rs = qs.RodSetup.from_params(STEEP)
    x0, y0 = rs.rest
    h = np.array([6.6])
    c = -3.533  # c = h + R − Z: the tip pressed 6.1 µm past touch-down
    Z = h[0] + rs.R - c
    # Sticking at rest the rod pushes the tip outward beyond the cap.
    sigma = -1.0
    assert _drive(rs, c, x0, sigma) > 0
    st = qs_rod.RodState(1)
    st.state[:] = STATE_STICK
    st.x[:], st.a[:] = x0, _normal_radius(rs, c + 0.016, x0)
    P, Ft, delta, released, _ = qs_rod.rod_step(rs, st, Z, h)
    assert not released[0] and st.state[0] == STATE_SLIP and st.sigma[0] == sigma
    # The slip ends where the push first falls to the cap, found on a grid of 0.005 L.
    grid = x0 - sigma * rs.L * np.arange(1, 401) * 5e-3
    drive = np.array([_drive(rs, c, x, sigma) for x in grid])
    k = int(np.argmax(drive <= 0))
    assert k > 0 and (drive[:k] > 0).all()
    x_end = brentq(lambda x: _drive(rs, c, x, sigma), grid[k - 1], grid[k], xtol=1e-13)
    # Newton's residual test (1e-10·Fc over a stiffness ~0.1 µN/µm): ~1e-9 µm; measured 2e-11.
    assert_allclose(st.x[0], x_end, rtol=0, atol=1e-8)
    assert x_end - x0 > 0.1 * rs.L  # beyond the reach of the sliding solve from the anchor
    # The tip is in compression, at the cap, on its own normal equilibrium.
    a_end = _normal_radius(rs, c, x_end)
    assert_allclose(st.a[0], a_end, rtol=1e-9)
    assert P[0] > 0 and delta[0] > 0
    assert_allclose(Ft[0], sigma * rs.cap(P[0]), rtol=1e-9)


@pytest.mark.parametrize("height", [6.0, 6.6, 8.0])
def test_a_compressed_tip_never_lets_go(height):
    """Pressed 0.7–0.9 L on an asperity, the steep seta slips once and lets go only in
    tension, once, on the retract."""
    r = qs.press_pull(STEEP, np.array([0.0, height]), 1.0, n_retract=600, record_setae=True)
    ps = r.per_seta
    mine = [(i, d) for i, j, d in r.releases if j == 1]
    assert len(mine) == 1
    step, overlap = mine[0]
    assert overlap < 0 and step > 500
    # Attached at every step from its touch-down to its release, its tip moved on a slip.
    state = np.asarray(ps["state"])[:, 1]
    touch = int(np.argmax(state != 0))
    assert (state[touch:step] != 0).all()
    assert (state == STATE_SLIP).any()
    assert math.isfinite(r.pull_off)


@pytest.mark.slow
def test_the_slip_matches_the_time_stepped_seta(monkeypatch):
    """The time-stepped rod seta on the same asperity (implicit step, stick spring k_t) slips
    outward too and stays attached: the quasi-static solver with the same k_t gives its force
    at the deepest press and the array's pull-off."""
    import gecko_agents.floor as floor
    from gecko_agents import protocol
    from gecko_agents.model import Model, Numerics

    heights = np.array([0.0, 6.6])
    monkeypatch.setattr(floor, "seta_heights", lambda n, sigma, rng: heights.copy())
    m = Model(STEEP, record_setae=True, numerics=Numerics(integrator="implicit"))
    with pytest.warns():  # the tip's a/R is past JKR's small-contact range (both solvers)
        h = m.run(protocol.press_pull(1.0), progress=False)
    q = qs.press_pull(
        STEEP, heights, 1.0, n_retract=1000, record_setae=True, tangential_stiffness=m.k_t
    )
    deep_agent = int(np.argmin(h["plate_y_um"]))
    deep_qs = int(np.argmin(q.plate_y))
    f_agent = np.asarray(h.setae["force_normal_uN"])[deep_agent, 1]
    f_qs = np.asarray(q.per_seta["force"])[deep_qs, 1]
    # Measured: 0.712 and 0.705 µN (a seta released while pressed would carry 0).
    assert_allclose(f_qs, f_agent, rtol=0.03)
    # Measured: 3.441 and 3.437 µN (3.109 µN with the seta let go at each plate step).
    assert_allclose(q.pull_off, h.peak_pull_off, rtol=0.01)


@pytest.mark.parametrize(
    "L, theta, k_t, sigma",
    [(5.0, 60.0, math.inf, 0.3), (5.0, 60.0, 0.3, 0.3), (10.0, 75.0, math.inf, 0.1)],
)
def test_every_rod_seta_lets_go_within_the_retract(L, theta, k_t, sigma):
    """The retract travel bounds every release (rod swing, axial and stick-spring stretch):
    the last seta lets go before its end, the steep seta after its slip too."""
    p = STEEP.replace(
        **{"seta.L": L, "seta.theta_deg": theta, "floor.sigma": sigma, "array.count": 30}
    )
    h = sigma * np.random.default_rng(1).standard_normal(30)
    h[0] = 0.66 * L  # pressed past its lateral fold on the steep rod
    r = qs.press_pull(p, h, 1.0, n_retract=400, tangential_stiffness=k_t)
    assert r.n_attached[-1] == 0 and len(r.releases) >= 30


def test_a_retract_too_short_for_every_release_is_refused(monkeypatch):
    solve = importlib.import_module("gecko_agents.quasistatic.solve")
    monkeypatch.setattr(solve, "travel_up", lambda *args: 1.0)
    with pytest.raises(RuntimeError, match="still attached after the retract's 1 µm"):
        qs.press_pull(STEEP, np.array([0.0, 0.5]), 1.0, n_retract=50)
