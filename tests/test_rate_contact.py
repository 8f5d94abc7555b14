"""Rate-dependent JKR contact (crack kinetics) and the detachment rules."""

import math
import warnings

import extras
import numpy as np
import pytest
from numpy.testing import assert_allclose
from scipy.integrate import solve_ivp

from gecko_agents import contact, protocol
from gecko_agents.model import Model
from gecko_agents.params import PAPER_TABLE1
from gecko_agents.physics import jkr

STUBBY = PAPER_TABLE1.replace(**{"mechanics": "rod", "seta.L": 5.0})


def _rate(v_star, n=0.5):
    return STUBBY.replace(**{"contact.crack_speed": v_star, "contact.crack_exponent": n})


def _pull(params, speed, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return Model(params, **kw).run(protocol.press_pull(0.3, speed), progress=False)


def test_infinite_crack_speed_is_the_elastic_law_exactly():
    p = STUBBY.replace(**{"contact.crack_speed": math.inf})
    assert type(contact.contact_law(p)) is contact.JKRSphere
    a, b = _pull(STUBBY, 0.05), _pull(p, 0.05)
    for c in a.scalars:
        np.testing.assert_array_equal(a[c], b[c])


def test_single_tip_on_a_rigid_mount_follows_the_crack_ode():
    # δ(t) = −V·t from the equilibrium at δ = 0: the law's step-by-step radius against
    # scipy's solve_ivp (Radau, tight tolerances) on ȧ = −v*((G − w)/w)^(1/n) while G > w.
    p = _rate(0.05)
    law = contact.RateJKRSphere(p.contact)
    R, w, E = law.R, law.w, law.E_star
    V, v_star, n = 0.02, law.v_star, law.n_exp
    a_eq0 = float(jkr.radius_from_overlap(0.0, R, w, E))

    def rhs(t, y):
        a, d = y[0], -V * t
        g = a * a / R - d
        G = E * g * g / (2 * math.pi * a)
        return [-v_star * max(G / w - 1.0, 0.0) ** (1.0 / n)]

    def P(a, d):
        return 2 * E * a * d - 2 * E * a**3 / (3 * R)

    t_end = 0.8 * (-20 * law.delta_c) / V
    ref = solve_ivp(rhs, (0.0, t_end), [a_eq0], method="Radau", rtol=1e-10, atol=1e-12,
                    dense_output=True, events=lambda t, y: y[0] - law.release_radius)  # fmt: skip
    dt, a, t = 0.01, a_eq0, 0.0
    forces, ref_forces = [], []
    while a > law.release_radius and t < ref.t[-1]:
        t += dt
        a = law.radius_scalar(-V * t, a, dt, law.constants)
        if a <= law.release_radius or t > ref.t[-1]:
            break
        forces.append(P(a, -V * t))
        ref_forces.append(P(float(ref.sol(t)[0]), -V * t))
    forces, ref_forces = np.array(forces), np.array(ref_forces)
    assert forces.size > 100
    peak_ref = float(np.max(-ref_forces))
    assert float(np.max(-forces)) == pytest.approx(peak_ref, rel=0.01)
    # Up to the peak the whole force history agrees (past it the edge runs away, where the
    # first-order step lags the ODE until it releases).
    k = int(np.argmax(-ref_forces))
    assert np.max(np.abs(forces[:k] - ref_forces[:k])) < 0.01 * peak_ref
    # Slower edges hold more: the rate-dependent peak exceeds the elastic pull-off.
    assert peak_ref > 1.05 * law.pull_off_force


def _press_then_pull(params, speed):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        prot = [protocol.PressTo(0.3, 0.05), protocol.PullOff(speed)]
        return Model(params).run(prot, progress=False)


@pytest.mark.slow
def test_pull_off_rises_with_speed_and_tends_to_the_elastic_value():
    # n = 1: G/w − 1 = |ȧ|/v*, so over 1.7 decades of pull speed the excess grows ~50-fold
    # while the seta stays quasi-static (the elastic pull-off moves < 0.3 % over these speeds).
    slow, speeds = 1e-3, (1e-3, 1e-2, 5e-2)
    elastic = _press_then_pull(STUBBY, slow).peak_pull_off
    p = _rate(1.0, n=1.0)
    peaks = [_press_then_pull(p, v).peak_pull_off for v in speeds]
    assert np.all(np.diff(peaks) > 0), peaks
    assert peaks[0] == pytest.approx(elastic, rel=0.01)
    assert peaks[-1] > 1.05 * elastic


def test_crack_work_is_dissipated_never_created():
    h = _pull(_rate(1.0), 0.02, record_every=1)
    D = h["energy_dissipated_pJ"]
    assert np.all(D >= 0.0)
    assert h.meta["tip_law"] == "sphere (crack kinetics)"
    # More is dissipated than by the elastic tip at the same speed: the crack's own work.
    assert D[-1] > _pull(STUBBY, 0.02)["energy_dissipated_pJ"][-1]


@pytest.mark.parametrize("kernel", ["numpy", "python", "numba"])
def test_kernels_agree_on_rate_dependent_contact(kernel):
    from gecko_agents.model import numba_available

    if kernel == "numba" and not numba_available():
        pytest.skip(extras.reason("fast"))
    p = _rate(1.0).replace(**{"array.count": 3, "floor.sigma": 0.2})
    ref = _pull(p, 0.05, kernel="numpy")
    h = _pull(p, 0.05, kernel=kernel)
    scale = float(np.max(np.abs(ref["force_normal_uN"])))
    assert_allclose(h["force_normal_uN"], ref["force_normal_uN"], rtol=0, atol=1e-9 * scale)


# Detachment rules ------------------------------------------------------------------------------


def _rule_overlap(rule):
    """Where each rule's formula says a tip lets go [µm], computed independently of the law."""
    R, w, E = PAPER_TABLE1.contact.jkr_args()
    a0 = (9 * math.pi * w * R * R / (2 * E)) ** (1 / 3)  # eq 9, zero-load radius
    if rule == "fold":
        return -0.75 * (math.pi**2 * w**2 * R / E**2) ** (1 / 3)  # δc
    if rule == "delta_s":
        return -0.21 * a0**2 / R  # the paper's δs, eq 8
    # load control: the branch point of least force (P = −Fc), by minimising eq 7 over a
    from scipy.optimize import minimize_scalar

    res = minimize_scalar(lambda x: float(jkr.force_from_radius(x, R, w, E)), bounds=(0.1, a0),
                          method="bounded", options={"xatol": 1e-12})  # fmt: skip
    return float(jkr.overlap_from_radius(res.x, R, w, E))


@pytest.mark.parametrize("rule", ["fold", "delta_s", "load_control"])
def test_each_detachment_rule_releases_where_its_formula_says(rule):
    p = PAPER_TABLE1.replace(**{"contact.detachment": rule})
    law = contact.contact_law(p)
    assert law.detach_overlap == pytest.approx(_rule_overlap(rule), rel=1e-6)
    # In the model: a stiff seta (short and thick) follows the plate; its tip lets go on the
    # first step past the rule's overlap.
    stiff = p.replace(**{"mechanics": "rod", "seta.L": 2.0, "seta.r": 1.5})
    h = _pull(stiff, 0.01, record_setae=True)
    release = h.detachments["overlap_um"]
    assert release.size == 1 and release[0] < law.detach_overlap
    steps = np.diff(h.setae["overlap_um"][:, 0])
    assert release[0] > law.detach_overlap - 2 * np.nanmax(np.abs(steps))


@pytest.mark.parametrize(
    "override, field",
    [({"contact.crack_speed": 0.0}, "crack_speed"), ({"contact.crack_speed": -1.0}, "crack_speed"),
     ({"contact.crack_exponent": 0.0}, "crack_exponent"),
     ({"contact.crack_exponent": 1.5}, "crack_exponent"),
     ({"contact.detachment": "yank"}, "detachment"),
     ({"contact.crack_speed": 1.0, "contact.detachment": "delta_s"}, "detachment")],
)  # fmt: skip
def test_bad_rate_parameters_are_refused(override, field):
    with pytest.raises(ValueError, match=field):
        PAPER_TABLE1.replace(**override)
