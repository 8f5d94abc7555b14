"""The per-step shortcuts of a few-seta run give the histories of the code they shortcut, bit
for bit: the compiled pad solve, friction test and books
(:mod:`gecko_agents.model.implicit_kernel`) against the numpy references
(``ImplicitStep._solve``, ``_stick_past_cap``, ``step_books``), the recorder's energies
without forces against the force functions', and the contact energy's constants cached per law
without leaking from one model into another. Every comparison is exact but the one closed-form
check that says what rounding it allows."""

import warnings

import extras
import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.model import Model, Numerics, implicit, numba_available
from gecko_agents.model.implicit_kernel import pad_kernels, pad_solver, step_books
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import beam, jkr

needs_numba = pytest.mark.skipif(not numba_available(), reason=extras.reason("fast"))

# 16 stubby setae on a rough pad floor (pads at different heights), dragged and pulled.
FEW = PAPER_ARRAY.replace(**{"array.count": 16, "seta.L": 5.0, "floor.sigma": 0.3})
DRAG = protocol.drag_pull(2.0, 3.0, 60.0, speed=0.05)


def _model(params, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return Model.from_options(
            params,
            seed=3,
            record_setae=True,
            **kw,
            numerics=Numerics(kernel="numba", record_every=1),
        )


def _run(params, compiled: bool, monkeypatch):
    """The run's history and whether the compiled pad kernels ran."""
    with monkeypatch.context() as mp:
        if not compiled:
            mp.setattr(implicit, "pad_solver", lambda m, step: None)
        m = _model(params)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            h = m.run(DRAG, progress=False)
    return h, m._implicit._pad is not None


def _assert_same(h1, h2):
    assert h1.columns == h2.columns
    for c in h1.columns:
        assert np.array_equal(h1[c], h2[c]), c
    for f in h1.setae:
        assert np.array_equal(h1.setae[f], h2.setae[f], equal_nan=f != "state"), f
    for k in h1.detachments:
        assert np.array_equal(h1.detachments[k], h2.detachments[k], equal_nan=True), k
    assert h1.meta["implicit_dissipated_pJ"] == h2.meta["implicit_dissipated_pJ"]


@pytest.mark.slow
@needs_numba
@pytest.mark.parametrize(
    "mechanics, mu, tip",
    [("rod", 0.2, "sphere"), ("rod", 10.0, "sphere"), ("linear", 0.2, "sphere"),
     ("linear", 10.0, "sphere"), ("rod", 10.0, "spatula")],
)  # fmt: skip
def test_compiled_pad_kernels_give_the_numpy_history(mechanics, mu, tip, monkeypatch):
    """16 setae pressed, dragged (sticking, then sliding at μ = 0.2) and pulled: every column,
    per-seta array and detachment of the run with the compiled solve, friction test and books
    equals the numpy reference's, bit for bit (the spatula's film too)."""
    params = FEW.replace(**{"mechanics": mechanics, "friction.mu": mu, "tip": tip})
    h_fast, used = _run(params, True, monkeypatch)
    h_ref, used_ref = _run(params, False, monkeypatch)
    assert used and not used_ref
    assert h_fast.detachments["seta"].size  # the run reached its releases
    _assert_same(h_fast, h_ref)


@needs_numba
@pytest.mark.parametrize("mechanics, tip", [("rod", "sphere"), ("linear", "sphere"),
                                            ("rod", "spatula")])  # fmt: skip
def test_compiled_solve_and_cap_test_match_numpy_on_random_states(mechanics, tip):
    """Random tip states, stiffnesses and dampers (some tips free, sliding or sticking; a
    film's off-diagonal stiffness): the compiled F' equals ImplicitStep._solve's bit for bit,
    and the compiled friction test says "past the cap" exactly where the numpy test slides a
    tip (both answers occur; the spatula keeps its own friction)."""
    m = _model(FEW.replace(**{"mechanics": mechanics, "tip": tip}))
    step = m._implicit
    kernels = pad_solver(m, step)
    assert kernels is not None
    rng = np.random.default_rng(7)
    s, n = m.state, m.n
    c = m._constants
    answers = set()
    for _ in range(200):
        s.pv[:] = rng.normal(0.0, [[1.0], [1.0], [0.05], [0.05]], (4, n))
        s.pv[1] += m.world.plate_start - 10.0
        s.xy[:] = s.pv[:2] + s.pv[2:] * m.dt
        s.F[:] = rng.normal(0.0, 1.0, (2, n))
        s.Ft[:] = rng.normal(0.0, 0.3, n)
        s.P[:] = rng.normal(0.0, 0.5, n)
        kn = rng.uniform(0.0, 10.0, n) * (rng.random(n) < 0.7)
        kt = m.k_t * (rng.random(n) < 0.5)
        cn, ct = np.where(kn > 0, m.c_n, 0.0), np.where(kt > 0, m.c_t, 0.0)
        roots = (float(rng.normal()), float(rng.normal(m.world.plate_start - 5.0)), 0.01, -0.02)
        step._kxy[:] = rng.normal(0.0, 2.0, n) if step.film else 0.0
        K = step.seta_stiffness(roots[0], roots[1])
        ref = step._solve(K, kn, kt, cn, ct, roots, s.F)
        step._pad = kernels
        fast = step._solve(None, kn, kt, cn, ct, roots, s.F)
        assert np.array_equal(fast[0], ref[0]) and np.array_equal(fast[1], ref[1])
        if step.film:
            continue
        past = kernels[1](s.pv, ref[0], ref[1], s.Ft, s.P, kt, ct, m.dt, m.mass, c.Fc, c.mu,
                          c.paper)  # fmt: skip
        step._pad = None
        slip = s.slip.copy()
        capped = step._stick_past_cap(ref[0], ref[1], kt.copy(), ct.copy())
        s.slip[:] = slip
        assert past == (capped is not None)
        answers.add(past)
    assert answers == (set() if step.film else {True, False})


@needs_numba
@pytest.mark.parametrize("rebook", [True, False])
def test_compiled_books_match_numpy_on_random_states(rebook):
    """pad_books returns step_books' terms and leaves ΔF, F and J as step_books does, bit for
    bit, on random forces and velocities of 16 tips."""
    rng = np.random.default_rng(5)
    for _ in range(50):
        vx, vy, fx, fy = rng.normal(0.0, 1.0, (4, 16))
        F, dF, fd, fc = rng.normal(0.0, 1.0, (4, 2, 16))
        arrays = [(F.copy(), dF.copy(), np.zeros((2, 16))) for _ in range(2)]
        out = []
        for books, (F_, dF_, J_) in zip((step_books, pad_kernels()[2]), arrays, strict=True):
            out.append(books(vx, vy, fx, fy, F_, dF_, fd, fc, J_, 0.37, rebook))
        assert np.array_equal(out[0][0], out[1][0])
        if rebook:
            assert np.array_equal(out[0][1], out[1][1])
        for a, b in zip(*arrays, strict=True):
            assert np.array_equal(a, b)


def test_spring_energies_are_the_force_functions_energies():
    """beam.rod_spring_energy and linear_spring_energy equal the energies of rod_spring_force
    and linear_spring_force bit for bit (one arithmetic, no forces)."""
    rng = np.random.default_rng(2)
    d = rng.normal([3.0, -4.0], 1.0, (50, 2))
    L, Ka, k_phi, theta = 5.0, 0.5, 1.3, 0.7
    _, E = beam.rod_spring_force(d, L, Ka, k_phi, theta)
    assert np.array_equal(beam.rod_spring_energy(d[:, 0], d[:, 1], L, Ka, k_phi, theta), E)
    K = beam.stiffness_matrix(Ka, 0.05, theta)
    _, E = beam.linear_spring_force(d, K)
    assert np.array_equal(beam.linear_spring_energy(d[:, 0], d[:, 1], K), E)


def test_contact_energy_constants_per_law_and_for_array_parameters():
    """jkr.contact_energy's constants are cached per (R, w, E*): two laws alternated give each
    its own energies (as computed first), and array parameters (not hashable) still work."""
    a = np.linspace(0.5, 3.0, 7)
    first = jkr.contact_energy(a, 4.0, 0.05, 1000.0)
    other = jkr.contact_energy(a, 3.0, 0.08, 500.0)
    assert not np.array_equal(first, other)
    assert np.array_equal(jkr.contact_energy(a, 4.0, 0.05, 1000.0), first)
    assert np.array_equal(jkr.contact_energy(a, 3.0, 0.08, 500.0), other)
    arr = jkr.contact_energy(a, np.full(7, 4.0), np.full(7, 0.05), np.full(7, 1000.0))
    assert np.array_equal(arr, first)
    # U(a_j) = 0: nothing stored at jump-in; 1e-15 allows ~100 roundings of its terms (~5e-3).
    aj = np.cbrt((np.sqrt(2.0 * np.pi * 0.05 / 1000.0) * 4.0) ** 2)
    assert abs(jkr.contact_energy(aj, 4.0, 0.05, 1000.0)) < 1e-15


@needs_numba
@pytest.mark.parametrize("integrator", ["implicit", "explicit"])
def test_two_models_stepped_interleaved_step_as_each_alone(integrator):
    """Two models of different tips (contact-energy constants, kernels, buffers) stepped in
    turn give, step by step, the forces and energies each gives alone: nothing one model keeps
    between steps leaks into the other."""
    other = FEW.replace(**{"contact.w": 0.08, "mechanics": "linear", "array.count": 3})

    def steps(models, n=400):
        out = [[] for _ in models]
        for k in range(n):
            v = (0.01, -0.05 if k < 250 else 0.05)
            for m, rec in zip(models, out, strict=True):
                reaction, work, spring, _ = m.step(v)
                rec.append((*reaction, work, *spring, *m.contact_energies(),
                            m.kinetic_energy(), *m.state.F.ravel()))  # fmt: skip
        return [np.array(r) for r in out]

    a_alone = steps([_model(FEW, integrator=integrator)])[0]
    b_alone = steps([_model(other, integrator=integrator)])[0]
    a, b = steps([_model(FEW, integrator=integrator), _model(other, integrator=integrator)])
    assert np.array_equal(a, a_alone) and np.array_equal(b, b_alone)
    assert np.count_nonzero(a[:, 3 + FEW.array.count : 3 + 2 * FEW.array.count])  # contacts
