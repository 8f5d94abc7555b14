"""Contact laws: every form of every law (numpy, scalar interpreted, scalar compiled, the
per-contact reference path) pinned to its closed form point by point."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from gecko_agents import contact, jkr, protocol
from gecko_agents.model import Model, numba_available
from gecko_agents.params import PAPER_TABLE1, TIPS

LAWS = [contact.JKRSphere, contact.HertzSphere]


def _overlaps(law):
    """Overlaps over the whole branch, dense near where it ends."""
    lo = law.detach_overlap
    ends = lo + np.geomspace(1e-9, 1.0, 200) * max(abs(lo), 0.1)
    return np.concatenate([ends, np.linspace(lo, 3.0, 400)[1:]])


def _closed_form(law, delta):
    """(a, P, U) from jkr.py for the law's material."""
    R, E = law.R, law.E_star
    if isinstance(law, contact.JKRSphere):
        w = law.w
        a = jkr.radius_from_overlap(delta, R, w, E)
        return a, jkr.force_from_radius(a, R, w, E), jkr.contact_energy(a, R, w, E)
    P = jkr.hertz_force(delta, R, E)
    a = jkr.hertz_contact_radius(P, R, E)
    U = 8.0 / 15.0 * E * math.sqrt(R) * delta**2.5  # ∫ P dδ of eq 1–3
    return a, P, U


def _scalar(fn, x, k):
    return np.array([fn(float(v), k) for v in x])


def test_every_tip_name_has_a_law():
    assert set(TIPS) == set(contact.TIP_LAWS)


@pytest.mark.parametrize("law_type", LAWS)
def test_numpy_and_scalar_forms_match_the_closed_form(law_type):
    law = law_type(PAPER_TABLE1.contact)
    d = _overlaps(law)
    a, P, U = _closed_form(law, d)
    scale_P = max(law.pull_off_force, float(np.max(np.abs(P))))
    assert_allclose(law.radius(d.copy()), a, rtol=1e-9, atol=1e-12)
    assert_allclose(law.force(a), P, rtol=1e-9, atol=1e-9 * scale_P)
    assert_allclose(law.energy(a), U, rtol=1e-9, atol=1e-9 * float(np.max(np.abs(U))))
    k = law.constants
    assert_allclose(_scalar(law.radius_scalar, d, k), a, rtol=1e-9, atol=1e-12)
    assert_allclose(_scalar(law.force_scalar, a, k), P, rtol=1e-9, atol=1e-9 * scale_P)
    assert_allclose(
        _scalar(law.energy_scalar, a, k), U, rtol=1e-9, atol=1e-9 * float(np.max(np.abs(U)))
    )


@pytest.mark.skipif(not numba_available(), reason="numba not installed (the 'fast' extra)")
@pytest.mark.parametrize("law_type", LAWS)
def test_compiled_scalar_forms_match_the_closed_form(law_type):
    import numba

    law = law_type(PAPER_TABLE1.contact)
    d = _overlaps(law)
    a, P, U = _closed_form(law, d)
    k = law.constants
    radius, force, energy = (
        numba.njit(f) for f in (law.radius_scalar, law.force_scalar, law.energy_scalar)
    )
    scale_P = max(law.pull_off_force, float(np.max(np.abs(P))))
    assert_allclose(_scalar(radius, d, k), a, rtol=1e-9, atol=1e-12)
    assert_allclose(_scalar(force, a, k), P, rtol=1e-9, atol=1e-9 * scale_P)
    assert_allclose(_scalar(energy, a, k), U, rtol=1e-9, atol=1e-9 * float(np.max(np.abs(U))))


@pytest.mark.parametrize("law_type", LAWS)
def test_energy_is_the_work_of_the_force(law_type):
    # dU/dδ = P along the branch (central differences), an oracle independent of U's formula.
    law = law_type(PAPER_TABLE1.contact)
    d = np.linspace(law.detach_overlap * 0.9 + 1e-3, 2.0, 50)
    h = 1e-6
    dU = (law.energy(law.radius(d + h)) - law.energy(law.radius(d - h))) / (2 * h)
    assert_allclose(dU, law.force(law.radius(d.copy())), rtol=1e-5, atol=1e-6)


def test_jkr_law_constants():
    law = contact.JKRSphere(PAPER_TABLE1.contact)
    R, w, E = PAPER_TABLE1.contact.jkr_args()
    assert law.pull_off_force == pytest.approx(1.5 * math.pi * R * w, rel=1e-12)
    assert law.detach_overlap == pytest.approx(jkr.snap_off_overlap(R, w, E), rel=1e-12)
    # Attachment at δ = 0 lands on the branch at the jump-in radius, where U = 0.
    assert float(law.radius(np.array([0.0]))[0]) == pytest.approx(law.jump_radius, rel=1e-9)
    assert law.energy_scalar(law.jump_radius, law.constants) == pytest.approx(0.0, abs=1e-12)


def test_hertz_law_has_no_adhesion():
    law = contact.HertzSphere(PAPER_TABLE1.contact)
    assert law.pull_off_force == 0.0 and law.detach_overlap == 0.0
    assert law.radius_scalar(-0.1, law.constants) == 0.0


@pytest.mark.parametrize("tip", ["sphere", "hertz"])
def test_reference_callback_path_agrees_with_every_kernel(tip):
    # The per-contact pre_solve path against the batch paths, on the same run.
    p = PAPER_TABLE1.replace(
        **{"mechanics": "rod", "seta.L": 5.0, "tip": tip, "array.count": 3, "floor.sigma": 0.2}
    )
    prot = protocol.press_pull(0.3, speed=0.05)
    ref = Model(p, contact="callback", record_every=5).run(prot, progress=False)
    kernels = ["numpy", "python"] + (["numba"] if numba_available() else [])
    for kernel in kernels:
        h = Model(p, kernel=kernel, record_every=5).run(prot, progress=False)
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
