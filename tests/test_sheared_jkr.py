"""The JKR sphere coupled to its shear (Savkoor & Briggs 1977): the closed forms of
gecko_agents.physics.savkoor_briggs against JKR and against each other, the contact law against
them, and
a dragged-and-pulled seta against the load-controlled pull-off under shear."""

import math
import warnings

import extras
import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from gecko_agents import protocol, quasistatic
from gecko_agents.analysis.pull import pull_off
from gecko_agents.contact import JKRSphere, ShearedJKRSphere, contact_law
from gecko_agents.contact.sheared_jkr import _radius
from gecko_agents.model import Model, Numerics, numba_available
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import jkr
from gecko_agents.physics import savkoor_briggs as sj
from gecko_agents.physics.friction import combined_shear_modulus

SHEARED = PAPER_ARRAY.replace(
    **{"contact.shear_coupling": "savkoor_briggs", "mechanics": "rod", "floor.sigma": 0.0}
)
C = SHEARED.contact
R, W, E = C.jkr_args()
G = float(combined_shear_modulus(C.E1, C.nu1, C.E2, C.nu2))


def test_no_shear_is_jkr():
    """T = 0: JKR's radius under load (eq 8) and its pull-off Fc = 1.5πwR."""
    P = np.linspace(-0.99, 5.0, 13) * jkr.pull_off_force(R, W)
    np.testing.assert_allclose(
        sj.radius_from_loads(P, 0.0, R, W, E, G), jkr.contact_radius_from_force(P, R, W, E),
        rtol=1e-12,
    )  # fmt: skip
    assert sj.pull_off_force(0.0, R, W, E, G) == pytest.approx(1.5 * math.pi * W * R, rel=1e-15)
    T_free = sj.shear_to_free(R, W, E, G)
    assert T_free == pytest.approx(6 * math.pi * W * R * math.sqrt(G / E), rel=1e-15)
    assert sj.pull_off_force(T_free, R, W, E, G) == pytest.approx(0.0, abs=1e-12)
    # At zero load the load-controlled contact exists just below that shear, not above it.
    assert np.isfinite(sj.radius_from_loads(0.0, T_free * (1 - 1e-9), R, W, E, G))
    assert np.isnan(sj.radius_from_loads(0.0, T_free * (1 + 1e-6), R, W, E, G))


@pytest.mark.parametrize("a_over_a0", [0.8, 1.0, 1.6])
@pytest.mark.parametrize("xi", [0.0, 0.05, 0.2])
def test_displacement_and_load_control_forms_agree(a_over_a0, xi):
    """A contact of radius a at tangential displacement ξ, its overlap from the displacement
    form, its loads P (Hertz + flat punch) and T = 8G*·a·ξ (Mindlin): the load-controlled
    Savkoor–Briggs radius of (P, T) is a again (radii on its load-stable branch, above the
    pull-off radius 0.63·a0). Two derivations, one contact."""
    a = a_over_a0 * float(jkr.zero_load_contact_radius(R, W, E))
    delta = sj.overlap_from_radius(a, xi, R, W, E, G)
    assert np.isfinite(delta)
    P = sj.force_from_state(a, delta, R, E)
    T = 8.0 * G * a * xi  # Mindlin's stick stiffness 8G*·a
    assert sj.radius_from_loads(P, T, R, W, E, G) == pytest.approx(a, rel=1e-10)


def test_energy_derivatives_are_the_forces():
    """U(a, δ, ξ): ∂U/∂δ = P, ∂U/∂ξ = 8G*·a·ξ (the stick spring), ∂U/∂a = 0 on the branch
    (central differences)."""
    a, xi = 2.0, 0.15
    delta = float(sj.overlap_from_radius(a, xi, R, W, E, G))
    h = 1e-6

    def U(a_, d_, x_):
        return float(sj.energy(a_, d_, x_, R, W, E, G))

    dU_dd = (U(a, delta + h, xi) - U(a, delta - h, xi)) / (2 * h)
    dU_dx = (U(a, delta, xi + h) - U(a, delta, xi - h)) / (2 * h)
    dU_da = (U(a + h, delta, xi) - U(a - h, delta, xi)) / (2 * h)
    d2U_da2 = (U(a + 1e-3, delta, xi) - 2 * U(a, delta, xi) + U(a - 1e-3, delta, xi)) / 1e-6
    assert d2U_da2 > 0.0  # the stable radius minimises the energy
    assert dU_dd == pytest.approx(float(sj.force_from_state(a, delta, R, E)), rel=1e-7)
    assert dU_dx == pytest.approx(8 * G * a * xi, rel=1e-7)
    assert abs(dU_da) < 1e-7 * abs(dU_dd)


@pytest.mark.parametrize("delta", [0.4, 0.0, -0.3, -0.56])
@pytest.mark.parametrize("xi", [0.0, 0.1, 0.3, 1.0])
def test_law_radius_is_the_stable_root(delta, xi):
    """The law's radius at (δ, ξ) is the largest root of the displacement form (scipy), and 0
    exactly where none exists; at ξ = 0 it is the JKR sphere's."""
    law = contact_law(SHEARED)
    a = _radius(delta, xi, law.constants)
    expected = oracle_radius(delta, xi)
    assert (a > 0.0) == (expected > 0.0)
    assert a == pytest.approx(expected, rel=1e-9)
    if xi == 0.0 and a > 0.0:
        jkr_a = float(JKRSphere(SHEARED.contact).radius(np.array([delta]))[0])
        assert a == pytest.approx(jkr_a, rel=1e-12)


def oracle_radius(delta, xi):
    """Largest root a of δ(a, ξ) = δ (the branch's stable side), 0 below the branch's end."""
    if fold_overlap(xi) > delta:
        return 0.0
    a_fold = minimize_scalar(
        lambda a: float(sj.overlap_from_radius(a, xi, R, W, E, G)),
        bounds=(4 * G * xi * xi / (2 * math.pi * W) + 1e-12, 10 * R), method="bounded",
        options={"xatol": 1e-12},
    ).x  # fmt: skip
    return brentq(
        lambda a: float(sj.overlap_from_radius(a, xi, R, W, E, G)) - delta, a_fold, 100 * R,
        xtol=1e-14,
    )  # fmt: skip


def fold_overlap(xi):
    """Overlap at the end of the branch at ξ: the minimum over a of δ(a, ξ) (scipy)."""
    a_min = 4 * G * xi * xi / (2 * math.pi * W)
    res = minimize_scalar(
        lambda a: float(sj.overlap_from_radius(a, xi, R, W, E, G)),
        bounds=(a_min * (1 + 1e-12) + 1e-12, 10 * R), method="bounded",
        options={"xatol": 1e-12},
    )  # fmt: skip
    return res.fun


@pytest.mark.parametrize("delta", [0.2, 0.0, -0.4])
def test_shear_that_ends_the_contact(delta):
    """At fixed δ the contact exists up to the ξ where the branch's end reaches δ: the law's
    boundary (bisection on its radius) against a scipy root of the fold overlap."""
    law = contact_law(SHEARED)
    xi_end = brentq(lambda x: fold_overlap(x) - delta, 0.0, 5.0, xtol=1e-12)
    lo, hi = 0.0, 5.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _radius(delta, mid, law.constants) > 0.0 else (lo, mid)
    assert lo == pytest.approx(xi_end, rel=1e-5)


def drive(law, k, delta, xs):
    """Drive the tip along the floor at fixed δ through offsets ``xs`` from where it attached:
    returns per step (P, T, a, slid) and the energy check (work, stored + dissipated)."""
    xa, a, u, work, diss, T_prev = 0.0, law.jump_radius, 0.0, 0.0, 0.0, 0.0
    z = law.R - delta
    out = law.step_scalar(0.0, z, a, 0.0, u, xa, k)
    a, xi, u, xa, stored0 = out[3], out[4], out[5], out[6], out[7]
    rows = []
    for j in range(1, len(xs)):
        P, T, _, a, xi, u, xa, U, de, slid = law.step_scalar(xs[j], z, a, xi, u, xa, k)
        work -= 0.5 * (T + T_prev) * (xs[j] - xs[j - 1])  # the drive works against T
        T_prev, diss = T, diss + de
        rows.append((P, T, a, slid))
        if a <= 0.0:
            break
    return np.array(rows), work, U - stored0 + diss


def test_tip_sticks_then_slides_at_the_cap_of_its_sheared_load():
    """μ = 0.2: the tip sticks on its own Mindlin spring 8G*·a (the contact shrinking as ξ
    grows), then slides at μ|P + 2Fc| with P the sheared contact's load; the drive's work is
    stored or dissipated."""
    law = contact_law(SHEARED)
    k = law.constants
    xs = np.linspace(0.0, 0.6, 3001)
    rows, work, books = drive(law, k, 0.1, xs)
    P, T, a, slid = rows.T
    stick, sliding = slid == 0.0, slid == 1.0
    assert stick.any() and sliding.any() and (a > 0).all()
    for j in np.flatnonzero(stick)[::50]:  # radius and stick force from the closed forms
        a_j = oracle_radius(0.1, xs[j + 1])
        assert a[j] == pytest.approx(a_j, rel=1e-9)
        assert -T[j] == pytest.approx(8 * G * a_j * xs[j + 1], rel=1e-9)
    for j in np.flatnonzero(sliding)[::50]:  # on the branch, at the cap μ|P + 2Fc|
        xi_j = -T[j] / (8 * G * a[j])
        assert float(sj.overlap_from_radius(a[j], xi_j, R, W, E, G)) == pytest.approx(
            0.1, abs=1e-12
        )
        assert P[j] == pytest.approx(float(sj.force_from_state(a[j], 0.1, R, E)), rel=1e-12)
        assert -T[j] == pytest.approx(0.2 * abs(P[j] + 2 * law_fc()), rel=1e-6)
    assert np.all(np.diff(a[stick]) < 0)  # shear shrinks the sticking contact
    assert work == pytest.approx(books, rel=2e-3)


def test_sheared_alone_it_lets_go_where_the_branch_ends():
    """μ = 10 (it never slides): driven sideways at δ = 0 the tip lets go at the ξ where the
    branch ends (scipy), holding less tension than Fc on the way."""
    law = contact_law(SHEARED.replace(**{"friction.mu": 10.0}))
    xs = np.linspace(0.0, 3.0, 30001)
    rows, _, _ = drive(law, law.constants, 0.0, xs)
    released_at = xs[len(rows)]
    assert rows[-1, 2] == 0.0 and (rows[:-1, 3] == 0.0).all()
    assert (-rows[:, 0]).max() < law_fc()
    xi_end = brentq(lambda x: fold_overlap(x) - 0.0, 0.0, 5.0, xtol=1e-12)
    assert released_at == pytest.approx(xi_end, abs=2 * (xs[1] - xs[0]))


def test_pressed_tip_slides_where_its_branch_ends():
    """μ = 10, pressed δ = 1 µm: the branch ends below the cap, but a tip pressed into the
    floor keeps its contact and slides at the shear the branch's end holds (its ξ where the
    fold overlap reaches δ, scipy), never letting go; the drive's work is stored or
    dissipated."""
    law = contact_law(SHEARED.replace(**{"friction.mu": 10.0}))
    xs = np.linspace(0.0, 4.0, 8001)
    rows, work, books = drive(law, law.constants, 1.0, xs)
    P, T, a, slid = rows.T
    assert len(rows) == len(xs) - 1 and (a > 0).all()
    assert slid[-1] == 1.0 and P[-1] > 0.0
    xi_end = brentq(lambda x: fold_overlap(x) - 1.0, 0.0, 5.0, xtol=1e-12)
    assert -T[-1] / (8 * G * a[-1]) == pytest.approx(xi_end, rel=1e-4)
    assert work == pytest.approx(books, rel=2e-3)


def _drag_pull(params, drag, kernel="auto", speed=0.05, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        p = params.replace(**{"array.count": 1})
        m = Model.from_options(p, seed=1, **kw, numerics=Numerics(kernel=kernel, record_every=1))
        return m.run(protocol.drag_pull(0.2, drag, 90.0, speed=speed), progress=False)


def test_pull_off_after_a_gripping_drag_is_savkoor_briggs():
    """One rod seta (θ = 60°, μ = 10) pressed to 0.2 µN, dragged 8 µm back along its shaft and
    pulled straight off: the soft seta loads its tip nearly as a dead load, so the pull-off is
    the load-controlled Fc − E*T²/(24πwRG*) at the shear T it carries then (2.61 µN at
    T = 2.25 µN, 16 % below Fc); without the coupling it is Fc whatever the shear."""
    p = SHEARED.replace(**{"friction.mu": 10.0, "seta.theta_deg": 60.0})
    h = _drag_pull(p, -8.0)
    held = pull_off(h)  # the largest adhesion in the pull after the drag
    T = abs(held.shear)
    assert T > 0.5 * law_fc()
    assert held.adhesion == pytest.approx(float(sj.pull_off_force(T, R, W, E, G)), rel=0.01)
    plain = _drag_pull(p.replace(**{"contact.shear_coupling": "none"}), -8.0, speed=0.2)
    assert -plain["force_normal_uN"].min() == pytest.approx(law_fc(), rel=1e-3)


def law_fc():
    return float(jkr.pull_off_force(R, W))


def test_without_friction_it_is_the_jkr_sphere():
    """μ = 0 with the paper's friction law: the tip never carries shear (ξ = 0), and a
    press–pull gives the JKR sphere's history to rounding."""
    p = SHEARED.replace(**{"friction.mu": 0.0, "friction.law": "paper"})
    # The laws' kernels compared on the explicit step. Under the implicit step the histories
    # part at the jump-in step (cap 0): the JKR sphere's tip is taken out of its stick spring
    # after the solve (ImplicitStep._stick_past_cap: friction 0, marked sliding), the sheared
    # law's keeps its own friction and the stick spring in the Jacobian, 0.23 % of Fc off.
    # Without that spring alone it is 0.28 %: the laws' slip states then differ.
    ex = {"speed": 0.2, "integrator": "explicit"}
    sheared = _drag_pull(p, 0.0, **ex)
    plain = _drag_pull(p.replace(**{"contact.shear_coupling": "none"}), 0.0, **ex)
    assert len(sheared) == len(plain)
    for col in ("force_normal_uN", "work_plate_pJ"):
        scale = np.abs(plain[col]).max()
        assert np.abs(sheared[col] - plain[col]).max() <= 1e-6 * scale, col
    # The JKR sphere counts its energy from the jump-in, this law from the free tip: the
    # books split differently while attached, and agree in sum and once it has let go.
    books = [h["energy_elastic_pJ"] + h["energy_dissipated_pJ"] for h in (sheared, plain)]
    np.testing.assert_allclose(books[0], books[1], atol=1e-6 * np.abs(books[1]).max())
    assert sheared["energy_dissipated_pJ"][-1] == pytest.approx(
        plain["energy_dissipated_pJ"][-1], rel=1e-6
    )


@pytest.mark.slow
@pytest.mark.parametrize("kernel", ["python", "numba"])
def test_kernels_agree(kernel):
    """Three setae dragged both ways and pulled: the per-seta loop (compiled or interpreted)
    gives the numpy path's history to rounding."""

    if kernel == "numba" and not numba_available():
        pytest.skip(extras.reason("fast"))
    p = SHEARED.replace(**{"array.count": 3, "friction.mu": 0.5})
    dp = protocol.drag_pull(0.4, 6.0, 60.0, speed=0.05)
    prot = [*dp[:-1], protocol.Move(dx=-10.0, speed=0.05), dp[-1]]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = Model(p, numerics=Numerics(kernel="numpy")).run(prot, progress=False)
        h = Model(p, numerics=Numerics(kernel=kernel)).run(prot, progress=False)
    for col in ref.scalars:
        scale = np.abs(ref[col]).max() + 1e-300
        assert np.abs(ref[col] - h[col]).max() <= 1e-9 * scale, col


@pytest.mark.parametrize(
    "change, field",
    [
        ({"contact.shear_coupling": "mindlin"}, "shear_coupling"),
        ({"contact.crack_speed": 1.0}, "shear_coupling"),
        ({"contact.detachment": "delta_s"}, "shear_coupling"),
    ],
)
def test_bad_values_refused_naming_the_field(change, field):
    with pytest.raises(ValueError, match=field):
        SHEARED.replace(**change)


def test_refused_where_it_is_not_modelled():
    """The quasi-static solver (JKR only) and a continuous floor refuse it, naming it."""
    with pytest.raises(ValueError, match="shear_coupling"):
        quasistatic.single_seta(SHEARED.replace(**{"array.count": 1}), [0.0])
    p = SHEARED.replace(**{"floor.sigma": 0.1, "floor.correlation_length": 5.0})
    with pytest.raises(ValueError, match="shear_coupling"):
        Model(p.replace(**{"array.count": 1}), seed=1).run(
            protocol.drag_pull(0.2, 1.0, 90.0), progress=False
        )


def test_law_is_chosen_by_the_coupling():
    assert type(contact_law(SHEARED)) is ShearedJKRSphere
    assert type(contact_law(PAPER_ARRAY)) is JKRSphere


def test_normal_stiffness_is_the_jkr_branch_slope():
    """The implicit step's normal stiffness of the sheared tip is dP/dδ of the unsheared
    JKR branch (eq 7 over eq 10, differentiated in a): checked against central differences
    of P(a) and δ(a) at three radii."""
    law = contact_law(SHEARED)
    a = np.array([0.8, 1.0, 2.5]) * float(jkr.zero_load_contact_radius(R, W, E))
    h = 1e-6 * a
    dP = jkr.force_from_radius(a + h, R, W, E) - jkr.force_from_radius(a - h, R, W, E)
    dd = jkr.overlap_from_radius(a + h, R, W, E) - jkr.overlap_from_radius(a - h, R, W, E)
    delta = jkr.overlap_from_radius(a, R, W, E)
    np.testing.assert_allclose(law.stiffness(a, delta), dP / dd, rtol=1e-6)


@pytest.mark.parametrize(("lift", "move"), [(0.1, -0.001), (0.1, 0.01), (0.3, 0.01)])
def test_a_lifted_contact_slides_back_within_its_cap(lift, move):
    """μ = 0.2: a tip dragged at δ = 0.1 µm until it slides (its shear at the cap μ|P + 2Fc|),
    then lifted by ``lift`` and moved by ``move`` along the drag: the lifted contact carries
    less shear than before, so it slips back to where it holds. The slip relieves the trial
    shear (|ξ| ≤ the trial's), the force is Coulomb's at the new load (|T| = μ|P + 2Fc|), the
    radius is on the branch at the new (δ, ξ) (Savkoor & Briggs, closed form) and the slip
    dissipates work (≥ 0)."""
    law = contact_law(SHEARED)
    k = law.constants
    delta = 0.1
    _, _, _, a, xi, u, xa, *_ = law.step_scalar(0.0, law.R - delta, law.jump_radius, 0, 0, 0, k)
    x, slid = 0.0, 0.0
    while slid == 0.0:  # drag until the contact slides
        x += 1e-3
        _, _, _, a, xi, u, xa, _, _, slid = law.step_scalar(x, law.R - delta, a, xi, u, xa, k)
    x += move
    trial = abs(x - xa)
    P, T, _, a, xi, _, _, _, de, slid = law.step_scalar(x, law.R - delta + lift, a, xi, u, xa, k)
    assert slid == 1.0 and a > 0.0
    assert abs(xi) <= trial
    assert -T == pytest.approx(0.2 * abs(P + 2 * law_fc()), rel=1e-6)
    assert -T == pytest.approx(8 * G * a * xi, rel=1e-12)
    delta_new = float(sj.overlap_from_radius(a, xi, R, W, E, G))
    assert delta_new == pytest.approx(delta - lift, abs=1e-12)
    assert de > 0.0


def test_a_tensile_contact_slides_freely_under_the_papers_friction_law():
    """The paper's cap μ·max(P, 0) is 0 under tension: a tip pulled to δ = 0.99δc (the end of
    its branch near, its JKR radius ≈ 1.0 µm) and sheared slides back to ξ = 0 and keeps the
    JKR contact at that δ (eq 10: radius, eq 8: force), carrying no shear."""
    law = contact_law(SHEARED.replace(**{"friction.law": "paper"}))
    k = law.constants
    delta = 0.99 * law.detach_overlap
    a_jkr = float(jkr.radius_from_overlap(delta, R, W, E))
    for shear in (0.01, 0.1):
        P, T, _, a, xi, *_, slid = law.step_scalar(shear, law.R - delta, a_jkr, 0.0, 0.0, 0.0, k)
        assert slid == 1.0 and T == 0.0 and abs(xi) < 1e-15
        assert a == pytest.approx(a_jkr, rel=1e-9)
        assert P == pytest.approx(float(jkr.force_from_radius(a_jkr, R, W, E)), rel=1e-9)


def test_a_tip_past_the_end_of_its_branch_lets_go_with_no_force():
    """Pulled past JKR's snap-off overlap δc, no contact exists at any shear: the tip lets go,
    carrying no force and moving no attachment point (a = 0); it hands back what its contact
    stored when its force last acted, for the kernels to dissipate."""
    law = contact_law(SHEARED)
    k = law.constants
    z = law.R - 1.1 * law.detach_overlap
    P, T, shift, a, xi, u, xa, U, de, slid = law.step_scalar(0.05, z, 0.9, 0.04, 0.3, 0.01, k)
    assert (P, T, shift, a, xi) == (0.0, 0.0, 0.0, 0.0, 0.0)
    assert (u, xa, U, de, slid) == (0.3, 0.01, 0.3, 0.0, 0.0)


def test_a_tip_attaches_with_jkrs_radius_at_zero_overlap():
    """The radius the kernels give a tip on attachment (δ = 0, no shear) is on JKR's branch
    there: a²/R = √(2πwa/E*), a = (2πwR²/E*)^(1/3) (eq 10 at δ = 0, the closed form of
    :func:`jkr.radius_from_overlap`), the radius the law's own step finds at (δ, ξ) = 0."""
    law = contact_law(SHEARED)
    a_jkr = float(jkr.radius_from_overlap(0.0, R, W, E))
    assert law.jump_radius == pytest.approx(a_jkr, rel=1e-12)
    assert law.jump_radius == pytest.approx((2 * math.pi * W * R * R / E) ** (1 / 3), rel=1e-12)
    assert law.step_scalar(0.0, law.R, 1.0, 0.0, 0.0, 0.0, law.constants)[3] == pytest.approx(
        law.jump_radius, rel=1e-12
    )
