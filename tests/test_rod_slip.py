"""A quasi-static rod seta pressed until its lateral equilibrium folds slips along the floor and
stays attached: it never lets go while its contact is compressed. The end of the slip is
checked against an independent path search (scipy's brentq on the normal equilibrium at each
tip position and on the friction balance along the path)."""

import importlib
import math
import warnings

import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.optimize import brentq

from gecko_agents import quasistatic as qs
from gecko_agents.diagnostics import ValidityWarning
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


def _drive_at(x, rs, c, sigma):
    """:func:`_drive` with x first, for brentq."""
    return _drive(rs, c, x, sigma)


def _stick_start(rs, c, anchor):
    """Where the tip held by its stick spring k_t at ``anchor`` [µm] sits (x [µm]): the root of
    F_rod,x − k_t(x − anchor) along x, by brentq, the tip on its normal equilibrium."""
    if math.isinf(rs.k_t):
        return anchor
    args = (rs.R, rs.w, rs.E_star)

    def lateral(x):
        y = c - jkr.overlap_from_radius(_normal_radius(rs, c, x), *args)
        return rod_force(x, y, rs.Ka, rs.k_phi, rs.L, rs.theta)[0][0] - rs.k_t * (x - anchor)

    return brentq(lateral, anchor, anchor + 0.1 * rs.L, xtol=1e-14)


@pytest.mark.parametrize("k_t", [math.inf, 7.4], ids=["rigid stick", "stick spring"])
def test_pressed_tips_slip_to_the_first_point_where_friction_holds_them(k_t):
    rs = qs.RodSetup.from_params(STEEP, "coupled", 1.0, k_t)
    x0, y0 = rs.rest
    h = np.array([6.6, 6.9, 7.4])
    Z = 6.6 + rs.R + 3.533
    c = h + rs.R - Z  # the tips pressed 6.1–6.9 µm past touch-down
    st = qs_rod.RodState(3)
    st.state[:] = STATE_STICK
    st.x[:] = x0
    st.a[:] = [_normal_radius(rs, ci - 0.016, x0) for ci in c]  # one plate step before
    P, Ft, delta, released, _ = qs_rod.rod_step(rs, st, Z, h)
    assert not released.any() and (st.state == STATE_SLIP).all()
    for i, ci in enumerate(c):
        start = _stick_start(rs, ci, x0)
        # The rod pushes each tip outward beyond the cap: friction points inward (σ = −1).
        sigma = -1.0
        assert _drive(rs, ci, start, sigma) > 0 and st.sigma[i] == sigma
        # The slip ends where the push first falls to the cap, found on a grid of 0.005 L.
        grid = start - sigma * rs.L * np.arange(1, 401) * 5e-3
        drive = np.array([_drive(rs, ci, x, sigma) for x in grid])
        k = int(np.argmax(drive <= 0))
        assert k > 0 and (drive[:k] > 0).all()
        x_end = brentq(_drive_at, grid[k - 1], grid[k], args=(rs, ci, sigma), xtol=1e-13)
        # Bisection to 2⁻⁴⁰ of 0.05 L (5e-13 µm) on a push whose normal solve stops within
        # 1e-10·Fc: measured within 1.2e-10 µm.
        assert_allclose(st.x[i], x_end, rtol=0, atol=1e-9)
        assert x_end - start > 0.1 * rs.L  # beyond the reach of the sliding solve
        # The tip is in compression, at the cap, on its own normal equilibrium.
        assert_allclose(st.a[i], _normal_radius(rs, ci, x_end), rtol=1e-9)
        assert P[i] > 0 and delta[i] > 0
        assert_allclose(Ft[i], sigma * rs.cap(P[i]), rtol=1e-9)


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
    # The snap: the tip's longest run of moves faster than 0.05 µm a record (a record is
    # ~0.02 µm of plate travel; the steady slide after the snap is slower). Measured 3.77 and
    # 3.75 µm.
    snap_agent = _longest_snap(np.asarray(h.setae["tip_x_um"])[:, 1])
    snap_qs = _longest_snap(np.asarray(q.per_seta["tip_dx"])[:, 1])
    assert_allclose(snap_qs, snap_agent, rtol=0.03)


def _longest_snap(x):
    """The largest sum of consecutive moves of ``x`` [µm] each above 0.05 µm."""
    best = run = 0.0
    for d in np.abs(np.diff(x)):
        run = run + d if d > 0.05 else 0.0
        best = max(best, run)
    return best


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
    with pytest.raises(RuntimeError, match=r"\b1 µm"):
        qs.press_pull(STEEP, np.array([0.0, 0.5]), 1.0, n_retract=50)


def test_no_quasi_static_seta_lets_go_pressed():
    """Over drawn arrays (rod and linear setae, rigid stick or a stick spring, both friction
    laws, floors up to half a seta length rough): every seta lets go at most once, and in
    tension (its release overlap below the zero-load overlap a0²/3R of JKR's stable branch)."""
    rng = np.random.default_rng(7)
    for _ in range(12):
        sigma = float(rng.uniform(0.5, 5.0))
        mechanics = str(rng.choice(["rod", "linear"]))
        # A linear seta steeper than 70° self-locks under friction (refused).
        steepest = 80.0 if mechanics == "rod" else 70.0
        p = PAPER_ARRAY.replace(
            **{
                "mechanics": mechanics,
                "seta.L": float(rng.uniform(5.0, 30.0)),
                "seta.theta_deg": float(rng.uniform(20.0, steepest)),
                "friction.mu": float(rng.uniform(0.0, 0.3)),
                "friction.law": str(rng.choice(["adhesive", "paper"])),
                "floor.sigma": sigma,
                "array.count": 20,
            }
        )
        k_t = float(rng.choice([math.inf, rng.uniform(0.5, 20.0)]))
        h = sigma * rng.standard_normal(20)
        with warnings.catch_warnings():
            warnings.simplefilter("error", ValidityWarning)  # no release of a pressed seta
            r = qs.press_pull(p, h, sigma, n_retract=400, tangential_stiffness=k_t)
        a0 = jkr.zero_load_contact_radius(*p.contact.jkr_args())
        zero_load = a0**2 / (3 * p.contact.R)
        seta = [j for _, j, _ in r.releases]
        assert len(seta) == len(set(seta)), p
        assert all(d < zero_load for _, _, d in r.releases), p


def test_a_stick_spring_too_soft_to_hold_a_pressed_tip_is_reported():
    """With k_t = 0.02 µN/µm (the contact's is ~7 µN/µm) the steep seta's stick trial has no
    equilibrium while pressed: it is let go and touches again, step after step. The run says
    so, counting those releases."""
    with pytest.warns(ValidityWarning) as caught:
        r = qs.press_pull(
            STEEP, np.array([0.0, 6.6]), 1.0, n_retract=600, tangential_stiffness=0.02
        )
    seta = [j for _, j, _ in r.releases]
    assert len(seta) > len(set(seta))  # let go more than once: pressed again after letting go
    assert sum(issubclass(w.category, ValidityWarning) for w in caught) == 1  # one per run
