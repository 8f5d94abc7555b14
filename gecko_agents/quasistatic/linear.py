"""One plate position of the linear seta: every seta put in static equilibrium (eq 22–27).

Each seta is a linear spring between its root on the plate and a JKR tip on a locally flat
floor; the branches it can sit on are those of :class:`~gecko_agents.quasistatic.branches.Branches`.
A free tip jumps in where it touches; an attached tip sticks at its anchor if friction allows
(return mapping), else slides with F_t = ±cap; where no branch holds, it lets go at the fold.
Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

import numpy as np

from gecko_agents.history import STATE_FREE as FREE
from gecko_agents.history import STATE_SLIP as SLIP
from gecko_agents.history import STATE_STICK as STICK
from gecko_agents.physics import jkr
from gecko_agents.quasistatic.branches import Branches
from gecko_agents.quasistatic.state import State, jump_in


def step(br: Branches, st: State, Z: float, h: np.ndarray, margins: bool = False):
    """Equilibrate every seta at plate height Z; update ``st`` in place.

    Returns (P, F_t, δ, released mask, release overlaps), and with ``margins`` also the
    decision variables of attached setae (NaN elsewhere) that
    :class:`~gecko_agents.quasistatic.blocks.Blocks` splits blocks with: ``stick`` = cap − |F_t| of
    the
    stick trial (≥ 0: sticks), ``ft`` = F_t of the stick trial (its sign is the slide
    direction), ``fold`` = G_fold − target of the slide branch (< 0: no equilibrium, the tip
    lets go).
    """
    n = len(h)
    t0 = (Z - br.touchdown) - h  # G target for zero lateral shift
    # (P, F_t, δ, released, release overlap); a free tip has δ = h + R − p0_y.
    out = (np.zeros(n), np.zeros(n), -t0, np.zeros(n, dtype=bool), np.full(n, np.nan))
    _, att = jump_in(st, out[2])
    mg = {k: np.full(n, np.nan) for k in ("stick", "ft", "fold")} if margins else None
    idx = np.flatnonzero(att)
    if idx.size and br.lateral == "free":
        _free(br, st, t0, idx, out, mg)
    elif idx.size:
        stick_ok, exists, sig_all = _stick_trial(br, st, t0, idx, out, mg)
        if not stick_ok.all():
            k = ~stick_ok
            _slide_or_release(br, st, t0, idx[k], sig_all[k], exists[k], out)
    return out + ((mg,) if margins else ())


def _free(br: Branches, st: State, t0, idx, out, mg):
    """Eq 25: the tip free to move sideways, on the ``free`` branch or let go at its fold."""
    P, _, delta, released, rel_overlap = out
    args = (br.R, br.w, br.E_star)
    a = br.invert("free", t0[idx])
    ok = np.isfinite(a)
    ai = np.where(ok, a, br.a_fold["free"])
    Pi = jkr.force_from_radius(ai, *args)
    P[idx[ok]] = Pi[ok]
    delta[idx[ok]] = jkr.overlap_from_radius(ai[ok], *args)
    st.state[idx] = np.where(ok, SLIP, FREE)
    gone = idx[~ok]
    released[gone] = True
    rel_overlap[gone] = jkr.overlap_from_radius(br.a_fold["free"], *args)
    if mg is not None:
        mg["fold"][idx] = br.G_grid["free"][0] - t0[idx]


def _stick_trial(br: Branches, st: State, t0, idx, out, mg):
    """Stick at the previous anchor (u: anchor abscissa relative to the rest tip) where the
    tangential force stays within the cap; writes those setae into ``out``.

    Returns (sticks, the stick branch has an equilibrium, slide direction the spring demands)
    over ``idx``.
    """
    P, Ft, delta, _, _ = out
    args = (br.R, br.w, br.E_star)
    u = st.u[idx]
    t0i = t0[idx]
    a = br.invert("stick", t0i - br.r_t * br.Kxy * u / br.Kyy_stick)
    exists = np.isfinite(a)
    a_s = np.where(exists, a, br.a_fold["stick"])
    Ps = jkr.force_from_radius(a_s, *args)
    dy = (Ps - br.r_t * br.Kxy * u) / br.Kyy_stick
    e = br.r_t * u - (1.0 - br.r_t) * br.Kxy * dy / br.Kxx  # tip abscissa
    Ft_s = br.Kxx * e + br.Kxy * dy
    cap_s = br.cap(Ps)
    abs_ft = np.abs(Ft_s)
    stick_ok = abs_ft <= cap_s * (1 + 1e-12)
    stick_ok &= exists
    sig_all = np.where(Ft_s >= 0, 1.0, -1.0)
    if mg is not None:
        mg["stick"][idx] = np.where(exists, cap_s - abs_ft, -np.inf)
        mg["ft"][idx] = Ft_s
        mg["fold"][idx] = np.where(sig_all > 0, br.G_grid["slip+"][0], br.G_grid["slip-"][0]) - t0i
    if stick_ok.all():
        P[idx], Ft[idx] = Ps, Ft_s
        delta[idx] = jkr.overlap_from_radius(a_s, *args)
        st.state[idx] = STICK
        return stick_ok, exists, sig_all
    j = idx[stick_ok]
    P[j], Ft[j] = Ps[stick_ok], Ft_s[stick_ok]
    delta[j] = jkr.overlap_from_radius(a_s[stick_ok], *args)
    st.state[j] = STICK
    return stick_ok, exists, sig_all


def _slide_or_release(br: Branches, st: State, t0, jk, sig, stick_exists, out):
    """Setae ``jk`` that cannot stick slide, friction taking the sign ``sig`` the spring
    demanded; where the slide branch has no equilibrium either, the tip lets go at its fold."""
    P, Ft, delta, released, rel_overlap = out
    args = (br.R, br.w, br.E_star)
    was_sliding = st.state[jk] == SLIP  # the step before's state (the stick trial kept it)
    a_sl = np.full(jk.size, np.nan)
    fold = np.empty(jk.size)
    for s, name in ((1.0, "slip+"), (-1.0, "slip-")):
        m = sig == s
        if np.any(m):
            a_sl[m] = br.invert(name, t0[jk[m]])
            fold[m] = br.a_fold[name]
    ok = np.isfinite(a_sl)
    ai = np.where(ok, a_sl, fold)
    Pk = jkr.force_from_radius(ai, *args)
    cap = sig * br.cap(Pk)
    dyk = (Pk - br.Kxy / br.Kxx * cap) / br.Ky
    uk = (cap - br.Kxy * dyk) / br.Kxx
    good = jk[ok]
    P[good], Ft[good] = Pk[ok], cap[ok]
    delta[good] = jkr.overlap_from_radius(ai[ok], *args)
    st.state[good] = SLIP
    # The anchor trails the sliding tip by cap/k_t (F_t = −k_t·(tip − anchor)).
    st.u[good] = uk[ok] + (1.0 - br.r_t) / br.r_t * cap[ok] / br.Kxx
    st.sigma[good] = sig[ok]
    if not ok.all():  # no equilibrium on either branch: the tip lets go at its fold
        gone = jk[~ok]
        st.state[gone] = FREE
        st.u[gone] = 0.0
        released[gone] = True
        # Release overlap: the fold of the branch the tip was on, the slide's if it slid in
        # the step before or its stick held no longer; the stick's if it never slid.
        rel_a = np.where(stick_exists | was_sliding, fold, br.a_fold["stick"])[~ok]
        rel_overlap[gone] = jkr.overlap_from_radius(rel_a, *args)
        delta[gone] = -t0[gone]
