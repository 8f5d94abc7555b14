"""The per-seta loop of a pad-floor step, compiled by numba or run by the interpreter.

Units and sign conventions as :mod:`gecko_agents.model.step_numpy`, whose
:class:`~gecko_agents.model.step_numpy.NumpyStep` computes the same step vectorized: the loop
follows its formulas and its order of operations, so both give the same history to rounding
(``tests/test_model.py``), and it calls the contact law's scalar functions
(:mod:`gecko_agents.contact`), so a new law needs nothing here. Built once per law class and
mode by :func:`pad_loop`.
"""

from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from gecko_agents.contact.base import K_ATTACH_FILM, K_ATTACH_RADIUS
from gecko_agents.model.state import (
    AC,
    AX,
    AY,
    DELTA,
    DMPX,
    DMPY,
    FDX,
    FDY,
    FT,
    FX,
    FY,
    JUMP,
    P0,
    PX,
    PY,
    S0,
    UC,
    UX,
    UY,
    VX,
    VY,
    XI,
    X,
    Y,
)
from gecko_agents.model.state import P as PN
from gecko_agents.physics._util import jitable, register_jitables
from gecko_agents.physics.friction import friction_cap

__all__ = ["PadArrays", "PlateStep", "pad_loop", "numba_available"]


class PadArrays(NamedTuple):
    """The arrays one step of the pad loop reads and writes (one record: numba takes a named
    tuple of arrays as one argument)."""

    data: np.ndarray  # the batch rows (x, y, vx, vy) in pymunk's order [µm, µm/µs]
    rows: np.ndarray  # seta i's row in ``data``
    out: np.ndarray  # the forces written for pymunk, rows as ``data`` [µN]
    h: np.ndarray  # each seta's pad height [µm]
    cand: np.ndarray  # the tip is a contact candidate (bool (N,))
    attached: np.ndarray  # (bool (N,))
    slip: np.ndarray  # (bool (N,))
    S: np.ndarray  # the state block (rows as gecko_agents.model.state)
    ext: np.ndarray  # extra force on each tip (N, 2) [µN]
    pad_c: np.ndarray  # each pad window's centre [µm]
    rest: np.ndarray  # the linear seta's rest tip offsets (2, N) [µm]
    root: np.ndarray  # the rod's root offsets (2, N) [µm]
    lost_idx: np.ndarray  # setae whose tips lost their candidate while attached (int64 (N,))
    gone_idx: np.ndarray  # setae whose tips let go (int64 (N,))
    res: np.ndarray  # plate force (x, y), dissipation, #lost, #gone, max |u|², max drift


class PlateStep(NamedTuple):
    """The plate's motion over one step of the pad loop."""

    pnx: float  # the plate where the step evaluates forces [µm]
    pny: float
    vpx: float  # the plate's velocity [µm/µs]
    vpy: float
    vref: float  # the reference speed of the release marks [µm/µs]
    has_ext: bool  # some tip has an extra force


@jitable  # called from inside the compiled loops too
def seta_spring(i, r, data, S, c, pnx, pny, vpx, vpy, rest, root):
    """Seta i (batch row r of ``data``): stores its position and velocity and the evaluation
    point x + v·dt in ``S``, and returns (x, y, vx, vy, fx, fy, fdx, fdy, |u|²): the seta's
    spring force on the tip (``rod``: :func:`gecko_agents.physics.beam.rod_spring_force`; linear:
    −K·u, eq 20–21) [µN] and its damping relative to the plate [µN], and the linear seta's
    squared deflection [µm²] (0 for the rod). The plate is at (pnx, pny) [µm], moving at
    (vpx, vpy) [µm/µs]; ``c`` is a :class:`gecko_agents.model.step_numpy.LoopConstants`."""
    dt = c.dt
    px, py, vx, vy = data[r, 0], data[r, 1], data[r, 2], data[r, 3]
    S[PX, i], S[PY, i], S[VX, i], S[VY, i] = px, py, vx, vy
    x = vx * dt + px
    y = vy * dt + py
    S[X, i], S[Y, i] = x, y
    u2 = 0.0
    if c.rod:
        dx = (x - pnx) - root[0, i]
        dy = (y - pny) - root[1, i]
        ell = math.sqrt(dx * dx + dy * dy)
        dphi = math.atan2(dy, dx) + (c.theta + math.pi)
        dphi = dphi % (2.0 * math.pi) - math.pi
        t0 = (ell - c.L) * -c.Ka / ell
        t1 = dphi * c.k_phi / ell / ell
        fx = t0 * dx + t1 * dy
        fy = t0 * dy - t1 * dx
    else:
        ux = (x - pnx) - rest[0, i]
        uy = (y - pny) - rest[1, i]
        S[UX, i], S[UY, i] = ux, uy
        fx = ux * c.k00 + uy * c.k01
        fy = ux * c.k10 + uy * c.k11
        u2 = ux * ux + uy * uy
    fdx = (vx - vpx) * -c.c_seta
    fdy = (vy - vpy) * -c.c_seta
    S[FDX, i], S[FDY, i] = fdx, fdy
    return x, y, vx, vy, fx, fy, fdx, fdy, u2


BLOCK = 128
"""Setae per block of the pad loop: its three passes run over one block at a time (the data
stay in cache), and its sums are summed per block first, then over blocks in block order."""

PARALLEL_MIN_SETAE = 16_384
"""Fewest setae for which :class:`gecko_agents.model.Model` runs the pad loop's blocks on
numba's threads (below it a step is too short to pay for the threads)."""


def _jit(compiled: bool, **options):
    """numba's ``njit`` with ``options`` when ``compiled`` (None if numba is missing), else the
    identity: the interpreter runs the same function."""
    if not compiled:
        return lambda fn: fn
    try:
        import numba
    except ImportError:
        return None
    register_jitables()
    return numba.njit(error_model="numpy", **options)


def _springs_pass(energy, rate: bool, jit):
    """Pass 1 of a block: springs, damping, overlaps and contact state changes."""

    def springs(b0, b1, a, p, c, k):
        data, rows, h, cand, attached, S, ext = a.data, a.rows, a.h, a.cand, a.attached, a.S, a.ext
        rest, root, lost_idx, gone_idx = a.rest, a.root, a.lost_idx, a.gone_idx
        pnx, pny, vpx, vpy, has_ext = p.pnx, p.pny, p.vpx, p.vpy, p.has_ext
        R, dc, kt, arel = c.R, c.detach, c.k_t, c.release
        opx = opy = diss = sfdx = sfdy = max_u2 = 0.0
        nl = ng = 0
        for i in range(b0, b1):
            x, y, vx, vy, fx, fy, fdx, fdy, u2 = seta_spring(
                i, rows[i], data, S, c, pnx, pny, vpx, vpy, rest, root
            )
            if u2 > max_u2:
                max_u2 = u2
            sfdx += fdx
            sfdy += fdy
            fx += fdx
            fy += fdy
            opx += fx
            opy += fy
            if has_ext:
                fx += ext[i, 0]
                fy += ext[i, 1]
            S[FX, i], S[FY, i] = fx, fy
            # Contact with the tip's own pad: n = (0, 1), t = (1, 0), q = (x, h).
            d = R - (y - h[i])
            S[DELTA, i] = d
            if attached[i]:
                gone = False
                if not cand[i]:
                    lost_idx[b0 + nl] = i
                    nl += 1
                    gone = True
                elif d < dc or (rate and S[AC, i] <= arel):
                    gone_idx[b0 + ng] = i
                    ng += 1
                    gone = True
                if gone:  # snap-off: what the contact stored is dissipated
                    attached[i] = False
                    xs = S[XI, i]
                    diss += energy(S[AC, i], d, k) + 0.5 * kt * xs * xs
            elif cand[i] and d >= 0.0:
                attached[i] = True
                S[AX, i], S[AY, i] = x, h[i]
                S[XI, i] = np.inf  # marks an attachment for pass 3
        return opx, opy, sfdx, sfdy, max_u2, diss, nl, ng

    return jit(springs)


def _radius_pass(radius, energy, rate: bool, jit):
    """Pass 2 of a block: the contact radius on the law's branch. It is a long chain of
    dependent sqrt/cbrt/divisions that overlaps between setae only in a short loop of its
    own."""

    def radii(b0, b1, c, k, attached, S, diss):
        dt = c.dt
        for i in range(b0, b1):
            if attached[i]:
                a_old, d = S[AC, i], S[DELTA, i]
                a_new = radius(d, a_old, dt, k)
                S[AC, i] = a_new
                if rate and S[XI, i] != np.inf:  # work of the moving edge ≥ 0
                    diss += energy(a_old, d, k) - energy(a_new, d, k)
        return diss

    return jit(radii)


def _force_pass(force, energy, jit):
    """Pass 3 of a block: contact forces, stick/slip, release bookkeeping, dissipation and
    the forces written for pymunk."""

    def forces(b0, b1, a, c, k, fast2, slow2, diss):
        rows, out, attached, slip, S, pad_c = a.rows, a.out, a.attached, a.slip, a.S, a.pad_c
        cn, ct, kt, mu, paper, Fc, hm = c.c_n, c.c_t, c.k_t, c.mu, c.paper, c.Fc, c.hm
        dd = drift = 0.0
        for i in range(b0, b1):
            vx, vy, x = S[VX, i], S[VY, i], S[X, i]
            fx, fy, fdx, fdy = S[FX, i], S[FY, i], S[FDX, i], S[FDY, i]
            dmpx = dmpy = 0.0
            if attached[i]:
                new = S[XI, i] == np.inf
                a = S[AC, i]
                P = force(a, S[DELTA, i], k)
                xi = x - S[AX, i]
                cap = friction_cap(P, Fc, mu, paper)
                trial = xi * -kt
                dtg = vx * -ct
                if abs(trial) > cap:
                    xin = math.copysign(cap / kt, xi)
                    diss += cap * abs(xi - xin)  # Coulomb work of the slip
                    dtg = 0.0
                    ft = -kt * xin + dtg
                    sl = True
                else:
                    xin = xi
                    ft = trial + dtg
                    sl = False
                S[AX, i] = x - xin
                dn = vy * -cn
                fx += ft
                fy += P + dn
                dmpx, dmpy = dtg, dn
                S[PN, i], S[FT, i], S[XI, i] = P, ft, xin
                slip[i] = sl
                if new:  # attachment starts the branch at U = 0
                    diss -= energy(a, S[DELTA, i], k) + 0.5 * kt * xin * xin
                s2 = vx * vx + vy * vy
                if s2 > fast2:
                    if math.isnan(S[JUMP, i]):
                        S[JUMP, i] = S[DELTA, i]
                elif s2 < slow2:
                    S[JUMP, i] = np.nan
            S[FX, i], S[FY, i], S[DMPX, i], S[DMPY, i] = fx, fy, dmpx, dmpy
            r = rows[i]
            out[r, 0], out[r, 1] = fx, fy
            vmx = fx * hm + vx
            vmy = fy * hm + vy
            dd += (fdx + dmpx) * vmx + (fdy + dmpy) * vmy
            dr = abs(x - pad_c[i])
            if dr > drift:
                drift = dr
        return diss, dd, drift

    return jit(forces)


def _gather(sums, n_blocks, lost_idx, gone_idx, vpx, vpy, dt, res):
    """Block sums in block order into ``res``; each block's detached tips (stored from its
    first seta on) moved down to the front, ascending."""
    tot = sums[0].copy()
    nl, ng = int(sums[0, 8]), int(sums[0, 9])
    for b in range(1, n_blocks):
        for j in range(6):
            tot[j] += sums[b, j]
        tot[6] = max(tot[6], sums[b, 6])
        tot[7] = max(tot[7], sums[b, 7])
        b0 = b * BLOCK
        for j in range(int(sums[b, 8])):
            lost_idx[nl] = lost_idx[b0 + j]
            nl += 1
        for j in range(int(sums[b, 9])):
            gone_idx[ng] = gone_idx[b0 + j]
            ng += 1
    opx, opy, diss, dd, sfdx, sfdy = tot[0], tot[1], tot[2], tot[3], tot[4], tot[5]
    res[0], res[1] = opx, opy
    res[2] = diss - (dd - vpx * sfdx - vpy * sfdy) * dt
    res[3], res[4], res[5], res[6] = nl, ng, tot[6], tot[7]


@functools.cache
def pad_loop(law_type, compiled: bool, parallel: bool = False):
    """The pad-floor step of every seta as one loop, for contact laws of class ``law_type``.

    Returns ``loop(a, p, c, k)``: with the arrays ``a`` (:class:`PadArrays`) and the plate's
    motion ``p`` (:class:`PlateStep`), reads the batch rows ``a.data`` (x, y, vx, vy; seta i
    in row ``a.rows[i]``), writes the forces into ``a.out`` and the state block ``a.S`` (rows as
    :mod:`gecko_agents.model.state`), the detached tips into ``a.lost_idx``/``a.gone_idx``
    (ascending) and into ``a.res``: plate force (x, y), dissipation, #lost, #gone, max |u|²,
    max pad-window drift. ``c`` is a :class:`gecko_agents.model.step_numpy.LoopConstants`,
    ``k`` the law's constants. ``compiled``: numba (None if numba is missing) or the
    interpreter.
    ``parallel``: the blocks of ``BLOCK`` setae run on numba's threads. Setae are
    independent within a step and every sum is taken per block, then over the blocks in
    their order, so the result is the same bit for bit with and without threads (and, for
    N ≤ ``BLOCK``, the same as one running sum). Built once per law and mode.
    """
    if getattr(law_type, "tangential", False):
        return _tangential_loop(law_type, compiled)
    jit = _jit(compiled)
    if jit is None:
        return None
    laws = (law_type.radius_scalar, law_type.force_scalar, law_type.energy_scalar)
    radius, force, energy = map(_jit(compiled, cache=True), laws)
    rate = law_type.rate_dependent  # a compile-time constant of the loop
    springs = _springs_pass(energy, rate, jit)
    radii = _radius_pass(radius, energy, rate, jit)
    forces = _force_pass(force, energy, jit)
    gather = jit(_gather)
    blocks = range
    if compiled:
        import numba

        blocks = numba.prange

    def loop(
        a,
        p,
        c,
        k,
    ):
        n = a.S.shape[1]
        vref = p.vref
        fast2, slow2 = 4.0 * vref * vref, vref * vref
        n_blocks = (n + BLOCK - 1) // BLOCK
        sums = np.zeros((max(n_blocks, 1), 10))
        for b in blocks(n_blocks):  # the three passes over one block at a time (cache)
            b0 = b * BLOCK
            b1 = min(n, b0 + BLOCK)
            opx, opy, sfdx, sfdy, max_u2, diss, nl, ng = springs(b0, b1, a, p, c, k)
            diss = radii(b0, b1, c, k, a.attached, a.S, diss)
            diss, dd, drift = forces(b0, b1, a, c, k, fast2, slow2, diss)
            sb = sums[b]
            sb[0], sb[1], sb[2], sb[3], sb[4], sb[5] = opx, opy, diss, dd, sfdx, sfdy
            sb[6], sb[7], sb[8], sb[9] = max_u2, drift, nl, ng
        gather(sums, n_blocks, a.lost_idx, a.gone_idx, p.vpx, p.vpy, c.dt, a.res)

    # (A closure is compiled anew in every process, ~2 s: numba cannot cache it on disk.)
    return _jit(compiled, parallel=parallel)(loop)


def _film_contact(step, jit, damp_sliding=True):
    """The contact of one seta with a law that takes the tip's tangential position (the
    spatula's ``step_scalar``): attachment, release, the film's forces and the tip body's
    friction (its stick anchor in ``S[XI]``, relative to the front), as
    :meth:`gecko_agents.model.step_numpy.NumpyStep.contact_pads_tangential`. ``damp_sliding``: the
    tangential contact damping also acts while the tip slides (else only while it sticks, as
    the sphere's)."""

    def film(i, x, y, vx, vy, d, c, k, h, cand, attached, slip, S, fast2, slow2, diss):
        """Returns (tangential and normal contact force, their damping, dissipation so far,
        0 or 1 lost candidate, 0 or 1 release) of seta i."""
        fcx = fcy = dmpx = dmpy = 0.0
        lost = gone = 0
        new = False
        if attached[i]:
            if not cand[i]:
                lost = 1
                attached[i] = False
                diss += S[UC, i]
            elif d < c.detach:
                gone = 1
                attached[i] = False
                diss += S[UC, i]
        elif cand[i] and d >= 0.0:
            attached[i] = True
            new = True
            S[AX, i], S[AY, i] = x, h[i]
            S[AC, i], S[S0, i] = k[K_ATTACH_RADIUS], k[K_ATTACH_FILM]
            S[P0, i], S[UC, i] = 0.0, 0.0
            S[XI, i] = 0.0  # the tip body's stick anchor, under the tip with the front
        if attached[i]:
            P, T, shift, ell, p0, s0, xa, U, de, slid = step(
                x - S[AX, i], y - h[i], S[AC, i], S[P0, i], S[S0, i], S[XI, i], k
            )
            diss += -U if new else de
            S[AX, i] += shift
            S[AC, i], S[P0, i], S[S0, i], S[XI, i], S[UC, i] = ell, p0, s0, xa, U
            if ell <= 0.0:  # the film has peeled off: what it stored is dissipated
                gone = 1
                attached[i] = False
                diss += U
            else:
                dmpx, dmpy = vx * -c.c_t, vy * -c.c_n
                if slid > 0.0 and not damp_sliding:
                    dmpx = 0.0
                fcx, fcy = T + dmpx, P + dmpy
                S[PN, i], S[FT, i] = P, T
                slip[i] = slid > 0.0
                s2 = vx * vx + vy * vy
                if s2 > fast2:
                    if math.isnan(S[JUMP, i]):
                        S[JUMP, i] = d
                elif s2 < slow2:
                    S[JUMP, i] = np.nan
        return fcx, fcy, dmpx, dmpy, diss, lost, gone

    return jit(film)


def _tangential_loop(law_type, compiled: bool):
    """:func:`pad_loop` for a law that takes the tip's tangential position (``step_scalar``,
    the spatula): the springs as the sphere's loop, the contact by :func:`_film_contact`, one
    seta at a time in the order of :meth:`gecko_agents.model.step_numpy.NumpyStep.
    contact_pads_tangential`."""
    jit = _jit(compiled)
    if jit is None:
        return None
    film = _film_contact(_jit(compiled)(law_type.step_scalar), jit, law_type.damp_sliding)

    def loop(
        a,
        p,
        c,
        k,
    ):
        data, rows, out, h, cand, attached, slip, S = (
            a.data, a.rows, a.out, a.h, a.cand, a.attached, a.slip, a.S
        )  # fmt: skip
        ext, pad_c, rest, root, lost_idx, gone_idx, res = (
            a.ext, a.pad_c, a.rest, a.root, a.lost_idx, a.gone_idx, a.res
        )  # fmt: skip
        pnx, pny, vpx, vpy, vref, has_ext = p
        R, hm = c.R, c.hm
        fast2, slow2 = 4.0 * vref * vref, vref * vref
        opx = opy = diss = dd = sfdx = sfdy = max_u2 = drift = 0.0
        nl = ng = 0
        for i in range(S.shape[1]):
            x, y, vx, vy, fx, fy, fdx, fdy, u2 = seta_spring(
                i, rows[i], data, S, c, pnx, pny, vpx, vpy, rest, root
            )
            if u2 > max_u2:
                max_u2 = u2
            sfdx += fdx
            sfdy += fdy
            fx += fdx
            fy += fdy
            opx += fx
            opy += fy
            if has_ext:
                fx += ext[i, 0]
                fy += ext[i, 1]
            d = R - (y - h[i])
            S[DELTA, i] = d
            fcx, fcy, dmpx, dmpy, diss, lost, gone = film(
                i, x, y, vx, vy, d, c, k, h, cand, attached, slip, S, fast2, slow2, diss
            )
            if lost:
                lost_idx[nl] = i
                nl += 1
            if gone:
                gone_idx[ng] = i
                ng += 1
            if attached[i]:
                fx += fcx
                fy += fcy
            S[FX, i], S[FY, i], S[DMPX, i], S[DMPY, i] = fx, fy, dmpx, dmpy
            out[rows[i], 0], out[rows[i], 1] = fx, fy
            vmx = fx * hm + vx
            vmy = fy * hm + vy
            dd += (fdx + dmpx) * vmx + (fdy + dmpy) * vmy
            dr = abs(x - pad_c[i])
            if dr > drift:
                drift = dr
        res[0], res[1] = opx, opy
        res[2] = diss - (dd - vpx * sfdx - vpy * sfdy) * c.dt
        res[3], res[4], res[5], res[6] = nl, ng, max_u2, drift

    return jit(loop)


def numba_available() -> bool:
    """Whether numba is installed (a dependency: ``pip install numba``)."""
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True
