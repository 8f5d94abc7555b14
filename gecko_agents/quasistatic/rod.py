"""The quasi-static ``rod`` seta (``params.mechanics == "rod"``): large rotations, solved by Newton.

The rod is rigid, pivots at its root on a rotary spring and stretches on an axial spring
(:func:`rod_force`); its JKR tip (eq 7, 10) sticks or slides under Coulomb friction and lets go
where the rod–contact equilibrium folds. Each plate position is one damped Newton solve per seta
(:func:`rod_newton`, :func:`rod_step`). Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from gecko_agents.history import STATE_FREE as FREE
from gecko_agents.history import STATE_SLIP as SLIP
from gecko_agents.history import STATE_STICK as STICK
from gecko_agents.params import SetaArray
from gecko_agents.physics import jkr
from gecko_agents.quasistatic.heights import plate_start_height
from gecko_agents.quasistatic.rod_equilibrium import rod_force, rod_newton
from gecko_agents.quasistatic.rod_setup import RodSetup
from gecko_agents.quasistatic.state import State, jump_in


class RodState(State):
    """:class:`~gecko_agents.quasistatic.state.State` plus the rod tip abscissa x [µm] (from the
    root),
    contact radius a [µm] and tangential contact force ft [µN] of each seta's last
    equilibrium."""

    def __init__(self, n):
        super().__init__(n)
        self.x = np.zeros(n)
        self.a = np.zeros(n)
        self.ft = np.zeros(n)

    def copy(self):
        c = RodState(0)
        for k in ("state", "sigma", "u", "x", "a", "ft"):
            setattr(c, k, getattr(self, k).copy())
        return c


def rod_step(rs: RodSetup, st: RodState, Z: float, h: np.ndarray):
    """Equilibrate every rod seta at plate height Z; update ``st`` in place.

    As :func:`~gecko_agents.quasistatic.linear.step`, with the large-rotation rod instead of the
    linear spring: a free tip jumps in where it touches (δ ≥ 0) and anchors there; an attached
    tip first tries to stick at its anchor (F_t = −k_t(x − anchor), |F_t| ≤ cap), otherwise
    slides with F_t = ±cap in the direction the stick trial demanded (return mapping, as the
    agent model). Where neither has a stable equilibrium within 0.1 L but the stick trial has
    a normal equilibrium, the tip slips to the next sliding equilibrium
    (``_rod_slip``); otherwise the spring–contact system has folded and the tip lets go.
    The overlap recorded for a release is that of the tip's last equilibrium (within one plate
    step of the fold). ``st.u`` is the anchor relative to the rest tip
    abscissa [µm].

    Returns (P, F_t, δ, released mask, release overlaps), as
    :func:`~gecko_agents.quasistatic.linear.step`.
    """
    n = len(h)
    x0, y0 = rs.rest
    c = h + rs.R - Z
    # (P, F_t, δ, released, release overlap); a free tip has δ = c − y0.
    out = (np.zeros(n), np.zeros(n), c - y0, np.zeros(n, dtype=bool), np.full(n, np.nan))
    jump, att = jump_in(st, out[2])
    if jump.any():
        st.x[jump] = x0
        st.a[jump] = rs.a0
    idx = np.flatnonzero(att)
    if idx.size == 0:
        return out
    trial = _RodTrial(idx, c[idx], st.x[idx], st.a[idx], 0.1 * rs.L)
    sig = st.sigma[idx].copy()
    if rs.lateral == "free":
        todo = np.ones(idx.size, dtype=bool)
        sig[:] = 1.0
    else:
        todo, sig, stick = _rod_stick(rs, st, trial)
    if todo.any():
        t = np.flatnonzero(todo)
        s = sig[t] if rs.lateral == "coupled" else np.zeros(t.size)
        xk, ak, okk = rod_newton(rs, trial.c[t], trial.x[t], trial.a[t], s=s, max_jump=trial.jump)
        trial.new_x[t[okk]], trial.new_a[t[okk]] = xk[okk], ak[okk]
        trial.state[t[okk]] = SLIP
        sig[t] = s
        if rs.lateral == "coupled":
            xs, as_, held = stick
            slip = t[~okk & held[t]]
            _rod_slip(rs, trial, slip, sig, xs[slip], as_[slip])
    _rod_commit(rs, st, c, trial, sig, out)
    return out


class _RodTrial:
    """The attached setae ``idx`` of one rod step: their c = h + R − Z [µm], last tip abscissa
    x and contact radius a [µm], and the new equilibrium (new_x, new_a, state) being found.
    ``jump`` [µm]: the largest move of x that still counts as the same branch."""

    def __init__(self, idx, c, x, a, jump):
        self.idx, self.c, self.x, self.a, self.jump = idx, c, x, a, jump
        self.new_x, self.new_a = x.copy(), a.copy()
        self.state = np.full(idx.size, FREE, dtype=np.int8)


def _rod_stick(rs: RodSetup, st: RodState, tr: _RodTrial):
    """Stick trial at each anchor; where it holds within the cap, the tip sticks.

    Returns (the setae still to slide, their slide direction: the direction the spring
    demands, or where the stick branch has folded that of the last tangential force, and the
    stick trial's equilibria (x [µm], a [µm], where it has one)).
    """
    args = (rs.R, rs.w, rs.E_star)
    x0, _ = rs.rest
    anchor = x0 + st.u[tr.idx]
    xs, as_, ok = rod_newton(rs, tr.c, tr.x, tr.a, anchor=anchor, max_jump=tr.jump)
    Ps = jkr.force_from_radius(as_, *args)
    if math.isinf(rs.k_t):
        Fts = -rod_force(
            xs, tr.c - jkr.overlap_from_radius(as_, *args), rs.Ka, rs.k_phi, rs.L, rs.theta
        )[0][0]
    else:
        Fts = -rs.k_t * (xs - anchor)
    stick_ok = ok & (np.abs(Fts) <= rs.cap(Ps) * (1 + 1e-12))
    tr.new_x[stick_ok], tr.new_a[stick_ok] = xs[stick_ok], as_[stick_ok]
    tr.state[stick_ok] = STICK
    sig = np.where(np.where(ok, Fts, st.ft[tr.idx]) >= 0, 1.0, -1.0)
    return ~stick_ok, sig, (xs, as_, ok)


SLIP_STEPS = 40
"""Points of the search for the end of a slip, 0.05 L apart (a slip of up to 2 L)."""


def _rod_slip(rs: RodSetup, tr: _RodTrial, t: np.ndarray, sig, start, a) -> None:
    """A tip whose lateral equilibrium has folded while its normal one holds slips along the
    floor (friction at the cap, F_t = σ·cap(P)) to the first sliding equilibrium in its
    direction of motion −σ, and stays attached.

    ``t`` (indices into ``tr``): the tips with neither a stick nor a sliding equilibrium within
    ``tr.jump`` whose stick trial has a normal equilibrium (x = ``start``, a = ``a`` [µm]),
    where the slip starts; ``sig``: the direction σ = ±1 of the friction force the stick trial
    demanded (indexed as ``tr``). The tip is held at
    x = start − σ·k·0.05 L (k = 1 … :data:`SLIP_STEPS`), its normal equilibrium a(x)
    continued from one point to the next; the slip ends in the first interval where the rod's
    push −σ·F_x falls to the cap, found there by bisection to 2⁻⁴⁰ of the interval. It is
    the quasi-static (overdamped) limit of a frictional snap: the tip stops where the cap first
    holds it again, a stable sliding equilibrium (the push falls through the cap). Where the
    normal equilibrium folds on the way (the JKR branch ends), or the push never falls to the
    cap within 2 L, the tip lets go. Updates ``tr`` for the setae ``t``.
    """
    if t.size == 0:
        return
    hold = dataclasses.replace(rs, k_t=math.inf)  # the tip held at each x of the path
    args = (rs.R, rs.w, rs.E_star)
    c, s, a = tr.c[t], sig[t], a.copy()
    step = -s * 0.05 * rs.L

    def excess(k, x, a):
        """The push beyond the cap [µN] of the tips k held at x, and their a and ok."""
        _, ak, ok = rod_newton(hold, c[k], x, a, anchor=x)
        y = c[k] - jkr.overlap_from_radius(ak, *args)
        push = -s[k] * rod_force(x, y, rs.Ka, rs.k_phi, rs.L, rs.theta)[0][0]
        return push - rs.cap(jkr.force_from_radius(ak, *args)), ak, ok

    end = np.full(t.size, np.nan)  # the first sample past the end of the slip
    going = np.ones(t.size, dtype=bool)  # no end found, normal equilibrium held so far
    for n in range(1, SLIP_STEPS + 1):
        k = np.flatnonzero(going)
        if k.size == 0:
            break
        g, ak, ok = excess(k, start[k] + n * step[k], a[k])
        a[k] = np.where(ok, ak, a[k])
        going[k] = ok & (g > 0)
        hit = k[ok & (g <= 0)]
        end[hit] = start[hit] + n * step[hit]
    k = np.flatnonzero(np.isfinite(end))
    if k.size == 0:
        return
    lo, hi = end[k] - step[k], end[k]
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        g, ak, ok = excess(k, mid, a[k])
        past = ~ok | (g <= 0)
        hi, lo = np.where(past, mid, hi), np.where(past, lo, mid)
        a[k] = np.where(ok, ak, a[k])
    _, ak, ok = excess(k, hi, a[k])
    m = t[k[ok]]
    tr.new_x[m], tr.new_a[m] = hi[ok], ak[ok]
    tr.state[m] = SLIP


def _rod_commit(rs: RodSetup, st: RodState, c, tr: _RodTrial, sig, out):
    """Write the step's equilibria into ``st`` and ``out``; setae without one let go."""
    P, Ft, delta, released, rel_overlap = out
    args = (rs.R, rs.w, rs.E_star)
    x0, y0 = rs.rest
    idx, state, new_x, new_a = tr.idx, tr.state, tr.new_x, tr.new_a
    good = state != FREE
    j = idx[good]
    Pj = jkr.force_from_radius(new_a[good], *args)
    dj = jkr.overlap_from_radius(new_a[good], *args)
    P[j], delta[j] = Pj, dj
    slip = state[good] == SLIP
    capj = rs.cap(Pj)
    if rs.lateral == "free":
        Ft[j] = 0.0
    else:
        yj = c[j] - dj
        Ft[j] = -rod_force(new_x[good], yj, rs.Ka, rs.k_phi, rs.L, rs.theta)[0][0]
    st.state[idx] = state
    st.x[idx], st.a[idx] = new_x, new_a
    st.ft[idx] = Ft[idx]
    st.sigma[idx] = np.where(state == SLIP, sig, 0.0)
    # Anchor: a sliding tip's anchor trails it by cap/k_t (F_t = −k_t(x − anchor)).
    trail = capj[slip] * sig[good][slip] / rs.k_t  # 0 for a rigid stick (k_t = ∞)
    st.u[j[slip]] = new_x[good][slip] + trail - x0
    gone = idx[~good]
    if gone.size:
        released[gone] = True
        rel_overlap[gone] = jkr.overlap_from_radius(tr.a[~good], *args)
        st.state[gone] = FREE
        st.u[gone] = 0.0
        st.sigma[gone] = 0.0
        delta[gone] = c[gone] - y0


def rod_retract_travel(params: SetaArray, rs: RodSetup, heights, Z_from: float) -> float:
    """Plate travel up from Z_from [µm] after which every rod seta has surely let go [µm].

    Back past the start height, plus the swing of the rod to upright, L(1 − sin θ), its axial
    stretch under Fc and the stick spring's, and a margin of 20|δc|.
    """
    stretch = rs.Fc / rs.Ka + rs.Fc / rs.k_t  # no stick spring's stretch at k_t = ∞
    return (
        plate_start_height(params, heights, 0.0)
        - Z_from
        + rs.L * (1.0 - math.sin(rs.theta))
        + 1.5 * stretch
        + 20 * abs(params.contact.snap_off_overlap)
    )
