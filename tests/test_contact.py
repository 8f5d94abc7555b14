"""Contact laws: every form of every law (numpy, scalar interpreted, scalar compiled, the
per-contact reference path) pinned to its closed form point by point."""

import math

import extras
import numpy as np
import pytest
from numpy.testing import assert_allclose

from gecko_agents import contact, protocol
from gecko_agents.model import Model, Numerics, numba_available
from gecko_agents.params import PAPER_TABLE1, TIPS
from gecko_agents.physics import jkr

RATE = PAPER_TABLE1.replace(**{"contact.crack_speed": 0.5}).contact


def _laws():
    """Every law, the rate-dependent one included (it is tested on its equilibrium branch)."""
    return [
        contact.JKRSphere(PAPER_TABLE1.contact),
        contact.HertzSphere(PAPER_TABLE1.contact),
        contact.RateJKRSphere(RATE),
    ]


def _overlaps(law):
    """Overlaps over the whole branch, dense near where it ends."""
    lo = law.delta_c if law.rate_dependent else law.detach_overlap
    ends = lo + np.geomspace(1e-9, 1.0, 200) * max(abs(lo), 0.1)
    return np.concatenate([ends, np.linspace(lo, 3.0, 400)[1:]])


def _closed_form(law, delta):
    """(a, P, U) from jkr.py for the law's material (JKR branch or Hertz)."""
    R, E = law.R, law.E_star
    if isinstance(law, contact.JKRSphere):
        w = law.w
        a = jkr.radius_from_overlap(delta, R, w, E)
        return a, jkr.force_from_radius(a, R, w, E), jkr.contact_energy(a, R, w, E)
    P = jkr.hertz_force(delta, R, E)
    a = jkr.hertz_contact_radius(P, R, E)
    U = 8.0 / 15.0 * E * math.sqrt(R) * delta**2.5  # ∫ P dδ of eq 1–3
    return a, P, U


def _check_forms(law, radius, force, energy):
    d = _overlaps(law)
    a, P, U = _closed_form(law, d)
    k = law.constants
    scale_P = max(law.pull_off_force, float(np.max(np.abs(P))))
    scale_U = float(np.max(np.abs(U)))
    # At equilibrium (a_prev on the branch) every law's radius is the branch radius.
    assert_allclose([radius(x, y, 0.1, k) for x, y in zip(d, a, strict=True)], a, rtol=1e-9,
                    atol=1e-12)  # fmt: skip
    assert_allclose([force(x, y, k) for x, y in zip(a, d, strict=True)], P, rtol=1e-9,
                    atol=1e-9 * scale_P)  # fmt: skip
    assert_allclose([energy(x, y, k) for x, y in zip(a, d, strict=True)], U, rtol=1e-9,
                    atol=1e-9 * scale_U)  # fmt: skip


def test_every_tip_name_has_a_law():
    assert set(TIPS) == set(contact.TIP_LAWS)


@pytest.mark.parametrize("i", range(3))
def test_numpy_and_scalar_forms_match_the_closed_form(i):
    law = _laws()[i]
    d = _overlaps(law)
    a, P, U = _closed_form(law, d)
    scale_P = max(law.pull_off_force, float(np.max(np.abs(P))))
    assert_allclose(law.radius(d.copy(), a, 0.1), a, rtol=1e-9, atol=1e-12)
    assert_allclose(law.force(a, d), P, rtol=1e-9, atol=1e-9 * scale_P)
    assert_allclose(law.energy(a, d), U, rtol=1e-9, atol=1e-9 * float(np.max(np.abs(U))))
    _check_forms(law, law.radius_scalar, law.force_scalar, law.energy_scalar)


@extras.needs("fast")
@pytest.mark.parametrize("i", range(3))
def test_compiled_scalar_forms_match_the_closed_form(i):
    import numba

    law = _laws()[i]
    jit = numba.njit(error_model="numpy")
    _check_forms(law, jit(law.radius_scalar), jit(law.force_scalar), jit(law.energy_scalar))


@pytest.mark.parametrize("i", range(3))
def test_energy_is_the_work_of_the_force(i):
    # dU/dδ = P along the branch (central differences), an oracle independent of U's formula.
    law = _laws()[i]
    lo = law.delta_c if law.rate_dependent else law.detach_overlap
    d = np.linspace(lo * 0.9 + 1e-3, 2.0, 50)
    h = 1e-6
    el = contact.JKRSphere(PAPER_TABLE1.contact) if law.rate_dependent else law

    def U(x):
        return law.energy(el.radius(x, None, 0.0), x)

    dU = (U(d + h) - U(d - h)) / (2 * h)
    assert_allclose(dU, law.force(el.radius(d.copy(), None, 0.0), d), rtol=1e-5, atol=1e-6)


def test_jkr_law_constants():
    law = contact.JKRSphere(PAPER_TABLE1.contact)
    R, w, E = PAPER_TABLE1.contact.jkr_args()
    assert law.pull_off_force == pytest.approx(1.5 * math.pi * R * w, rel=1e-12)
    assert law.detach_overlap == pytest.approx(jkr.snap_off_overlap(R, w, E), rel=1e-12)
    # Attachment at δ = 0 lands on the branch at the jump-in radius, where U = 0.
    r = float(law.radius(np.array([0.0]), None, 0.0)[0])
    assert r == pytest.approx(law.jump_radius, rel=1e-9)
    assert law.energy_scalar(law.jump_radius, 0.0, law.constants) == pytest.approx(0.0, abs=1e-12)


def test_hertz_law_has_no_adhesion():
    law = contact.HertzSphere(PAPER_TABLE1.contact)
    assert law.pull_off_force == 0.0 and law.detach_overlap == 0.0
    assert law.radius_scalar(-0.1, 0.0, 0.1, law.constants) == 0.0


@pytest.mark.slow
@pytest.mark.parametrize("tip", ["sphere", "hertz"])
def test_reference_callback_path_agrees_with_every_kernel(tip):
    # The per-contact pre_solve path against the batch paths, on the same run.
    p = PAPER_TABLE1.replace(
        **{"mechanics": "rod", "seta.L": 5.0, "tip": tip, "array.count": 3, "floor.sigma": 0.2}
    )
    prot = protocol.press_pull(0.3, speed=0.05)
    ref = Model(p, numerics=Numerics(contact="callback", record_every=5)).run(prot, progress=False)
    kernels = ["numpy", "python"] + (["numba"] if numba_available() else [])
    for kernel in kernels:
        h = Model(p, numerics=Numerics(kernel=kernel, record_every=5, integrator="explicit")).run(
            prot, progress=False
        )
        scale = max(float(np.max(np.abs(ref["force_normal_uN"]))), 1e-12)
        (
            assert_allclose(
                h["force_normal_uN"], ref["force_normal_uN"], rtol=0, atol=1e-9 * scale
            ),
            kernel,
        )


def test_hertz_tips_press_without_adhesion():
    p = PAPER_TABLE1.replace(**{"mechanics": "rod", "seta.L": 5.0, "tip": "hertz"})
    h = Model(p).run(protocol.press_pull(0.3, speed=0.05), progress=False)
    assert h["force_normal_uN"].min() >= 0.0  # never in tension
    assert h["force_normal_uN"].max() > 0.0
    assert h.peak_pull_off == 0.0
    assert h.meta["tip_law"] == "hertz"
    assert h["n_attached"][-1] == 0


def test_unknown_tip_is_refused():
    with pytest.raises(ValueError, match="tip"):
        PAPER_TABLE1.replace(**{"tip": "suction cup"})
