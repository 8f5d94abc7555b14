"""The branched seta (contact.spatulae.SpatulaeTip): N = 1 is the spatula bit for bit, N
identical films sharing the load are N times one film (the closed form of their steady peel as
the oracle), the energy books close, and bad parameters are refused."""

import hashlib
import math
import warnings

import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.contact import contact_law
from gecko_agents.contact.spatula import K_MU
from gecko_agents.contact.spatulae import EXTENSIVE, SpatulaeTip, peel_force, seta_pull_off
from gecko_agents.history import ENERGY_RTOL, energy_balance_error
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.params.literature import FRICTIONAL_SPATULA, TOKAY_SETA

SPATULAE = FRICTIONAL_SPATULA.replace(tip="spatulae")


def _run(params, prot, kernel="auto", integrator="auto"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(
            params, seed=1, numerics=Numerics(record_every=1, kernel=kernel, integrator=integrator)
        )
        return m.run(prot, progress=False)


def _digest(h) -> str:
    d = hashlib.sha256()
    for k in sorted(h.scalars):
        d.update(k.encode())
        d.update(np.ascontiguousarray(h.scalars[k]).tobytes())
    for k in sorted(h.detachments):
        d.update(np.ascontiguousarray(h.detachments[k]).tobytes())
    return d.hexdigest()


@pytest.mark.parametrize("kernel", ["auto", "numpy"])
def test_one_spatula_is_the_spatula_tip_bit_for_bit(kernel):
    """N = 1: the same history as ``tip = "spatula"``, every recorded number and detachment
    (a gripping drag of 1 µm at μ = 10 pulled off at 60°, the film peeling off)."""
    prot = protocol.drag_pull(0.2, -1.0, 60.0, speed=0.1)
    assert _digest(_run(SPATULAE, prot, kernel)) == _digest(_run(FRICTIONAL_SPATULA, prot, kernel))


def test_extensive_constants_scale_and_intensive_ones_do_not():
    law = contact_law(SPATULAE.replace(**{"spatulae.count": 7}))
    one = contact_law(FRICTIONAL_SPATULA)
    assert isinstance(law, SpatulaeTip)
    for i, (a, b) in enumerate(zip(law.constants, one.constants, strict=True)):
        assert a == (7.0 * b if i in EXTENSIVE else b), i
    assert law.pull_off_force == 7.0 * one.pull_off_force


@pytest.mark.parametrize("n", [2, 300])
def test_a_step_of_n_films_is_n_times_one_film(n):
    """step_scalar from random states: forces, energy and dissipation N times one film's,
    the front's shift, pad length and free length the same, the pre-tension N times (the
    state's P0 is the N films' total)."""
    law = contact_law(SPATULAE.replace(**{"spatulae.count": n}))
    one = contact_law(FRICTIONAL_SPATULA)
    rng = np.random.default_rng(3)
    for _ in range(200):
        dx, z = rng.uniform(-6, 2), rng.uniform(one.R - 0.3, one.R + 6)
        ell, p0 = rng.uniform(0.2, 3.0), rng.uniform(0.0, 0.3)
        s0, xa = rng.uniform(1.0, 4.0), rng.uniform(-0.1, 0.1)
        a = law.step_scalar(dx, z, ell, n * p0, s0, xa, law.constants)
        b = one.step_scalar(dx, z, ell, p0, s0, xa, one.constants)
        for i in (0, 1, 7, 8):  # P, T, U, dissipation
            assert a[i] == pytest.approx(n * b[i], rel=1e-9, abs=1e-12 * n)
        for i in (2, 3, 5, 6, 9):  # shift, ℓ, s0, xa, slid
            assert a[i] == pytest.approx(b[i], rel=1e-9, abs=1e-12)
        assert a[4] == pytest.approx(n * b[4], rel=1e-9, abs=1e-12 * n)


def test_the_closed_form_is_kendalls():
    """peel_force: Kendall's F = b·E_f·h(√(c² + 2w/(E_f·h)) − c), c = 1 − cos φ, and the
    inextensible w·b/(1 − cos φ)."""
    w, b, E, h = 0.05, 0.2, 1600.0, 0.01
    for phi in np.radians([10.0, 30.0, 60.0, 90.0, 150.0]):
        c = 1.0 - math.cos(phi)
        kendall = b * E * h * (math.sqrt(c * c + 2.0 * w / (E * h)) - c)
        assert float(peel_force(phi, w, b, E, h)) == pytest.approx(kendall, rel=1e-12)
        assert float(peel_force(phi, w, b, 1e12, h)) == pytest.approx(w * b / c, rel=1e-6)


@pytest.mark.parametrize("phi_deg", [30.0, 90.0])
def test_n_films_peel_at_n_times_kendalls_force(phi_deg):
    """A stiff mount pulls the N films' common end at a fixed angle φ from their front (the
    pad held: μ → ∞) until they let go: the largest tension is seta_pull_off's N·F_Kendall."""
    n = 40
    law = contact_law(TOKAY_SETA.replace(**{"spatulae.count": n, "spatula.interface": "bonded"}))
    k = law.constants.copy()
    k[K_MU] = 1e12
    phi = math.radians(phi_deg)
    ell, p0, s0, xf, s, F = law.ell0, 0.0, law.s_attach, 0.0, law.s_attach, 0.0
    for _ in range(200_000):
        s += 2e-5
        dx, zf = -s * math.cos(phi), s * math.sin(phi)
        x = xf + dx  # the mount, held through the step
        P, T, shift, ell, p0, s0 = law.step_scalar(dx, zf + law.R, ell, p0, s0, dx, k)[:6]
        if ell <= 0.0:
            break
        F = math.hypot(P, T)  # the films' tension after the step
        xf += shift
        s = math.hypot(x - xf, zf)
    normal, shear = seta_pull_off(n, phi, law.w, law.b, law.E_f, law.h)
    assert ell <= 0.0
    assert F == pytest.approx(math.hypot(normal, shear), rel=0.01)


@pytest.mark.slow
def test_energy_books_close_on_a_branched_seta_and_a_patch():
    """A 50-spatula seta and a patch of three on a rough floor, pressed, dragged back and
    pulled at 60°: the energy balance within the film law's tolerance (2·ENERGY_RTOL)."""
    prot = protocol.drag_pull(0.2, -2.0, 60.0, speed=0.05)
    p = SPATULAE.replace(**{"spatulae.count": 50})
    for params, preload in ((p, 0.2), (p.replace(**{"array.count": 3, "floor.sigma": 0.3}), 0.6)):
        prot = protocol.drag_pull(preload, -2.0, 60.0, speed=0.05)
        h = _run(params, prot)
        assert energy_balance_error(h) <= 2.0 * ENERGY_RTOL
        assert np.max(-np.asarray(h["force_normal_uN"])) > 0.0  # it held in tension


@pytest.mark.parametrize(
    ("field", "value"),
    [("spatulae.count", 0), ("spatulae.count", 2.5), ("spatulae.branch_radius", -1.0)],
)
def test_bad_values_refused_naming_the_field(field, value):
    with pytest.raises(ValueError, match=field.split(".")[1]):
        SPATULAE.replace(**{field: value})


def test_spatulae_on_another_tip_refused():
    with pytest.raises(ValueError, match="Spatulae.count = 5 acts on tip = 'spatulae' only"):
        PAPER_ARRAY.replace(**{"spatulae.count": 5})


@pytest.mark.slow
def test_tokay_seta_lets_go_at_n_times_kendalls_force_at_its_release_angle():
    """The tokay preset pressed and pulled straight up (no drag, so no pre-tension): at
    release the seta's force has the magnitude seta_pull_off gives at the angle φ it makes
    with the floor there, N·F_Kendall(φ) (the shaft, not the plate, sets φ)."""
    from gecko_agents.analysis.pull import release_point

    h = _run(TOKAY_SETA, protocol.drag_pull(1.0, 0.0, 90.0, speed=0.05), integrator="explicit")
    rel = release_point(h)
    phi = math.atan2(rel.adhesion, rel.shear)
    law = contact_law(TOKAY_SETA)
    normal, shear = seta_pull_off(law.count, phi, law.w, law.b, law.E_f, law.h)
    assert 30.0 < math.degrees(phi) < 90.0
    assert math.hypot(rel.adhesion, rel.shear) == pytest.approx(math.hypot(normal, shear), rel=0.03)


def test_let_go_forces_reads_each_attachment_at_its_largest_adhesion():
    """Two attachments, the first let go, the second still on at the end of the run: one
    let-go, at the first attachment's largest tension."""
    from types import SimpleNamespace

    from gecko_agents.studies.gecko_seta import let_go_forces

    nan = math.nan
    ell = np.array([nan, 0.2, 0.2, 0.1, nan, nan, 0.2, 0.2])[:, None]
    P = np.array([0.0, 1.0, -3.0, -2.0, 0.0, 0.0, -1.0, -4.0])
    T = np.array([0.0, 0.0, 1.5, 1.0, 0.0, 0.0, 0.5, 2.0])

    class Run(SimpleNamespace):
        def __getitem__(self, key):
            return {"force_normal_uN": P, "force_tangential_uN": T}[key]

    assert let_go_forces(Run(setae={"film_attached_um": ell})) == ([3.0], [1.5])


def test_the_quasi_static_solver_refuses_the_branched_seta_naming_the_tip():
    """The quasi-static solver models the JKR sphere only: it refuses tip = 'spatulae' before
    any work, naming the tip and pointing to the time-stepped model."""
    from gecko_agents.quasistatic import single_seta

    with pytest.raises(ValueError, match="tip = 'spatulae' must be 'sphere'; run the time-stepped"):
        single_seta(TOKAY_SETA, [100.0, 90.0])
