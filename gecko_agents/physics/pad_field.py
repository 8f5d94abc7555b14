"""The fibre field on a backing layer at the size of a pad (10⁵–10⁷ fibres): the model of
:mod:`gecko_agents.physics.layer_field` solved by load steps instead of event to event.

Same fibres, layer, probe and law (units µm, µN, MPa; compression positive): fibre i is a
spring of stiffness k on the layer's compliance C
(:func:`gecko_agents.physics.layer.point_kernel` on the lattice), attached fibres satisfy
(C_AA + I/k)·f_A = d + h_A, and a fibre lets go at the tension F_r. What changes is how the
path is followed:

* **the press** is the frictionless unilateral contact of the fibres with the probe at the
  preload P: attached fibres push (f ≥ 0), free ones clear the probe (gap ≤ 0), solved by
  an active set (all penetrated fibres added, all pulling ones dropped, at the depth that
  carries P, until neither is left; Kikuchi & Oden 1988, Contact Problems in Elasticity,
  SIAM, ch. 5, the active-set method for the discrete Signorini problem). The event-to-event
  press reaches the same state wherever every attached fibre's force grows with depth (a
  linear complementarity problem with a positive definite matrix has one solution; Cottle,
  Pang & Stone 1992, The Linear Complementarity Problem, Academic Press, thm 3.1.6);
* **the pull** goes from release to release: for the attached set A, f = f₀ + a·(d − d₀) with
  (C_AA + I/k)·a = 1 (one warm-started solve per step), which gives the depth of the next
  release exactly; there every fibre within ``force_tol``·F_r of its pull-off goes together,
  and the cascade at that depth is solved by re-solving (C_AA + I/k)·f_A = d + h_A after
  each round of releases until no fibre is over its pull-off (one solve per round); within a
  cascade the fibres within ``cascade_tol``·F_r go in the next round too, and a round after
  which the cascade would stop is taken again without them (so the tolerance never moves
  where a cascade ends).

The tolerance's effect on the pull-off, against
:func:`~gecko_agents.physics.layer_field.press_pull` (the oracle of small fields), is pinned in
``tests/test_layer_field_pad.py`` and measured against N by :mod:`gecko_agents.bench_pad`.
C·f is one real FFT of the field padded to n + (the kernel's reach,
:data:`gecko_agents.physics.layer.CUTOFF` thicknesses), at most 2n (``scipy.fft``, ``workers``
threads); the solves are scipy's conjugate gradients on the whole lattice with the free fibres'
rows the identity (Jacobi preconditioned).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import scipy.fft as sfft
from scipy.interpolate import CubicSpline
from scipy.sparse.linalg import LinearOperator, cg

from gecko_agents.physics import layer
from gecko_agents.physics.layer_field import FieldTest, LayerField

__all__ = ["PAD_TOLERANCES", "PadField", "PadOperator", "lattice_kernel", "press_pull_pad"]

DIRECT_MAX = 2_000
"""Distinct lattice distances up to which the kernel is evaluated point by point (a field of
about 45² and less); beyond, the layer's smooth correction is interpolated
(:func:`lattice_kernel`)."""
_CHUNK = 128  # distances per call of the point kernel: its quadrature holds 128 × 10⁴ values
SPLINE_STEP = 1.0 / 64.0
"""Node spacing of the interpolated correction, in layer thicknesses [-] (its error, 4e-11 of
the self term, in ``tests/test_layer_field_pad.py``)."""
PAD_TOLERANCES = {
    "force_tol": 3e-3,
    "cascade_tol": 0.05,
    "cg_tol": 1e-5,
    "single": True,
    "stop_early": True,
}
"""The pad studies' settings of :func:`press_pull_pad`: their cost in pull-off against the
event-to-event test is pinned (≤ 0.5 %, ``tests/test_layer_field_pad.py``) and measured
against N by :mod:`gecko_agents.bench_pad`."""


@dataclass(frozen=True)
class PadField(LayerField):
    """A :class:`~gecko_agents.physics.layer_field.LayerField` of up to 4096² fibres (a pad of
    16 mm at a 4 µm pitch); the same attributes and ranges otherwise."""

    n_max: ClassVar[int] = 4096


def _interpolated_kernel(r, thickness, modulus, poisson, radius):
    """:func:`~gecko_agents.physics.layer.point_kernel` at many distances ``r`` [µm]: the
    half-space's 1/(πE*r) exactly, less the layer's correction (smooth on the scale of t, the
    Hankel transform of (1 − g(s))) from a cubic spline through it every ``SPLINE_STEP``·t."""
    t = float(thickness)
    Es = layer.contact_modulus(modulus, poisson)
    out = np.zeros_like(r)
    self_ = r == 0.0
    out[self_] = layer.point_kernel(0.0, thickness, modulus, poisson, radius)
    near = ~self_ & (r <= layer.CUTOFF * t)
    if near.any():
        lo, hi = float(r[near].min()), float(r[near].max())
        count = max(4, math.ceil((hi - lo) / (SPLINE_STEP * t)) + 1)
        nodes = np.linspace(lo, hi, count)
        kernel = np.concatenate([
            layer.point_kernel(nodes[i : i + _CHUNK], thickness, modulus, poisson, radius)
            for i in range(0, count, _CHUNK)
        ])  # fmt: skip
        corr = 1.0 / (math.pi * Es * nodes) - kernel
        out[near] = 1.0 / (math.pi * Es * r[near]) - CubicSpline(nodes, corr)(r[near])
    return out


def lattice_kernel(field: LayerField, m: int) -> np.ndarray:
    """The layer's kernel [µm/µN] at every slot of an m×m grid (m ≥ n) holding the lattice
    offsets 0 … n − 1 then −(m − n) … −1 along each axis: the FFT's wrapped kernel. Distances
    are taken once each (by the integer i² + j²); past ``DIRECT_MAX`` of them through
    ``_interpolated_kernel``."""
    n, s = field.n, field.pitch
    i = np.arange(m)
    off = np.where(i < n, i, i - m).astype(np.int64)
    key = off[:, None] ** 2 + off[None, :] ** 2
    u, inv = np.unique(key, return_inverse=True)
    r = np.sqrt(u.astype(float)) * s
    args = (field.thickness, field.modulus, field.poisson, field.radius)
    if math.isinf(field.thickness) or u.size <= DIRECT_MAX:
        values = layer.point_kernel(r, *args)
    else:
        values = _interpolated_kernel(r, *args)
    return values[inv].reshape(m, m)


class PadOperator:
    """w = C·f [µm] on the field's lattice by real FFTs, zero-padded to the next fast length
    past n + (the kernel's reach in pitches), at most 2n: the convolution is not periodic,
    and a thin layer's field needs little padding. ``workers``: FFT threads (scipy.fft);
    ``single``: the transforms in single precision (relative error ~1e-7, half the time)."""

    def __init__(self, field: LayerField, workers: int | None = None, single: bool = False):
        n, s, t = field.n, field.pitch, field.thickness
        reach = n if math.isinf(t) else min(n, math.ceil(layer.CUTOFF * t / s))
        self.n, self.m, self.workers = n, sfft.next_fast_len(n + reach, real=True), workers
        kernel = lattice_kernel(field, self.m)
        self.self_term = float(kernel[0, 0])
        self.dtype = np.float32 if single else np.float64
        self._k_hat = sfft.rfft2(kernel.astype(self.dtype), workers=workers)
        self.calls = 0

    def __call__(self, f: np.ndarray) -> np.ndarray:
        """Displacements w [µm] (n, n) of the roots under forces ``f`` [µN] (n, n)."""
        self.calls += 1
        shape = (self.m, self.m)
        f_hat = sfft.rfft2(f.astype(self.dtype, copy=False), s=shape, workers=self.workers)
        w = sfft.irfft2(f_hat * self._k_hat, s=shape, workers=self.workers)
        return w[: self.n, : self.n].astype(float)


class _MaskedSystem:
    """(C_AA + I/k)·x_A = rhs_A on the whole lattice, the free fibres' rows the identity (their
    x stays 0), by Jacobi-preconditioned conjugate gradients (scipy) from a warm start, to a
    root-mean-square error of x below ``cg_tol``·``scale`` per attached fibre (the residual
    over 1/k bounds the error: C_AA + I/k ≥ I/k)."""

    def __init__(self, op: PadOperator, stiffness: float, release_force: float, cg_tol: float):
        self.op, self.k, self.F_r, self.cg_tol, self.solves = (
            op,
            stiffness,
            release_force,
            cg_tol,
            0,
        )
        self.shape = (op.n, op.n)

    def solve(self, att: np.ndarray, rhs: np.ndarray, x0: np.ndarray, scale: float) -> np.ndarray:
        free, size = ~att, att.size
        atol = self.cg_tol * scale * math.sqrt(att.sum()) / self.k

        def mv(v):
            v = v.reshape(self.shape) * att
            return np.where(att, self.op(v) + v / self.k, 0.0).ravel() + (free * v).ravel()

        diag = np.where(att, self.op.self_term + 1.0 / self.k, 1.0).ravel()
        A = LinearOperator((size, size), matvec=mv, dtype=float)
        M = LinearOperator((size, size), matvec=lambda v: v / diag, dtype=float)
        b = np.where(att, rhs, 0.0).ravel()
        x, info = cg(A, b, x0=np.where(att, x0, 0.0).ravel(), rtol=0.0, atol=atol, M=M,
                     maxiter=10_000)  # fmt: skip
        if info != 0:
            raise RuntimeError(f"conjugate gradients did not converge ({info})")
        self.solves += 1
        return np.where(att, x.reshape(self.shape), 0.0)


def _press(system, h, att, preload, gap_tol, F_r, max_rounds=200):
    """The contact at the preload by active sets; returns (depth, forces, unit response)."""
    op, k = system.op, system.k
    a = np.zeros_like(h)
    b = np.zeros_like(h)
    for _ in range(max_rounds):
        a = system.solve(att, np.ones_like(h), a, k)
        b = system.solve(att, h, b, F_r)
        d = (preload - b.sum()) / a.sum()
        f = a * d + b
        gap = d + h - op(f)  # > 0: the probe is past the free fibre's tip
        add = ~att & (gap > gap_tol)
        drop = att & (f < 0.0)
        if not (add.any() or drop.any()):
            return float(d), f, a
        att |= add
        att &= ~drop
    raise RuntimeError(f"the press's active set did not settle in {max_rounds} rounds")


def _release(att, f, going, d, force, radius, released, path):
    """Let the fibres ``going`` go at depth ``d`` (one event of the path)."""
    released_at, event = released
    path.append((d, force, int(att.sum()), float(radius[going].mean())))
    released_at[going], event[going] = d, len(path) - 1
    att &= ~going
    return np.where(att, f, 0.0)


def _cascade(system, h, att, f, d, force, limits, radius, released, path, stop):
    """The cascade at depth ``d`` after its first release, round by round: in each round the
    fibres over their pull-off go and, with them, those within the cascade tolerance; should
    the cascade then stop, that round is taken again with the fibres over their pull-off
    alone (the cascade's end is not moved by the tolerance). Returns (forces, stopped)."""
    limit, in_cascade = limits
    over = att & (f <= limit)
    first = True
    while over.any():
        going = over if first else att & (f <= in_cascade)
        saved = att.copy(), f, len(path)
        f = _release(att, f, going, d, force, radius, released, path)
        if not att.any() or stop(att):
            return f, True
        f_new = system.solve(att, d + h, f, system.F_r)
        if not (att & (f_new <= limit)).any() and (going & ~over).any():
            att[:], f = saved[0], saved[1]  # the tolerance ran past the cascade's end
            del path[saved[2] :]
            released[0][going], released[1][going] = np.nan, -1
            f = _release(att, f, over, d, force, radius, released, path)
            if not att.any() or stop(att):
                return f, True
            f_new = system.solve(att, d + h, f, system.F_r)
        f, force, first = f_new, float(f_new.sum()), False
        over = att & (f <= limit)
    return f, False


def _pull(system, h, att, d, f, a, F_r, tols, radius, released, path, stop_early):
    """Pull from release to release, each cascade solved round by round at its depth; notes
    in ``released`` (depth, event) where each fibre let go; returns the largest tension [µN]
    and the last depth [µm]."""
    force_tol, cascade_tol = tols
    limit = -F_r * (1.0 - force_tol) + 1e-12 * F_r
    limits = limit, -F_r * (1.0 - max(force_tol, cascade_tol)) + 1e-12 * F_r
    best = 0.0

    def stop(att):
        return stop_early and att.sum() * F_r <= best

    while att.any():
        a = system.solve(att, np.ones_like(h), a, system.k)
        with np.errstate(divide="ignore", invalid="ignore"):
            d_rel = np.where(att & (a > 0.0), d - (f + F_r) / a, -np.inf)
        d_next = float(d_rel.max())
        if not math.isfinite(d_next):
            raise RuntimeError("no attached fibre lets go as the probe is pulled")
        f, d = f + a * (d_next - d), d_next
        force = float(f.sum())
        best = max(best, -force)
        f, stopped = _cascade(system, h, att, f, d, force, limits, radius, released, path, stop)
        if stopped:
            break
    return best, d


def press_pull_pad(
    field: LayerField,
    heights,
    preload: float,
    force_tol: float = 1e-3,
    cascade_tol: float = 0.0,
    cg_tol: float = 1e-7,
    workers: int | None = None,
    single: bool = False,
    stop_early: bool = False,
) -> FieldTest:
    """Press the probe onto ``field`` to ``preload`` [µN] and pull it off by load steps
    (module docstring); the result as :func:`gecko_agents.physics.layer_field.press_pull`'s,
    the press as its end state only.

    Parameters
    ----------
    field : a :class:`PadField` (or :class:`~gecko_agents.physics.layer_field.LayerField`).
    heights : h ≤ 0 [µm] (n, n) of the probe over the fibres' tips.
    preload : compressive force the press reaches [µN], > 0.
    force_tol : fibres within ``force_tol``·F_r of their pull-off when one lets go go with it;
        a free fibre the probe has passed by less than ``force_tol``·F_r/k [µm] is left free;
        in [0, 0.1).
    cascade_tol : within a cascade (a round of releases at one depth left fibres over their
        pull-off), every fibre within ``cascade_tol``·F_r of its pull-off goes in the next
        round, in [0, 0.2].
    cg_tol : root-mean-square error of the solved forces per fibre over F_r, in (0, 1e-3].
    workers : FFT threads (None: scipy's default, 1). single : single-precision transforms
        (:class:`PadOperator`).
    stop_early : stop once the fibres still attached could not hold the largest tension
        reached (N_A·F_r ≤ pull-off): the pull-off is then decided; they keep release depth
        NaN and event −1.
    """
    h = np.asarray(heights, float)
    if h.shape != (field.n, field.n) or not np.all(np.isfinite(h)):
        raise ValueError(f"heights must be a finite ({field.n}, {field.n}) array, got {h.shape}")
    if not (math.isfinite(preload) and preload > 0):
        raise ValueError(f"preload = {preload!r} µN must be in (0, inf)")
    if not 0.0 <= force_tol < 0.1:
        raise ValueError(f"force_tol = {force_tol!r} must be in [0, 0.1)")
    if not 0.0 <= cascade_tol <= 0.2:
        raise ValueError(f"cascade_tol = {cascade_tol!r} must be in [0, 0.2]")
    if not 0.0 < cg_tol <= 1e-3:
        raise ValueError(f"cg_tol = {cg_tol!r} must be in (0, 1e-3]")
    op = PadOperator(field, workers, single)
    system = _MaskedSystem(op, field.stiffness, field.release_force, cg_tol)
    F_r, k = field.release_force, field.stiffness
    att = h >= h.max() - 1e-12 * (np.ptp(h) + 1.0)
    d_max, f, a = _press(system, h, att, preload, force_tol * F_r / k, F_r)
    path: list = [(d_max, preload, int(att.sum()), math.nan)]
    n_max = int(att.sum())
    released = np.full(h.shape, np.nan), np.full(h.shape, -1)
    x, y = field.positions()
    best, d = _pull(
        system,
        h,
        att,
        d_max,
        f,
        a,
        F_r,
        (force_tol, cascade_tol),
        np.hypot(x, y),
        released,
        path,
        stop_early,
    )
    path.append((d, 0.0, int(att.sum()), math.nan))
    depth, force, n, front = (np.array(v) for v in zip(*path, strict=True))
    return FieldTest(
        best, d_max, n_max, depth, force, n.astype(int), front, *released, system.solves, op.calls
    )
