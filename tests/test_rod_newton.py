"""The rod's Newton solve iterates each seta on its own: same equilibria as iterating the
whole batch until every seta has converged (the solver before), in its vectorized form
exactly and compiled by numba to rounding, on batches where setae sit at their fold."""

import math

import extras
import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

from gecko_agents import quasistatic as qs
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.quasistatic import rod as rodmod
from gecko_agents.quasistatic import rod_equilibrium as req

ROD = PAPER_ARRAY.replace(**{"seta.L": 5.0, "mechanics": "rod"})
HAVE_NUMBA = req.newton_loop() is not None


def full_batch_newton(rs, c, x, a, anchor=None, s=None, iters=60, max_jump=math.inf):
    """The iteration before: every seta of the batch is evaluated each iteration until all
    have converged (converged ones take a zero step), for at most ``iters`` iterations."""
    mode = req.SLIDE if anchor is None else (req.STICK_RIGID if math.isinf(rs.k_t) else 1)
    K = req.constants(rs)
    anc = np.zeros_like(x) if anchor is None else anchor
    sd = np.zeros_like(x) if s is None else s
    x_start = x
    x, a = x.copy(), a.copy()
    a_min = rs.a_c * (1.0 + 1e-9)
    conv = np.zeros(x.size, dtype=bool)
    for _ in range(iters):
        r1, r2, j11, j12, j21, j22, P, Fx = req.rod_residual(mode, K, c, x, a, anc, sd)
        scale = 1e-10 * rs.Fc + 1e-12 * (np.abs(P) + np.abs(Fx))
        conv = (np.abs(r1) <= scale) & (np.abs(r2) <= scale)
        if conv.all():
            break
        xn, an = req.newton_step(r1, r2, j11, j12, j21, j22, x, a, rs.L)
        x = np.where(conv, x, xn)
        a = np.maximum(np.where(conv, a, an), a_min)
    ok = req.rod_stable(mode, K, c, x, a, sd)
    ok &= conv & (a > a_min) & np.isfinite(x)
    ok &= np.abs(x - x_start) <= max_jump
    return x, a, ok


def _recorded_batches(params, heights, tangential_stiffness):
    """Every rod_newton call (its arguments) of a press-pull of ``params`` over ``heights``."""
    calls = []
    real = rodmod.rod_newton

    def spy(rs, c, x, a, anchor=None, s=None, max_jump=math.inf):
        calls.append((rs, c.copy(), x.copy(), a.copy(), anchor, s, max_jump))
        return real(rs, c, x, a, anchor=anchor, s=s, max_jump=max_jump)

    rodmod.rod_newton = spy
    try:
        qs.press_pull(
            params, heights, 0.5, n_retract=300, tangential_stiffness=tangential_stiffness
        )
    finally:
        rodmod.rod_newton = real
    return calls


@pytest.fixture(scope="module", params=[math.inf, 2.0], ids=["rigid stick", "stick spring"])
def batches(request):
    p = ROD.replace(**{"array.count": 40, "floor.sigma": 0.3})
    h = 0.3 * np.random.default_rng(3).standard_normal(40)
    return _recorded_batches(p, h, request.param)


def _compare(batches, compiled):
    """(number of batches where a seta never converged while others did, largest |Δx|, |Δa|
    [µm] over the setae with an equilibrium) of rod_newton against the full-batch iteration;
    the ok masks must agree exactly."""
    folds, dx, da = 0, 0.0, 0.0
    for rs, c, x, a, anchor, s, jump in batches:
        xr, ar, okr = full_batch_newton(rs, c, x, a, anchor, s, max_jump=jump)
        xn, an, okn = req.rod_newton(rs, c, x, a, anchor, s, max_jump=jump, compiled=compiled)
        assert_array_equal(okn, okr)
        if okr.any() and not okr.all():
            folds += 1
        if okr.any():
            dx = max(dx, float(np.abs(xn - xr)[okr].max()))
            da = max(da, float(np.abs(an - ar)[okr].max()))
    return folds, dx, da


def test_vectorized_solve_of_each_seta_equals_the_full_batch_iteration(batches):
    folds, dx, da = _compare(batches, compiled=False)
    # The batches include setae at their fold next to converged ones (what masking changes).
    assert folds >= 5
    # Each seta's iterates are computed by the same elementwise operations: exactly equal.
    assert dx == 0.0 and da == 0.0


@pytest.mark.skipif(not HAVE_NUMBA, reason=extras.reason("fast"))
def test_compiled_solve_equals_the_full_batch_iteration_to_rounding(batches):
    folds, dx, da = _compare(batches, compiled=True)
    assert folds >= 5
    # The compiled loop's arctan2/hypot may differ from numpy's (SIMD) in the last bit; both
    # stop within the residual tolerance 1e-10·Fc, i.e. within ~1e-10·Fc/K ≈ 1e-11 µm of the
    # root at a seta stiffness K ~ 0.1 µN/µm (Fc ≈ 6 µN here): allow 1e-9 µm.
    assert dx < 1e-9 and da < 1e-9


def test_the_per_seta_loop_interpreted_equals_the_full_batch_iteration(batches, monkeypatch):
    """The loop numba compiles (:func:`newton_each`), run interpreted through ``rod_newton``:
    the same equilibria as the full-batch iteration, so the compiled path is tested where
    numba is switched off too."""
    monkeypatch.setattr(req, "newton_loop", lambda: req.newton_each)
    folds, dx, da = _compare(batches, compiled=True)
    assert folds >= 5
    # Scalar and vectorized numpy may round hypot/arctan2 apart in the last bit (see above).
    assert dx < 1e-9 and da < 1e-9


@pytest.mark.skipif(not HAVE_NUMBA, reason=extras.reason("fast"))
def test_compiled_and_vectorized_histories_agree():
    """A whole press-pull of 40 rod setae (stick and slide, releases at folds) with either
    Newton: the same releases at the same steps and the same force curve to rounding."""
    p = ROD.replace(**{"array.count": 40, "floor.sigma": 0.3})
    h = 0.3 * np.random.default_rng(5).standard_normal(40)
    real = rodmod.rod_newton
    out = {}
    for compiled in (False, True):
        rodmod.rod_newton = lambda *a, _c=compiled, **k: real(*a, compiled=_c, **k)
        try:
            out[compiled] = qs.press_pull(p, h, 0.5, n_retract=400)
        finally:
            rodmod.rod_newton = real
    v, n = out[False], out[True]
    assert v.releases and [(i, j) for i, j, _ in v.releases] == [(i, j) for i, j, _ in n.releases]
    # Equilibria within ~1e-11 µm (see above) move a tip's force by ~1e-11·K: the curve agrees
    # to 1e-9 of the pull-off.
    assert_allclose(n.force_normal, v.force_normal, rtol=0, atol=1e-9 * abs(v.pull_off))
    assert_allclose(n.force_tangential, v.force_tangential, rtol=0, atol=1e-9 * abs(v.pull_off))


def test_compiled_without_numba_is_refused(monkeypatch):
    monkeypatch.setattr(req, "newton_loop", lambda: None)
    rs = qs.RodSetup.from_params(ROD)
    one = np.ones(1)
    with pytest.raises(ValueError, match="compiled = True needs numba"):
        req.rod_newton(rs, one, one, one, compiled=True)


def test_no_compiled_loop_when_numba_compilation_is_off(monkeypatch):
    """NUMBA_DISABLE_JIT would run the per-seta loop interpreted: the vectorized path is used."""
    numba = extras.require("fast")
    monkeypatch.setattr(numba.config, "DISABLE_JIT", True)
    req.newton_loop.cache_clear()
    try:
        assert req.newton_loop() is None
    finally:
        req.newton_loop.cache_clear()
