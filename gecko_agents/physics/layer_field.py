"""A quasi-static field of N×N fibres on an elastic backing layer, pressed and pulled by the
holder: load sharing through the layer's thickness for an area array under a flat or
spherical probe, aligned or misaligned.

The model is that of :mod:`gecko_agents.physics.fibril_probe_halfspace` (Bettscheider et al.
2021, J Mech Phys Solids 104365; units µm, µN, MPa, compression positive) with the half-space
replaced by a layer of thickness t bonded to the rigid holder
(:mod:`gecko_agents.physics.layer`), and solved for fields of 10⁴ fibres and more:

* fibre i, at (x_i, y_i) on a square lattice of pitch s, is a spring of stiffness k
  (:meth:`LayerField.from_params`: the seta's normal stiffness Ky, eq 20, in series with
  the tip law's zero-load contact stiffness) that holds the probe from the moment the probe
  reaches its tip until its tension reaches the tip law's pull-off F_r;
* its root stands on the layer, which couples the roots: w = C·f, C the layer's compliance
  between lattice sites (:func:`gecko_agents.physics.layer.point_kernel`, the fibre's base a
  disc of radius c). C is a convolution on the lattice, so C·f is one zero-padded FFT, O(N log
  N), and the attached fibres' forces solve (C_AA + I/k)·f_A = d + h_A by conjugate gradients
  (C_AA + I/k is symmetric positive definite);
* the probe's height over fibre i is h_i ≤ 0 (:func:`probe_heights`: flat, flat tilted by
  the misalignment, or a sphere, :func:`gecko_agents.floor.probe.probe_heights`), d the depth
  the holder has moved past first touch.

Between events f_A = a·d + b is linear in d, so the press (to the preload) and the pull go
from event to event as in :func:`~gecko_agents.physics.fibril_probe_halfspace.probe_test`:
free fibres attach when the probe reaches them (the layer around pressed fibres sinks and
lowers them), attached ones let go at −F_r, and several that cross within ``resolution`` [µm]
of depth of the first go together (the exact event-driven test is
``probe_test(h, I/k + C, F_r, P)``; ``tests/test_layer_field.py`` holds this one to it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from scipy.sparse.linalg import LinearOperator, cg

from gecko_agents.floor.probe import probe_heights as sphere_heights
from gecko_agents.physics import layer

__all__ = ["FieldTest", "LayerField", "LayerOperator", "press_pull", "probe_heights"]


@dataclass(frozen=True)
class LayerField:
    """An n×n square field of fibres on an elastic layer bonded to the rigid holder.

    Attributes
    ----------
    n : fibres per side (n² in all), 1 … ``n_max``.
    pitch : lattice spacing s [µm], > 0.
    radius : fibre base radius c [µm], in (0, s/2].
    stiffness : fibre stiffness k [µN/µm], > 0.
    release_force : tension F_r at which a fibre lets go [µN], > 0.
    thickness : layer thickness t [µm], in (0, inf] (inf: the half-space).
    modulus : layer Young's modulus E [MPa], > 0.
    poisson : layer Poisson ratio ν, in [0, 0.5] (0.5, incompressible, is regular here:
        :mod:`gecko_agents.physics.layer`).
    """

    n: int
    pitch: float
    radius: float
    stiffness: float
    release_force: float
    thickness: float
    modulus: float
    poisson: float
    n_max: ClassVar[int] = 1000
    """Largest n taken: the event-to-event solution of :func:`press_pull` is the oracle of
    small fields (:mod:`gecko_agents.physics.pad_field` takes pads to 4096².)"""

    def __post_init__(self):
        def bad(name, span):
            raise ValueError(
                f"{type(self).__name__}.{name} = {getattr(self, name)!r} must be in {span}"
            )

        if not (isinstance(self.n, int | np.integer) and 1 <= self.n <= self.n_max):
            bad("n", f"[1, {self.n_max}] (an integer)")
        for name in ("pitch", "stiffness", "release_force", "modulus"):
            v = getattr(self, name)
            if not (isinstance(v, int | float) and math.isfinite(v) and v > 0):
                bad(name, "(0, inf)")
        if not (isinstance(self.radius, int | float) and 0 < self.radius <= 0.5 * self.pitch):
            bad("radius", f"(0, pitch/2 = {0.5 * self.pitch:g}] µm")
        if not (isinstance(self.thickness, int | float) and self.thickness > 0):
            bad("thickness", "(0, inf] µm")
        if not (isinstance(self.poisson, int | float) and 0.0 <= self.poisson <= 0.5):
            bad("poisson", "[0, 0.5]")

    @classmethod
    def from_params(cls, params, n: int, **layer_kw) -> LayerField:
        """The field of a :class:`gecko_agents.params.SetaArray`: pitch ``array.pitch``, base
        ``seta.r``, stiffness 1/(1/Ky + 1/k_c) (eq 20 and the tip law's zero-load contact
        stiffness k_c), release at the tip law's pull-off force, the layer of
        ``params.backing`` (t_b, E_b, nu_b); ``layer_kw`` (thickness, modulus, poisson)
        override it."""
        from gecko_agents.contact import contact_law

        law = contact_law(params)
        k = 1.0 / (1.0 / params.Ky + 1.0 / law.zero_load_stiffness)
        b = params.backing
        kw = {"thickness": b.t_b, "modulus": b.E_b, "poisson": b.nu_b} | layer_kw
        return cls(
            n=int(n),
            pitch=params.array.pitch,
            radius=params.seta.r,
            stiffness=k,
            release_force=law.pull_off_force,
            **kw,
        )

    def positions(self) -> tuple[np.ndarray, np.ndarray]:
        """Fibre positions (x, y) [µm], each (n, n), the field centred on 0."""
        c = (np.arange(self.n) - 0.5 * (self.n - 1)) * self.pitch
        return np.meshgrid(c, c, indexing="ij")


def probe_heights(field: LayerField, probe_radius=math.inf, tilt_deg=0.0) -> np.ndarray:
    """Heights h ≤ 0 [µm] (n, n) of the probe over the fibres' tips, 0 where it touches
    first: a flat probe (``probe_radius = inf``) turned by ``tilt_deg`` about the y axis (the
    −x edge touches first, as ``Backing.misalignment_deg``), or a sphere of radius R_p
    centred over the field (:func:`gecko_agents.floor.probe.probe_heights`; −R_p beyond its
    equator)."""
    x, y = field.positions()
    if not (probe_radius > 0):
        raise ValueError(f"probe_radius = {probe_radius!r} µm must be in (0, inf]")
    if not -10.0 <= tilt_deg <= 10.0:
        raise ValueError(f"tilt_deg = {tilt_deg!r} must be in [-10, 10]")
    if math.isfinite(probe_radius):
        if tilt_deg:
            raise ValueError("tilt_deg needs a flat probe (probe_radius = inf)")
        return sphere_heights(np.hypot(x, y), probe_radius)
    h = -math.tan(math.radians(abs(tilt_deg))) * x * math.copysign(1.0, tilt_deg)
    return h - h.max()


class LayerOperator:
    """w = C·f on the field's lattice by FFT: the layer's kernel
    (:func:`gecko_agents.physics.layer.point_kernel`) at every lattice offset, zero-padded to
    (2n)² so that the convolution is not periodic. Units µm/µN."""

    def __init__(self, field: LayerField):
        n, s = field.n, field.pitch
        self.n, self.m = n, 2 * n
        i = np.arange(self.m)
        off = np.where(i < n, i, i - self.m) * s  # offsets 0…n−1, then −n…−1
        r = np.hypot(off[:, None], off[None, :])
        u, inv = np.unique(np.round(r, 9), return_inverse=True)
        args = (field.thickness, field.modulus, field.poisson, field.radius)
        kernel = layer.point_kernel(u, *args)[inv].reshape(r.shape)
        self.self_term = float(kernel[0, 0])
        self._k_hat = np.fft.rfft2(kernel)
        self.calls = 0

    def __call__(self, f: np.ndarray) -> np.ndarray:
        """Displacements w [µm] (n, n) of the roots under forces ``f`` [µN] (n, n)."""
        self.calls += 1
        w = np.fft.irfft2(np.fft.rfft2(f, (self.m, self.m)) * self._k_hat, (self.m, self.m))
        return w[: self.n, : self.n]


@dataclass(frozen=True)
class FieldTest:
    """Result of :func:`press_pull`.

    Attributes
    ----------
    pull_off : largest tension on the probe [µN] (0 if none).
    depth_max : depth at the preload [µm]. attached_max : fibres attached there.
    depth, force, attached : the path through its events (depth [µm], force on the probe
        [µN, compression positive], fibres attached), pressing then pulling.
    front : for each pulled event, the mean distance [µm] from the field's centre of the
        fibres that let go there (NaN where none did): where the detachment runs.
    released_at : depth [µm] (n, n) at which each fibre let go (NaN if never attached).
    release_event : index (n, n) into the path of the event at which each fibre let go (−1
        if never attached): the order of a cascade at one depth.
    solves : conjugate-gradient solves; matvecs : FFT products C·f.
    """

    pull_off: float
    depth_max: float
    attached_max: int
    depth: np.ndarray
    force: np.ndarray
    attached: np.ndarray
    front: np.ndarray
    released_at: np.ndarray
    release_event: np.ndarray
    solves: int
    matvecs: int


class _Solver:
    """f_A = a·d + b for the attached set: (C_AA + I/k)·[a, b] = [1, h_A] by Jacobi-
    preconditioned conjugate gradients from the last solution."""

    def __init__(self, field, op, h, rtol):
        self.op, self.h, self.rtol, self.k = op, h, rtol, field.stiffness
        self.a = np.zeros_like(h)
        self.b = np.zeros_like(h)
        self.solves = 0

    def solve(self, att):
        idx = np.flatnonzero(att)
        full = np.zeros(att.shape)

        def mv(v):
            full.ravel()[idx] = v
            return self.op(full).ravel()[idx] + v / self.k

        A = LinearOperator((idx.size, idx.size), matvec=mv, dtype=float)
        diag = self.op.self_term + 1.0 / self.k
        M = LinearOperator((idx.size, idx.size), matvec=lambda v: v / diag, dtype=float)
        out = []
        for rhs, x0 in ((np.ones(idx.size), self.a), (self.h.ravel()[idx], self.b)):
            x, info = cg(A, rhs, x0=x0.ravel()[idx], rtol=self.rtol, atol=0.0, M=M, maxiter=5000)
            if info != 0:
                raise RuntimeError(f"conjugate gradients did not converge ({info})")
            full_x = np.zeros(att.shape)
            full_x.ravel()[idx] = x
            out.append(full_x)
            self.solves += 1
        self.a, self.b = out
        return self.a, self.b


def _press(solver, op, h, att, preload, resolution, path):
    """Press from first touch to ``preload`` [µN]; returns the depth reached."""
    d = -float(h.max())
    while True:
        a, b = solver.solve(att)
        d_pre = (preload - b.sum()) / a.sum()
        ua, ub = op(a), op(b)
        free = ~att
        slope, gap0 = 1.0 - ua[free], h[free] - ub[free]
        with np.errstate(divide="ignore", invalid="ignore"):
            cross = np.where(slope > 0.0, -gap0 / slope, np.inf)
        first = float(cross.min()) if cross.size else math.inf
        if d_pre <= first:
            path.append((d_pre, preload, int(att.sum()), math.nan))
            return d_pre
        d = max(d, first)
        path.append((d, float(a.sum() * d + b.sum()), int(att.sum()), math.nan))
        idx = np.flatnonzero(free)[cross <= d + resolution]
        att.ravel()[idx] = True


def _pull(solver, h, att, d, F_r, resolution, radius, released, path):
    """Pull until every fibre has let go, noting in ``released`` (depth, event) where each
    let go; returns the largest tension [µN]."""
    released_at, event = released
    best, ftol = 0.0, 1e-9 * F_r
    while att.any():
        a, b = solver.solve(att)
        f = a * d + b
        over = att & (f < -F_r - ftol)
        if over.any():  # unstable after a release: these follow at the same depth
            path.append((d, float(f[att].sum()), int(att.sum()), float(radius[over].mean())))
            released_at[over], event[over] = d, len(path) - 1
            att[over] = False
            continue
        with np.errstate(divide="ignore", invalid="ignore"):
            d_rel = np.where(att & (a > 0.0), (-F_r - b) / a, -np.inf)
        d = min(d, float(d_rel.max()))
        force = float(a[att].sum() * d + b[att].sum())
        best = max(best, -force)
        going = att & (d_rel >= d - resolution)
        path.append((d, force, int(att.sum()), float(radius[going].mean())))
        released_at[going], event[going] = d, len(path) - 1
        att[going] = False
    path.append((d, 0.0, 0, math.nan))
    return best


def press_pull(
    field: LayerField, heights, preload: float, resolution: float = 1e-4, rtol: float = 1e-9
) -> FieldTest:
    """Press the probe onto ``field`` to ``preload`` [µN] and pull it off (module docstring).

    Parameters
    ----------
    field : the :class:`LayerField`. heights : h ≤ 0 [µm] (n, n) (:func:`probe_heights`).
    preload : compressive force the press reaches [µN], > 0. resolution : fibres that reach
        their event within this depth [µm] of the first go with it, > 0. rtol : relative
        tolerance of the conjugate-gradient solves.
    """
    h = np.asarray(heights, float)
    if h.shape != (field.n, field.n) or not np.all(np.isfinite(h)):
        raise ValueError(f"heights must be a finite ({field.n}, {field.n}) array, got {h.shape}")
    if not (math.isfinite(preload) and preload > 0):
        raise ValueError(f"preload = {preload!r} µN must be in (0, inf)")
    if not (math.isfinite(resolution) and resolution > 0):
        raise ValueError(f"resolution = {resolution!r} µm must be in (0, inf)")
    op = LayerOperator(field)
    solver = _Solver(field, op, h, rtol)
    att = h >= h.max() - 1e-12 * (np.ptp(h) + 1.0)
    path: list = []
    d_max = _press(solver, op, h, att, preload, resolution, path)
    n_max = int(att.sum())
    released = np.full(h.shape, np.nan), np.full(h.shape, -1)
    x, y = field.positions()
    best = _pull(
        solver, h, att, d_max, field.release_force, resolution, np.hypot(x, y), released, path
    )
    d, F, n, front = (np.array(v) for v in zip(*path, strict=True))
    return FieldTest(
        best, d_max, n_max, d, F, n.astype(int), front, *released, solver.solves, op.calls
    )
