"""The linearly implicit step's pieces (:mod:`gecko_agents.model.implicit` and its compiled pad
kernels, :mod:`gecko_agents.model.implicit_kernel`) against oracles that do not share its code:
each Jacobian against central finite differences of the force it linearises, the 2×2 solve
against the residual of the step it solves (the force at the step's end, Hairer & Wanner 1996,
§IV.7), a free linear seta's steps against the scheme's own recurrence solved by
``numpy.linalg.solve``, and the energy books of a free linear seta, which close to rounding
(semi-implicit Euler books a linear spring exactly; the step books the work of F' − F).

One to three setae and a few dozen steps each: the fast tier's guard of the implicit step.
Units: µm, µN, µs, ng, pJ.
"""

import extras
import numpy as np
import pytest

from gecko_agents.model import Damping, Model, Numerics
from gecko_agents.model.implicit_kernel import pad_kernels, pad_solve, step_books
from gecko_agents.params import PAPER_TABLE1
from gecko_agents.physics import beam, jkr

THREE = PAPER_TABLE1.replace(**{"array.count": 3})


def _model(params=THREE, n=3, kernel="numpy", **kw):
    return Model(params, n_sim=n, numerics=Numerics(integrator="implicit", kernel=kernel), **kw)


def _fd_stiffness(force, d, h=1e-6):
    """−∂F/∂d (2×2) by central differences of ``force`` (d (2,) [µm] → F (2,) [µN])."""
    K = np.empty((2, 2))
    for j in range(2):
        e = np.zeros(2)
        e[j] = h
        K[:, j] = -(force(d + e) - force(d - e)) / (2 * h)
    return K


def test_linear_seta_stiffness_is_minus_the_spring_force_gradient():
    """The linear seta's K (eq 20–21) is −∂F/∂u of its spring force F = −K·u, every entry
    (the beam's K is not diagonal at θ = 30°: measured agreement 1e-10)."""
    m = _model(THREE.replace(mechanics="linear"))
    kxx, kxy, kyx, kyy = m._implicit.seta_stiffness(0.3, -0.2)
    K = np.array([[kxx, kxy], [kyx, kyy]])
    u = np.array([0.4, -0.7])
    fd = _fd_stiffness(lambda x: beam.linear_spring_force(x[None], m.K)[0][0], u)
    assert abs(K[0, 1]) > 0.1 * abs(K[0, 0])
    np.testing.assert_allclose(K, fd, rtol=1e-8, atol=1e-9)


def _rod_case(theta_deg):
    """A rod model of three setae at rest angle ``theta_deg`` [°], with their tips placed on
    their rest axes (Δφ = 0) at lengths 0.9 L, 1.05 L and 1.3 L from roots at (rx, ry)."""
    m = _model(THREE.replace(**{"mechanics": "rod", "seta.theta_deg": theta_deg}))
    rx, ry = 0.7, 31.0
    m.world.root_dy = np.array(
        [0.5, -1.0, 2.0]
    )  # roots off the plate's line (the rows of a 2-D array)
    ell = m.L * np.array([0.9, 1.05, 1.3])
    d = ell[None, :] * m.axis[:, None]  # (2, 3) root-to-tip
    m.state.xy[0] = rx + m.world.root_dx + d[0]
    m.state.xy[1] = ry + m.world.root_dy + d[1]
    return m, rx, ry, d, ell


def _rod_oracle(m, di, ell_i):
    """The rod seta's K on its rest axis from finite differences: in tension −∂F/∂d of the
    whole rod force; in compression the rotary spring's −∂F/∂d alone plus Ka·e eᵀ (the
    axial spring's negative stiffness across the rod, Ka(ℓ − L)/ℓ < 0, is clamped to 0)."""

    def force(ka, kphi):
        return lambda x: beam.rod_spring_force(x[None], m.L, ka, kphi, m.theta)[0][0]

    if ell_i >= m.L:
        return _fd_stiffness(force(m.Ka, m.k_phi), di)
    e = di / ell_i
    return _fd_stiffness(force(0.0, m.k_phi), di) + m.Ka * np.outer(e, e)


@pytest.mark.parametrize("theta_deg", [30.0, 63.0])
def test_rod_stiffness_on_its_rest_axis_is_minus_the_force_gradient(theta_deg):
    """On its rest axis (no rotation) the rod's K is −∂F/∂x of its force (Ka along the rod,
    kφ/ℓ² + Ka(ℓ − L)/ℓ across it), the tension clamped ≥ 0 in compression (module
    docstring); the numpy K and the compiled pad solve's K alike (the latter seen through its
    solve). Measured agreement 3e-9 relative (the differences' error)."""
    m, rx, ry, d, ell = _rod_case(theta_deg)
    step = m._implicit
    K = np.array(step.seta_stiffness(rx, ry))  # (4, 3)
    for i in range(3):
        oracle = _rod_oracle(m, d[:, i], ell[i])
        np.testing.assert_allclose(K[:, i].reshape(2, 2), oracle, rtol=1e-7, atol=1e-8)
    # The compiled solve with the rod's own K: the same F' as the numpy solve with the oracle's.
    rng = np.random.default_rng(2)
    s = m.state
    s.pv[2:] = rng.normal(0.0, 0.3, (2, 3))
    F = rng.normal(0.0, 1.0, (2, 3))
    zero = np.zeros(3)
    roots = (rx, ry, 0.02, -0.05)
    out = pad_solve(
        True, m.K, m.L, m.Ka, m.k_phi, s.xy, m.world.root_dx, m.world.root_dy, s.pv, F,
        zero, zero, zero, zero, False, zero, m.c_seta, m.dt, m.mass, *roots,
    )  # fmt: skip
    for i in range(3):
        Ko = _rod_oracle(m, d[:, i], ell[i])
        expect = _implicit_force(Ko, np.zeros((2, 2)), m.c_seta, s.pv[2:, i], roots[2:], F[:, i],
                                 m.dt, m.mass)  # fmt: skip
        np.testing.assert_allclose(out[:, i], expect, rtol=1e-7, atol=1e-9)


def _implicit_force(Ks, Kc, c, v0, vr, F, dt, mass, Cc=None):
    """F' of the linearly implicit step by numpy.linalg.solve: the force at the step's end,
    F' = F − dt·[Ks·(v₁ − v_root) + Kc·v₁] − (c·I + Cc)·(v₁ − v₀), v₁ = v₀ + F'·dt/m, for the
    seta's stiffness ``Ks``, the contact's ``Kc`` and dampers ``Cc`` (2×2), one tip."""
    Cc = np.zeros((2, 2)) if Cc is None else Cc
    C = c * np.eye(2) + Cc
    v0, vr = np.asarray(v0, float), np.asarray(vr, float)
    # F' = A⁻¹·b with v₁ = v₀ + F'·dt/m substituted.
    A = np.eye(2) + (dt / mass) * C + (dt * dt / mass) * (Ks + Kc)
    b = F - dt * (Ks @ (v0 - vr) + Kc @ v0)
    return np.linalg.solve(A, b)


def _contact_matrices(kn, kt, cn, ct, normal=None, kxy=0.0):
    """The contact's 2×2 stiffness and damper: kn·n nᵀ + kt·t tᵀ (+ the film's kxy off the
    diagonal), n the normal ((0, 1) on a pad), t = (n_y, −n_x)."""
    n = np.array([0.0, 1.0]) if normal is None else np.asarray(normal)
    t = np.array([n[1], -n[0]])
    Kc = kn * np.outer(n, n) + kt * np.outer(t, t) + kxy * np.array([[0.0, 1.0], [1.0, 0.0]])
    return Kc, cn * np.outer(n, n) + ct * np.outer(t, t)


@pytest.mark.parametrize("floor", ["pad", "continuous", "film"])
def test_the_two_by_two_solve_is_the_force_at_the_step_end(floor):
    """Random seta stiffnesses (not symmetric), contact stiffnesses and dampers, velocities and
    roots: ImplicitStep._solve and the compiled pad_solve (on a pad) give the F' that
    numpy.linalg.solve gives for the step's linear system (agreement 1e-15 measured)."""
    m = _model()
    step = m._implicit
    rng = np.random.default_rng({"pad": 1, "continuous": 2, "film": 3}[floor])
    s = m.state
    for _ in range(5):
        s.pv[2:] = rng.normal(0.0, 0.5, (2, 3))
        F = rng.normal(0.0, 1.0, (2, 3))
        K = tuple(rng.uniform(0.1, 3.0, 4) * [1.0, 0.3, -0.4, 1.0])
        kn, kt = rng.uniform(0.0, 10.0, 3), rng.uniform(0.0, 5.0, 3)
        cn, ct = rng.uniform(0.0, 2.0, 3), rng.uniform(0.0, 2.0, 3)
        roots = (0.0, 0.0, 0.03, -0.07)
        normal = None
        step.film = floor == "film"
        step._kxy[:] = rng.normal(0.0, 2.0, 3) if step.film else 0.0
        if floor == "continuous":
            ang = rng.uniform(-1.0, 1.0, 3)
            normal = np.array([np.sin(ang), np.cos(ang)])
        step.normal = normal
        fx, fy = step._solve(K, kn, kt, cn, ct, roots, F)
        Ks = np.array(K).reshape(2, 2)
        for i in range(3):
            Kc, Cc = _contact_matrices(
                kn[i], kt[i], cn[i], ct[i], None if normal is None else normal[:, i],
                step._kxy[i],
            )  # fmt: skip
            expect = _implicit_force(Ks, Kc, m.c_seta, s.pv[2:, i], roots[2:], F[:, i], m.dt,
                                     m.mass, Cc)  # fmt: skip
            np.testing.assert_allclose([fx[i], fy[i]], expect, rtol=1e-12, atol=1e-14)
        if normal is None:
            out = pad_solve(
                False, Ks, m.L, m.Ka, m.k_phi, s.xy, m.world.root_dx, m.world.root_dy, s.pv,
                F, kn, kt, cn, ct, step.film, step._kxy, m.c_seta, m.dt, m.mass, *roots,
            )  # fmt: skip
            np.testing.assert_allclose(out, [fx, fy], rtol=1e-12, atol=1e-14)


def _jkr_slope(law, a, h=1e-6):
    """dP/dδ along the JKR branch at contact radius ``a`` [µm] by central differences in a
    (eq 7 and 10 of Johnson, Kendall & Roberts 1971, Proc. R. Soc. A 324:301)."""
    P = [jkr.force_from_radius(x, law.R, law.w, law.E_star) for x in (a + h, a - h)]
    d = [jkr.overlap_from_radius(x, law.R, law.w, law.E_star) for x in (a + h, a - h)]
    return (P[0] - P[1]) / (d[0] - d[1])


def test_contact_stiffness_is_the_branch_slope_and_the_stick_spring():
    """A free tip, a sticking one and a sliding one on the JKR branch: the normal stiffness is
    dP/dδ of the branch (finite differences, 1e-8), 0 where free; the stick spring k_t and
    its damper c_t only where the tip sticks; the normal damper c_n where attached. Past the
    load-controlled pull-off (dP/dδ < 0) the normal stiffness is 0, at 30 Fc it is clamped
    to the law's stiffest tangent at 5 Fc; the rate of dP/dδ over a step is their difference
    over dt."""
    m = _model()
    step, s, law = m._implicit, m.state, m.law
    a = np.array([0.0, 1.1 * law.a0, 0.8 * law.a0])
    s.attached[:] = [False, True, True]
    s.slip[:] = [False, False, True]
    s.a[:] = a
    s.delta[:] = [np.nan, *jkr.overlap_from_radius(a[1:], law.R, law.w, law.E_star)]
    kn, kt, cn, ct = (x.copy() for x in step.contact_stiffness())
    assert kn[0] == 0.0 and kt[0] == 0.0 and cn[0] == 0.0 and ct[0] == 0.0
    for i in (1, 2):
        assert kn[i] == pytest.approx(_jkr_slope(law, a[i]), rel=1e-7)
        assert cn[i] == m.c_n
    assert kt[1] == m.k_t and ct[1] == m.c_t and m.k_t > 0.0 and m.c_t > 0.0
    assert kt[2] == 0.0 and ct[2] == 0.0
    k_first = step._k_raw.copy()
    assert np.isnan(k_first[0]) and k_first[1] == kn[1]
    # Below the pull-off radius the branch's slope is negative; far above it, past the cap.
    a_pull = jkr.contact_radius_from_force(-law.pull_off_force, law.R, law.w, law.E_star)
    a_hard = jkr.contact_radius_from_force(30 * law.pull_off_force, law.R, law.w, law.E_star)
    a2 = np.array([0.0, 0.9 * a_pull, a_hard])
    s.a[:] = a2
    s.delta[1:] = jkr.overlap_from_radius(a2[1:], law.R, law.w, law.E_star)
    kn, kt, cn, ct = step.contact_stiffness()
    slope = _jkr_slope(law, a2[1])
    assert slope < 0.0 and kn[1] == 0.0 and step._k_raw[1] == pytest.approx(slope, rel=1e-7)
    # The cap: the law's stiffest tangent at 5 Fc, 2E*·a there (the Hertz limit, 12.5 µN/µm;
    # the JKR branch's own slope there is 10.1).
    a5 = jkr.contact_radius_from_force(5 * law.pull_off_force, law.R, law.w, law.E_star)
    assert step.k_cap == pytest.approx(2 * law.E_star * a5, rel=1e-12)
    assert _jkr_slope(law, a2[2]) > 1.1 * step.k_cap
    assert kn[2] == step.k_cap
    rate = (step._k_raw - k_first) / m.dt
    np.testing.assert_allclose(step._k_rate[1:], rate[1:], rtol=1e-12)
    assert np.isnan(step._k_rate[0])


def _free_linear(kernel, zeta, v0=(0.3, -0.2)):
    """A free linear seta (plate held still) whose tip starts at rest position with velocity
    ``v0`` [µm/µs], seta damping ratio ``zeta``."""
    m = _model(PAPER_TABLE1.replace(mechanics="linear"), n=1, kernel=kernel,
               damping=Damping(seta=zeta))  # fmt: skip
    m.world.tips[0].velocity = v0
    return m


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
def test_a_free_linear_seta_steps_as_the_linearly_implicit_recurrence(kernel):
    """Eight steps of a free, damped linear seta: the tip's positions and velocities are the
    scheme's recurrence x₁ = x₀ + v₀·dt (pymunk's), (m + c·dt + K·dt²)·v₁ = m·v₀ − dt·K·(x₁ −
    rest) (the force at x₁ + v₁·dt, the step's end: backward Euler for the velocity), solved
    by numpy (agreement 1e-15 µm measured). At ω·dt = 15 it decays (backward Euler damps what rings
    faster than 1/dt) where the explicit step would diverge."""
    if kernel == "numba" and pad_kernels() is None:
        pytest.skip(extras.reason("fast"))
    m = _free_linear(kernel, 1.0)
    dt, mass, c, K = m.dt, m.mass, m.c_seta, m.K
    assert m.omega_max * dt > 2.0  # past the explicit step's stability bound
    x = np.array(m.world.tips[0].position)
    v = np.array(m.world.tips[0].velocity)
    rest = x.copy()
    A = (mass + c * dt) * np.eye(2) + dt * dt * K
    speeds = []
    for _ in range(8):
        m.advance(0.0, 0.0)
        x = x + v * dt
        v = np.linalg.solve(A, mass * v - dt * K @ (x - rest))
        np.testing.assert_allclose(m.world.tips[0].position, x, rtol=0, atol=1e-12)
        np.testing.assert_allclose(m.world.tips[0].velocity, v, rtol=0, atol=1e-12)
        speeds.append(np.hypot(*v))
    assert speeds[-1] < 0.1 * speeds[0]


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
@pytest.mark.parametrize("switch", [False, True])
def test_a_free_linear_springs_books_close_to_rounding(kernel, switch):
    """An undamped free linear seta ringing at ω·dt = 15 (a step the explicit scheme cannot
    take): kinetic (½m·v₀·v₁) + elastic + dissipated energy stays what it was to 1e-12 (1e-15
    measured; 1e-14 with the step switched between dt and dt/3 every step, the switch term
    booked), while the scheme's own dissipation, booked as the work of F' − F, takes most of
    the energy (it damps what rings faster than 1/dt)."""
    if kernel == "numba" and pad_kernels() is None:
        pytest.skip(extras.reason("fast"))
    m = _free_linear(kernel, 0.0)
    step, dt = m._implicit, m.dt
    total, dissipated = [], 0.0
    for k in range(24):
        if switch:
            step.set_dt(dt / 3 if k % 2 else dt)
        m.advance(0.0, 0.0)
        dissipated += m.physics.diss
        total.append(m.kinetic_energy() + float(m.spring_energies().sum()) + dissipated)
    e0 = 0.5 * m.mass * (0.3**2 + 0.2**2)  # the tip's kinetic energy at the start
    np.testing.assert_allclose(total, e0, rtol=1e-12)
    assert step.numerical_dissipated == pytest.approx(dissipated, rel=1e-12)
    assert dissipated > 0.9 * e0


def test_the_loops_rebooked_dampers_give_the_numpy_books():
    """A damped free linear seta: the per-seta loop (which books its dampers at the explicit
    mid-step velocity and rebooks them on F' − F) books the same dissipation, step by step,
    as the numpy step (1e-16 pJ measured)."""
    if pad_kernels() is None:
        pytest.skip(extras.reason("fast"))
    books = []
    for kernel in ("numpy", "python"):
        m = _free_linear(kernel, 1.0)
        d = []
        for _ in range(10):
            m.advance(0.0, 0.0)
            d.append(m.physics.diss)
        books.append(d)
    assert abs(books[0][0]) > 1e-4
    np.testing.assert_allclose(books[1], books[0], rtol=1e-9, atol=1e-15)


def test_step_books_pair_each_velocity_with_the_corrections_of_two_steps():
    """step_books on two tips by hand: e = v₀·(ΔF_prev + ΔF), ed = F_damp·ΔF; afterwards
    ΔF := F' − F, F := F', J := (F' − seta damping − contact damping)·dt."""
    vx, vy = np.array([1.0, -2.0]), np.array([0.5, 3.0])
    fx, fy = np.array([2.0, 1.0]), np.array([-1.0, 4.0])
    F = np.array([[1.0, 1.5], [0.0, 2.0]])
    dF = np.array([[0.25, -0.5], [1.0, 0.0]])
    fd = np.array([[0.1, 0.2], [0.3, 0.4]])
    fc = np.array([[0.0, -0.2], [0.5, 1.0]])
    J = np.zeros((2, 2))
    e, ed = step_books(vx, vy, fx, fy, F, dF, fd, fc, J, 0.5, True)
    # tip 0: ΔF = (1, −1), ΔF_prev = (0.25, 1): 1·1.25 + 0.5·0; tip 1: ΔF = (−0.5, 2),
    # ΔF_prev = (−0.5, 0): −2·(−1) + 3·2
    np.testing.assert_allclose(e, [1.25, 8.0])
    np.testing.assert_allclose(ed, [0.1 * 1 + 0.8 * -1, 0.0 * -0.5 + 1.4 * 2])
    np.testing.assert_allclose(dF, [[1.0, -0.5], [-1.0, 2.0]])
    np.testing.assert_allclose(F, [[2.0, 1.0], [-1.0, 4.0]])
    np.testing.assert_allclose(J, [[0.95, 0.5], [-0.9, 1.3]])
    assert step_books(vx, vy, fx, fy, F, dF, fd, fc, J, 0.5, False)[1] is None


@pytest.mark.parametrize("continuous", [False, True])
def test_a_release_books_the_work_of_its_last_force_over_the_step(continuous):
    """Two tips let go in one step: each books −½·P·(n·v₀)·dt, half the work its last
    normal force P [µN] would have done over the step's normal displacement (by hand)."""
    m = _model()
    step, s = m._implicit, m.state
    s.pv[2:] = [[0.3, 0.0, -1.0], [0.4, 2.0, 0.0]]
    if continuous:
        step.normal = np.array([[0.6, 0.0, 1.0], [0.8, 1.0, 0.0]])  # n·v = 0.5, 2, −1
        vn = {0: 0.5, 2: -1.0}
    else:
        vn = {0: 0.4, 2: 0.0}
    out = step.book_releases([(0, 0.1, 2.0), (2, -0.2, -3.0)])
    assert out == pytest.approx(-0.5 * m.dt * (2.0 * vn[0] - 3.0 * vn[2]), rel=1e-15)
    assert step.book_releases([]) == 0.0


def test_the_energy_scale_is_the_largest_magnitude_seen():
    """note_energies raises the run's energy scale to the largest |plate work|, |elastic| or
    |dissipated| of any row so far, never lowers it, and reads no other column."""
    m = _model()
    step = m._implicit
    row = {"work_plate_pJ": 1.0, "energy_elastic_pJ": -3.0, "energy_dissipated_pJ": 2.0}
    step.note_energies(row | {"energy_kinetic_pJ": 50.0})
    assert step.energy_scale == 3.0
    step.note_energies({"work_plate_pJ": -0.5, "energy_elastic_pJ": 0.1,
                        "energy_dissipated_pJ": 4.0})  # fmt: skip
    assert step.energy_scale == 4.0
    step.note_energies(dict.fromkeys(row, 0.0))
    assert step.energy_scale == 4.0


def test_a_tangent_read_from_the_overlap_or_not_finite_is_taken_as_the_law_gives_it(
    monkeypatch,
):
    """The normal stiffness is the law's dP/dδ at the tips' radius and overlap: for a law
    whose tangent reads δ (Hertz's 2E*·√(Rδ), Johnson 1985 eq 4.23 differentiated) it is that
    tangent at each tip's δ; where the law's tangent is not finite (the end of a branch) the
    tip takes no normal stiffness and event location reads it as −∞ (past its pull-off)."""
    m = _model()
    step, s, law = m._implicit, m.state, m.law
    R, E = law.R, law.E_star
    monkeypatch.setattr(
        law,
        "stiffness",
        lambda a, d: np.where(d > 0.05, 2 * E * np.sqrt(R * np.maximum(d, 0.0)), np.inf),
    )
    s.attached[:] = True
    s.slip[:] = False
    s.a[:] = 1.0  # the same radius: only δ tells the tips apart
    s.delta[:] = [0.1, 0.2, 0.0]
    kn = step.contact_stiffness()[0]
    np.testing.assert_allclose(kn[:2], 2 * E * np.sqrt(R * np.array([0.1, 0.2])), rtol=1e-12)
    assert kn[2] == 0.0 and step._k_raw[2] == -np.inf


def test_a_film_tips_contact_stiffness_is_the_derivative_of_its_force():
    """A spatula's film (the front held): the stick, normal and off-diagonal stiffnesses are
    −∂(T, P)/∂(x, y) of the law's own force by central differences (1e-6 relative, as
    tests/test_integrator.py's check of the law's Jacobian), lifted and pressed; the
    tangential damper acts on every attached tip of a law that damps sliding, none on a
    free one."""
    from test_integrator import BONDED_SPATULA, _film_force_on_tip

    p = BONDED_SPATULA.replace(**{"friction.mu": 10.0, "array.count": 3})
    m = _model(p)
    step, s, law = m._implicit, m.state, m.law
    assert step.film and law.tangential and law.damp_sliding
    cases = [(-0.5, -0.3, 0.57, 0.0), (0.4, -0.2, 0.44, 0.0), (-1.2, 0.1, 1.0, -1.21)]
    s.attached[:] = True
    for i, (dx, delta, s0, xa) in enumerate(cases):
        s.anchor[0, i] = 3.0 * i - 1.0
        s.anchor[1, i] = 0.5 * i  # the front's height is not read: the floor is a pad
        s.xy[0, i] = s.anchor[0, i] + dx
        s.xy[1, i] = 40.0 - i  # the tip's height is read through δ alone
        s.delta[i], s.s0[i], s.xi[i] = delta, s0, xa
    s.a[:] = law.ell0  # the whole pad bonded
    s.p0[:] = 0.0
    s.attached[2] = True
    kn, kt, cn, ct = (x.copy() for x in step.contact_stiffness())
    k, e = law.constants, 1e-6
    for i, (dx, delta, s0, xa) in enumerate(cases):
        jx = (_film_force_on_tip(law, k, dx + e, delta, s0, xa)
              - _film_force_on_tip(law, k, dx - e, delta, s0, xa)) / (2 * e)  # fmt: skip
        jy = (_film_force_on_tip(law, k, dx, delta - e, s0, xa)
              - _film_force_on_tip(law, k, dx, delta + e, s0, xa)) / (2 * e)  # fmt: skip
        np.testing.assert_allclose(
            [[kt[i], step._kxy[i]], [step._kxy[i], kn[i]]],
            -np.column_stack([jx, jy]),
            rtol=1e-6,
            atol=1e-7,
        )
    assert np.all(ct == m.c_t) and np.all(cn == m.c_n)
    assert abs(step._kxy[0]) > 0.1 and kt[2] > 0.0 and kn[2] > 0.0
    s.attached[1] = False
    kn, kt, cn, ct = step.contact_stiffness()
    assert kn[1] == kt[1] == ct[1] == cn[1] == step._kxy[1] == 0.0 and ct[0] == m.c_t


@pytest.mark.parametrize("mechanics", ["rod", "linear"])
def test_the_compiled_pad_step_gives_the_numpy_steps(mechanics):
    """Three free setae under a plate moving up and sideways, twelve steps: the compiled pad
    solve and books (kernel "numba") and the numpy reference (kernel "numpy") give the same
    tip positions (bit for bit compiled; 1e-12 µm allowed for the interpreted loop) and the
    same books."""
    if pad_kernels() is None:
        pytest.skip(extras.reason("fast"))
    runs = []
    for kernel in ("numpy", "numba"):
        m = _model(THREE.replace(mechanics=mechanics), kernel=kernel)
        for i, tip in enumerate(m.world.tips):
            tip.velocity = (0.2 * (i - 1), -0.1 * i)
        xs, diss = [], []
        for k in range(12):
            m.advance(0.02 if k < 6 else -0.01, 0.03)
            xs.append([tuple(t.position) for t in m.world.tips])
            diss.append(m.physics.diss)
        runs.append((np.array(xs), np.array(diss), m._implicit._pad is not None))
    assert not runs[0][2] and runs[1][2]
    np.testing.assert_allclose(runs[1][0], runs[0][0], rtol=0, atol=1e-12)
    np.testing.assert_allclose(runs[1][1], runs[0][1], rtol=1e-9, atol=1e-15)


@pytest.mark.parametrize("interface", ["bonded", "sliding"])
def test_a_film_tip_whose_pad_slides_drops_its_row_along_the_floor(interface):
    """Adhesive friction, μ = 0.5, a film at 22° from the floor (tests/test_integrator.py's
    case): bonded, a pull of 1.05 times the pad's cap μ·2w·b slides the pad, and the tip's
    contact stiffness along the floor is 0 (the front follows it: ∂T/∂x = 0), its normal one
    unchanged; a sliding pad's locked pre-tension P0 = 1.2·cap above a pull of 1.1·cap holds
    it, its stiffness along the floor the film's (> 0)."""
    from test_integrator import SPATULA, _dx_for_pull

    p = SPATULA.replace(**{"friction.mu": 0.5, "spatula.interface": interface, "array.count": 3})
    m = _model(p)
    step, s, law = m._implicit, m.state, m.law
    zf, s0 = 0.2, 0.5
    cap = 0.5 * 2.0 * law.w * law.b
    share, p0 = (1.05, 0.0) if interface == "bonded" else (1.1, 1.2 * cap)
    dx = _dx_for_pull(law, zf, s0, share * cap)
    s.attached[:] = [True, True, False]
    s.anchor[0] = 0.0
    s.xy[0] = dx
    s.delta[:2], s.s0[:2], s.xi[:2] = -zf, s0, dx
    s.a[:2] = [law.ell0, law.ell0]
    s.p0[:2] = p0
    kn, kt = step.contact_stiffness()[:2]
    held = law.jacobian([dx], [-zf], [s0], [dx])  # the front held
    assert kn[0] == kn[1] == float(held[2][0]) > 0.0
    if interface == "bonded":
        assert kt[0] == kt[1] == step._kxy[0] == 0.0
    else:
        assert kt[0] == float(held[0][0]) > 0.0 and step._kxy[0] == float(held[1][0]) != 0.0


def test_a_soft_contacts_stick_spring_keeps_its_damper():
    """A contact 50 times softer (E₁/50): its stick spring (Mindlin's 8G*·a₀) is below
    1 µN/µm, and a sticking tip still takes it and its tangential damper; a free one neither."""
    m = _model(THREE.replace(**{"contact.E1": THREE.contact.E1 / 50}))
    s = m.state
    assert 0.0 < m.k_t < 1.0
    s.attached[:] = [True, False, True]
    s.slip[:] = False
    s.a[:] = m.law.a0
    s.delta[:] = 0.0
    kn, kt, cn, ct = m._implicit.contact_stiffness()
    assert list(kt) == [m.k_t, 0.0, m.k_t] and list(ct) == [m.c_t, 0.0, m.c_t]


def test_as_dt_falls_the_implicit_step_converges_at_first_order_to_the_exact_motion():
    """A free, critically damped linear seta flicked at (0.3, −0.2) µm/µs, its tip after 4 µs:
    the exact motion m·ẍ = −K·u − c·u̇ (matrix exponential of the state-space form) against
    the implicit step at dt = 0.05 and 0.025 µs (ω·dt ≤ 0.4): the error halves with dt (ratio
    1.91 measured: first order, backward Euler's) and the explicit step at the same dt stays
    within it (its error 0.3e-3 against 25e-3 µm at 0.05 µs), so the two steps meet as dt → 0."""
    from scipy.linalg import expm

    errors, gaps = [], []
    for dt in (0.05, 0.025):
        tips = []
        for integrator in ("implicit", "explicit"):
            m = Model(
                PAPER_TABLE1.replace(mechanics="linear"),
                n_sim=1,
                numerics=Numerics(integrator=integrator, kernel="numpy", dt=dt),
            )
            x0 = np.array(m.world.tips[0].position)
            m.world.tips[0].velocity = (0.3, -0.2)
            for _ in range(round(4.0 / dt)):
                m.advance(0.0, 0.0)
            tips.append(np.array(m.world.tips[0].position) - x0)
        A = np.zeros((4, 4))
        A[:2, 2:] = np.eye(2)
        A[2:, :2] = -m.K / m.mass
        A[2:, 2:] = -(m.c_seta / m.mass) * np.eye(2)
        exact = (expm(4.0 * A) @ [0.0, 0.0, 0.3, -0.2])[:2]
        errors.append(np.linalg.norm(tips[0] - exact))
        gaps.append(np.linalg.norm(tips[0] - tips[1]))
        assert np.linalg.norm(tips[1] - exact) < 0.05 * errors[-1]
    assert 1.8 < errors[0] / errors[1] < 2.1
    assert 1.8 < gaps[0] / gaps[1] < 2.1 and errors[1] < 0.015
