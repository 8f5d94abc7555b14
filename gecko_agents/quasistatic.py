"""The paper's quasi-static contact model (eq 22–27), vectorized over setae: our oracle.

Each seta is a linear spring (the 2×2 beam stiffness K of eq 16–21) between its root on the
plate and a JKR tip (eq 7, 10) on a locally flat floor at height h_i (eq 28). The plate moves
vertically through a list of heights Z; at every plate position every attached seta is put in
static equilibrium

    K·(p − p0) = (F_t, P),    p0 = root + L·(cos θ, −sin θ),    δ = h + R − p_y,

where p is the tip-sphere centre, P = P_JKR(δ) the normal force (positive compressive) and F_t
the tangential contact force. Lateral behaviour, chosen by ``lateral``:

* ``"coupled"`` (default): Coulomb stick/slip with the cap of ``params.friction`` (return
  mapping: try to stick at the previous tip abscissa; if |F_t| exceeds the cap, slide with
  F_t = ±cap). Sliding leaves the normal stiffness Ky of eq 20 plus a friction term; sticking
  gives the stiffer K_yy.
* ``"free"``: the paper's eq 25, F = y2·Ky: the tip is free to move sideways (no friction in
  the normal balance). Eq 26–27 then only describe the lateral bookkeeping.

Contact forms when the free tip touches the floor (δ = 0, jump-in) and is kept along the stable
JKR branch. It lets go where the spring–contact equilibrium ceases to exist: a fold, where the
contact stiffness dP/dδ equals −k with k the seta's effective normal stiffness in its current
stick/slip state (:func:`release_radius`). A soft seta (k → 0) lets go at the load-controlled
point (P = −Fc, a = 0.63 a0), a rigid one at δc (a = 0.303 a0).

Every seta's branch depends on its height only through a shift, so each branch is tabulated
once as a function of the contact radius a and inverted by interpolation plus Newton polishing:
one step costs O(N).

The paper's 10⁷ setae
---------------------
Every seta's history along the plate path depends on its floor height alone, smoothly except
where a discrete decision flips (jump-in, stick or slide, slide direction, release).
:func:`representative_heights` draws and sorts the heights and replaces them by the means of
blocks of consecutive setae, counted with their sizes; given the sorted sample too
(``return_sample=True``, then ``sample=`` to :func:`press_pull`, :func:`preload_pull` or
:func:`solve`), a block that a plate step leaves with such a boundary inside is split there and
both parts re-solved from the block's state before the step. Every block then holds setae with
one discrete history, its mean height represents them to second order, and 2000 blocks give the
curve of all 10⁷ setae solved one by one to ~1e-9 of the peak force (1000 plate positions in
about 1 s with the heights; ``python -m gecko_agents.bench``). Plain block means without the
sample err by about 0.7/n_blocks of the peak: a block crossing a boundary counts all its setae
on one side of it.

Units: µm, µN (see :mod:`gecko_agents.params`). The plate only moves vertically here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from . import beam, jkr
from .history import STATE_FREE as FREE
from .history import STATE_SLIP as SLIP
from .history import STATE_STICK as STICK
from .params import SetaArray

__all__ = [
    "release_radius",
    "Branches",
    "QuasiStaticResult",
    "solve",
    "press_pull",
    "retract_travel",
    "rod_force",
    "RodSetup",
    "rod_retract_travel",
    "preload_pull",
    "preload_pulls",
    "representative_heights",
    "quantile_heights",
    "plate_start_height",
    "single_seta",
]


def release_radius(k, R, w, E_star):
    """Contact radius at which a tip on a spring of stiffness k lets go [µm].

    The spring–contact equilibrium folds where dP/dδ = −k (:func:`jkr.contact_stiffness`);
    between a_c (k → ∞, displacement control) and 0.63 a0 (k → 0, load control).

    Parameters
    ----------
    k : effective normal stiffness of the mount [µN/µm], > 0.
    R [µm], w [µN/µm], E_star [MPa].
    """
    if not k > 0:
        raise ValueError(f"mount stiffness k = {k!r} must be > 0 [µN/µm]")
    ac = jkr.snap_off_radius(R, w, E_star)
    a_lc = 0.25 ** (1 / 3) * jkr.zero_load_contact_radius(R, w, E_star)

    def g(a):  # δ' + P'/k, sign change between a_c (P'<0, δ'=0) and a_lc (P'=0, δ'>0)
        dP = 4.0 * E_star * a * a / R - 1.5 * np.sqrt(8.0 * np.pi * w * E_star * a)
        dd = 2.0 * a / R - 0.5 * np.sqrt(2.0 * np.pi * w / (E_star * a))
        return dd + dP / k

    return brentq(g, ac * (1 + 1e-13), a_lc, xtol=1e-15 * ac, rtol=1e-15, maxiter=200)


@dataclass(frozen=True)
class Branches:
    """The equilibrium branches of one seta type, tabulated over the contact radius a.

    For branch b the plate height that holds a seta of floor height h at contact radius a is
    Z = h + R + L sin θ + shift + G_b(a), with G_b(a) = −δ(a) − D_b(a) and D_b the spring
    deflection: P/K_yy (stick), (P − qσ·cap(P))/Ky (slide in direction σ = ±1), P/Ky (free).
    Each G_b decreases for a above its fold a_fold[b]; inverting that part is the solve.
    """

    R: float
    w: float
    E_star: float
    Fc: float
    L: float
    theta: float
    Kxx: float
    Kxy: float
    Kyy: float
    Ky: float
    r_t: float
    Kyy_stick: float
    mu: float
    law: str
    lateral: str
    a_grid: dict = field(repr=False)
    G_grid: dict = field(repr=False)
    a_fold: dict = field(repr=False)

    @classmethod
    def from_params(
        cls,
        params: SetaArray,
        lateral: str = "coupled",
        stiffness_scale: float = 1.0,
        tangential_stiffness: float = math.inf,
        n_grid: int = 16384,
    ) -> Branches:
        """Build the branch tables for ``params``.

        ``stiffness_scale`` multiplies Ka and Kp (1e6 ≈ rigid setae: the Fuller–Tabor limit).
        ``tangential_stiffness`` k_t [µN/µm] is the stick spring of the contact (∞: a sticking
        tip does not move, as in eq 26–27). A sticking tip then sits on a lateral spring k_t to
        its anchor, which softens the stick branch to K_yy − K_xy²/(K_xx + k_t).
        """
        if not tangential_stiffness > 0:
            raise ValueError(f"tangential_stiffness = {tangential_stiffness!r} must be > 0")
        if lateral not in ("coupled", "free"):
            raise ValueError(f"lateral = {lateral!r} must be 'coupled' or 'free'")
        if not stiffness_scale > 0:
            raise ValueError(f"stiffness_scale = {stiffness_scale!r} must be > 0")
        R, w, Es = params.contact.jkr_args()
        K = beam.stiffness_matrix(
            params.axial_stiffness * stiffness_scale,
            params.bending_stiffness * stiffness_scale,
            params.seta.theta,
        )
        Kxx, Kxy, Kyy = float(K[0, 0]), float(K[0, 1]), float(K[1, 1])
        Ky = Kyy - Kxy * Kxy / Kxx  # Schur complement = eq 20
        r_t = (
            1.0
            if math.isinf(tangential_stiffness)
            else (tangential_stiffness / (Kxx + tangential_stiffness))
        )
        Kyy_stick = Kyy - Kxy * Kxy * (1.0 - r_t) / Kxx
        mu = params.friction.mu if lateral == "coupled" else 0.0
        self = cls(
            R,
            w,
            Es,
            params.contact.pull_off_force,
            params.seta.L,
            params.seta.theta,
            Kxx,
            Kxy,
            Kyy,
            Ky,
            r_t,
            Kyy_stick,
            mu,
            params.friction.law,
            lateral,
            {},
            {},
            {},
        )
        a0 = jkr.zero_load_contact_radius(R, w, Es)
        q = Kxy / Kxx
        names = ["free"] if lateral == "free" else ["stick", "slip+", "slip-"]
        for name in names:
            k_eff = {"stick": Kyy_stick, "free": Ky}.get(name)
            if k_eff is None:
                sigma = 1.0 if name == "slip+" else -1.0
                # Near the fold P < 0; the adhesive cap grows with P there, the paper's is 0.
                dcap = mu if params.friction.law == "adhesive" else 0.0
                factor = 1.0 - q * sigma * dcap
                if factor <= 0:
                    raise ValueError(
                        f"friction self-locks: μ = {mu} with θ = {params.seta.theta_deg}° makes "
                        "the sliding seta's normal stiffness negative; lower friction.mu"
                    )
                k_eff = Ky / factor
            a_f = release_radius(k_eff, R, w, Es)
            a = np.geomspace(a_f, max(40.0 * a0, 4.0 * a_f), n_grid)
            self.a_fold[name] = a_f
            self.a_grid[name] = a
            self.G_grid[name] = self.G(name, a)
        return self

    def cap(self, P):
        """Tangential force cap [µN] for normal force(s) P [µN]."""
        if self.law == "paper":
            return self.mu * np.maximum(P, 0.0)
        return self.mu * np.abs(P + 2.0 * self.Fc)

    def deflection(self, name, P):
        """Spring deflection D_b (tip minus rest, downward positive) for force P [µm]."""
        if name == "stick":
            return P / self.Kyy_stick
        if name == "free":
            return P / self.Ky
        sigma = 1.0 if name == "slip+" else -1.0
        return (P - self.Kxy / self.Kxx * sigma * self.cap(P)) / self.Ky

    def G(self, name, a):
        """G_b(a) = −δ(a) − D_b(P(a)) [µm]."""
        P = jkr.force_from_radius(a, self.R, self.w, self.E_star)
        return -jkr.overlap_from_radius(a, self.R, self.w, self.E_star) - self.deflection(name, P)

    def dG(self, name, a):
        """dG_b/da = −δ'(a) − D_b'(P)·P'(a) [-], from eq 7 and eq 10 differentiated."""
        R, w, Es = self.R, self.w, self.E_star
        a = np.asarray(a, dtype=float)
        dP = 4.0 * Es * a * a / R - 1.5 * np.sqrt(8.0 * np.pi * w * Es * a)
        dd = 2.0 * a / R - 0.5 * np.sqrt(2.0 * np.pi * w / (Es * a))
        if name == "stick":
            dD = 1.0 / self.Kyy_stick
        elif name == "free":
            dD = 1.0 / self.Ky
        else:
            sigma = 1.0 if name == "slip+" else -1.0
            P = jkr.force_from_radius(a, R, w, Es)
            dcap = self.mu if self.law == "adhesive" else self.mu * (P > 0)
            dD = (1.0 - self.Kxy / self.Kxx * sigma * dcap) / self.Ky
        return -dd - dD * dP

    def _G_dG(self, name, a):
        """G_b(a) and dG_b/da together (what :meth:`G` and :meth:`dG` give), sharing √a."""
        R, w, Es = self.R, self.w, self.E_star
        k1, k2 = math.sqrt(8.0 * math.pi * w * Es), math.sqrt(2.0 * math.pi * w / Es)
        sa = np.sqrt(a)
        a2 = a * a
        P = (4.0 * Es / (3.0 * R)) * a2 * a - k1 * (a * sa)  # eq 7
        dP = (4.0 * Es / R) * a2 - (1.5 * k1) * sa
        G = k2 * sa - a2 / R  # −δ, eq 10
        dG = (0.5 * k2) / sa - (2.0 / R) * a
        if name == "stick":
            G -= P / self.Kyy_stick
            dG -= dP / self.Kyy_stick
        elif name == "free":
            G -= P / self.Ky
            dG -= dP / self.Ky
        else:
            q = self.Kxy / self.Kxx * (1.0 if name == "slip+" else -1.0)
            G -= (P - q * self.cap(P)) / self.Ky
            dcap = self.mu if self.law == "adhesive" else self.mu * (P > 0)
            dG -= (1.0 - q * dcap) / self.Ky * dP
        return G, dG

    def invert(self, name, target):
        """Contact radius on branch b with G_b(a) = target, NaN where none exists [µm]."""
        a_tab, G_tab = self.a_grid[name], self.G_grid[name]
        target = np.asarray(target, dtype=float)
        if np.any(target < G_tab[-1]):
            raise ValueError(
                "a seta is compressed beyond the tabulated range "
                f"(G = {target.min():.3g} µm); the plate went implausibly deep"
            )
        a = np.interp(target, G_tab[::-1], a_tab[::-1])
        a_f = self.a_fold[name]
        for _ in range(2):  # Newton polish of the interpolated start; G' < 0 above the fold
            G, slope = self._G_dG(name, a)
            ok = slope < 0
            if ok.all():
                a = np.maximum(a - (G - target) / slope, a_f)
            else:
                a = np.where(ok, np.maximum(a - (G - target) / np.where(ok, slope, -1.0), a_f), a)
        return np.where(target <= G_tab[0], a, np.nan)


@dataclass
class QuasiStaticResult:
    """Quasi-static history of an array.

    Attributes (n = number of plate positions, N = number of (representative) setae)
    ----------
    plate_y : plate height above the floor's mean plane [µm], (n,).
    force_normal : total normal contact force [µN], positive compressive, (n,).
    force_tangential : total tangential contact force [µN], (n,).
    n_attached : number of attached setae (weighted), (n,).
    weights : setae each entry stands for, (N,).
    heights : floor height under each entry [µm], (N,).
    per_seta : optional dict of (n, N) arrays: ``force`` [µN], ``overlap`` [µm], ``state``,
        ``tip_dx`` (tip abscissa relative to rest) [µm].
    releases : list of (step, seta, overlap at release [µm]) in the order they happened.
    """

    plate_y: np.ndarray
    force_normal: np.ndarray
    force_tangential: np.ndarray
    n_attached: np.ndarray
    weights: np.ndarray
    heights: np.ndarray
    per_seta: dict = field(default_factory=dict)
    releases: list = field(default_factory=list)

    @property
    def pull_off(self) -> float:
        """Maximum tensile force magnitude [µN] (0 if the array never pulls)."""
        return float(max(0.0, -self.force_normal.min()))

    @property
    def preload(self) -> float:
        """Maximum compressive force reached [µN]."""
        return float(max(0.0, self.force_normal.max()))

    @property
    def turn_index(self) -> int:
        """Index of the deepest plate position (approach ends there)."""
        return int(np.argmin(self.plate_y))


class _State:
    """Per-seta state during a solve: contact state, slide direction, tip offset u = x − x0."""

    def __init__(self, n):
        self.state = np.zeros(n, dtype=np.int8)
        self.sigma = np.zeros(n)
        self.u = np.zeros(n)

    def copy(self):
        c = _State(0)
        c.state, c.sigma, c.u = self.state.copy(), self.sigma.copy(), self.u.copy()
        return c


def _step(br: Branches, st: _State, Z: float, h: np.ndarray, margins: bool = False):
    """Equilibrate every seta at plate height Z; update ``st`` in place.

    Returns (P, F_t, δ, released mask, release overlaps), and with ``margins`` also the
    decision variables of attached setae (NaN elsewhere) that :class:`_Blocks` splits blocks
    with: ``stick`` = cap − |F_t| of the stick trial (≥ 0: sticks), ``ft`` = F_t of the stick
    trial (its sign is the slide direction), ``fold`` = G_fold − target of the slide branch
    (< 0: no equilibrium, the tip lets go).
    """
    n = len(h)
    t0 = (Z - br.L * np.sin(br.theta) - br.R) - h  # G target for zero lateral shift
    P = np.zeros(n)
    Ft = np.zeros(n)
    delta = -t0  # free tip: δ = h + R − p0_y
    was = st.state != FREE
    jump = delta >= 0.0
    jump &= ~was
    if jump.any():  # jump-in at δ = 0
        st.state[jump] = STICK
        st.u[jump] = 0.0
        st.sigma[jump] = 0.0
    att = was | jump
    released = np.zeros(n, dtype=bool)
    rel_overlap = np.full(n, np.nan)
    mg = {k: np.full(n, np.nan) for k in ("stick", "ft", "fold")} if margins else None
    idx = np.flatnonzero(att)
    if idx.size == 0:
        return (P, Ft, delta, released, rel_overlap) + ((mg,) if margins else ())
    args = (br.R, br.w, br.E_star)

    if br.lateral == "free":
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
        if margins:
            mg["fold"][idx] = br.G_grid["free"][0] - t0[idx]
        return (P, Ft, delta, released, rel_overlap) + ((mg,) if margins else ())

    # 1) Stick trial at the previous anchor (u: anchor abscissa relative to the rest tip).
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
    if margins:
        mg["stick"][idx] = np.where(exists, cap_s - abs_ft, -np.inf)
        mg["ft"][idx] = Ft_s
        mg["fold"][idx] = np.where(sig_all > 0, br.G_grid["slip+"][0], br.G_grid["slip-"][0]) - t0i
    if stick_ok.all():
        P[idx], Ft[idx] = Ps, Ft_s
        delta[idx] = jkr.overlap_from_radius(a_s, *args)
        st.state[idx] = STICK
        return (P, Ft, delta, released, rel_overlap) + ((mg,) if margins else ())
    j = idx[stick_ok]
    P[j], Ft[j] = Ps[stick_ok], Ft_s[stick_ok]
    delta[j] = jkr.overlap_from_radius(a_s[stick_ok], *args)
    st.state[j] = STICK

    # 2) Slide where sticking is impossible: friction takes the sign the spring demanded.
    k = ~stick_ok
    jk = idx[k]
    sig = sig_all[k]
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
    # 3) No equilibrium on either branch: the tip lets go at its fold.
    if not ok.all():
        gone = jk[~ok]
        st.state[gone] = FREE
        st.u[gone] = 0.0
        released[gone] = True
        # Release overlap: the fold of the branch that failed (stick if it never slid).
        rel_a = np.where(exists[k], fold, br.a_fold["stick"])[~ok]
        rel_overlap[gone] = jkr.overlap_from_radius(rel_a, *args)
        delta[gone] = -t0[gone]
    return (P, Ft, delta, released, rel_overlap) + ((mg,) if margins else ())


class _Blocks:
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
        c = object.__new__(_Blocks)
        c.sample = self.sample
        for k in ("h", "w", "lo", "hi", "hmin", "hmax"):
            setattr(c, k, getattr(self, k).copy())
        return c

    @staticmethod
    def _codes(st):
        return np.where(
            st.state == FREE, 0, np.where(st.state == STICK, 1, np.where(st.sigma > 0, 2, 3))
        )

    def step(self, br: Branches, st: _State, Z: float):
        """:func:`_step` on the blocks, then split the blocks a boundary now runs through."""
        pre = st.copy()
        P, Ft, d, rel, rel_d, mg = _step(br, st, Z, self.h, margins=True)
        c0, c1 = self._codes(pre), self._codes(st)
        splits = {}
        h, lo, hi, hmin, hmax = self.h, self.lo, self.hi, self.hmin, self.hmax
        # Jump-in: setae with h ≥ Z − L sin θ − R touch; the block holding that height.
        h_in = Z - br.L * np.sin(br.theta) - br.R
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
        if not splits:
            return P, Ft, d, rel, rel_d
        js = np.array(sorted(splits), dtype=np.int64)
        cut = np.searchsorted(self.sample, [splits[j] for j in js.tolist()])
        cut = np.clip(cut, lo[js] + 1, hi[js] - 1)
        # The parts: lower [lo, cut), upper [cut, hi), each from the block's state before.
        plo, phi = np.concatenate([lo[js], cut]), np.concatenate([cut, hi[js]])
        ph = np.array([self.sample[a:b].mean() for a, b in zip(plo, phi, strict=True)])
        sub = _State(0)
        sub.state, sub.sigma, sub.u = (
            np.concatenate([x[js], x[js]]) for x in (pre.state, pre.sigma, pre.u)
        )
        sP, sFt, sd, srel, srel_d = _step(br, sub, Z, ph)
        m = js.size

        def put(a, part):  # block j becomes its lower part, its upper part follows it
            a = a.copy()
            a[js] = part[:m]
            return np.insert(a, js + 1, part[m:])

        self.h, self.lo, self.hi = put(h, ph), put(lo, plo), put(hi, phi)
        self.w = (self.hi - self.lo).astype(float)
        self.hmin, self.hmax = self.sample[self.lo], self.sample[self.hi - 1]
        st.state, st.sigma, st.u = (
            put(st.state, sub.state),
            put(st.sigma, sub.sigma),
            put(st.u, sub.u),
        )
        return (put(P, sP), put(Ft, sFt), put(d, sd), put(rel, srel), put(rel_d, srel_d))


# --------------------------------------------------------------------------------------------
# Rod mechanics (params.mechanics == "rod")
# --------------------------------------------------------------------------------------------
def rod_force(x, y, Ka, k_phi, L, theta):
    """Force of a rod seta on its tip and the tip's tangent stiffness (the agent's ``rod`` law).

    The rod is rigid, pivots at its root on a rotary spring k_φ = Kp·L² and has an axial spring
    Ka (Kp, Ka: eq 19, 17). With the tip at d = (x, y) from the root, ℓ = |d|, e = d/ℓ,
    e⊥ = (−e_y, e_x) and Δφ = atan2(y, x) + θ wrapped to (−π, π]:

        U = ½Ka(ℓ − L)² + ½k_φΔφ²,    F = −∇U = −Ka(ℓ − L)·e − (k_φΔφ/ℓ)·e⊥,
        H = ∇∇U = Ka·e eᵀ + (Ka(ℓ − L)/ℓ + k_φ/ℓ²)·e⊥e⊥ᵀ − (k_φΔφ/ℓ²)(e e⊥ᵀ + e⊥eᵀ).

    At rest (ℓ = L, Δφ = 0) H is the paper's 2×2 stiffness K of eq 20–21 (Ka along the rod,
    Kp across it), so rod and ``linear`` agree for small deflections. The same formula as
    :meth:`gecko_agents.model.Model.spring_force`.

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


@dataclass(frozen=True)
class RodSetup:
    """Constants of the quasi-static ``rod`` seta (see :func:`rod_force`).

    Attributes: R [µm], w [µN/µm], E_star [MPa], Fc [µN], L [µm], theta [rad], Ka [µN/µm],
    k_phi [µN·µm/rad], k_t (stick spring of the contact [µN/µm], ``inf``: a sticking tip does
    not move), mu [-], law, lateral (``"coupled"`` or ``"free"``), a_c (end of the JKR stable
    branch [µm]), a0 (zero-load radius [µm]), Ky (eq 20 [µN/µm]).
    """

    R: float
    w: float
    E_star: float
    Fc: float
    L: float
    theta: float
    Ka: float
    k_phi: float
    k_t: float
    mu: float
    law: str
    lateral: str
    a_c: float
    a0: float
    Ky: float
    Kxx: float
    Kxy: float

    @classmethod
    def from_params(
        cls,
        params: SetaArray,
        lateral: str = "coupled",
        stiffness_scale: float = 1.0,
        tangential_stiffness: float = math.inf,
    ) -> RodSetup:
        """The rod of ``params`` (Ka, Kp scaled by ``stiffness_scale``), contact and friction."""
        if not tangential_stiffness > 0:
            raise ValueError(f"tangential_stiffness = {tangential_stiffness!r} must be > 0")
        if lateral not in ("coupled", "free"):
            raise ValueError(f"lateral = {lateral!r} must be 'coupled' or 'free'")
        if not stiffness_scale > 0:
            raise ValueError(f"stiffness_scale = {stiffness_scale!r} must be > 0")
        R, w, Es = params.contact.jkr_args()
        Ka = params.axial_stiffness * stiffness_scale
        Kp = params.bending_stiffness * stiffness_scale
        K = beam.stiffness_matrix(Ka, Kp, params.seta.theta)
        L = params.seta.L
        return cls(
            R,
            w,
            Es,
            params.contact.pull_off_force,
            L,
            params.seta.theta,
            Ka,
            Kp * L * L,
            float(tangential_stiffness),
            params.friction.mu if lateral == "coupled" else 0.0,
            params.friction.law,
            lateral,
            float(jkr.snap_off_radius(R, w, Es)),
            float(jkr.zero_load_contact_radius(R, w, Es)),
            float(K[1, 1] - K[0, 1] ** 2 / K[0, 0]),
            float(K[0, 0]),
            float(K[0, 1]),
        )

    def cap(self, P):
        """Tangential force cap [µN] for normal force(s) P [µN] (as :meth:`Friction.cap`)."""
        if self.law == "paper":
            return self.mu * np.maximum(P, 0.0)
        return self.mu * np.abs(P + 2.0 * self.Fc)

    def dcap(self, P):
        """d cap / dP [-]."""
        if self.law == "paper":
            return self.mu * (P > 0)
        return self.mu * np.sign(P + 2.0 * self.Fc)

    @property
    def rest(self) -> tuple[float, float]:
        """Free tip position relative to the root [µm]."""
        return self.L * math.cos(self.theta), -self.L * math.sin(self.theta)


def _rod_newton(
    rs: RodSetup, c, x, a, anchor=None, s=None, iters: int = 60, max_jump: float = math.inf
):
    """Equilibrium of rod + JKR tip for each seta, by damped Newton on (x, a).

    The tip sits at (x, y) from its root with y = c − δ(a) (c = h + R − Z [µm]: floor height
    h, plate height Z), the normal force is P(a) (eq 7), the overlap δ(a) (eq 10). Lateral:
    ``anchor`` given: stick, F_t = −k_t(x − anchor) (``k_t = inf``: x = anchor); else slide in
    direction ``s`` = ±1 with F_t = s·cap(P). Equations: F_rod(x, y) + (F_t, P) = 0.

    ``max_jump`` [µm]: an equilibrium whose x is farther than this from the start does not
    count (it lies beyond a snap of the branch the tip was on).

    Returns (x, a, ok): ok where Newton converged to a stable equilibrium (the tangent
    stiffness of rod + contact + stick spring has positive determinant and trace) on the
    stable JKR branch (a > a_c). Where the equilibrium has folded away, ok is False.
    """
    R, w, Es = rs.R, rs.w, rs.E_star
    k1, k2 = math.sqrt(8.0 * math.pi * w * Es), math.sqrt(2.0 * math.pi * w / Es)
    stick = anchor is not None
    rigid = stick and math.isinf(rs.k_t)
    x_start = x
    x, a = x.copy(), a.copy()
    a_min = rs.a_c * (1.0 + 1e-9)
    tol = 1e-10 * rs.Fc
    conv = np.zeros(x.size, dtype=bool)
    for _ in range(iters):
        sa = np.sqrt(a)
        P = (4.0 * Es / (3.0 * R)) * a * a * a - k1 * a * sa
        dP = (4.0 * Es / R) * a * a - 1.5 * k1 * sa
        d = a * a / R - k2 * sa
        dd = 2.0 * a / R - 0.5 * k2 / sa
        y = c - d
        (Fx, Fy), (Hxx, Hxy, Hyy) = rod_force(x, y, rs.Ka, rs.k_phi, rs.L, rs.theta)
        # Residual r(x, a) and Jacobian; dy/da = −δ'(a).
        if rigid:
            r1 = rs.Ka * (anchor - x)
            j11, j12 = -rs.Ka * np.ones_like(x), np.zeros_like(x)
        elif stick:
            r1 = Fx - rs.k_t * (x - anchor)
            j11, j12 = -Hxx - rs.k_t, Hxy * dd
        else:
            r1 = Fx + s * rs.cap(P)
            j11, j12 = -Hxx, Hxy * dd + s * rs.dcap(P) * dP
        r2 = Fy + P
        j21, j22 = -Hxy, Hyy * dd + dP
        det = j11 * j22 - j12 * j21
        scale = tol + 1e-12 * (np.abs(P) + np.abs(Fx))
        conv = (np.abs(r1) <= scale) & (np.abs(r2) <= scale)
        if conv.all():
            break
        det = np.where(det == 0.0, 1e-300, det)
        dx = -(j22 * r1 - j12 * r2) / det
        da = -(-j21 * r1 + j11 * r2) / det
        # Damping: keep steps to a fraction of the rod length and of the contact radius.
        lim = np.minimum(
            1.0,
            np.minimum(
                0.1 * rs.L / np.maximum(np.abs(dx), 1e-300),
                0.3 * a / np.maximum(np.abs(da), 1e-300),
            ),
        )
        lim = np.where(conv, 0.0, lim)
        x = x + lim * dx
        a = np.maximum(a + lim * da, a_min)
    # Stability of the converged equilibrium: K_tot = H + contact (+ stick spring) in (x, y).
    sa = np.sqrt(a)
    P = (4.0 * Es / (3.0 * R)) * a * a * a - k1 * a * sa
    dP = (4.0 * Es / R) * a * a - 1.5 * k1 * sa
    dd = 2.0 * a / R - 0.5 * k2 / sa
    y = c - (a * a / R - k2 * sa)
    _, (Hxx, Hxy, Hyy) = rod_force(x, y, rs.Ka, rs.k_phi, rs.L, rs.theta)
    kc = dP / np.maximum(dd, 1e-300)  # dP/dδ
    if rigid:
        ok = Hyy + kc > 0
    else:
        kxx = Hxx + (rs.k_t if stick else 0.0)
        kxy = Hxy + (0.0 if stick else s * rs.dcap(P) * kc)
        ok = (kxx * (Hyy + kc) - kxy * Hxy > 0) & (kxx + Hyy + kc > 0)
    ok &= conv & (a > a_min) & np.isfinite(x)
    # An equilibrium far from the last one is the far side of a snap (e.g. the rod swinging
    # through upright): the branch the tip was on has folded; dynamically the tip lets go.
    ok &= np.abs(x - x_start) <= max_jump
    return x, a, ok


class _RodState(_State):
    """:class:`_State` plus the rod tip abscissa x [µm] (from the root), contact radius a [µm]
    and tangential contact force ft [µN] of each seta's last equilibrium."""

    def __init__(self, n):
        super().__init__(n)
        self.x = np.zeros(n)
        self.a = np.zeros(n)
        self.ft = np.zeros(n)

    def copy(self):
        c = _RodState(0)
        for k in ("state", "sigma", "u", "x", "a", "ft"):
            setattr(c, k, getattr(self, k).copy())
        return c


def _rod_step(rs: RodSetup, st: _RodState, Z: float, h: np.ndarray):
    """Equilibrate every rod seta at plate height Z; update ``st`` in place.

    As :func:`_step`, with the large-rotation rod instead of the linear spring: a free tip
    jumps in where it touches (δ ≥ 0) and anchors there; an attached tip first tries to stick
    at its anchor (F_t = −k_t(x − anchor), |F_t| ≤ cap), otherwise slides with F_t = ±cap in
    the direction the stick trial demanded (return mapping, as the agent model); where neither
    has a stable equilibrium, the spring–contact system has folded and the tip lets go. The
    overlap recorded for a release is that of the tip's last equilibrium (within one plate step
    of the fold). ``st.u`` is the anchor relative to the rest tip abscissa [µm].

    Returns (P, F_t, δ, released mask, release overlaps), as :func:`_step`.
    """
    n = len(h)
    x0, y0 = rs.rest
    c = h + rs.R - Z
    P = np.zeros(n)
    Ft = np.zeros(n)
    delta = c - y0
    was = st.state != FREE
    jump = (delta >= 0.0) & ~was
    if jump.any():
        st.state[jump] = STICK
        st.u[jump] = 0.0
        st.sigma[jump] = 0.0
        st.x[jump] = x0
        st.a[jump] = rs.a0
    att = was | jump
    released = np.zeros(n, dtype=bool)
    rel_overlap = np.full(n, np.nan)
    idx = np.flatnonzero(att)
    if idx.size == 0:
        return P, Ft, delta, released, rel_overlap
    args = (rs.R, rs.w, rs.E_star)
    ci, xi, ai = c[idx], st.x[idx], st.a[idx]
    jump_x = 0.1 * rs.L
    new_x, new_a = xi.copy(), ai.copy()
    state = np.full(idx.size, FREE, dtype=np.int8)
    sig = st.sigma[idx].copy()
    anchor = x0 + st.u[idx]
    if rs.lateral == "free":
        todo = np.ones(idx.size, dtype=bool)
        sig[:] = 1.0
    else:
        xs, as_, ok = _rod_newton(rs, ci, xi, ai, anchor=anchor, max_jump=jump_x)
        Ps = jkr.force_from_radius(as_, *args)
        if math.isinf(rs.k_t):
            Fts = -rod_force(
                xs, ci - jkr.overlap_from_radius(as_, *args), rs.Ka, rs.k_phi, rs.L, rs.theta
            )[0][0]
        else:
            Fts = -rs.k_t * (xs - anchor)
        stick_ok = ok & (np.abs(Fts) <= rs.cap(Ps) * (1 + 1e-12))
        new_x[stick_ok], new_a[stick_ok] = xs[stick_ok], as_[stick_ok]
        state[stick_ok] = STICK
        todo = ~stick_ok
        # Slide in the direction the spring demands; where the stick branch has folded, in
        # the direction of the tangential force at the last equilibrium.
        sig = np.where(np.where(ok, Fts, st.ft[idx]) >= 0, 1.0, -1.0)
    if todo.any():
        t = np.flatnonzero(todo)
        s = sig[t] if rs.lateral == "coupled" else np.zeros(t.size)
        xk, ak, okk = _rod_newton(rs, ci[t], xi[t], ai[t], s=s, max_jump=jump_x)
        new_x[t[okk]], new_a[t[okk]] = xk[okk], ak[okk]
        state[t[okk]] = SLIP
        sig[t] = s
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
    trail = 0.0 if math.isinf(rs.k_t) else capj[slip] * sig[good][slip] / rs.k_t
    st.u[j[slip]] = new_x[good][slip] + trail - x0
    gone = idx[~good]
    if gone.size:
        released[gone] = True
        rel_overlap[gone] = jkr.overlap_from_radius(ai[~good], *args)
        st.state[gone] = FREE
        st.u[gone] = 0.0
        st.sigma[gone] = 0.0
        delta[gone] = c[gone] - y0
    return P, Ft, delta, released, rel_overlap


def rod_retract_travel(params: SetaArray, rs: RodSetup, heights, Z_from: float) -> float:
    """Plate travel up from Z_from [µm] after which every rod seta has surely let go [µm].

    Back past the start height, plus the swing of the rod to upright, L(1 − sin θ), its axial
    stretch under Fc and the stick spring's, and a margin of 20|δc|.
    """
    stretch = rs.Fc / rs.Ka + (0.0 if math.isinf(rs.k_t) else rs.Fc / rs.k_t)
    return (
        plate_start_height(params, heights, 0.0)
        - Z_from
        + rs.L * (1.0 - math.sin(rs.theta))
        + 1.5 * stretch
        + 20 * abs(params.contact.snap_off_overlap)
    )


def _setup(
    params: SetaArray, lateral: str, stiffness_scale: float, tangential_stiffness: float
) -> Branches | RodSetup:
    """The seta model of ``params.mechanics``: :class:`Branches` (linear) or :class:`RodSetup`."""
    if params.mechanics == "rod":
        return RodSetup.from_params(params, lateral, stiffness_scale, tangential_stiffness)
    return Branches.from_params(params, lateral, stiffness_scale, tangential_stiffness)


def plate_start_height(params: SetaArray, heights, gap: float = 0.5) -> float:
    """Plate height at which the highest seta's free tip is ``gap`` [µm] above its floor [µm]."""
    return float(
        np.max(heights) + params.contact.R + params.seta.L * np.sin(params.seta.theta) + gap
    )


def solve(
    params: SetaArray,
    heights,
    plate_y,
    *,
    weights=None,
    lateral: str = "coupled",
    stiffness_scale: float = 1.0,
    tangential_stiffness: float = math.inf,
    record_setae: bool = False,
    branches: Branches | None = None,
    stop_when_free_after: int | None = None,
    sample=None,
) -> QuasiStaticResult:
    """Quasi-static history of setae over floor heights along a vertical plate path.

    Parameters
    ----------
    params : the array (its contact, seta and friction parts are used).
    heights : floor height under each seta [µm], (N,).
    plate_y : plate heights above the floor's mean plane, in order [µm], (n,).
    weights : setae each entry stands for (default 1 each).
    lateral : ``"coupled"`` (stick/slip friction) or ``"free"`` (eq 25).
    stiffness_scale : multiplies Ka and Kp (large → rigid setae).
    tangential_stiffness : stick spring of the contact [µN/µm] (∞: rigid stick).
    record_setae : keep per-seta force, overlap, state and lateral offset.
    branches : prebuilt :class:`Branches` (or :class:`RodSetup` for ``mechanics == "rod"``;
        ``lateral`` and ``stiffness_scale`` are then unused).
    stop_when_free_after : stop at the first step past this index where no seta is attached.
    sample : the sorted heights of every seta [µm] when ``heights``/``weights`` are block
        means and sizes of consecutive setae of it (``representative_heights(...,
        return_sample=True)``). Blocks are then split wherever a plate step puts a jump-in,
        stick/slide or release boundary inside one (see :class:`_Blocks`), so the blocks
        reproduce the force curve of all the setae to ~1e-9 of its peak instead of
        ~0.7/n_blocks; the result's ``heights``/``weights`` are the final blocks and
        ``releases`` index the blocks of their step. Not with ``record_setae``. With
        ``mechanics == "rod"`` the blocks are not split (the rod's decision boundaries are not
        linear in h): plain block means, an error of about 0.7/n_blocks of the peak.

    ``params.mechanics == "rod"`` solves the large-rotation rod of :func:`rod_force` instead of
    the linear spring (:func:`_rod_step`); the friction and release laws are the same.
    """
    rod = params.mechanics == "rod"
    br = branches or _setup(params, lateral, stiffness_scale, tangential_stiffness)
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    Zs = np.asarray(plate_y, dtype=float)
    if not np.all(np.isfinite(Zs)):
        raise ValueError("plate_y must be finite")
    blocks = None
    if sample is not None:
        if record_setae:
            raise ValueError("record_setae is not available with a sample (blocks split)")
        if not rod:
            blocks = _Blocks(sample, w, h)
    st = _RodState(h.size) if rod else _State(h.size)
    out = _Recorder(Zs.size, h.size, record_setae)
    for i, Z in enumerate(Zs):
        if rod:
            P, Ft, d, rel, rel_d = _rod_step(br, st, Z, h)
        elif blocks is None:
            P, Ft, d, rel, rel_d = _step(br, st, Z, h)
        else:
            P, Ft, d, rel, rel_d = blocks.step(br, st, Z)
            h, w = blocks.h, blocks.w
        out.record(i, P, Ft, d, st, w, rel, rel_d)
        if (
            stop_when_free_after is not None
            and i > stop_when_free_after
            and not np.any(st.state != FREE)
        ):
            return out.result(Zs, w, h, keep=i + 1)
    return out.result(Zs, w, h)


class _Recorder:
    def __init__(self, n, N, per_seta):
        self.F = np.zeros(n)
        self.T = np.zeros(n)
        self.na = np.zeros(n)
        self.per = (
            (
                {k: np.zeros((n, N)) for k in ("force", "overlap", "tip_dx")}
                | {"state": np.zeros((n, N), dtype=np.int8)}
            )
            if per_seta
            else {}
        )
        self.releases = []

    def record(self, i, P, Ft, d, st, w, rel, rel_d):
        self.F[i] = np.sum(w * P)
        self.T[i] = np.sum(w * Ft)
        self.na[i] = np.sum(w[st.state != FREE])
        if self.per:
            self.per["force"][i], self.per["overlap"][i] = P, d
            self.per["tip_dx"][i], self.per["state"][i] = st.u, st.state
        for j in np.flatnonzero(rel):
            self.releases.append((i, int(j), float(rel_d[j])))

    def result(self, Zs, w, h, keep=None):
        sl = slice(None) if keep is None else slice(0, keep)
        return QuasiStaticResult(
            Zs[sl],
            self.F[sl],
            self.T[sl],
            self.na[sl],
            w,
            h,
            {k: v[sl] for k, v in self.per.items()},
            self.releases,
        )


def retract_travel(params: SetaArray, br: Branches, heights, Z_from: float) -> float:
    """Plate travel up from Z_from [µm] after which every seta has surely let go [µm].

    Back past the start height, plus the stretch of the softest branch holding Fc.
    """
    k_soft = min(br.Ky / (1 + abs(br.Kxy / br.Kxx) * br.mu), br.Kyy)
    return (
        plate_start_height(params, heights, 0.0)
        - Z_from
        + 1.5 * params.contact.pull_off_force / k_soft
        + 20 * abs(params.contact.snap_off_overlap)
    )


def press_pull(
    params: SetaArray,
    heights,
    depth: float,
    *,
    n_approach: int = 500,
    n_retract: int = 2000,
    start_gap: float = 0.5,
    lateral: str = "coupled",
    stiffness_scale: float = 1.0,
    tangential_stiffness: float = math.inf,
    weights=None,
    record_setae: bool = False,
    sample=None,
) -> QuasiStaticResult:
    """Displacement control: approach to ``depth`` [µm], then retract.

    ``depth`` is measured from the plate height at which a resting tip touches the floor's
    mean plane (h = 0), so it does not depend on the highest asperity of a sample. The plate
    starts ``start_gap`` [µm] above the highest tip's touch-down and moves down to that depth
    in ``n_approach`` equal steps; it then retracts in ``n_retract`` equal
    steps over :func:`retract_travel`, stopping early once every seta has let go. Equilibria
    are exact at every step; the step only sets how finely the curve and the release points
    are sampled (friction slides in one direction per leg, so the path is resolved exactly).

    ``weights`` and ``sample``: see :func:`solve`. With a sample, the start height is set by
    the highest seta of the sample rather than the highest block mean.

    The paper's 10⁷ setae (σ = 1 µm, 1000 plate positions, < 1 s besides drawing the
    heights): ``h, w, s = representative_heights(10**7, 1.0, rng, 2000, return_sample=True)``
    then ``press_pull(PAPER_ARRAY, h, 1.0, weights=w, sample=s, n_approach=333,
    n_retract=667)``: 2000 blocks of 5000 setae, split on the fly wherever a jump-in,
    stick/slide or release boundary crosses one (a few hundred splits over the curve), which
    reproduces the curve of every seta solved on its own to ~1e-9 of the peak (tested against
    brute force on 10⁴ setae in tests/test_quasistatic.py).
    """
    if not depth > 0:
        raise ValueError(f"depth = {depth!r} must be > 0 [µm]")
    br = _setup(params, lateral, stiffness_scale, tangential_stiffness)
    top = heights if sample is None else sample[-1:]
    Z0 = plate_start_height(params, top, start_gap)
    Zmin = plate_start_height(params, [0.0], 0.0) - depth
    if Zmin >= Z0:
        raise ValueError(
            f"depth = {depth!r} µm does not reach the highest floor point "
            f"({np.max(top):.3g} µm above the mean plane)"
        )
    up = (rod_retract_travel if isinstance(br, RodSetup) else retract_travel)(params, br, top, Zmin)
    Zs = np.concatenate(
        [np.linspace(Z0, Zmin, n_approach + 1), Zmin + up * np.arange(1, n_retract + 1) / n_retract]
    )
    res = solve(
        params,
        heights,
        Zs,
        weights=weights,
        record_setae=record_setae,
        branches=br,
        stop_when_free_after=n_approach,
        sample=sample,
    )
    return res


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
    br = _setup(params, lateral, stiffness_scale, tangential_stiffness)
    rod = isinstance(br, RodSetup)
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    dz = abs(params.contact.snap_off_overlap) / 20 if dz is None else float(dz)
    if not dz > 0:
        raise ValueError(f"dz = {dz!r} must be > 0 [µm]")
    blocks = None
    if sample is not None:
        if record_setae:
            raise ValueError("record_setae is not available with a sample (blocks split)")
        if not rod:
            blocks = _Blocks(sample, w, h)
    top = h if sample is None else sample[-1:]
    st = _RodState(h.size) if rod else _State(h.size)
    Z_start = plate_start_height(params, top, 0.5)
    Z = Z_start
    Zs, results = [], []

    def advance(state, blk, Z):
        if rod:
            return _rod_step(br, state, Z, h), w
        if blk is None:
            return _step(br, state, Z, h), w
        return blk.step(br, state, Z), blk.w

    def keep(Z, res, state, weights):
        Zs.append(Z)
        results.append((res, state.copy(), weights))

    for _ in range(max_steps):
        saved = (st.copy(), None if blocks is None else blocks.copy())
        res, wk = advance(st, blocks, Z)
        if np.sum(wk * res[0]) < preload:
            keep(Z, res, st, wk)
            Z -= dz
            continue
        # Overshot: bisect the plate height between the last two steps from the saved state.
        lo, hi, best = Z + dz, Z, (res, st, blocks, wk)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            trial = saved[0].copy()
            tblk = None if blocks is None else saved[1].copy()
            r, wt = advance(trial, tblk, mid)
            if np.sum(wt * r[0]) >= preload:
                hi, best = mid, (r, trial, tblk, wt)
                if np.sum(wt * r[0]) - preload <= 1e-9 * preload:
                    break
            else:
                lo = mid
        res, st, blocks, wk = best
        Z = hi
        keep(Z, res, st, wk)
        break
    else:
        raise RuntimeError(
            f"preload {preload} µN not reached within {max_steps} steps of "
            f"{dz} µm; the floor may be out of reach"
        )
    # Retract until every seta has let go; a soft seta can stretch by up to ~Fc/Ky first.
    n_up = retract_steps or 4000
    dz_up = max(dz, (rod_retract_travel if rod else retract_travel)(params, br, top, Z) / n_up)
    for _ in range(n_up):
        Z += dz_up
        res, wk = advance(st, blocks, Z)
        keep(Z, res, st, wk)
        if Z > Z_start and not np.any(st.state != FREE):
            break
    if blocks is not None:
        h, w = blocks.h, blocks.w
    rec = _Recorder(len(Zs), h.size, record_setae)
    for i, ((P, Ft, d, rel, rel_d), s, wk) in enumerate(results):
        rec.record(i, P, Ft, d, s, wk, rel, rel_d)
    return rec.result(np.asarray(Zs), w, h)


def _concat_states(states):
    """One state holding the setae of several states one after another."""
    out = type(states[0])(0)
    for k in vars(out):
        setattr(out, k, np.concatenate([getattr(s, k) for s in states]))
    return out


def _take_state(st, idx):
    """The setae ``idx`` of a state (a copy)."""
    out = type(st)(0)
    for k in vars(out):
        setattr(out, k, getattr(st, k)[idx].copy())
    return out


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

    Returns
    -------
    One :class:`QuasiStaticResult` per preload, in the order given.
    """
    pre = np.atleast_1d(np.asarray(preloads, dtype=float))
    if pre.size == 0 or not np.all(pre > 0):
        raise ValueError(f"preloads = {preloads!r} must be one or more forces > 0 [µN]")
    br = _setup(params, lateral, stiffness_scale, tangential_stiffness)
    rod = isinstance(br, RodSetup)
    step_fn = _rod_step if rod else _step
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    h_of = None
    if gaussian is not None:
        from scipy.special import ndtr, ndtri

        g_sigma, edges = float(gaussian[0]), np.asarray(gaussian[1], dtype=float)
        if not (g_sigma > 0 and edges.size == h.size + 1 and np.all(np.diff(edges) > 0)):
            raise ValueError(
                f"gaussian = (sigma {g_sigma!r}, {edges.size} edges) needs sigma > 0 [µm] "
                f"and {h.size + 1} increasing edges for {h.size} heights"
            )
        lo_e, hi_e = edges[:-1], edges[1:]
        p_blk = ndtr(-lo_e) - ndtr(-hi_e)  # upper-tail form: accurate far out
        z_of_touch = params.contact.R + params.seta.L * math.sin(params.seta.theta)

        def h_of(Z):  # the part of every slice above the contact front at plate height Z
            zt = (Z - z_of_touch) / g_sigma
            lo = np.maximum(lo_e, zt)
            p_in = np.clip(ndtr(-lo) - ndtr(-hi_e), 0.0, None)
            dens = np.exp(-0.5 * lo * lo) - np.exp(-0.5 * np.minimum(hi_e, 1e3) ** 2)
            ok = p_in > 1e-300
            mean = np.where(ok, dens / math.sqrt(2 * math.pi) / np.where(ok, p_in, 1.0), hi_e)
            mean = np.where(ok, np.clip(mean, lo, hi_e), np.minimum(hi_e, lo))
            return g_sigma * mean, w * (p_in / p_blk)

        n_total = float(np.sum(w))
        z_top = float(ndtri(1.0 - 0.1 / max(n_total, 1.0)))
        Z_start = g_sigma * z_top + z_of_touch + 0.5
    else:
        Z_start = plate_start_height(params, h, 0.5)

    def at(Z):
        return (h, w) if h_of is None else h_of(Z)

    dz = abs(params.contact.snap_off_overlap) / 20 if dz is None else float(dz)
    if not dz > 0:
        raise ValueError(f"dz = {dz!r} must be > 0 [µm]")
    order = np.argsort(pre, kind="stable")
    st = _RodState(h.size) if rod else _State(h.size)
    Z = Z_start
    approach_Z, approach_F, approach_T, approach_n = [], [], [], []
    turns = {}  # preload index → (Z, state, forces, n steps of approach before it)
    k = 0
    for _ in range(max_steps):
        saved = st.copy()
        hz, wz = at(Z)
        res = step_fn(br, st, Z, hz)
        F = float(np.sum(wz * res[0]))
        while k < order.size and F >= pre[order[k]]:
            target = pre[order[k]]
            # Illinois regula falsi on the plate height between the last two steps (the force
            # grows as the plate descends), from the state before the step; bisection where
            # the secant leaves the bracket.
            lo, hi, best = Z + dz, Z, (res, st.copy(), hz, wz)
            f_lo = (approach_F[-1] if approach_F else 0.0) - target
            f_hi, side = F - target, 0
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
            turns[int(order[k])] = (hi, best[1], best[0], len(approach_Z), best[2], best[3])
            k += 1
        if k == order.size:
            break
        approach_Z.append(Z)
        approach_F.append(F)
        approach_T.append(float(np.sum(wz * res[1])))
        approach_n.append(float(np.sum(wz[st.state != FREE])))
        Z -= dz
    else:
        raise RuntimeError(
            f"preload {pre[order[k]]} µN not reached within {max_steps} steps of "
            f"{dz} µm; the floor may be out of reach"
        )
    # Retracts of every preload together: copy c of the setae starts from turn c.
    n_up = retract_steps or 4000
    K, n = pre.size, h.size
    Zc = np.array([turns[c][0] for c in range(K)])
    travel = rod_retract_travel if rod else retract_travel
    top = h if h_of is None else np.array([Z_start - 0.5 - z_of_touch])
    trav = np.array([travel(params, br, top, Zc[c]) for c in range(K)])
    dzc = np.maximum(dz, trav / n_up)
    n_c = np.full(K, n_up)
    if retract_dz is not None:
        if not retract_dz > 0:
            raise ValueError(f"retract_dz = {retract_dz!r} must be > 0 [µm]")
        # A step of at most retract_dz; a rod can swing past upright and hold on beyond the
        # estimated travel, so a copy goes on (up to 10× the estimate) until all have let go.
        dzc = np.minimum(dzc, float(retract_dz))
        n_c = (10 * np.maximum(n_up, np.ceil(trav / dzc))).astype(int)
        n_up = int(n_c.max())
    big = _concat_states([turns[c][1] for c in range(K)])
    hh = np.concatenate([turns[c][4] for c in range(K)])
    ww = np.concatenate([turns[c][5] for c in range(K)])
    owner = np.repeat(np.arange(K), n)
    rec = [{"Z": [Zc[c]], "F": [], "T": [], "n": [], "rel": []} for c in range(K)]
    for c in range(K):
        r, wt = turns[c][2], turns[c][5]
        rec[c]["F"].append(float(np.sum(wt * r[0])))
        rec[c]["T"].append(float(np.sum(wt * r[1])))
        rec[c]["n"].append(float(np.sum(wt[turns[c][1].state != FREE])))
        rec[c]["rel"] += [(0, int(j), float(r[4][j])) for j in np.flatnonzero(r[3])]
    active = np.arange(K)
    sel = np.arange(K * n)
    best = {c: (rec[c]["F"][0], 0, _take_state(big, slice(c * n, (c + 1) * n))) for c in range(K)}
    for t in range(1, n_up + 1):
        Zs = Zc[owner[sel]] + t * dzc[owner[sel]]
        P, Ft, _, rel, rel_d = step_fn(br, big, Zs, hh[sel])
        att = big.state != FREE
        wp, wf, wa = ww[sel] * P, ww[sel] * Ft, ww[sel] * att
        done = []
        for m, c in enumerate(active):
            s = slice(m * n, (m + 1) * n)
            rc = rec[c]
            rc["Z"].append(Zc[c] + t * dzc[c])
            rc["F"].append(float(wp[s].sum()))
            rc["T"].append(float(wf[s].sum()))
            rc["n"].append(float(wa[s].sum()))
            for j in np.flatnonzero(rel[s]):
                rc["rel"].append((t, int(j), float(rel_d[s][j])))
            if refine_peak and rc["F"][-1] < best[c][0]:
                best[c] = (rc["F"][-1], t, _take_state(big, np.arange(m * n, (m + 1) * n)))
            if t >= n_c[c] or (rc["Z"][-1] > Z_start and not att[s].any()):
                done.append(m)
        if done:
            keep = np.setdiff1d(np.arange(active.size), done)
            if keep.size == 0:
                break
            rows = (keep[:, None] * n + np.arange(n)[None, :]).ravel()
            big = _take_state(big, rows)
            sel = sel[rows]
            active = active[keep]
    if refine_peak:
        _refine_peaks(br, step_fn, rec, best, hh, ww, n, Zc, dzc)
    out = []
    for c in range(K):
        na = turns[c][3]
        rc = rec[c]
        shift = na
        out.append(
            QuasiStaticResult(
                np.array(approach_Z[:na] + rc["Z"]),
                np.array(approach_F[:na] + rc["F"]),
                np.array(approach_T[:na] + rc["T"]),
                np.array(approach_n[:na] + rc["n"]),
                turns[c][5],
                turns[c][4],
                {},
                [(i + shift, j, d) for i, j, d in rc["rel"]],
            )
        )
    return out


def _refine_peaks(br, step_fn, rec, best, hh, ww, n, Zc, dzc, halvings: int = 30):
    """Bisect, for every copy at once, the step after its highest sampled tension for the
    last plate height before a release; insert that point into the copy's record."""
    cs = [
        c
        for c, (_, t, _) in best.items()
        if t + 1 < len(rec[c]["F"]) and any(i == t + 1 for i, _, _ in rec[c]["rel"])
    ]
    if not cs:
        return
    base = _concat_states([best[c][2] for c in cs])
    rows = np.concatenate([np.arange(c * n, (c + 1) * n) for c in cs])
    lo = np.array([Zc[c] + best[c][1] * dzc[c] for c in cs])
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
        t = best[c][1]
        rc = rec[c]
        for key, v in zip(("Z", "F", "T", "n"), keep[m], strict=True):
            rc[key].insert(t + 1, float(v))
        rc["rel"] = [(i + (i > t), j, d) for i, j, d in rc["rel"]]


def quantile_heights(n_setae: int, sigma: float, n_blocks: int = 256, *, return_edges=False):
    """Representative floor heights on a fixed grid of Gaussian quantiles (eq 28) [µm].

    The normal distribution of RMS ``sigma`` is cut into ``n_blocks`` slices of equal
    probability at the quantiles z_j = Φ⁻¹(j/n_blocks); slice j is represented by its
    conditional mean σ·n_blocks·(φ(z_j) − φ(z_{j+1})) (φ, Φ: standard normal density and
    distribution) and stands for n_setae/n_blocks setae. No random draw: the heights are σ
    times a fixed set of numbers, so a model built on them changes smoothly with σ and with
    every other parameter (a random draw of blocks instead jumps when it is redrawn). This is
    the expectation over floors of the array's floor-height distribution, which a 10⁷-seta
    array samples to ~1e-3 of σ per block anyway.

    Returns
    -------
    (heights [µm], weights [-]), each of length n_blocks (1 and [n_setae] when σ = 0); with
    ``return_edges`` also the standard quantiles z_j (n_blocks + 1, −∞ … +∞; None when σ = 0)
    for :func:`preload_pulls`'s ``gaussian``.
    """
    from scipy.special import ndtri

    if not (isinstance(n_blocks, int | np.integer) and n_blocks >= 1):
        raise ValueError(f"n_blocks = {n_blocks!r} must be an integer ≥ 1")
    if not (n_setae >= 1 and sigma >= 0):
        raise ValueError(f"n_setae = {n_setae!r} must be ≥ 1 and sigma = {sigma!r} ≥ 0 [µm]")
    if sigma == 0 or n_blocks == 1:
        out = np.zeros(1), np.array([float(n_setae)])
        return out + (None,) if return_edges else out
    z = ndtri(np.arange(n_blocks + 1) / n_blocks)  # −∞ … +∞
    phi = np.exp(-0.5 * np.where(np.isfinite(z), z, 0.0) ** 2) / math.sqrt(2 * math.pi)
    phi = np.where(np.isfinite(z), phi, 0.0)
    means = n_blocks * (phi[:-1] - phi[1:])
    out = sigma * means, np.full(n_blocks, float(n_setae) / n_blocks)
    return out + (z,) if return_edges else out


def representative_heights(
    n_setae: int,
    sigma: float,
    rng: np.random.Generator,
    n_blocks: int = 20_000,
    *,
    return_sample: bool = False,
):
    """Draw n_setae Gaussian heights (eq 28), sort, and return block means and weights.

    Under a monotone press-and-pull a seta's whole history depends only on its floor height,
    so setae adjacent in sorted height behave alike; each block of ~n_setae/n_blocks of them is
    simulated once with its mean height and counted with its size. On its own this errs by
    about 0.7/n_blocks of the peak force (a block crossing a jump-in, stick/slide or release
    boundary counts all its setae on one side); passing the sorted sample to
    :func:`press_pull` / :func:`preload_pull` / :func:`solve` (``sample=``) splits such blocks
    exactly and removes that error (measured against brute force in tests/test_quasistatic.py).

    Returns
    -------
    (heights [µm], weights [-]) each of length min(n_blocks, n_setae); with ``return_sample``
    also the sorted heights of all n_setae setae [µm].
    """
    h = rng.standard_normal(int(n_setae))
    h *= sigma
    h.sort()
    n_blocks = min(int(n_blocks), h.size)
    edges = np.linspace(0, h.size, n_blocks + 1).astype(np.int64)
    sums = np.add.reduceat(h, edges[:-1])
    counts = np.diff(edges).astype(float)
    if return_sample:
        return sums / counts, counts, h
    return sums / counts, counts


def single_seta(params: SetaArray, plate_y, height: float = 0.0, **kw) -> QuasiStaticResult:
    """One seta (eq 22–27) over a floor at ``height`` [µm] along plate heights ``plate_y``."""
    return solve(params, np.array([float(height)]), plate_y, record_setae=True, **kw)
