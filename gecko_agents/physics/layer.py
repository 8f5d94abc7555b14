"""The surface compliance of an elastic layer bonded to a rigid base: how the backing layer
shares the fibres' loads through its thickness.

An isotropic elastic layer of thickness t [µm], Young's modulus E [MPa = µN/µm²] and Poisson
ratio ν, bonded (no slip) to a rigid base (the holder) at its bottom, carries a normal pressure
p on its free top surface, no shear. Units µm, µN, MPa; compression positive, the surface
displacement w > 0 towards the base.

**Fourier space.** A pressure p̂(q)·cos(q·x) gives a displacement ŵ(q)·cos(q·x) with

    ŵ/p̂ = G(q) = 2/(E*·q)·g(qt),   E* = E/(1 − ν²),
    g(s) = [(3 − 4ν)·sinh 2s − 2s] / [(3 − 4ν)·cosh 2s + 2s² + 5 − 12ν + 8ν²]

(:func:`fourier_compliance`, :func:`layer_factor`). Derived here from Navier's equations in
plane strain (displacements (U(z) sin qx, W(z) cos qx), solutions (A + Bz)e^{±qz}; boundary
conditions σ_zz = −p̂, σ_xz = 0 on top, U = W = 0 at the base; solved symbolically); the same
expression is the finite-thickness Green's function of ContactMechanics'
``PeriodicFFTElasticHalfSpace(thickness=…)`` (ContactEngineering, MIT; its stiffness
E*q/2 times 1/g), which ``tests/test_layer.py`` compares where that package is installed.
For an isotropic layer it depends on the wave vector's length only, so it is also the 3-D
(area) Green's function with q = |q|.

**Limits.** Thick (qt → ∞): g → 1, the half-space's 2/(E*q) (Johnson 1985, Contact Mechanics,
§13.2: ŵ = 2p̂/(E*q) for a wavy pressure). Thin (qt → 0, ν < ½): G → t/M, a bed of
independent springs of the confined (oedometric) modulus M = E(1 − ν)/((1 + ν)(1 − 2ν))
(:func:`confined_modulus`; λ + 2μ, the stiffness of a laterally confined column in uniaxial
strain, and the q → 0 limit of the expression above), valid for wavelengths 2π/q ≫ t/√(1 − 2ν): G =
(t/M)·[1 + O((qt)²/(1 − 2ν))]. Incompressible (ν = ½): M is infinite and the thin layer
is not a bed of springs but squeezes sideways, G → q²t³/(3μ) (μ = E/3; the limit of the
expression above, the lubrication form w = −(t³/3μ)∇²p of a thin bonded incompressible
layer): it is handled explicitly here (the expression is regular at ν = ½).

**Real space.** :func:`line_kernel` (plane strain, the engine's row: each fibre's force spread
over a strip of width w along the row and over the row spacing b across it) and
:func:`point_kernel` (3-D, an N×N field: Boussinesq's 1/(πE*r) minus the layer's correction,
the self term the mean over the fibre's base disc of radius c, both as in
:func:`gecko_agents.physics.fibril_probe_halfspace.halfspace_compliance`, to which it reduces
at t = ∞). A bonded layer's kernel decays as e^{−κr/t} (G is analytic and even in q), so
beyond :data:`CUTOFF` thicknesses it is set to 0.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.special import j0, j1

__all__ = [
    "CUTOFF",
    "confined_modulus",
    "contact_modulus",
    "field_compliance",
    "fourier_compliance",
    "layer_factor",
    "line_kernel",
    "point_kernel",
    "row_compliance",
    "thin_layer_compliance",
]

CUTOFF = 30.0
"""Distance, in layer thicknesses, beyond which the kernels are taken as 0 [-]: the layer's
kernel there is below 1e-10 of its value at 0 (``tests/test_layer.py``)."""

_S_MAX = 40.0  # the integrands' tails in s = qt decay as e^{−s}: e^{−40} ≈ 4e-18
_PANELS, _NODES = 640, 16  # composite Gauss–Legendre on [0, _S_MAX]: ~20 nodes per period


def _check_layer(thickness, modulus, poisson, infinite_ok=True):
    """Refuse a thickness ∉ (0, ∞] (∞ only if ``infinite_ok``), a modulus ∉ (0, ∞) and
    ν ∉ [0, ½], naming the argument, its value and the range."""
    t, E, nu = float(thickness), float(modulus), float(poisson)
    if not (t > 0.0 and (math.isfinite(t) or (infinite_ok and t == math.inf))):
        span = "(0, inf]" if infinite_ok else "(0, inf)"
        raise ValueError(f"thickness = {thickness!r} µm must be in {span}")
    if not (math.isfinite(E) and E > 0.0):
        raise ValueError(f"modulus = {modulus!r} MPa must be in (0, inf)")
    if not 0.0 <= nu <= 0.5:
        raise ValueError(f"poisson = {poisson!r} must be in [0, 0.5]")
    return t, E, nu


def contact_modulus(modulus: float, poisson: float) -> float:
    """E* = E/(1 − ν²) [MPa] of the layer against a rigid body (Johnson 1985, §4.2).

    Parameters
    ----------
    modulus : E [MPa]. poisson : ν [-].
    """
    return modulus / (1.0 - poisson * poisson)


def confined_modulus(modulus: float, poisson: float) -> float:
    """Confined (oedometric) modulus M = λ + 2μ = E(1 − ν)/((1 + ν)(1 − 2ν)) [MPa]: the
    stress per strain of a column that cannot expand sideways (uniaxial strain of Hooke's law
    in Lamé's constants); ``inf`` at ν = ½ (incompressible).

    Parameters
    ----------
    modulus : E [MPa], > 0. poisson : ν, in [0, ½].
    """
    _, E, nu = _check_layer(1.0, modulus, poisson)
    if nu == 0.5:
        return math.inf
    return E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu))


def thin_layer_compliance(thickness: float, modulus: float, poisson: float) -> float:
    """Compliance per area t/M [µm³/µN] of a thin layer on a rigid base: a fibre standing on
    an area A of it is a spring of stiffness M·A/t (module docstring, "Limits"); 0 at ν = ½
    (an incompressible layer does not give under a uniform pressure).

    Parameters
    ----------
    thickness : t [µm]. modulus : E [MPa]. poisson : ν, in [0, ½].
    """
    t, _, _ = _check_layer(thickness, modulus, poisson, infinite_ok=False)
    return t / confined_modulus(modulus, poisson)


def _sinh_minus(x):
    """sinh x − x without cancellation at small x (its series below 0.1)."""
    x = np.asarray(x, float)
    small = np.abs(x) < 0.1
    x2 = x * x
    series = x * x2 / 6.0 * (1.0 + x2 / 20.0 * (1.0 + x2 / 42.0 * (1.0 + x2 / 72.0)))
    with np.errstate(over="ignore"):
        return np.where(small, series, np.sinh(x) - x)


def layer_factor(s, poisson: float):
    """The layer's factor g(s) = G(q)·E*q/2 at s = qt [-] (module docstring): 1 on a
    half-space, E*s/(2M) + O(s³) for a thin compressible layer, 2s³/3 + O(s⁵) at ν = ½.

    Written with e^{−2s} so that it neither overflows nor cancels: (3 − 4ν)·sinh 2s − 2s =
    (3 − 4ν)(sinh 2s − 2s) + 4s(1 − 2ν).

    Parameters
    ----------
    s : qt ≥ 0 [-] (array). poisson : ν, in [0, ½].
    """
    nu = _check_layer(1.0, 1.0, poisson)[2]
    s = np.asarray(s, float)
    a = 3.0 - 4.0 * nu
    c = 5.0 - 12.0 * nu + 8.0 * nu * nu
    big = s > 20.0
    sb = np.where(big, s, 0.0)
    e2, e4 = np.exp(-2.0 * sb), np.exp(-4.0 * sb)
    g_big = (a * (1.0 - e4) - 4.0 * sb * e2) / (a * (1.0 + e4) + 2.0 * (2.0 * sb * sb + c) * e2)
    sm = np.where(big, 0.0, s)
    num = a * _sinh_minus(2.0 * sm) + 4.0 * sm * (1.0 - 2.0 * nu)
    den = a * np.cosh(2.0 * sm) + 2.0 * sm * sm + c
    return np.where(big, g_big, num / den)


def fourier_compliance(q, thickness: float, modulus: float, poisson: float):
    """Surface compliance G(q) = ŵ/p̂ [µm³/µN] of the layer at wave number q [1/µm] (module
    docstring): 2/(E*q)·g(qt); t/M at q = 0 (0 at ν = ½); 2/(E*q) for ``thickness = inf``
    (the half-space, infinite at q = 0).

    Parameters
    ----------
    q : wave numbers |q| ≥ 0 [1/µm] (array). thickness : t [µm], in (0, inf].
    modulus : E [MPa]. poisson : ν, in [0, ½].
    """
    t, E, nu = _check_layer(thickness, modulus, poisson)
    q = np.abs(np.asarray(q, float))
    Es = contact_modulus(E, nu)
    with np.errstate(divide="ignore"):
        hs = 2.0 / (Es * q)
    if t == math.inf:
        return hs
    g = layer_factor(q * t, nu)
    q0 = 0.0 if nu == 0.5 else t / confined_modulus(E, nu)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(q > 0.0, hs * g, q0)


@functools.lru_cache(maxsize=16)
def _rule(panels: int):
    x, w = np.polynomial.legendre.leggauss(_NODES)
    h = _S_MAX / panels
    left = h * np.arange(panels)[:, None]
    return (left + 0.5 * h * (x + 1.0)).ravel(), np.tile(0.5 * h * w, panels)


def _quadrature(frequency: float = CUTOFF):
    """Nodes and weights of a composite Gauss–Legendre rule on [0, _S_MAX] in s = qt for
    integrands oscillating up to ``frequency`` radians per unit of s: at least two panels of
    16 nodes per period."""
    return _rule(max(_PANELS, math.ceil(_S_MAX * frequency / math.pi)))


def _second_antiderivative(x, t):
    """Φ(x) with Φ'' = (1/2π)·ln((x² + t²)/x²), the line load's kernel on a half-space cut
    off at the depth t (constants and linear terms dropped: they cancel in a second
    difference)."""
    x = np.asarray(x, float)
    ax = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        xlog = np.where(ax > 0.0, x * x * np.log(np.where(ax > 0.0, ax, 1.0)), 0.0)
    return (
        0.5 * (x * x - t * t) * np.log(x * x + t * t) + 2.0 * t * x * np.arctan(x / t) - xlog
    ) / (2.0 * np.pi)


def line_kernel(d, thickness: float, modulus: float, poisson: float, width: float):
    """Plane-strain kernel K(d) [µm²/µN]: the mean displacement over a strip of width w
    of the surface under a line load of 1 µN/µm spread uniformly over another strip of
    width w, their centres d apart,

        K(d) = (1/π)∫₀^∞ G(q)·sinc²(qw/2)·cos(qd) dq,   sinc x = sin x/x.

    Evaluated as the half-space cut off at depth t, 2(1 − e^{−qt})/(E*q), whose line-load
    kernel (1/(πE*))·ln((t² + d²)/d²) is averaged over the two strips in closed form, plus
    the rest, smooth and decaying as e^{−qt}, by quadrature in s = qt. Zero beyond
    :data:`CUTOFF`·t (and finite: the layer's base holds it, where a half-space in plane
    strain has no datum, so ``thickness`` must be finite).

    Parameters
    ----------
    d : centre distances ≥ 0 [µm] (array). thickness : t [µm], finite. modulus : E [MPa].
    poisson : ν, in [0, ½]. width : w [µm], > 0 (e.g. the row's pitch: each fibre's force
    spread over its own cell).
    """
    t, E, nu = _check_layer(thickness, modulus, poisson, infinite_ok=False)
    w = float(width)
    if not (math.isfinite(w) and w > 0.0):
        raise ValueError(f"width = {width!r} µm must be in (0, inf)")
    d = np.abs(np.asarray(d, float))
    Es = contact_modulus(E, nu)
    cut = (
        _second_antiderivative(d + w, t)
        - 2.0 * _second_antiderivative(d, t)
        + _second_antiderivative(d - w, t)
    ) / (w * w)
    s, ws = _quadrature(CUTOFF + w / t)
    rest = (layer_factor(s, nu) - 1.0 + np.exp(-s)) / s * np.sinc(s * w / (2.0 * np.pi * t)) ** 2
    near = d <= CUTOFF * t
    k = np.zeros_like(d)
    if near.any():
        osc = np.cos(np.outer(d[near] / t, s))
        k[near] = 2.0 / Es * (cut[near] + osc @ (ws * rest) / np.pi)
    return k


def row_compliance(x, thickness, modulus, poisson, width, depth):
    """Compliance matrix [µm/µN] of fibre roots at abscissae ``x`` [µm] in a row standing for
    an infinite set of identical rows ``depth`` b [µm] apart (plane strain): C_ij =
    K(|x_i − x_j|)/b (:func:`line_kernel`), the force f_j [µN] of fibre j spread over a strip
    of width w along the row and b across it.

    Parameters
    ----------
    x : root abscissae [µm]. thickness, modulus, poisson, width : as :func:`line_kernel`.
    depth : b [µm], > 0 (the row spacing, ``array.pitch``).
    """
    b = float(depth)
    if not (math.isfinite(b) and b > 0.0):
        raise ValueError(f"depth = {depth!r} µm must be in (0, inf)")
    x = np.asarray(x, float)
    d = np.abs(x[:, None] - x[None, :])
    u, inv = np.unique(np.round(d, 12), return_inverse=True)
    return (line_kernel(u, thickness, modulus, poisson, width) / b)[inv].reshape(d.shape)


def point_kernel(r, thickness: float, modulus: float, poisson: float, radius: float):
    """3-D kernel C(r) [µm/µN]: the displacement at distance r > 0 from a point force of
    1 µN, and at r = 0 the mean over a disc of radius c of the displacement under 1 µN spread
    uniformly over it,

        C(r) = 1/(πE*r) − (1/(πE*t))·∫₀^∞ (1 − g(s))·J₀(s·r/t) ds,
        C(0) = 16/(3π²E*c) − (1/(πE*t))·∫₀^∞ (1 − g(s))·Λ(s·c/t)² ds,   Λ(x) = 2J₁(x)/x,

    from w(r) = (1/2π)∫₀^∞ G(q)·J₀(qr)·q dq with G = 2g/(E*q): the half-space's terms are
    Boussinesq's point load and the disc's mean (16/(3π²E*c); ∫₀^∞ J₁²(x)/x² dx = 4/(3π)),
    the values of :func:`gecko_agents.physics.fibril_probe_halfspace.halfspace_compliance`,
    to which this reduces at ``thickness = inf``; the layer's correction (1 − g(s) ≤ 1,
    decaying as s²e^{−2s}) by quadrature. Zero beyond :data:`CUTOFF`·t.

    Parameters
    ----------
    r : distances ≥ 0 [µm] (array). thickness : t [µm], in (0, inf]. modulus : E [MPa].
    poisson : ν, in [0, ½]. radius : c [µm], > 0 (the fibre's base).
    """
    t, E, nu = _check_layer(thickness, modulus, poisson)
    c = float(radius)
    if not (math.isfinite(c) and c > 0.0):
        raise ValueError(f"radius = {radius!r} µm must be in (0, inf)")
    r = np.abs(np.asarray(r, float))
    Es = contact_modulus(E, nu)
    self_ = r == 0.0
    with np.errstate(divide="ignore"):
        k = np.where(self_, 16.0 / (3.0 * np.pi * c), 1.0 / np.where(self_, 1.0, r))
    if t < math.inf:
        s, ws = _quadrature()
        tail = ws * (1.0 - layer_factor(s, nu))
        near = (r <= CUTOFF * t) & ~self_
        k = np.where(r > CUTOFF * t, 0.0, k)
        if near.any():
            k[near] -= j0(np.outer(r[near] / t, s)) @ tail / t
        if self_.any():
            s, ws = _quadrature(2.0 * c / t)
            tail = ws * (1.0 - layer_factor(s, nu))
            x = s * c / t
            lam = np.where(x > 0.0, 2.0 * j1(x) / np.where(x > 0.0, x, 1.0), 1.0)
            k[self_] -= float(tail @ (lam * lam)) / t
    return k / (np.pi * Es)


def field_compliance(x, y, thickness, modulus, poisson, radius):
    """Compliance matrix [µm/µN] of fibre roots at (``x``, ``y``) [µm] on the layer,
    C_ij = :func:`point_kernel` (|r_i − r_j|): at ``thickness = inf`` the half-space's of
    :func:`gecko_agents.physics.fibril_probe_halfspace.halfspace_compliance`.

    Parameters
    ----------
    x, y : root positions [µm] (distinct, at least 2c apart). thickness, modulus, poisson,
    radius : as :func:`point_kernel`.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    r = np.hypot(x[:, None] - x[None, :], y[:, None] - y[None, :])
    off = r[~np.eye(r.shape[0], dtype=bool)]
    if off.size and off.min() < 2.0 * float(radius):
        raise ValueError(f"fibrils of radius {radius} µm overlap: roots closer than 2c")
    u, inv = np.unique(np.round(r, 12), return_inverse=True)
    return point_kernel(u, thickness, modulus, poisson, radius)[inv].reshape(r.shape)
