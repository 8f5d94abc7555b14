"""Force control: approach until the array carries a preload, then retract.

:func:`preload_pull` does one preload; :func:`preload_pulls` does several with one shared
approach and the retracts batched into one vectorized solve. The turning point is bisected
from the state before the step that passed it, so the preload is hit to 1e-9 relative.
Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from gecko_agents.history import STATE_FREE as FREE
from gecko_agents.params import SetaArray
from gecko_agents.quasistatic.heights import contact_front, plate_start_height
from gecko_agents.quasistatic.linear import step as linear_step
from gecko_agents.quasistatic.result import QuasiStaticResult, Recorder
from gecko_agents.quasistatic.rod import RodSetup, RodState, rod_step
from gecko_agents.quasistatic.solve import blocks_of, setup, travel_up
from gecko_agents.quasistatic.state import State, concat_states, take_state


def _approach_step(params: SetaArray, dz) -> float:
    """The approach step [µm]: ``dz``, by default |δc|/20."""
    dz = abs(params.contact.snap_off_overlap) / 20 if dz is None else float(dz)
    if not dz > 0:
        raise ValueError(f"dz = {dz!r} must be > 0 [µm]")
    return dz


def preload_pull(
    params: SetaArray,
    heights,
    preload: float,
    *,
    dz: float | None = None,
    weights=None,
    lateral: str = "coupled",
    stiffness_scale: float = 1.0,
    tangential_stiffness: float = math.inf,
    record_setae: bool = False,
    max_steps: int = 200_000,
    retract_steps: int | None = None,
    sample=None,
) -> QuasiStaticResult:
    """Force control: approach until the total normal force equals ``preload`` [µN], retract.

    The turning point is found by bisection on the last approach step (restarting from the
    saved state), so the preload is hit to 1e-9 relative; the plate then retracts in up to
    ``retract_steps`` (default 4000) steps of at least ``dz`` [µm] over
    :func:`retract_travel`, stopping once every seta has let go.

    Parameters
    ----------
    preload : target compressive force [µN], > 0.
    dz : plate step [µm]; default |δc|/20.
    weights, sample : see :func:`solve` (with a sample, blocks are split as they go).
    """
    if not preload > 0:
        raise ValueError(f"preload = {preload!r} must be > 0 [µN]")
    br = setup(params, lateral, stiffness_scale, tangential_stiffness)
    rod = isinstance(br, RodSetup)
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    dz = _approach_step(params, dz)
    blocks = blocks_of(sample, w, h, rod, record_setae)
    top = h if sample is None else sample[-1:]
    st = RodState(h.size) if rod else State(h.size)
    Z_start = plate_start_height(params, top, 0.5)
    path = _ForcePath(br, h, w, blocks, Z_start)
    st, Z = path.approach(st, Z_start, dz, preload, max_steps)
    # Retract until every seta has let go; a soft seta can stretch by up to ~Fc/Ky first.
    n_up = retract_steps or 4000
    dz_up = max(dz, travel_up(params, br, top, Z) / n_up)
    path.retract(st, Z, dz_up, n_up)
    if path.blocks is not None:
        h, w = path.blocks.h, path.blocks.w
    rec = Recorder(len(path.Zs), h.size, record_setae)
    for i, ((P, Ft, d, rel, rel_d), s, wk) in enumerate(path.results):
        rec.record(i, P, Ft, d, s, wk, rel, rel_d)
    return rec.result(np.asarray(path.Zs), w, h)


class _ForcePath:
    """One plate path under force control: the steps taken, kept as (Z, equilibria, state,
    weights), over fixed heights ``h`` and weights ``w`` or over splitting ``blocks``, from
    the start height ``Z_start`` [µm]."""

    def __init__(self, br, h, w, blocks, Z_start):
        self.br, self.h, self.w, self.blocks = br, h, w, blocks
        self.Z_start = Z_start
        self.Zs, self.results = [], []

    def advance(self, state, blk, Z):
        """Equilibria at plate height Z from ``state`` (updated), and the weights they carry."""
        if isinstance(self.br, RodSetup):
            return rod_step(self.br, state, Z, self.h), self.w
        if blk is None:
            return linear_step(self.br, state, Z, self.h), self.w
        return blk.step(self.br, state, Z), blk.w

    def keep(self, Z, res, state, weights):
        self.Zs.append(Z)
        self.results.append((res, state.copy(), weights))

    def approach(self, st, Z, dz, preload, max_steps):
        """Step down by ``dz`` until the force reaches ``preload``; bisect that last step.

        Returns the state at the turning point and its plate height [µm].
        """
        for _ in range(max_steps):
            saved = (st.copy(), None if self.blocks is None else self.blocks.copy())
            res, wk = self.advance(st, self.blocks, Z)
            if np.sum(wk * res[0]) < preload:
                self.keep(Z, res, st, wk)
                Z -= dz
                continue
            res, st, self.blocks, wk, Z = self._bisect(
                saved, (res, st, self.blocks, wk), Z, dz, preload
            )
            self.keep(Z, res, st, wk)
            return st, Z
        raise RuntimeError(
            f"preload {preload} µN not reached within {max_steps} steps of "
            f"{dz} µm; the floor may be out of reach"
        )

    def _bisect(self, saved, best, Z, dz, preload):
        """Overshot: bisect the plate height between the last two steps from the saved state.

        Returns (equilibria, state, blocks, weights, plate height) at the turning point.
        """
        lo, hi = Z + dz, Z
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            trial = saved[0].copy()
            tblk = None if self.blocks is None else saved[1].copy()
            r, wt = self.advance(trial, tblk, mid)
            if np.sum(wt * r[0]) >= preload:
                hi, best = mid, (r, trial, tblk, wt)
                if np.sum(wt * r[0]) - preload <= 1e-9 * preload:
                    break
            else:
                lo = mid
        return (*best, hi)

    def retract(self, st, Z, dz_up, n_up):
        """Step up by ``dz_up`` until every seta has let go past the start (at most n_up)."""
        for _ in range(n_up):
            Z += dz_up
            res, wk = self.advance(st, self.blocks, Z)
            self.keep(Z, res, st, wk)
            if Z > self.Z_start and not np.any(st.state != FREE):
                break


class _Turn(NamedTuple):
    """The turning point of one preload: plate height Z [µm], the state there and its
    equilibria (as a step returns them), the number of approach steps before it, and the
    heights [µm] and weights of the setae then represented."""

    Z: float
    state: State
    res: tuple
    n_before: int
    heights: np.ndarray
    weights: np.ndarray


def preload_pulls(
    params: SetaArray,
    heights,
    preloads,
    *,
    dz: float | None = None,
    weights=None,
    lateral: str = "coupled",
    stiffness_scale: float = 1.0,
    tangential_stiffness: float = math.inf,
    max_steps: int = 200_000,
    retract_steps: int | None = None,
    gaussian: tuple | None = None,
    refine_peak: bool = False,
    retract_dz: float | None = None,
    approach_stride: int = 1,
    retract_stride: int = 1,
    turning: str = "secant",
) -> list[QuasiStaticResult]:
    """:func:`preload_pull` for several preloads [µN] at once, with one shared approach.

    The plate approaches once, on the same grid of steps ``dz`` as :func:`preload_pull`; each
    time the total normal force passes the next preload, that turning point is found by
    bisection from the state before the step (as :func:`preload_pull` does) and saved, and the
    approach goes on from the unbisected step. The retracts from all saved states then run
    together as one vectorized solve over (preloads × setae), each with the step
    :func:`preload_pull` would use. Every result equals :func:`preload_pull`'s for that preload
    (same plate heights, same equilibria; tested), in about the time of the deepest one.

    Parameters as :func:`preload_pull` (no ``sample``: plain representative heights, e.g.
    :func:`quantile_heights`); ``preloads`` [µN], each > 0, in any order.

    ``gaussian = (sigma, edges)``: the heights are the slices of a Gaussian floor of RMS sigma
    [µm] between the standard quantiles ``edges`` (n + 1, from −∞ to +∞;
    ``quantile_heights(..., return_edges=True)``). During the approach each slice is then
    represented by the part of it above the contact front h_t(Z) = Z − R − L sin θ (setae
    below it have not touched): weight w·Pr(z > z_t | slice), height σ·E[z | z > z_t, slice]
    (truncated normal), so a slice enters contact gradually instead of all at once and the
    force, the turning point and the pull-off vary continuously with every parameter (a plain
    grid jumps by one block whenever the block at the front changes). Slices wholly below the
    front sit at their top edge. The plate starts where 0.1 seta is expected above the front.
    The retract keeps each preload's slices as they were at its turning point.

    ``refine_peak``: the tension of an array of blocks rises between releases and drops at
    each, so its sampled maximum (the top of one tooth) moves by up to one plate step's rise
    whenever a release crosses a step. With this option the step that ends the highest
    sampled tooth is bisected (30 halvings, from the state before it) for the last plate height
    before any of that copy's setae lets go, and that point is added to the curve: the
    pull-off is then the tooth's exact top, continuous in the parameters.

    ``retract_dz`` [µm]: an upper bound on the retract step max(dz, travel/retract_steps); the
    retract then goes on until every seta has let go (up to 10× the estimated travel).

    ``approach_stride``: once every seta is attached and pressed (P > 0), the approach steps
    grow (doubling) up to this many ``dz``, and a long step that changed any seta's state
    (stick, slide, its direction) is taken again in steps of ``dz``. A step that changes no
    state lands where the short ones would (eq 22–27): a stuck tip's equilibrium depends only
    on its anchor and the plate height, a sliding one's only on the plate height (its anchor
    trails it at the cap); so the turning points and retracts are those of ``dz`` steps to the
    root finder's 1e-9 (tested), with far fewer steps down a deep press. Linear setae on
    fixed heights only (1 otherwise); the approach's record is then sparser.

    ``retract_stride``: the same on the retract's grid of steps (not with ``refine_peak``):
    a copy whose last step changed no seta's state moves up to this many steps at once, and
    one step at a time again where a move changed one. On a branch each seta's force is
    monotone in the plate height (eq 22–27), so the force is monotone between state changes
    and the steps next to every change (every release among them) are still visited: the
    sampled pull-off, the releases and the attached counts are those of single steps.

    ``turning``: how a turning point is found in its step: ``"secant"`` (Illinois regula
    falsi, few solves) or ``"bisect"`` (halving, as :func:`preload_pull` does). Where the force
    is not monotone within a step (a block jumping in pulls) the two may stop at different
    crossings of the preload, a block apart; ``"bisect"`` stops where :func:`preload_pull` does.

    Returns
    -------
    One :class:`QuasiStaticResult` per preload, in the order given.
    """
    pre = np.atleast_1d(np.asarray(preloads, dtype=float))
    if pre.size == 0 or not np.all(pre > 0):
        raise ValueError(f"preloads = {preloads!r} must be one or more forces > 0 [µN]")
    br = setup(params, lateral, stiffness_scale, tangential_stiffness)
    rod = isinstance(br, RodSetup)
    step_fn = rod_step if rod else linear_step
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    at, Z_start, top = contact_front(params, h, w, gaussian)
    dz = _approach_step(params, dz)
    st = RodState(h.size) if rod else State(h.size)
    if not (isinstance(approach_stride, int) and approach_stride >= 1):
        raise ValueError(f"approach_stride = {approach_stride!r} must be an integer ≥ 1")
    if turning not in ("secant", "bisect"):
        raise ValueError(f"turning = {turning!r} must be 'secant' or 'bisect'")
    if not (isinstance(retract_stride, int) and retract_stride >= 1):
        raise ValueError(f"retract_stride = {retract_stride!r} must be an integer ≥ 1")
    stride = approach_stride if gaussian is None and not rod else 1
    turn = _turning_point if turning == "secant" else _bisected_turn
    approach, turns = _shared_approach(
        br, step_fn, at, st, (Z_start, dz, stride), pre, max_steps, turn
    )
    # Retracts of every preload together: copy c of the setae starts from turn c.
    Zc = np.array([turns[c].Z for c in range(pre.size)])
    dzc, n_c, n_up = _retract_schedule(params, br, top, Zc, dz, retract_steps, retract_dz)
    rec, peaks, hh, ww = _batched_retracts(
        br,
        step_fn,
        [turns[c] for c in range(pre.size)],
        (Zc, dzc, n_c, n_up, Z_start),
        refine_peak,
        1 if refine_peak or rod else retract_stride,
    )
    if refine_peak:
        _refine_peaks(br, step_fn, rec, peaks, hh, ww, h.size, Zc, dzc)
    return [_joined(approach, turns[c], rec[c]) for c in range(pre.size)]


def _changed(before, after) -> bool:
    """Whether a step changed any seta's contact state or slide direction."""
    return bool(np.any(before.state != after.state) or np.any(before.sigma != after.sigma))


def _shared_approach(br, step_fn, at, st, path, pre, max_steps, turn):
    """Step the plate down by ``dz`` from Z [µm] (``path`` = (Z, dz, stride)); each time the
    force passes the next preload, find that turning point (``turn``: :func:`_turning_point`
    or :func:`_bisected_turn`) from the state before the step and go on. With ``stride`` > 1,
    steps of up to ``stride``·dz where every seta is attached and pressed (see
    :func:`preload_pulls`' ``approach_stride``).

    Returns (the approach's Z, F, T, n lists by key, :class:`_Turn` by preload index).
    """
    Z, dz, stride = path
    order = np.argsort(pre, kind="stable")
    ap = {"Z": [], "F": [], "T": [], "n": []}
    turns = {}
    k, gap = 0, dz  # gap: this step's plate travel [µm]
    for _ in range(max_steps):
        saved = st.copy()
        hz, wz = at(Z)
        res = step_fn(br, st, Z, hz)
        if gap > dz and _changed(saved, st):  # a long step that changed a state: retake it
            st, Z, gap = saved, Z + gap - dz, dz
            continue
        F = float(np.sum(wz * res[0]))
        while k < order.size and F >= pre[order[k]]:
            target = pre[order[k]]
            F_prev = ap["F"][-1] if ap["F"] else 0.0
            hi, best = turn(
                br, step_fn, at, saved, Z, gap, (F_prev, F), target, (res, st.copy(), hz, wz)
            )
            turns[int(order[k])] = _Turn(hi, best[1], best[0], len(ap["Z"]), best[2], best[3])
            k += 1
        if k == order.size:
            return ap, turns
        ap["Z"].append(Z)
        ap["F"].append(F)
        ap["T"].append(float(np.sum(wz * res[1])))
        ap["n"].append(float(np.sum(wz[st.state != FREE])))
        pressed = stride > 1 and np.all(res[0] > 0) and not np.any(st.state == FREE)
        gap = min(2 * gap, stride * dz) if pressed else dz
        Z -= gap
    raise RuntimeError(
        f"preload {pre[order[k]]} µN not reached within {max_steps} steps of "
        f"{dz} µm; the floor may be out of reach"
    )


def _turning_point(br, step_fn, at, saved, Z, dz, forces, target, best):
    """Plate height [µm] in (Z, Z + dz] where the force first reaches ``target`` [µN], to 1e-9
    of it, and (equilibria, state, heights, weights) there.

    Illinois regula falsi on the plate height between the last two steps (the force grows as
    the plate descends; ``forces`` at Z + dz and at Z), from the state ``saved`` before the
    step; bisection where the secant leaves the bracket. ``best``: what the step at Z gave.
    """
    lo, hi = Z + dz, Z
    f_lo = forces[0] - target
    f_hi, side = forces[1] - target, 0
    gap = f_hi  # the true excess force at hi (f_hi is halved by the Illinois rule)
    for _ in range(60):
        if gap <= 1e-9 * target:
            break
        mid = hi - f_hi * (hi - lo) / (f_hi - f_lo) if f_hi != f_lo else 0.5 * (lo + hi)
        if not hi < mid < lo:
            mid = 0.5 * (lo + hi)
        trial = saved.copy()
        hm, wm = at(mid)
        r = step_fn(br, trial, mid, hm)
        Fm = float(np.sum(wm * r[0]))
        if Fm >= target:
            hi, f_hi, best = mid, Fm - target, (r, trial, hm, wm)
            gap = f_hi
            if side == 1:
                f_lo *= 0.5
            side = 1
        else:
            lo, f_lo = mid, Fm - target
            if side == -1:
                f_hi *= 0.5
            side = -1
    return hi, best


def _bisected_turn(br, step_fn, at, saved, Z, dz, forces, target, best):
    """:func:`_turning_point` by halving the step, as :meth:`_ForcePath._bisect` does: the
    highest plate height found with force ≥ ``target`` [µN] (to 1e-9 of it, or after 60
    halvings) and (equilibria, state, heights, weights) there."""
    lo, hi = Z + dz, Z
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        trial = saved.copy()
        hm, wm = at(mid)
        r = step_fn(br, trial, mid, hm)
        Fm = float(np.sum(wm * r[0]))
        if Fm >= target:
            hi, best = mid, (r, trial, hm, wm)
            if Fm - target <= 1e-9 * target:
                break
        else:
            lo = mid
    return hi, best


def _retract_schedule(params, br, top, Zc, dz, retract_steps, retract_dz):
    """Retract step of each copy [µm], its number of steps, and the most of any copy."""
    n_up = retract_steps or 4000
    trav = np.array([travel_up(params, br, top, Zc[c]) for c in range(Zc.size)])
    dzc = np.maximum(dz, trav / n_up)
    n_c = np.full(Zc.size, n_up)
    if retract_dz is not None:
        if not retract_dz > 0:
            raise ValueError(f"retract_dz = {retract_dz!r} must be > 0 [µm]")
        # A step of at most retract_dz; a rod can swing past upright and hold on beyond the
        # estimated travel, so a copy goes on (up to 10× the estimate) until all have let go.
        dzc = np.minimum(dzc, float(retract_dz))
        n_c = (10 * np.maximum(n_up, np.ceil(trav / dzc))).astype(int)
        n_up = int(n_c.max())
    return dzc, n_c, n_up


def _turn_record(turn: _Turn, Z) -> dict:
    """The first retract record of a copy: its turning point at plate height Z [µm]."""
    r, wt = turn.res, turn.weights
    return {
        "Z": [Z],
        "F": [float(np.sum(wt * r[0]))],
        "T": [float(np.sum(wt * r[1]))],
        "n": [float(np.sum(wt[turn.state.state != FREE]))],
        "rel": [(0, int(j), float(r[4][j])) for j in np.flatnonzero(r[3])],
    }


def _batched_retracts(br, step_fn, turns, grid, refine_peak, stride=1):
    """The retracts of all copies as one solve over (copies × setae), each copy from its turn.

    ``grid`` = (Zc, dzc, n_c, n_up, Z_start): copy c visits plate heights Zc[c] + t·dzc[c],
    t = 1 … n_c[c] (at most n_up moves), and stops once all its setae have let go above
    ``Z_start`` [µm]. With ``stride`` > 1 (not with ``refine_peak``) a copy whose
    last step changed no seta's state moves up to ``stride`` steps of the grid at once, and
    takes such a move again step by step where it changed one (see :func:`preload_pulls`'
    ``retract_stride``). Returns (the records of each copy, its highest sampled tension (F,
    step, state before the next step), the concatenated heights [µm] and weights of all
    copies).
    """
    Zc, dzc, n_c, n_up, Z_start = grid
    K, n = len(turns), turns[0].heights.size
    big = concat_states([turn.state for turn in turns])
    hh = np.concatenate([turn.heights for turn in turns])
    ww = np.concatenate([turn.weights for turn in turns])
    owner = np.repeat(np.arange(K), n)
    rec = [_turn_record(turns[c], Zc[c]) for c in range(K)]
    active, sel = np.arange(K), np.arange(K * n)
    tc, gap = np.zeros(K, dtype=int), np.ones(K, dtype=int)  # grid step, next move
    peaks = {c: (rec[c]["F"][0], 0, take_state(big, slice(c * n, (c + 1) * n))) for c in range(K)}
    for _ in range(n_up):
        gap[active] = np.minimum(gap[active], n_c[active] - tc[active])
        saved = big.copy() if stride > 1 else None
        o = owner[sel]
        out = step_fn(br, big, Zc[o] + (tc[o] + gap[o]) * dzc[o], hh[sel])
        changed = np.zeros(active.size, dtype=bool)
        if saved is not None:
            changed = ((saved.state != big.state) | (saved.sigma != big.sigma)).reshape(-1, n)
            changed = changed.any(axis=1)
            redo = np.flatnonzero(changed & (gap[active] > 1))
            if redo.size:  # a long move that changed a state: one grid step instead
                gap[active[redo]] = 1
                rows = (redo[:, None] * n + np.arange(n)[None, :]).ravel()
                o = owner[sel[rows]]
                _retake(
                    br, step_fn, saved, big, out, rows, Zc[o] + (tc[o] + 1) * dzc[o], hh[sel[rows]]
                )
        tc[active] += gap[active]
        P, Ft, _, rel, rel_d = out
        att = big.state != FREE
        wp, wf, wa = ww[sel] * P, ww[sel] * Ft, ww[sel] * att
        done = []
        for m, c in enumerate(active):
            s = slice(m * n, (m + 1) * n)
            rc, t = rec[c], int(tc[c])
            rc["Z"].append(Zc[c] + t * dzc[c])
            rc["F"].append(float(wp[s].sum()))
            rc["T"].append(float(wf[s].sum()))
            rc["n"].append(float(wa[s].sum()))
            for j in np.flatnonzero(rel[s]):
                rc["rel"].append((len(rc["Z"]) - 1, int(j), float(rel_d[s][j])))
            if refine_peak and rc["F"][-1] < peaks[c][0]:
                peaks[c] = (rc["F"][-1], t, take_state(big, np.arange(m * n, (m + 1) * n)))
            if t >= n_c[c] or (rc["Z"][-1] > Z_start and not att[s].any()):
                done.append(m)
            gap[c] = min(2 * gap[c], stride) if stride > 1 and not changed[m] else 1
        if done:
            keep = np.setdiff1d(np.arange(active.size), done)
            if keep.size == 0:
                break
            rows = (keep[:, None] * n + np.arange(n)[None, :]).ravel()
            big = take_state(big, rows)
            sel = sel[rows]
            active = active[keep]
    return rec, peaks, hh, ww


def _retake(br, step_fn, saved, big, out, rows, Z, h) -> None:
    """Step the setae ``rows`` again from ``saved`` to plate heights ``Z`` [µm] over floor
    heights ``h`` [µm], writing their state into ``big`` and their equilibria into ``out``."""
    sub = take_state(saved, rows)
    again = step_fn(br, sub, Z, h)
    for k in vars(big):
        getattr(big, k)[rows] = getattr(sub, k)
    for arr, new in zip(out, again, strict=True):
        arr[rows] = new


def _joined(approach: dict, turn: _Turn, rc: dict) -> QuasiStaticResult:
    """The shared approach up to a copy's turning point followed by that copy's retract."""
    na = turn.n_before
    return QuasiStaticResult(
        np.array(approach["Z"][:na] + rc["Z"]),
        np.array(approach["F"][:na] + rc["F"]),
        np.array(approach["T"][:na] + rc["T"]),
        np.array(approach["n"][:na] + rc["n"]),
        turn.weights,
        turn.heights,
        {},
        [(i + na, j, d) for i, j, d in rc["rel"]],
    )


def _refine_peaks(br, step_fn, rec, peaks, hh, ww, n, Zc, dzc, halvings: int = 30):
    """Bisect, for every copy at once, the step after its highest sampled tension for the
    last plate height before a release; insert that point into the copy's record.

    ``peaks``: copy → (tension, step, state at that step), as :func:`_batched_retracts`
    gives; ``n`` setae per copy.
    """
    cs = [
        c
        for c, (_, t, _) in peaks.items()
        if t + 1 < len(rec[c]["F"]) and any(i == t + 1 for i, _, _ in rec[c]["rel"])
    ]
    if not cs:
        return
    base = concat_states([peaks[c][2] for c in cs])
    rows = np.concatenate([np.arange(c * n, (c + 1) * n) for c in cs])
    lo = np.array([Zc[c] + peaks[c][1] * dzc[c] for c in cs])
    hi = lo + np.array([dzc[c] for c in cs])
    keep = [None] * len(cs)
    for _ in range(halvings):
        mid = 0.5 * (lo + hi)
        trial = base.copy()
        P, Ft, _, rel, _ = step_fn(br, trial, np.repeat(mid, n), hh[rows])
        for m in range(len(cs)):
            s = slice(m * n, (m + 1) * n)
            if rel[s].any():
                hi[m] = mid[m]
            else:
                lo[m] = mid[m]
                w = ww[rows][s]
                att = trial.state[s] != FREE
                keep[m] = (mid[m], (w * P[s]).sum(), (w * Ft[s]).sum(), w[att].sum())
    for m, c in enumerate(cs):
        if keep[m] is None:
            continue
        t = peaks[c][1]
        rc = rec[c]
        for key, v in zip(("Z", "F", "T", "n"), keep[m], strict=True):
            rc[key].insert(t + 1, float(v))
        rc["rel"] = [(i + (i > t), j, d) for i, j, d in rc["rel"]]
