"""The implicit step's 2×2 solves, its friction check and its books on a pad floor compiled by
numba: a few calls instead of some ninety numpy operations on arrays of a few setae.

Units, sign conventions, the equations and their sources: :mod:`gecko_agents.model.implicit`,
whose :meth:`~gecko_agents.model.implicit.ImplicitStep.seta_stiffness`,
``ImplicitStep._solve`` and ``ImplicitStep._stick_past_cap`` are the reference (the books':
:func:`step_books` here). The loops do their arithmetic operation for operation in their
order (no fast-math, so no reassociation or fused multiply-add; only +, −, ×, ÷, √ and |·|,
which IEEE 754 rounds alike everywhere) and give the same forces and answers bit for bit
(``tests/test_step_overhead.py``). Only a pad floor (n = (0, 1), t = (1, 0)) under a plate
whose roots are one point (the rigid backing) takes them.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from gecko_agents.physics._util import jitable, register_jitables
from gecko_agents.physics.friction import friction_cap

try:  # np.clip's ufunc, called without np.clip's wrapper (the same result)
    from numpy._core.umath import clip
except ImportError:  # numpy < 2
    from numpy.core.umath import clip

__all__ = [
    "clip",
    "pad_books",
    "pad_past_cap",
    "pad_solve",
    "pad_kernels",
    "pad_solver",
    "past_cap",
    "solve",
    "step_books",
]


@jitable
def rod_stiffness(dx: float, dy: float, L: float, Ka: float, k_phi: float):
    """(kxx, kxy, kyy) [µN/µm] of a rod seta whose tip sits (``dx``, ``dy``) [µm] from its
    root: axial Ka·e eᵀ plus rotary kφ/ℓ²·e⊥e⊥ᵀ plus its tension's Ka(ℓ − L)/ℓ·e⊥e⊥ᵀ clamped
    ≥ 0 (:meth:`gecko_agents.model.implicit.ImplicitStep.seta_stiffness`; L [µm], Ka
    [µN/µm], ``k_phi`` [µN·µm/rad²])."""
    ell = math.sqrt(dx * dx + dy * dy)
    ex, ey = dx / ell, dy / ell
    t = Ka * (ell - L) / ell
    if not (t >= 0.0 or t != t):  # np.maximum(t, 0.0), NaN kept
        t = 0.0
    kp = k_phi / (ell * ell) + t
    return Ka * ex * ex + kp * ey * ey, (Ka - kp) * ex * ey, Ka * ey * ey + kp * ex * ex


def pad_solve(
    rod,
    K,
    L,
    Ka,
    k_phi,
    xy,
    root_dx,
    root_dy,
    pv,
    F,
    kn,
    kt,
    cn,
    ct,
    film,
    q,
    c_seta,
    dt,
    mass,
    rx,
    ry,
    rvx,
    rvy,
):
    """F' [µN] of every tip ((2, N), new): the linearly implicit step's 2×2 solve
    (``ImplicitStep._solve`` on a pad floor, with the seta's
    stiffness of :meth:`~gecko_agents.model.implicit.ImplicitStep.seta_stiffness`).

    Parameters
    ----------
    rod : the rod seta (its K from the tip's position) or the linear one (``K``).
    K : the linear seta's 2×2 stiffness [µN/µm] (unused for the rod).
    L, Ka, k_phi : the rod's rest length [µm], axial stiffness [µN/µm], rotary stiffness
        [µN·µm/rad²].
    xy : (2, N) evaluation points x + v·dt [µm]; root_dx, root_dy : (N,) root offsets from
        the plate [µm]; pv : (4, N) positions [µm] and velocities [µm/µs]; F : (2, N) the
        explicit forces [µN].
    kn, kt, cn, ct : (N,) contact normal and stick stiffnesses [µN/µm] and dampers
        [µN·µs/µm] (:meth:`~gecko_agents.model.implicit.ImplicitStep.contact_stiffness`).
    film, q : a film tip (the spatula) and its film's off-diagonal stiffness (N,) [µN/µm].
    c_seta : the seta's damper [µN·µs/µm]; dt : the step [µs]; mass : the tip's mass [ng].
    rx, ry, rvx, rvy : the plate (the seta springs' root) [µm] and its velocity [µm/µs].
    """
    n = kn.shape[0]
    out = np.empty((2, n))
    kxx, kxy, kyx, kyy = K[0, 0], K[0, 1], K[1, 0], K[1, 1]
    h, h2 = dt / mass, dt * dt / mass
    for i in range(n):
        if rod:
            dx = xy[0, i] - rx - root_dx[i]
            dy = xy[1, i] - ry - root_dy[i]
            kxx, kxy, kyy = rod_stiffness(dx, dy, L, Ka, k_phi)
            kyx = kxy
        vx, vy = pv[2, i], pv[3, i]
        wx, wy = vx - rvx, vy - rvy
        gx = kxx * wx + kxy * wy
        gy = kyx * wx + kyy * wy
        gx += kt[i] * vx
        gy += kn[i] * vy
        axx = 1.0 + h * (c_seta + ct[i]) + h2 * (kxx + kt[i])
        ayy = 1.0 + h * (c_seta + cn[i]) + h2 * (kyy + kn[i])
        axy = h2 * kxy
        ayx = h2 * kyx
        if film:  # the film's off-diagonal stiffness (symmetric)
            gx += q[i] * vy
            gy += q[i] * vx
            axy = axy + h2 * q[i]
            ayx = ayx + h2 * q[i]
        bx = F[0, i] - dt * gx
        by = F[1, i] - dt * gy
        det = axx * ayy - axy * ayx
        out[0, i] = (ayy * bx - axy * by) / det
        out[1, i] = (axx * by - ayx * bx) / det
    return out


def pad_past_cap(pv, fx, fy, Ft, P, kt, ct, dt, mass, Fc, mu, paper):
    """Whether a sticking tip's implicit friction exceeds its Coulomb cap, the test of
    ``ImplicitStep._stick_past_cap`` on a pad floor (t = (1, 0)):
    F' = (``fx``, ``fy``) [µN]; ``pv`` (4, N) positions and velocities [µm, µm/µs]; ``Ft``,
    ``P`` (N,) the kernel's tangential and normal forces [µN]; ``kt``, ``ct`` (N,) the stick
    spring [µN/µm] and damper [µN·µs/µm] (0 where sliding); ``dt`` [µs]; ``mass`` [ng];
    ``Fc`` [µN], ``mu`` [-], ``paper`` as :func:`gecko_agents.physics.friction.friction_cap`."""
    h = dt / mass
    for i in range(kt.shape[0]):
        if kt[i] > 0.0:
            v0t = pv[2, i] * 1.0 + pv[3, i] * 0.0
            v1t = v0t + (fx[i] * 1.0 + fy[i] * 0.0) * h
            f = Ft[i] - dt * kt[i] * v1t - ct[i] * (v1t - v0t)
            if abs(f) > friction_cap(P[i], Fc, mu, paper):
                return True
    return False


def step_books(vx, vy, fx, fy, F, dF, fd, fc, J, dt, rebook):
    """The implicit step's books (:meth:`gecko_agents.model.implicit.ImplicitStep.correct`):
    returns the terms (N,) of Σ v₀·(ΔF_prev + ΔF) [µN·µm/µs] and, with ``rebook``, of
    Σ F_damp·ΔF [µN²] (else None), ΔF = F' − F; then sets ``dF`` (2, N) := ΔF [µN], ``F``
    := F' = (``fx``, ``fy``) [µN] and ``J`` (2, N) := (F' − ``fd`` − ``fc``)·``dt`` [µN·µs]
    (the impulse without the seta's and the contact's damping). ``vx``, ``vy`` (N,) [µm/µs]
    are the velocities v₀, ``fd``, ``fc`` (2, N) the seta's and the contact's damping [µN]."""
    Fx, Fy = F
    e = vx * (dF[0] + fx - Fx) + vy * (dF[1] + fy - Fy)
    ed = (fd[0] + fc[0]) * (fx - Fx) + (fd[1] + fc[1]) * (fy - Fy) if rebook else None
    np.subtract(fx, Fx, out=dF[0])
    np.subtract(fy, Fy, out=dF[1])
    Fx[:] = fx
    Fy[:] = fy
    np.subtract(F, fd, out=J)
    J -= fc
    J *= dt
    return e, ed


def pad_books(vx, vy, fx, fy, F, dF, fd, fc, J, dt, rebook):
    """:func:`step_books` as a loop (its ``ed`` is empty without ``rebook``)."""
    n = vx.shape[0]
    e = np.empty(n)
    ed = np.empty(n if rebook else 0)
    for i in range(n):
        dx, dy = fx[i] - F[0, i], fy[i] - F[1, i]
        e[i] = vx[i] * (dF[0, i] + fx[i] - F[0, i]) + vy[i] * (dF[1, i] + fy[i] - F[1, i])
        if rebook:
            ed[i] = (fd[0, i] + fc[0, i]) * dx + (fd[1, i] + fc[1, i]) * dy
        dF[0, i], dF[1, i] = dx, dy
        F[0, i], F[1, i] = fx[i], fy[i]
        J[0, i] = (F[0, i] - fd[0, i] - fc[0, i]) * dt
        J[1, i] = (F[1, i] - fd[1, i] - fc[1, i]) * dt
    return e, ed


@functools.cache
def pad_kernels():
    """(:func:`pad_solve`, :func:`pad_past_cap`, :func:`pad_books`) compiled by numba (cached
    on disk), or None without numba."""
    try:
        import numba
    except ImportError:
        return None
    register_jitables()
    jit = numba.njit(error_model="numpy", cache=True)
    return jit(pad_solve), jit(pad_past_cap), jit(pad_books)


def pad_solver(model, step):
    """The compiled :func:`pad_kernels` for ``model``'s implicit ``step``
    (:class:`gecko_agents.model.implicit.ImplicitStep`) where they apply, else None: the
    model's pad loop is numba's (``kernel = "numba"``), the floor is the pads (no contact
    normals), the roots ride on a rigid plate and the seta is linear or a rod."""
    applies = (
        model.kernel == "numba"
        and step.normal is None
        and model.backing.rigid
        and model.params.mechanics in ("linear", "rod")
    )
    return pad_kernels() if applies else None


def solve(kernels, step, kn, kt, kxy, cn, ct, roots, F):
    """F' [µN] (two (N,) arrays) by the compiled :func:`pad_solve` of ``kernels``
    (:func:`pad_solver`) for the implicit ``step``: the stiffnesses (``kxy`` a film tip's
    off-diagonal one [µN/µm]) and dampers, ``roots`` and ``F`` as ``ImplicitStep._solve``'s."""
    m = step.m
    s, w = m.state, m.world
    rod = m.params.mechanics != "linear"
    out = kernels[0](
        rod,
        m.K,
        m.L,
        m.Ka,
        m.k_phi,
        s.xy,
        w.root_dx,
        w.root_dy,
        s.pv,
        F,
        kn,
        kt,
        cn,
        ct,
        step.film,
        kxy,
        m.c_seta,
        m.dt,
        m.mass,
        *roots,
    )
    return out[0], out[1]


def past_cap(kernels, m, fx, fy, kt, ct) -> bool:
    """The compiled :func:`pad_past_cap` of ``kernels`` (:func:`pad_solver`) for model ``m``,
    F' = (``fx``, ``fy``) [µN] and the stick spring ``kt`` [µN/µm] and damper ``ct``
    [µN·µs/µm]."""
    s, c = m.state, m.constants
    return kernels[1](s.pv, fx, fy, s.Ft, s.P, kt, ct, m.dt, m.mass, c.Fc, c.mu, c.paper)
