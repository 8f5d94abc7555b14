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
one step costs O(N). For very large arrays (the paper's 10⁷ setae) :func:`representative_heights`
replaces the sorted heights by block means with weights: every seta's history under a monotone
press-and-pull depends on its height alone, so blocks of neighbours in height behave alike.

Units: µm, µN (see :mod:`gecko_agents.params`). The plate only moves vertically here.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from . import beam, jkr
from .params import SetaArray

__all__ = ["release_radius", "Branches", "QuasiStaticResult", "solve", "press_pull",
           "retract_travel",
           "preload_pull", "representative_heights", "plate_start_height", "single_seta"]

FREE, STICK, SLIP = 0, 1, 2


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
    def from_params(cls, params: SetaArray, lateral: str = "coupled",
                    stiffness_scale: float = 1.0, tangential_stiffness: float = math.inf,
                    n_grid: int = 16384) -> Branches:
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
        K = beam.stiffness_matrix(params.axial_stiffness * stiffness_scale,
                                  params.bending_stiffness * stiffness_scale, params.seta.theta)
        Kxx, Kxy, Kyy = float(K[0, 0]), float(K[0, 1]), float(K[1, 1])
        Ky = Kyy - Kxy * Kxy / Kxx      # Schur complement = eq 20
        r_t = 1.0 if math.isinf(tangential_stiffness) else (
            tangential_stiffness / (Kxx + tangential_stiffness))
        Kyy_stick = Kyy - Kxy * Kxy * (1.0 - r_t) / Kxx
        mu = params.friction.mu if lateral == "coupled" else 0.0
        self = cls(R, w, Es, params.contact.pull_off_force, params.seta.L, params.seta.theta,
                   Kxx, Kxy, Kyy, Ky, r_t, Kyy_stick, mu, params.friction.law, lateral,
                   {}, {}, {})
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
                        "the sliding seta's normal stiffness negative; lower friction.mu")
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

    def invert(self, name, target):
        """Contact radius on branch b with G_b(a) = target, NaN where none exists [µm]."""
        a_tab, G_tab = self.a_grid[name], self.G_grid[name]
        target = np.asarray(target, dtype=float)
        if np.any(target < G_tab[-1]):
            raise ValueError("a seta is compressed beyond the tabulated range "
                             f"(G = {target.min():.3g} µm); the plate went implausibly deep")
        a = np.interp(target, G_tab[::-1], a_tab[::-1])
        a_f = self.a_fold[name]
        for _ in range(2):  # Newton polish of the interpolated start; G' < 0 above the fold
            slope = self.dG(name, a)
            ok = slope < 0
            a = np.where(ok, np.maximum(a - (self.G(name, a) - target) / np.where(ok, slope, -1.0),
                                        a_f), a)
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


def _step(br: Branches, st: _State, Z: float, h: np.ndarray):
    """Equilibrate every seta at plate height Z; update ``st`` in place.

    Returns (P, F_t, δ, released mask, release overlaps).
    """
    n = len(h)
    t0 = Z - br.L * np.sin(br.theta) - h - br.R   # G target for zero lateral shift
    P = np.zeros(n)
    Ft = np.zeros(n)
    delta = -t0.copy()                            # free tip: δ = h + R − p0_y
    was = st.state != FREE
    st.state[(~was) & (delta >= 0.0)] = STICK     # jump-in at δ = 0
    st.u[(~was) & (delta >= 0.0)] = 0.0
    st.sigma[(~was) & (delta >= 0.0)] = 0.0
    att = st.state != FREE
    released = np.zeros(n, dtype=bool)
    rel_overlap = np.full(n, np.nan)
    idx = np.flatnonzero(att)
    if idx.size == 0:
        return P, Ft, delta, released, rel_overlap
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
        return P, Ft, delta, released, rel_overlap

    # 1) Stick trial at the previous anchor (u: anchor abscissa relative to the rest tip).
    u = st.u[idx]
    a = br.invert("stick", t0[idx] - br.r_t * br.Kxy * u / br.Kyy_stick)
    exists = np.isfinite(a)
    a_s = np.where(exists, a, br.a_fold["stick"])
    Ps = jkr.force_from_radius(a_s, *args)
    dy = (Ps - br.r_t * br.Kxy * u) / br.Kyy_stick
    e = br.r_t * u - (1.0 - br.r_t) * br.Kxy * dy / br.Kxx   # tip abscissa
    Ft_s = br.Kxx * e + br.Kxy * dy
    stick_ok = exists & (np.abs(Ft_s) <= br.cap(Ps) * (1 + 1e-12))
    j = idx[stick_ok]
    P[j], Ft[j] = Ps[stick_ok], Ft_s[stick_ok]
    delta[j] = jkr.overlap_from_radius(a_s[stick_ok], *args)
    st.state[j] = STICK

    # 2) Slide where sticking is impossible: friction takes the sign the spring demanded.
    k = ~stick_ok
    if np.any(k):
        jk = idx[k]
        sig = np.where(Ft_s[k] >= 0, 1.0, -1.0)
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
        gone = jk[~ok]
        st.state[gone] = FREE
        st.u[gone] = 0.0
        released[gone] = True
        # Release overlap: the fold of the branch that failed (stick if it never slid).
        rel_a = np.where(exists[k], fold, br.a_fold["stick"])[~ok]
        rel_overlap[gone] = jkr.overlap_from_radius(rel_a, *args)
        delta[gone] = -t0[gone]
    return P, Ft, delta, released, rel_overlap


def plate_start_height(params: SetaArray, heights, gap: float = 0.5) -> float:
    """Plate height at which the highest seta's free tip is ``gap`` [µm] above its floor [µm]."""
    return float(np.max(heights) + params.contact.R + params.seta.L * np.sin(params.seta.theta)
                 + gap)


def solve(params: SetaArray, heights, plate_y, *, weights=None, lateral: str = "coupled",
          stiffness_scale: float = 1.0, tangential_stiffness: float = math.inf,
          record_setae: bool = False, branches: Branches | None = None,
          stop_when_free_after: int | None = None) -> QuasiStaticResult:
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
    branches : prebuilt :class:`Branches` (``lateral`` and ``stiffness_scale`` are then unused).
    stop_when_free_after : stop at the first step past this index where no seta is attached.
    """
    br = branches or Branches.from_params(params, lateral, stiffness_scale, tangential_stiffness)
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    Zs = np.asarray(plate_y, dtype=float)
    if not np.all(np.isfinite(Zs)):
        raise ValueError("plate_y must be finite")
    st = _State(h.size)
    out = _Recorder(Zs.size, h.size, record_setae)
    for i, Z in enumerate(Zs):
        P, Ft, d, rel, rel_d = _step(br, st, Z, h)
        out.record(i, P, Ft, d, st, w, rel, rel_d)
        if stop_when_free_after is not None and i > stop_when_free_after and not np.any(
                st.state != FREE):
            return out.result(Zs, w, h, keep=i + 1)
    return out.result(Zs, w, h)


class _Recorder:
    def __init__(self, n, N, per_seta):
        self.F = np.zeros(n)
        self.T = np.zeros(n)
        self.na = np.zeros(n)
        self.per = ({k: np.zeros((n, N)) for k in ("force", "overlap", "tip_dx")}
                    | {"state": np.zeros((n, N), dtype=np.int8)}) if per_seta else {}
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
        return QuasiStaticResult(Zs[sl], self.F[sl], self.T[sl], self.na[sl], w, h,
                                 {k: v[sl] for k, v in self.per.items()}, self.releases)


def retract_travel(params: SetaArray, br: Branches, heights, Z_from: float) -> float:
    """Plate travel up from Z_from [µm] after which every seta has surely let go [µm].

    Back past the start height, plus the stretch of the softest branch holding Fc.
    """
    k_soft = min(br.Ky / (1 + abs(br.Kxy / br.Kxx) * br.mu), br.Kyy)
    return (plate_start_height(params, heights, 0.0) - Z_from
            + 1.5 * params.contact.pull_off_force / k_soft
            + 20 * abs(params.contact.snap_off_overlap))


def press_pull(params: SetaArray, heights, depth: float, *, n_approach: int = 500,
               n_retract: int = 2000, start_gap: float = 0.5, lateral: str = "coupled",
               stiffness_scale: float = 1.0, tangential_stiffness: float = math.inf,
               weights=None,
               record_setae: bool = False) -> QuasiStaticResult:
    """Displacement control: approach to ``depth`` [µm], then retract.

    ``depth`` is measured from the plate height at which a resting tip touches the floor's
    mean plane (h = 0), so it does not depend on the highest asperity of a sample. The plate
    starts ``start_gap`` [µm] above the highest tip's touch-down and moves down to that depth
    in ``n_approach`` equal steps; it then retracts in ``n_retract`` equal
    steps over :func:`retract_travel`, stopping early once every seta has let go. Equilibria
    are exact at every step; the step only sets how finely the curve and the release points
    are sampled (friction slides in one direction per leg, so the path is resolved exactly).
    """
    if not depth > 0:
        raise ValueError(f"depth = {depth!r} must be > 0 [µm]")
    br = Branches.from_params(params, lateral, stiffness_scale, tangential_stiffness)
    Z0 = plate_start_height(params, heights, start_gap)
    Zmin = plate_start_height(params, [0.0], 0.0) - depth
    if Zmin >= Z0:
        raise ValueError(f"depth = {depth!r} µm does not reach the highest floor point "
                         f"({np.max(heights):.3g} µm above the mean plane)")
    up = retract_travel(params, br, heights, Zmin)
    Zs = np.concatenate([np.linspace(Z0, Zmin, n_approach + 1),
                         Zmin + up * np.arange(1, n_retract + 1) / n_retract])
    res = solve(params, heights, Zs, weights=weights, record_setae=record_setae, branches=br,
                stop_when_free_after=n_approach)
    return res


def preload_pull(params: SetaArray, heights, preload: float, *, dz: float | None = None,
                 weights=None, lateral: str = "coupled", stiffness_scale: float = 1.0,
                 tangential_stiffness: float = math.inf, record_setae: bool = False,
                 max_steps: int = 200_000,
                 retract_steps: int | None = None) -> QuasiStaticResult:
    """Force control: approach until the total normal force equals ``preload`` [µN], retract.

    The turning point is found by bisection on the last approach step (restarting from the
    saved state), so the preload is hit to 1e-9 relative; the plate then retracts in up to
    ``retract_steps`` (default 4000) steps of at least ``dz`` [µm] over
    :func:`retract_travel`, stopping once every seta has let go.

    Parameters
    ----------
    preload : target compressive force [µN], > 0.
    dz : plate step [µm]; default |δc|/20.
    """
    if not preload > 0:
        raise ValueError(f"preload = {preload!r} must be > 0 [µN]")
    br = Branches.from_params(params, lateral, stiffness_scale, tangential_stiffness)
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    dz = abs(params.contact.snap_off_overlap) / 20 if dz is None else float(dz)
    if not dz > 0:
        raise ValueError(f"dz = {dz!r} must be > 0 [µm]")
    st = _State(h.size)
    Z_start = plate_start_height(params, h, 0.5)
    Z = Z_start
    Zs, results = [], []

    def keep(Z, res, state):
        Zs.append(Z)
        results.append((res, state.copy()))

    for _ in range(max_steps):
        saved = st.copy()
        res = _step(br, st, Z, h)
        if np.sum(w * res[0]) < preload:
            keep(Z, res, st)
            Z -= dz
            continue
        # Overshot: bisect the plate height between the last two steps from the saved state.
        lo, hi, best = Z + dz, Z, (res, st)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            trial = saved.copy()
            r = _step(br, trial, mid, h)
            if np.sum(w * r[0]) >= preload:
                hi, best = mid, (r, trial)
                if np.sum(w * r[0]) - preload <= 1e-9 * preload:
                    break
            else:
                lo = mid
        res, st = best
        Z = hi
        keep(Z, res, st)
        break
    else:
        raise RuntimeError(f"preload {preload} µN not reached within {max_steps} steps of "
                           f"{dz} µm; the floor may be out of reach")
    # Retract until every seta has let go; a soft seta can stretch by up to ~Fc/Ky first.
    n_up = retract_steps or 4000
    dz_up = max(dz, retract_travel(params, br, h, Z) / n_up)
    for _ in range(n_up):
        Z += dz_up
        res = _step(br, st, Z, h)
        keep(Z, res, st)
        if Z > Z_start and not np.any(st.state != FREE):
            break
    rec = _Recorder(len(Zs), h.size, record_setae)
    for i, ((P, Ft, d, rel, rel_d), s) in enumerate(results):
        rec.record(i, P, Ft, d, s, w, rel, rel_d)
    return rec.result(np.asarray(Zs), w, h)


def representative_heights(n_setae: int, sigma: float, rng: np.random.Generator,
                           n_blocks: int = 20_000) -> tuple[np.ndarray, np.ndarray]:
    """Draw n_setae Gaussian heights (eq 28), sort, and return block means and weights.

    Under a monotone press-and-pull a seta's whole history depends only on its floor height,
    so setae adjacent in sorted height behave alike; each block of ~n_setae/n_blocks of them is
    simulated once with its mean height and counted with its size. The error is measured
    against brute force in tests/test_quasistatic.py.

    Returns
    -------
    (heights [µm], weights [-]) each of length min(n_blocks, n_setae).
    """
    h = np.sort(sigma * rng.standard_normal(int(n_setae)))
    n_blocks = min(int(n_blocks), h.size)
    edges = np.linspace(0, h.size, n_blocks + 1).astype(np.int64)
    sums = np.add.reduceat(h, edges[:-1])
    counts = np.diff(edges).astype(float)
    return sums / counts, counts


def single_seta(params: SetaArray, plate_y, height: float = 0.0, **kw) -> QuasiStaticResult:
    """One seta (eq 22–27) over a floor at ``height`` [µm] along plate heights ``plate_y``."""
    return solve(params, np.array([float(height)]), plate_y, record_setae=True, **kw)
