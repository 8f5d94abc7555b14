"""The chain's pivot solve of :mod:`gecko_agents.backing.pivots` as one compiled loop (numba):
the same equations, written link by link, with J M⁻¹ Jᵀ factorised as a block-tridiagonal
matrix of 2×2 blocks (block LDLᵀ, the block Thomas algorithm: Golub & Van Loan 2013, Matrix
Computations, 4th ed., §4.5.1). LAPACK's banded Cholesky called from numpy costs ~0.3 ms for a
1 500-link chain, about a whole step of the rigid plate's 10 000 setae.

Units: µm, µN, µs, ng, pJ. Compiled when numba is installed (:func:`compiled`), else None:
:class:`gecko_agents.backing.pivots.ChainPivots` then uses its numpy path.
"""

from __future__ import annotations

import math

import numpy as np

try:  # the helpers are called from inside the compiled solve
    from numba.extending import register_jitable as _jitable
except ImportError:  # numba is optional: then they are plain functions

    def _jitable(fn):
        return fn


__all__ = ["chain_pivot_forces", "compiled"]


@_jitable
def _factor(d, off_b):
    """Block LDLᵀ (block Thomas) of the symmetric block-tridiagonal A with 2×2 diagonal
    blocks d[k] = (a00, a11, a01) and off-diagonal blocks off_b[k] = (b00, b11, b01)
    (symmetric, A[k, k+1] = A[k+1, k]): returns S_k⁻¹ as (P, 3) and G_k = S_k⁻¹·B_k as (P, 4)
    (row-major), S_0 = D_0, S_k = D_k − G_{k−1}ᵀ·B_{k−1}."""
    P = d.shape[0]
    sinv, g = np.empty((P, 3)), np.zeros((P, 4))
    for k in range(P):
        a00, a11, a01 = d[k, 0], d[k, 1], d[k, 2]
        if k > 0:  # − G_{k−1}ᵀ B_{k−1}
            g00, g01, g10, g11 = g[k - 1, 0], g[k - 1, 1], g[k - 1, 2], g[k - 1, 3]
            b00, b11, b01 = off_b[k - 1, 0], off_b[k - 1, 1], off_b[k - 1, 2]
            a00 -= g00 * b00 + g10 * b01
            a11 -= g01 * b01 + g11 * b11
            a01 -= g00 * b01 + g10 * b11
        det = a00 * a11 - a01 * a01
        i00, i11, i01 = a11 / det, a00 / det, -a01 / det
        sinv[k, 0], sinv[k, 1], sinv[k, 2] = i00, i11, i01
        if k + 1 < P:
            b00, b11, b01 = off_b[k, 0], off_b[k, 1], off_b[k, 2]
            g[k, 0] = i00 * b00 + i01 * b01
            g[k, 1] = i00 * b01 + i01 * b11
            g[k, 2] = i01 * b00 + i11 * b01
            g[k, 3] = i01 * b01 + i11 * b11
    return sinv, g


@_jitable
def _solve(sinv, g, b):
    """In place: b ← A⁻¹b for the factors of :func:`_factor` (y_k = b_k − G_{k−1}ᵀ·y_{k−1},
    then x_k = S_k⁻¹·y_k − G_k·x_{k+1})."""
    P = sinv.shape[0]
    for k in range(1, P):
        yx, yy = b[2 * k - 2], b[2 * k - 1]
        b[2 * k] -= g[k - 1, 0] * yx + g[k - 1, 2] * yy
        b[2 * k + 1] -= g[k - 1, 1] * yx + g[k - 1, 3] * yy
    nx = ny = 0.0
    for k in range(P - 1, -1, -1):
        yx, yy = b[2 * k], b[2 * k + 1]
        xx = sinv[k, 0] * yx + sinv[k, 2] * yy - (g[k, 0] * nx + g[k, 1] * ny)
        xy = sinv[k, 2] * yx + sinv[k, 1] * yy - (g[k, 2] * nx + g[k, 3] * ny)
        b[2 * k], b[2 * k + 1] = xx, xy
        nx, ny = xx, xy


@_jitable
def _gaps(x, y, c, s, h, off, ax, ay, g):
    """Pivot gaps (left point − right point) [µm] into g[0::2], g[1::2]; returns the largest.
    Pivot k holds link k + off on its right and the link before it (or the anchor) on its left."""
    big = 0.0
    for k in range(g.size // 2):
        r = k + off
        gx = h * c[r] - x[r]
        gy = h * s[r] - y[r]
        if r == 0:
            gx += ax
            gy += ay
        else:
            gx += x[r - 1] + h * c[r - 1]
            gy += y[r - 1] + h * s[r - 1]
        g[2 * k], g[2 * k + 1] = gx, gy
        big = max(big, gx * gx + gy * gy)
    return math.sqrt(big)


@_jitable
def _generalised(lam, c, s, h, off, fx, fy, tq):
    """fx, fy, tq ← Jᵀλ: right link −λ and h·p·λ, left link +λ and h·p·λ (p = (−sin, cos))."""
    fx[:] = 0.0
    fy[:] = 0.0
    tq[:] = 0.0
    for k in range(lam.size // 2):
        r = k + off
        lx, ly = lam[2 * k], lam[2 * k + 1]
        fx[r] -= lx
        fy[r] -= ly
        tq[r] += h * (c[r] * ly - s[r] * lx)
        if r > 0:
            fx[r - 1] += lx
            fy[r - 1] += ly
            tq[r - 1] += h * (c[r - 1] * ly - s[r - 1] * lx)


def chain_pivot_forces(
    x, y, phi, vx, vy, w, m, inertia, dt, h, beta, clamp, ax, ay, newton, fx, fy, tq
):
    """Pivot forces fx, fy [µN] and torques tq [pJ] (written in place) of
    :meth:`gecko_agents.backing.pivots.ChainPivots.forces`; returns (gap_max, gap_next) [µm]."""
    n = x.size
    P = n - 1 + clamp
    off = n - P
    c, s = np.cos(phi), np.sin(phi)
    inv_m, hh = 1.0 / m, h * h / inertia
    d, off_b = np.empty((P, 3)), np.empty((P, 3))
    for k in range(P):
        r = k + off
        a00 = inv_m + hh * s[r] * s[r]
        a11 = inv_m + hh * c[r] * c[r]
        a01 = -hh * s[r] * c[r]
        # Pivots k and k + 1 share link r: −I₂/m + h²·p pᵀ/I.
        off_b[k, 0], off_b[k, 1], off_b[k, 2] = a00 - 2.0 * inv_m, a11 - 2.0 * inv_m, a01
        if r > 0:
            a00 += inv_m + hh * s[r - 1] * s[r - 1]
            a11 += inv_m + hh * c[r - 1] * c[r - 1]
            a01 -= hh * s[r - 1] * c[r - 1]
        d[k, 0], d[k, 1], d[k, 2] = a00, a11, a01
    sinv, g = _factor(d, off_b)
    rhs = np.empty(2 * P)
    gap_max = _gaps(x, y, c, s, h, off, ax, ay, rhs)
    k_b = beta / dt
    for k in range(P):  # −β·C/dt − J·v
        r = k + off
        dx = -vx[r] - h * w[r] * s[r]
        dy = -vy[r] + h * w[r] * c[r]
        if r > 0:
            dx += vx[r - 1] - h * w[r - 1] * s[r - 1]
            dy += vy[r - 1] + h * w[r - 1] * c[r - 1]
        rhs[2 * k] = -k_b * rhs[2 * k] - dx
        rhs[2 * k + 1] = -k_b * rhs[2 * k + 1] - dy
    _solve(sinv, g, rhs)
    imp = rhs.copy()  # [µN·µs]
    x2, y2, c2, s2 = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
    gap_next = 0.0
    for it in range(newton + 1):
        _generalised(imp, c, s, h, off, fx, fy, tq)
        for j in range(n):  # where the step then takes the links next: x⁺ + v⁺·dt
            x2[j] = x[j] + (vx[j] + fx[j] * inv_m) * dt
            y2[j] = y[j] + (vy[j] + fy[j] * inv_m) * dt
            a = phi[j] + (w[j] + tq[j] / inertia) * dt
            c2[j], s2[j] = math.cos(a), math.sin(a)
        gap_next = _gaps(x2, y2, c2, s2, h, off, ax, ay, rhs)
        if it == newton:
            break
        for i in range(2 * P):
            rhs[i] = -rhs[i] / dt
        _solve(sinv, g, rhs)
        for i in range(2 * P):
            imp[i] += rhs[i]
    for j in range(n):
        fx[j] /= dt
        fy[j] /= dt
        tq[j] /= dt
    return gap_max, gap_next


_COMPILED = []


def compiled():
    """:func:`chain_pivot_forces` compiled by numba (once, cached on disk), or None without
    numba."""
    if not _COMPILED:
        try:
            import numba
        except ImportError:
            _COMPILED.append(None)
        else:
            _COMPILED.append(numba.njit(error_model="numpy", cache=True)(chain_pivot_forces))
    return _COMPILED[0]
