"""The equilibrium of a quasi-static ``rod`` seta on its JKR tip: the rod's force and the
damped Newton solve on (x, a) of :func:`rod_newton`.

Each seta is solved on its own: a seta that has converged keeps its iterate, so one seta
sitting at its fold (where Newton never converges) costs only its own iterations. With numba
installed the per-seta loop is compiled (:func:`newton_loop`); without it the same iteration
runs vectorized over the setae not yet converged (:func:`newton_masked`). Both evaluate the
same residual (:func:`rod_residual`) and step (:func:`newton_step`), which numba compiles into
its loop. Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from gecko_agents.physics import jkr
from gecko_agents.physics._util import jitable, register_jitables
from gecko_agents.physics.friction import friction_cap, friction_cap_slope
from gecko_agents.quasistatic.rod_setup import RodSetup

SLIDE, STICK_SPRING, STICK_RIGID = 0, 1, 2
"""Lateral mode of a solve: slide with F_t = s·cap(P); stick on the contact's spring k_t;
stick rigidly (k_t = ∞, x = anchor)."""

ITERS = 60
"""Newton iterations before a seta counts as not converged (its equilibrium has folded)."""


@jitable
def rod_force(x, y, Ka, k_phi, L, theta):
    """Force of a rod seta on its tip and the tip's tangent stiffness (the agent's ``rod`` law).

    The rod is rigid, pivots at its root on a rotary spring k_φ = Kp·L² and has an axial spring
    Ka (Kp, Ka: eq 19, 17). With the tip at d = (x, y) from the root, ℓ = |d|, e = d/ℓ,
    e⊥ = (−e_y, e_x) and Δφ = atan2(y, x) + θ wrapped to (−π, π]:

        U = ½Ka(ℓ − L)² + ½k_φΔφ²,    F = −∇U = −Ka(ℓ − L)·e − (k_φΔφ/ℓ)·e⊥,
        H = ∇∇U = Ka·e eᵀ + (Ka(ℓ − L)/ℓ + k_φ/ℓ²)·e⊥e⊥ᵀ − (k_φΔφ/ℓ²)(e e⊥ᵀ + e⊥eᵀ).

    At rest (ℓ = L, Δφ = 0) H is the paper's 2×2 stiffness K of eq 20–21 (Ka along the rod,
    Kp across it), so rod and ``linear`` agree for small deflections. The same formula as
    :meth:`~gecko_agents.model.stepping.Stepping.spring_force`.
    Scalars or arrays (numba compiles it into
    :func:`newton_loop`).

    Parameters
    ----------
    x, y : tip position relative to the root [µm] (y up, the rest tip at L(cos θ, −sin θ)).
    Ka : axial stiffness [µN/µm]. k_phi : rotary stiffness [µN·µm/rad]. L : rod length [µm].
    theta : rest angle below the plate [rad].

    Returns
    -------
    (Fx, Fy) [µN] and (H_xx, H_xy, H_yy) [µN/µm].
    """
    ell = np.hypot(x, y)
    ex, ey = x / ell, y / ell
    dphi = np.remainder(np.arctan2(y, x) + theta + np.pi, 2 * np.pi) - np.pi
    fa = Ka * (ell - L)
    ft = k_phi * dphi / ell
    Fx = -fa * ex + ft * ey
    Fy = -fa * ey - ft * ex
    perp = fa / ell + k_phi / (ell * ell)
    cross = ft / ell
    Hxx = Ka * ex * ex + perp * ey * ey + 2.0 * cross * ex * ey
    Hyy = Ka * ey * ey + perp * ex * ex - 2.0 * cross * ex * ey
    Hxy = Ka * ex * ey - perp * ex * ey + cross * (ey * ey - ex * ex)
    return (Fx, Fy), (Hxx, Hxy, Hyy)


# jkr.branch_terms (eq 7, 10 and their slopes) and the cap's slope, compiled into the loop
# where numba is present.
_branch_terms = jitable(jkr.branch_terms)
_cap_slope = jitable(friction_cap_slope)


def constants(rs: RodSetup) -> tuple:
    """The constants :func:`rod_residual` takes: (R [µm], w [µN/µm], E* [MPa], Ka [µN/µm],
    k_φ [µN·µm/rad], L [µm], θ [rad], k_t [µN/µm], Fc [µN], μ [-], paper cap [bool])."""
    return (
        rs.R,
        rs.w,
        rs.E_star,
        rs.Ka,
        rs.k_phi,
        rs.L,
        rs.theta,
        rs.k_t,
        rs.Fc,
        rs.mu,
        rs.law == "paper",
    )


@jitable
def rod_residual(mode, K, c, x, a, anchor, s):
    """Residual (r1, r2) [µN] of F_rod(x, y) + (F_t, P) = 0 at (x, a) with y = c − δ(a), its
    Jacobian (j11, j12, j21, j22) in (x, a) [µN/µm], and P and the rod's F_x [µN] that scale
    the convergence test; scalars or arrays.

    ``mode``: :data:`SLIDE` (F_t = s·cap(P), direction s = ±1), :data:`STICK_SPRING`
    (F_t = −k_t(x − anchor)) or :data:`STICK_RIGID` (x = anchor). ``K``: :func:`constants`.
    P(a), δ(a): JKR eq 7, 10 (:func:`jkr.branch_terms`); the rod: :func:`rod_force`; the cap:
    :func:`~gecko_agents.physics.friction.friction_cap`.
    """
    R, w, Es, Ka, k_phi, L, theta, k_t, Fc, mu, paper = K
    P, dP, d, dd = _branch_terms(a, R, w, Es)
    y = c - d
    (Fx, Fy), (Hxx, Hxy, Hyy) = rod_force(x, y, Ka, k_phi, L, theta)
    # dy/da = −δ'(a).
    if mode == STICK_RIGID:
        r1 = Ka * (anchor - x)
        j11, j12 = -Ka + 0.0 * x, 0.0 * x
    elif mode == STICK_SPRING:
        r1 = Fx - k_t * (x - anchor)
        j11, j12 = -Hxx - k_t, Hxy * dd
    else:
        r1 = Fx + s * friction_cap(P, Fc, mu, paper)
        j11, j12 = -Hxx, Hxy * dd + s * _cap_slope(P, Fc, mu, paper) * dP
    r2 = Fy + P
    j21, j22 = -Hxy, Hyy * dd + dP
    return r1, r2, j11, j12, j21, j22, P, Fx


@jitable
def newton_step(r1, r2, j11, j12, j21, j22, x, a, L):
    """The damped Newton step from (x, a) [µm] with residuals (r1, r2) [µN] and Jacobian
    (j11 … j22) of :func:`rod_residual`: the new (x, a) [µm], the step limited to 0.1 of the
    rod length L [µm] in x and 0.3 of a in a. Scalars or arrays."""
    det = j11 * j22 - j12 * j21
    det = det + (det == 0.0) * 1e-300
    dx = -(j22 * r1 - j12 * r2) / det
    da = -(-j21 * r1 + j11 * r2) / det
    lim = np.minimum(
        1.0,
        np.minimum(
            0.1 * L / np.maximum(np.abs(dx), 1e-300), 0.3 * a / np.maximum(np.abs(da), 1e-300)
        ),
    )
    return x + lim * dx, a + lim * da


@jitable
def rod_stable(mode, K, c, x, a, s):
    """Where the equilibrium at (x, a) is stable: the tangent stiffness K_tot = H + contact
    (+ stick spring) in (x, y) has positive determinant and trace (with a rigid stick, x is
    held: the normal stiffness H_yy + dP/dδ is positive). Arguments as :func:`rod_residual`;
    scalars or arrays."""
    R, w, Es, Ka, k_phi, L, theta, k_t, Fc, mu, paper = K
    P, dP, d, dd = _branch_terms(a, R, w, Es)
    y = c - d
    _, (Hxx, Hxy, Hyy) = rod_force(x, y, Ka, k_phi, L, theta)
    kc = dP / np.maximum(dd, 1e-300)  # dP/dδ
    if mode == STICK_RIGID:
        return Hyy + kc > 0
    if mode == STICK_SPRING:
        kxx, kxy = Hxx + k_t, Hxy + 0.0
    else:
        kxx, kxy = Hxx + 0.0, Hxy + s * _cap_slope(P, Fc, mu, paper) * kc
    return (kxx * (Hyy + kc) - kxy * Hxy > 0) & (kxx + Hyy + kc > 0)


def newton_masked(mode, K, c, x, a, anchor, s, iters, a_min):
    """Damped Newton for every seta at once, each iteration over the setae not yet converged
    (a converged seta keeps its (x, a)). Arrays c, x, a, anchor, s (n,) [µm, µm, µm, µm, -];
    ``x``, ``a`` are updated in place. Returns where each converged (see :func:`rod_newton`)."""
    conv = np.zeros(x.size, dtype=bool)
    act = np.arange(x.size)  # the setae not yet converged, and their c, x, a, anchor, s
    sub = (c, x.copy(), a.copy(), anchor, s)
    tol = 1e-10 * K[8]
    for _ in range(iters):
        r1, r2, j11, j12, j21, j22, P, Fx = rod_residual(mode, K, *sub)
        scale = tol + 1e-12 * (np.abs(P) + np.abs(Fx))
        done = (np.abs(r1) <= scale) & (np.abs(r2) <= scale)
        terms = (r1, r2, j11, j12, j21, j22)
        if done.any():
            conv[act[done]] = True
            if done.all():
                break
            left = ~done
            act = act[left]
            sub = tuple(v[left] for v in sub)
            terms = tuple(v[left] for v in terms)
        xa, aa = newton_step(*terms, sub[1], sub[2], K[5])
        aa = np.maximum(aa, a_min)
        x[act], a[act] = xa, aa
        sub = (sub[0], xa, aa, sub[3], sub[4])
    return conv


def newton_each(mode, K, c, x, a, anchor, s, iters, a_min):
    """:func:`newton_masked` as one loop over the setae, the form numba compiles
    (:func:`newton_loop`): each seta iterates until it converges or has taken ``iters`` steps,
    with the same residual, step and test. Arguments as :func:`newton_masked`; ``x``, ``a``
    are updated in place. Returns (converged, stable there: :func:`rod_stable`). Interpreted it
    is far slower than :func:`newton_masked`; it is called so only to test the loop itself."""
    conv = np.zeros(x.size, dtype=np.bool_)
    stab = np.zeros(x.size, dtype=np.bool_)
    tol = 1e-10 * K[8]
    for i in range(x.size):
        xi, ai = x[i], a[i]
        for _ in range(iters):
            r1, r2, j11, j12, j21, j22, P, Fx = rod_residual(mode, K, c[i], xi, ai, anchor[i], s[i])
            scale = tol + 1e-12 * (np.abs(P) + np.abs(Fx))
            if np.abs(r1) <= scale and np.abs(r2) <= scale:
                conv[i] = True
                break
            xi, ai = newton_step(r1, r2, j11, j12, j21, j22, xi, ai, K[5])
            ai = np.maximum(ai, a_min)
        x[i], a[i] = xi, ai
        if conv[i]:
            stab[i] = rod_stable(mode, K, c[i], xi, ai, s[i])
    return conv, stab


@functools.cache
def newton_loop():
    """:func:`newton_each` compiled by numba, or None without numba or when numba's
    compilation is switched off (``NUMBA_DISABLE_JIT=1``: interpreted, the loop would be far
    slower than :func:`newton_masked`)."""
    try:
        import numba
    except ImportError:
        return None
    if numba.config.DISABLE_JIT:
        return None
    register_jitables()
    return numba.njit(cache=True, error_model="numpy")(newton_each)


def _batch(v, shape) -> np.ndarray:
    """``v`` as a contiguous float array of ``shape`` (a copy only where needed)."""
    v = np.asarray(v, dtype=float)
    if v.shape != shape or not v.flags.c_contiguous:
        v = np.ascontiguousarray(np.broadcast_to(v, shape))
    return v


def rod_newton(
    rs: RodSetup,
    c,
    x,
    a,
    anchor=None,
    s=None,
    iters: int = ITERS,
    max_jump: float = math.inf,
    compiled: bool | None = None,
):
    """Equilibrium of rod + JKR tip for each seta, by damped Newton on (x, a).

    The tip sits at (x, y) from its root with y = c − δ(a) (c = h + R − Z [µm]: floor height
    h, plate height Z), the normal force is P(a) (eq 7), the overlap δ(a) (eq 10). Lateral:
    ``anchor`` given: stick, F_t = −k_t(x − anchor) (``k_t = inf``: x = anchor); else slide in
    direction ``s`` = ±1 with F_t = s·cap(P). Equations: F_rod(x, y) + (F_t, P) = 0.

    A seta has converged where both residuals are within 1e-10·Fc + 1e-12(|P| + |F_x|) [µN]
    at its (x, a), which it then keeps: each seta iterates on its own, so one seta at its fold
    (which never converges in ``iters`` iterations) costs its own iterations, not the batch's.
    ``compiled``: the numba loop (:func:`newton_loop`) or the vectorized one
    (:func:`newton_masked`); default: numba if installed. They give the same equilibria to
    rounding.

    ``max_jump`` [µm]: an equilibrium whose x is farther than this from the start does not
    count (it lies beyond a snap of the branch the tip was on).

    Returns (x, a, ok): ok where Newton converged to a stable equilibrium (the tangent
    stiffness of rod + contact + stick spring has positive determinant and trace) on the
    stable JKR branch (a > a_c). Where the equilibrium has folded away, ok is False.
    """
    x_start = np.asarray(x, dtype=float)
    x, a = np.array(x, dtype=float), np.array(a, dtype=float)
    c = _batch(c, x.shape)
    mode = SLIDE if anchor is None else (STICK_RIGID if math.isinf(rs.k_t) else STICK_SPRING)
    anc = np.zeros(x.shape) if anchor is None else _batch(anchor, x.shape)
    dirs = np.zeros(x.shape) if s is None else _batch(s, x.shape)
    a_min = rs.a_c * (1.0 + 1e-9)
    loop = newton_loop() if compiled or compiled is None else None
    if compiled and loop is None:
        raise ValueError("compiled = True needs numba (pip install numba)")
    K = constants(rs)
    if loop is None:
        ok = newton_masked(mode, K, c, x, a, anc, dirs, int(iters), a_min)
        k = np.flatnonzero(ok)
        ok[k] = rod_stable(mode, K, c[k], x[k], a[k], dirs[k])
    else:
        conv, ok = loop(mode, K, c, x, a, anc, dirs, int(iters), a_min)
    ok &= (a > a_min) & np.isfinite(x)
    # An equilibrium far from the last one is the far side of a snap (e.g. the rod swinging
    # through upright): the branch the tip was on has folded; dynamically the tip lets go.
    ok &= np.abs(x - x_start) <= max_jump
    return x, a, ok
