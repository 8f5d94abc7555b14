"""Blocks of consecutive setae of a sorted height sample, split where their histories part.

Lets a few thousand representative setae reproduce the force curve of all 10⁷ of a sorted
sample of floor heights to ~1e-9 of its peak (see :mod:`gecko_agents.quasistatic`). Linear
seta only. Units: µm, µN.
"""

from __future__ import annotations

import numpy as np

from gecko_agents.history import STATE_FREE as FREE
from gecko_agents.history import STATE_SLIP as SLIP
from gecko_agents.history import STATE_STICK as STICK
from gecko_agents.quasistatic.branches import Branches
from gecko_agents.quasistatic.linear import step as linear_step
from gecko_agents.quasistatic.state import State


class Blocks:
    """Blocks of consecutive setae of a sorted height sample, split on the fly.

    Every seta's history under the plate path depends on its height alone and is smooth in it
    except where a discrete decision changes: jump-in, stick or slide, slide direction, release.
    After each plate step, a block in which such a boundary now lies is split there, and both
    parts are re-solved from the block's state before the step, so each block keeps setae with
    one discrete history and its mean height represents them to second order. Where the
    boundary lies: jump-in at h = Z − L sin θ − R (exact); release at the slide branch's fold
    where G_fold − target, which is linear in h with slope 1, vanishes (exact); stick/slide and
    slide direction by linear interpolation of the decision variable between the two
    neighbouring blocks that decided differently.
    """

    def __init__(self, sample, weights, heights):
        sample = np.asarray(sample, dtype=float)
        counts = np.asarray(weights, dtype=float)
        if sample.ndim != 1 or sample.size == 0 or np.any(np.diff(sample) < 0):
            raise ValueError("sample must be the sorted 1-D array of setae heights [µm]")
        if (
            np.any(counts < 1)
            or np.any(counts != np.round(counts))
            or int(counts.sum()) != sample.size
        ):
            raise ValueError(
                "with a sample, weights must be the whole numbers of consecutive "
                f"setae in each block, summing to the sample size {sample.size}"
            )
        self.sample = sample
        self.hi = np.cumsum(counts.astype(np.int64))
        self.lo = self.hi - counts.astype(np.int64)
        means = np.add.reduceat(sample, self.lo) / counts
        h = np.asarray(heights, dtype=float)
        if h.shape != means.shape or not np.allclose(h, means, rtol=0.0, atol=1e-9):
            raise ValueError(
                "heights must be the means of the sample's consecutive blocks of "
                "`weights` setae (as representative_heights(..., "
                "return_sample=True) gives)"
            )
        self.h, self.w = h.copy(), counts.copy()
        self.hmin, self.hmax = sample[self.lo], sample[self.hi - 1]

    def copy(self):
        c = object.__new__(Blocks)
        c.sample = self.sample
        for k in ("h", "w", "lo", "hi", "hmin", "hmax"):
            setattr(c, k, getattr(self, k).copy())
        return c

    @staticmethod
    def _codes(st):
        return np.where(
            st.state == FREE, 0, np.where(st.state == STICK, 1, np.where(st.sigma > 0, 2, 3))
        )

    def step(self, br: Branches, st: State, Z: float):
        """:func:`~gecko_agents.quasistatic.linear.step` on the blocks, then split the blocks a
        boundary now runs through."""
        pre = st.copy()
        P, Ft, d, rel, rel_d, mg = linear_step(br, st, Z, self.h, margins=True)
        splits = self._boundaries(br, Z, pre, st, mg)
        if not splits:
            return P, Ft, d, rel, rel_d
        return self._split(br, Z, pre, st, splits, (P, Ft, d, rel, rel_d))

    def _boundaries(self, br: Branches, Z: float, pre: State, st: State, mg) -> dict:
        """Block index → height of the decision boundary that now lies inside it [µm]."""
        c0, c1 = self._codes(pre), self._codes(st)
        splits = {}
        h, hmin, hmax = self.h, self.hmin, self.hmax
        # Jump-in: setae with h ≥ Z − (R + L sin θ) touch; the block holding that height.
        h_in = Z - br.touchdown
        j = int(np.searchsorted(hmax, h_in))
        if j < h.size and hmin[j] < h_in and c0[j] == 0:
            splits[j] = h_in
        # Release: the slide branch's fold margin is linear in h with slope 1.
        fold = mg["fold"]
        cand = np.flatnonzero((c0 != 0) & ((c1 == 0) | (st.state == SLIP)) & np.isfinite(fold))
        if cand.size:
            hs = h[cand] - fold[cand]
            inside = (hmin[cand] < hs) & (hs <= hmax[cand])
            for jj, hh in zip(cand[inside].tolist(), hs[inside].tolist(), strict=True):
                splits.setdefault(jj, hh)
        # Stick/slide and slide direction: interpolate between neighbours that differ now.
        bnd = np.flatnonzero(
            (c1[1:] != c1[:-1]) & (c0[1:] == c0[:-1]) & (c1[1:] != 0) & (c1[:-1] != 0)
        )
        for b in bnd.tolist():
            g = mg["ft"] if {int(c1[b]), int(c1[b + 1])} == {2, 3} else mg["stick"]
            g1, g2 = g[b], g[b + 1]
            if not (np.isfinite(g1) and np.isfinite(g2)) or g1 == g2:
                continue
            hh = h[b] + (h[b + 1] - h[b]) * g1 / (g1 - g2)
            for jj in (b, b + 1):
                if hmin[jj] < hh <= hmax[jj]:
                    splits.setdefault(jj, hh)
        return splits

    def _split(self, br: Branches, Z: float, pre: State, st: State, splits: dict, res):
        """Split each block of ``splits`` at its boundary, re-solve both parts from the state
        before the step, and put them in place of the block in ``st`` and the step's output."""
        lo, hi = self.lo, self.hi
        js = np.array(sorted(splits), dtype=np.int64)
        cut = np.searchsorted(self.sample, [splits[j] for j in js.tolist()])
        cut = np.clip(cut, lo[js] + 1, hi[js] - 1)
        # The parts: lower [lo, cut), upper [cut, hi), each from the block's state before.
        plo, phi = np.concatenate([lo[js], cut]), np.concatenate([cut, hi[js]])
        ph = np.array([self.sample[a:b].mean() for a, b in zip(plo, phi, strict=True)])
        sub = State(0)
        sub.state, sub.sigma, sub.u = (
            np.concatenate([x[js], x[js]]) for x in (pre.state, pre.sigma, pre.u)
        )
        parts = linear_step(br, sub, Z, ph)
        m = js.size

        def put(a, part):  # block j becomes its lower part, its upper part follows it
            a = a.copy()
            a[js] = part[:m]
            return np.insert(a, js + 1, part[m:])

        self.h, self.lo, self.hi = put(self.h, ph), put(lo, plo), put(hi, phi)
        self.w = (self.hi - self.lo).astype(float)
        self.hmin, self.hmax = self.sample[self.lo], self.sample[self.hi - 1]
        st.state, st.sigma, st.u = (
            put(st.state, sub.state),
            put(st.sigma, sub.sigma),
            put(st.u, sub.u),
        )
        return tuple(put(a, p) for a, p in zip(res, parts, strict=True))
