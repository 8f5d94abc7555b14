"""Peeling a pad through a pre-peeled leader arm (:mod:`gecko_agents.studies.pad_peel`): the arm
is laid out at the peel angle without stress, the detachment front starts at the pulled edge and
runs across, and the steady peel force obeys Kendall's tape law with a work of adhesion that
does not come from the run under test.

Kendall (1975, J Phys D 8:1449, "Thin-film peeling — the elastic term"; its abstract read at
doi:10.1088/0022-3727/8/13/005, the paper's equations not): an energy balance of a steady peel,
in which an elastic stretching term lowers the force and matters only at small angles or
stresses near the film's modulus. The strip here is a chain of inextensible links
(:mod:`gecko_agents.backing.elastic`), so that term is zero and the balance is the inextensible
one: peeling a length da with the tape straight along the force at θ from the floor moves the
force's point by da·(1 − cos θ) along the force, so

    (F/b)·(1 − cos θ) = w        [µN/µm = J/m²]

(F [µN] the force, b [µm] the width, w [µN/µm] the work of separation per area; at θ = 90°,
F/b = w, the form a secondary source citing Kendall 1975 gives). The model's inputs, not the
run, fix w: a seta on the strip is a linear spring Ky on a JKR tip (eq 16–21, eq 7, 10); pulled
off from the preload, its root held by a rigid plate, it takes the work

    W = [P_f²/(2Ky) + U(a_f)] − [P_pre²/(2Ky) + U(a_pre)]        [pJ]

(U the JKR contact energy from jump-in, :func:`gecko_agents.physics.jkr.contact_energy`; a_f the
fold where dP/dδ = −Ky, :func:`gecko_agents.quasistatic.release_radius`; pre: the equilibrium
with the root 0.3 µm below touch-down, the pad's preload), all of which is lost when it snaps.
With the model's friction (μ = 0.2, the tip slides as it is pulled) the same work is the
quasi-static solver's ∫(−P)dZ of one seta (a code path apart from the agent model), 12.47 pJ
(friction lowers it 1.8 % from the frictionless 12.70 pJ). One seta per pitch² of the pad:
w = W/pitch² = 0.779 µN/µm.

The start-up transient: the arm starts stress-free and the pulled edge has no bending zone yet,
so the first rows peel at a force far above the steady one and the excess decays with the rows
peeled (measured, 0.5 µm/µs: over rows 0–20, F(1 − cos ψ)/b is 1.46 × the plateau at 30° and
3.2 × at 90°; the excess falls by e over ≈ 20 rows at 30° and ≈ 30 at 90°, 2–3 bending lengths
λ = 39 µm). Rows are setae, pitch 4 µm apart. The comparison averages over rows 80–160 (30°) and
120–220 (90°); its tolerance is what the transient still adds there (the difference between
the 20 rows before the window and the window, an upper bound since the excess decays
monotonically), plus twice the standard error of five blocks of the window (setae let go one by
one), plus the quasi-static work's discretisation bracket (0.15 %).

Measured (2026-11-26): 30°, 400 setae: F/b = 5.35 µN/µm at ψ = 31.2°, F(1 − cos ψ)/b = 0.775
µN/µm, −0.6 % from w (tolerance 1.5 %: transient 1.1 %, noise 0.4 %). A shorter pad has no
steady stretch at 30°: from ≈ 200 rows before the pad's end the force falls (240 setae: −5.8 %
over rows 80–160), so the 30° pad has 400 setae peeled to 45 %. 90°, 240 setae: F/b = 0.779 at
ψ = 97.2° (the tail bends into an S and the force leans back), F(1 − cos ψ)/b = 0.877, +12.5 %
against a tolerance of 8.9 % (noise 5.1 %, transient 3.8 %): an xfail, see its reason.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from gecko_agents import history
from gecko_agents import quasistatic as qs
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import jkr

SPEED = 0.5  # handle speed [µm/µs]: 3 % below 0.2 µm/µs's F/b (pad_peel's docstring)
PEELS = {  # ψ [deg] → (setae, fraction of the pad peeled, window of rows averaged)
    30.0: (400, 0.45, (80, 160)),
    90.0: (240, 1.0, (120, 220)),
}
PRE_ROWS = 20  # rows before the window: what the start-up transient still adds there
BLOCKS = 5  # blocks of the window for its standard error


@pytest.fixture(scope="module")
def pad_peel():
    from gecko_agents.studies import pad_peel

    return pad_peel


@pytest.fixture(scope="module")
def peels(pad_peel):
    """The two peels, each (model, history): 30° and 90°, 0.5 µm/µs. Built once for the module,
    before conftest's per-test check is patched in, so the invariants are checked here."""
    out = {}
    for psi, (n, fraction, _) in PEELS.items():
        m = pad_peel.preloaded_model(n, psi)
        h = pad_peel.peel(m, psi, speed=SPEED, front_fraction=fraction)
        assert history.invariant_violations(h) == []
        out[psi] = (m, h)
    return out


def seta_work_quasistatic(params, depth: float, lateral: str, n_retract: int = 4000):
    """Work [pJ] the rigid plate does pulling one seta off from ``depth`` [µm] below
    touch-down, quasi-statically: ∫(−P)dZ over the retraction while attached, bracketed by the
    step in which it lets go (the lower end leaves it out, the upper one adds it at the last
    force). Returns (low, high)."""
    p = params.replace(**{"array.count": 1})
    br = qs.Branches.from_params(p, lateral)
    z_start = qs.plate_start_height(p, [0.0], 0.5)
    z_min = qs.plate_start_height(p, [0.0], 0.0) - depth
    up = qs.retract_travel(p, br, [0.0], z_min)
    zs = np.concatenate(
        [np.linspace(z_start, z_min, 501), z_min + up * np.arange(1, n_retract + 1) / n_retract]
    )
    r = qs.solve(p, np.array([0.0]), zs, lateral=lateral, branches=br, stop_when_free_after=500)
    k = r.turn_index
    z, P = r.plate_y[k:], r.force_normal[k:]
    last = int(np.flatnonzero(r.n_attached[k:] > 0)[-1])
    low = float(np.trapezoid(-P[: last + 1], z[: last + 1]))
    return low, low - float(P[last]) * (z[1] - z[0])


def seta_work_closed_form(params, depth: float) -> float:
    """W = [P_f²/(2Ky) + U(a_f)] − [P_pre²/(2Ky) + U(a_pre)] [pJ] (module docstring): a
    frictionless seta of stiffness Ky on its JKR tip, root ``depth`` [µm] below touch-down."""
    R, w, E = params.contact.jkr_args()
    k = params.Ky

    def energy(a):
        return jkr.force_from_radius(a, R, w, E) ** 2 / (2 * k) + jkr.contact_energy(a, R, w, E)

    def balance(a):  # the spring, compressed by depth − δ, carries the contact force
        return k * (depth - jkr.overlap_from_radius(a, R, w, E)) - jkr.force_from_radius(a, R, w, E)

    a_pre = brentq(balance, jkr.snap_off_radius(R, w, E), 10 * R, xtol=1e-14)
    return float(energy(qs.release_radius(k, R, w, E)) - energy(a_pre))


def work_of_adhesion_from_setae(pad_peel) -> tuple[float, float]:
    """w = W/pitch² [µN/µm] of the pad's setae with the model's friction, (low, high)."""
    low, high = seta_work_quasistatic(pad_peel.BASE, pad_peel.DEPTH, "coupled")
    area = pad_peel.BASE.array.pitch**2
    return low / area, high / area


def release_rate(h, m, rows: tuple[float, float]) -> tuple[float, float, float]:
    """F(1 − cos ψ)/b [µN/µm], F/b [µN/µm] and ψ [deg] of the time-mean handle force vector
    while the front is between ``rows`` (setae peeled from the pulled edge); b = pitch."""
    pitch = m.params.array.pitch
    front = h["strip_front_x_um"]
    peeled = (float(m.world.root_dx.max()) - front) / pitch
    inside = np.isfinite(front) & (peeled >= rows[0]) & (peeled < rows[1])
    fx, fy = h["plate_force_x_uN"][inside].mean(), h["plate_force_y_uN"][inside].mean()
    F = math.hypot(fx, fy) / pitch
    psi = math.atan2(-fy, -fx)  # the force on the strip is minus that on the handle
    return F * (1.0 - math.cos(psi)), F, math.degrees(psi)


def kendall_comparison(h, m, window) -> dict:
    """The window's F(1 − cos ψ)/b, the transient still in it, its noise and the tolerance
    (fractions of the window's value; module docstring)."""
    r0, r1 = window
    G, F, psi = release_rate(h, m, window)
    pre = release_rate(h, m, (r0 - PRE_ROWS, r0))[0]
    edges = np.linspace(r0, r1, BLOCKS + 1)
    blocks = [release_rate(h, m, (a, b))[0] for a, b in zip(edges[:-1], edges[1:], strict=True)]
    noise = 2.0 * np.std(blocks, ddof=1) / math.sqrt(BLOCKS) / G
    transient = abs(pre - G) / G
    start = release_rate(h, m, (0, PRE_ROWS))[0] / G
    return {"G": G, "F": F, "psi": psi, "transient": transient, "noise": noise, "start": start}


def test_leader_arm_is_laid_out_at_the_peel_angle_stress_free(pad_peel):
    """The arm's links continue the pad's +x end at ψ: its end node sits at the pad's edge
    plus the arm's length along ψ, and the strip stores no bending energy in that shape."""
    p = pad_peel.BASE.replace(**{"array.count": 20})
    m = Model(p.replace(backing={"leader_arm": 30.0, "peel_angle_deg": 40.0}))
    b = m.backing.info
    x, y = m.backing.strip.nodes()
    arm = b["leader_arm_um"]
    assert arm >= 30.0 and b["n_links"] == b["pad_links"] + round(arm / b["link_um"])
    y0 = m.plate.position.y
    assert x[-1] == pytest.approx(0.5 * b["length_um"] + arm * math.cos(math.radians(40.0)))
    assert y[-1] == pytest.approx(y0 + arm * math.sin(math.radians(40.0)))
    assert np.allclose(y[: b["pad_links"] + 1], y0)
    m.backing.strip.step(m.dt)
    assert m.backing.strip.energy_bending == pytest.approx(0.0, abs=1e-12)


@pytest.mark.parametrize(
    "kwargs",
    [{"leader_arm": -1.0}, {"leader_arm": 10.0, "peel_angle_deg": 180.0},
     {"leader_arm": 10.0, "peel_angle_deg": 0.0}],
)  # fmt: skip
def test_bad_leader_arm_refused(pad_peel, kwargs):
    with pytest.raises(ValueError, match="leader_arm|peel_angle_deg"):
        Model(pad_peel.BASE.replace(**{"array.count": 8}), **kwargs)


def test_leader_arm_needs_the_peel_drive():
    p = PAPER_ARRAY.replace(**{"array.count": 8, "backing.kind": "elastic"})
    with pytest.raises(ValueError, match="Backing.drive"):
        Model(p.replace(backing={"leader_arm": 10.0}))


def test_seta_work_of_separation_quasistatic_against_its_closed_form(pad_peel):
    """Without friction the quasi-static pull-off work of one seta brackets the closed form
    [P_f²/(2Ky) + U(a_f)] − [P_pre²/(2Ky) + U(a_pre)] = 12.70 pJ (the bracket is the plate
    step in which the tip lets go, 0.15 % wide); with the model's μ = 0.2 the sliding tip lets
    go a little earlier: 1.8 % less, 12.47 pJ."""
    exact = seta_work_closed_form(pad_peel.BASE, pad_peel.DEPTH)
    assert exact == pytest.approx(12.703, abs=5e-4)  # 12.7029 pJ, the sum above evaluated
    low, high = seta_work_quasistatic(pad_peel.BASE, pad_peel.DEPTH, "free")
    assert low <= exact <= high and high - low < 2e-3 * exact
    low_mu, high_mu = seta_work_quasistatic(pad_peel.BASE, pad_peel.DEPTH, "coupled")
    assert high_mu < low and low_mu > 0.97 * exact


@pytest.mark.slow
def test_the_front_starts_at_the_pulled_edge_and_runs_across(peels):
    """The front starts at the pulled (+x) edge and moves only towards −x: over 90 % of the
    pad at 90° (then crosses it), over the 45 % peeled at 30°."""
    for psi, (m, h) in peels.items():
        front = h["strip_front_x_um"]
        front = front[np.isfinite(front)]
        edge = float(m.world.root_dx.max())
        assert front[0] == pytest.approx(edge)
        span = edge - m.world.root_dx.min()
        fraction = PEELS[psi][1]
        # Monotone while the pad holds; the last few setae may touch down again as the
        # strip's free end springs back (a seta 4 µm behind the front re-attached at 90°).
        reach = 0.9 * span if fraction == 1.0 else 0.95 * fraction * span
        running = front[: np.argmax(front < edge - reach) + 1]
        assert running[-1] < edge - reach and np.all(np.diff(running) <= 0.0)
        if fraction == 1.0:
            assert front[-1] < edge - 0.8 * span


@pytest.mark.slow
@pytest.mark.parametrize("psi", PEELS)
def test_the_start_up_transient_has_decayed_before_the_window(peels, psi):
    """The first 20 rows peel well above the steady force (measured 1.46 × at 30°, 3.2 × at
    90°); at the window less than a tenth of that excess is left (measured 1.1 % and 3.8 %),
    so the window measures the steady peel and the tolerance below is not the transient."""
    m, h = peels[psi]
    c = kendall_comparison(h, m, PEELS[psi][2])
    assert c["start"] > 1.3
    assert c["transient"] < 0.1 * (c["start"] - 1.0)


XFAIL_90 = pytest.mark.xfail(
    strict=True,
    reason="at 90° F(1 − cos ψ)/b = 0.877 µN/µm is 12.5 % above the setae's w = 0.779 "
    "(tolerance 8.9 %): the run dissipates 10 % more per peeled area than the rigid-plate "
    "pull-off of its setae (0.857 µN/µm with the adhesion energy given back; −1.4 % at 30°; "
    "+7 % on a 400-seta pad), and the S-bent tail stores energy as it grows. The excess grows "
    "as the peel slows (+14 % at 0.2 µm/µs) and the strip's dampers at a sixth of their "
    "damping lower it by 2 % only: not a rate loss; a softer mount than the rigid plate (the "
    "strip's local compliance in series with the releasing seta) would do it, not derived",
)


@pytest.mark.slow
@pytest.mark.parametrize("psi", [30.0, pytest.param(90.0, marks=XFAIL_90)])
def test_steady_peel_force_is_kendalls_with_the_setae_work_of_adhesion(peels, pad_peel, psi):
    """F(1 − cos ψ)/b over the window equals w = W/pitch² of the setae (module docstring)
    within what the start-up transient still adds, twice the window's standard error and the
    quasi-static bracket; ψ the measured angle of the mean force."""
    m, h = peels[psi]
    c = kendall_comparison(h, m, PEELS[psi][2])
    low, high = work_of_adhesion_from_setae(pad_peel)
    w = 0.5 * (low + high)
    tolerance = c["transient"] + c["noise"] + (high - low) / (2 * w)
    assert c["G"] == pytest.approx(w, rel=tolerance)
    # The force leans back from the nominal angle as the peeled tail bends (an S at 90°):
    # measured 31.2° at 30°, 97.2° at 90°.
    assert abs(c["psi"] - psi) < (3.0 if psi < 45 else 12.0)


@pytest.mark.slow
def test_shallow_peel_needs_more_force_than_a_steep_one(peels):
    """Kendall's order: F/b at 30° is (1 − cos 97°)/(1 − cos 31°) = 7.5 × F/b at 90° for
    equal w; measured 6.9 × (w is 12 % larger at 90°, see the xfail above). Bounded below
    by 2.5, a third of Kendall's ratio: F/b must grow as the angle falls."""
    (m30, h30), (m90, h90) = peels[30.0], peels[90.0]
    f30 = kendall_comparison(h30, m30, PEELS[30.0][2])["F"]
    f90 = kendall_comparison(h90, m90, PEELS[90.0][2])["F"]
    assert f30 > 2.5 * f90
