"""The elastic layer's compliance (gecko_agents.physics.layer) at its edges: the factor g(s)
against its closed form in 50-digit arithmetic across its three branches, the moduli at the
ends of ν's range, the kernels' cut-off and symmetry, and each refusal at the edge of its
range (just inside taken, just outside refused, naming the parameter)."""

import math
from decimal import Decimal, localcontext

import numpy as np
import pytest
from scipy import integrate

from gecko_agents.physics import fibril_probe_halfspace as halfspace
from gecko_agents.physics import layer

pytestmark = pytest.mark.filterwarnings("error")

E, NU = 1.413, 0.3


def _g_exact(s: float, nu: float) -> float:
    """g(s) = [(3 − 4ν) sinh 2s − 2s] / [(3 − 4ν) cosh 2s + 2s² + 5 − 12ν + 8ν²] (the module
    docstring's closed form) in 60-digit decimal arithmetic: no cancellation at small s."""
    with localcontext() as ctx:
        ctx.prec = 60
        S, N = Decimal(s), Decimal(nu)
        e2, em2 = (2 * S).exp(), (-2 * S).exp()
        a = 3 - 4 * N
        num = a * (e2 - em2) / 2 - 2 * S
        den = a * (e2 + em2) / 2 + 2 * S * S + 5 - 12 * N + 8 * N * N
        return float(num / den)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_layer_factor_is_its_closed_form_on_every_branch(nu):
    """g(s) on the series branch (2s < 0.1: s = 1e-4 … 0.0499), the direct one and the
    e^{−2s} one (s > 20), at ν = 0, 0.3 and ½, to 1e-14 of the closed form in 60 digits
    (measured 1.7e-15); the thin-layer slope g ≈ E*s/(2M) (ν < ½) and 2s³/3 (ν = ½)."""
    s = np.array([1e-4, 1e-3, 0.01, 0.0499, 0.0501, 0.3, 1.0, 5.0, 19.9, 20.0, 20.1, 35.0])
    g = layer.layer_factor(s, nu)
    exact = np.array([_g_exact(v, nu) for v in s])
    np.testing.assert_allclose(g, exact, rtol=1e-14, atol=0)
    if nu < 0.5:
        slope = layer.contact_modulus(1.0, nu) / (2.0 * layer.confined_modulus(1.0, nu))
        assert g[0] == pytest.approx(slope * 1e-4, rel=1e-7)
    else:
        assert g[0] == pytest.approx(2.0 / 3.0 * 1e-12, rel=1e-7)
    assert layer.layer_factor(0.0, nu) == 0.0
    # deep in the e^{−2s} branch: exactly the half-space's 1, with no overflow (no warning)
    np.testing.assert_array_equal(layer.layer_factor(np.array([400.0, 1e4]), nu), 1.0)


@pytest.mark.parametrize("nu", [0.3, 0.5])
def test_layer_factor_keeps_its_last_corrections_past_the_switch(nu):
    """Just past s = 20, where g switches to its e^{−2s} form, the corrections
    (2s² + 5 − 12ν + 8ν²)·e^{−2s} and 4s·e^{−2s} are still ~1e-15 of g: kept to rounding,
    within 5e-16 (2 ulp) of the closed form in 60 digits (measured 2.2e-16)."""
    s = np.array([20.0001, 20.1])
    exact = np.array([_g_exact(v, nu) for v in s])
    np.testing.assert_allclose(layer.layer_factor(s, nu), exact, rtol=5e-16, atol=0)


def test_moduli_at_the_ends_of_poisson():
    """E* = E/(1 − ν²) and M = E(1 − ν)/((1 + ν)(1 − 2ν)): E* = E and M = E at ν = 0
    (no lateral coupling); M = 6E/5 at ν = ¼, 4E/3 E* at ν = ½ (E* = 4E/3, M infinite)."""
    assert layer.contact_modulus(E, 0.0) == E
    assert layer.contact_modulus(E, 0.5) == pytest.approx(4 * E / 3, rel=1e-15)
    assert layer.confined_modulus(E, 0.0) == pytest.approx(E, rel=1e-15)
    assert layer.confined_modulus(E, 0.25) == pytest.approx(1.2 * E, rel=1e-15)
    assert layer.confined_modulus(E, math.nextafter(0.5, 0.0)) > 1e14 * E
    assert layer.thin_layer_compliance(3.0, E, 0.0) == pytest.approx(3.0 / E, rel=1e-15)


def test_fourier_compliance_is_even_and_has_its_limits():
    """G(−q) = G(q); at q = 0 the thin layer's t/M (0 at ν = ½); at t = inf the half-space's
    2/(E*q) exactly, infinite at q = 0; between, 2g(qt)/(E*q)."""
    q = np.array([0.0, 1e-3, 0.1, 1.0, 10.0])
    G = layer.fourier_compliance(q, 5.0, E, NU)
    np.testing.assert_array_equal(layer.fourier_compliance(-q, 5.0, E, NU), G)
    assert G[0] == pytest.approx(5.0 / layer.confined_modulus(E, NU), rel=1e-15)
    Es = E / (1 - NU * NU)
    expected = 2.0 / (Es * q[1:]) * np.array([_g_exact(5.0 * v, NU) for v in q[1:]])
    np.testing.assert_allclose(G[1:], expected, rtol=1e-14)
    assert layer.fourier_compliance(0.0, 5.0, E, 0.5) == 0.0
    hs = layer.fourier_compliance(q, math.inf, E, NU)
    assert math.isinf(hs[0])
    np.testing.assert_allclose(hs[1:], 2.0 / (Es * q[1:]), rtol=1e-15)


def test_kernels_are_even_and_cut_off():
    """The line and point kernels depend on |d| and are exactly 0 beyond CUTOFF = 30
    thicknesses (and not 0 up to it, 30t included, where it is below 1e-10 of its value at
    0, :data:`~gecko_agents.physics.layer.CUTOFF`); the point kernel at t = inf is the
    half-space's Boussinesq 1/(πE*r) and the disc's 16/(3π²E*c) at r = 0."""
    t, w, c = 2.0, 4.0, 1.5
    d = np.array([0.0, 3.0, 29.9 * t, 30.0 * t, 30.1 * t, 100.0 * t])
    K = layer.line_kernel(d, t, E, NU, w)
    np.testing.assert_array_equal(layer.line_kernel(-d, t, E, NU, w), K)
    assert np.all(K[:4] != 0.0) and np.all(K[4:] == 0.0)  # taken at CUTOFF·t, 0 beyond
    assert abs(K[3]) < 1e-10 * K[0]  # where the layer's kernel has died out (measured 1e-13)
    P = layer.point_kernel(d, t, E, NU, c)
    np.testing.assert_array_equal(layer.point_kernel(-d, t, E, NU, c), P)
    assert np.all(P[:4] != 0.0) and np.all(P[4:] == 0.0)
    assert abs(P[3]) < 1e-10 * P[0]  # measured 7e-15
    Es = E / (1 - NU * NU)
    r = np.array([0.0, 4.0, 1e3])
    hs = layer.point_kernel(r, math.inf, E, NU, c)
    np.testing.assert_allclose(hs, [16 / (3 * math.pi**2 * Es * c), *(1 / (math.pi * Es * r[1:]))],
                               rtol=1e-15)  # fmt: skip


def test_row_and_field_compliance_are_the_kernels():
    """The row's C_ij = K(|x_i − x_j|)/b and the field's C_ij = C(|r_i − r_j|), symmetric,
    the roots in any order; the field's bases may touch (2c apart) but not overlap."""
    t, w, b = 5.0, 4.0, 3.0
    x = np.array([0.0, 2.5, -1.3])
    C = layer.row_compliance(x, t, E, NU, w, b)
    K = layer.line_kernel(np.array([0.0, 2.5, 1.3, 3.8]), t, E, NU, w) / b
    np.testing.assert_allclose(C, K[[[0, 1, 2], [1, 0, 3], [2, 3, 0]]], rtol=1e-15)
    xs, ys = np.array([0.0, 3.0, 0.0]), np.array([0.0, 0.0, -5.0])
    C = layer.field_compliance(xs, ys, t, E, NU, 1.5)
    P = layer.point_kernel(np.array([0.0, 3.0, 5.0, math.hypot(3.0, 5.0)]), t, E, NU, 1.5)
    # distances rounded to 1e-12 µm: measured 1e-12 of C_ij
    np.testing.assert_allclose(C, P[[[0, 1, 2], [1, 0, 3], [2, 3, 0]]], rtol=1e-11)
    with pytest.raises(ValueError, match="radius 1.5"):
        layer.field_compliance([0.0, math.nextafter(3.0, 0.0)], [0.0, 0.0], t, E, NU, 1.5)
    x, y = halfspace.square_lattice(3.0, 5.0)
    C_hs = halfspace.halfspace_compliance(x, y, 1.5, E, NU)
    np.testing.assert_allclose(layer.field_compliance(x, y, math.inf, E, NU, 1.5), C_hs, rtol=1e-11)


LAYER_TAKEN = [{"thickness": 1e-300}, {"thickness": math.inf}, {"modulus": 1e-300},
               {"poisson": 0.0}, {"poisson": 0.5}]  # fmt: skip
LAYER_REFUSED = [("thickness", 0.0, r"\(0, inf\]"), ("thickness", math.nan, r"\(0, inf\]"),
                 ("thickness", -math.inf, r"\(0, inf\]"), ("modulus", 0.0, r"\(0, inf\)"),
                 ("modulus", math.inf, r"\(0, inf\)"), ("modulus", math.nan, r"\(0, inf\)"),
                 ("poisson", -1e-12, r"\[0, 0\.5\]"),
                 ("poisson", math.nextafter(0.5, 1.0), r"\[0, 0\.5\]")]  # fmt: skip


@pytest.mark.parametrize("kw", LAYER_TAKEN)
def test_a_layer_is_taken_at_the_ends_of_its_ranges(kw):
    """A thickness from 1e-300 µm to inf, a modulus as small as 1e-300 MPa, ν at 0 and ½:
    a finite, positive compliance at q = 1/µm."""
    args = {"thickness": 10.0, "modulus": E, "poisson": NU} | kw
    G = float(layer.fourier_compliance(1.0, **args))
    assert 0.0 < G < math.inf


@pytest.mark.parametrize(("name", "value", "span"), LAYER_REFUSED)
def test_a_layer_is_refused_just_outside_its_ranges(name, value, span):
    """Just outside (a zero, NaN or infinite modulus, a zero, NaN or −inf thickness, ν past
    0 or ½), every law refuses, naming the parameter, its value and its range."""
    args = {"thickness": 10.0, "modulus": E, "poisson": NU} | {name: value}
    with pytest.raises(ValueError, match=rf"^{name} = {value!r} .* {span}$"):
        layer.fourier_compliance(1.0, **args)


def test_plane_strain_and_the_base_need_finite_widths():
    """The line kernel needs a finite layer (range (0, inf)) and a width in (0, inf); the
    row a depth in (0, inf); the point kernel a radius in (0, inf): each refused at 0, inf
    and NaN, naming it; the smallest positive values taken."""
    with pytest.raises(ValueError, match=r"^thickness = inf µm .* \(0, inf\)$"):
        layer.line_kernel(1.0, math.inf, E, NU, 4.0)
    with pytest.raises(ValueError, match=r"^thickness = inf µm .* \(0, inf\)$"):
        layer.thin_layer_compliance(math.inf, E, NU)
    for bad in (0.0, math.inf, math.nan, -1.0):
        with pytest.raises(ValueError, match=rf"^width = {bad!r} µm .* \(0, inf\)$"):
            layer.line_kernel(1.0, 5.0, E, NU, bad)
        with pytest.raises(ValueError, match=rf"^depth = {bad!r} µm .* \(0, inf\)$"):
            layer.row_compliance([0.0, 4.0], 5.0, E, NU, 4.0, bad)
        with pytest.raises(ValueError, match=rf"^radius = {bad!r} µm .* \(0, inf\)$"):
            layer.point_kernel(1.0, 5.0, E, NU, bad)
    assert layer.row_compliance([0.0, 4.0], 5.0, E, NU, 4.0, 1e-300)[0, 0] > 0.0
    assert layer.point_kernel(1.0, math.inf, E, NU, 1e-300) > 0.0


def test_narrow_strips_against_quadrature():
    """Strips narrower than 1 µm (w = 0.5 µm on a 2 µm layer, centres 0.3 and 0.7 µm apart:
    the closed-form part's arguments d ± w below 1 µm) against
    K(d) = (1/π)∫G·sinc²(qw/2)·cos(qd) dq by adaptive quadrature (QUADPACK's Fourier
    integrals, good to ~1e-7 here; measured 1e-8)."""
    t, w = 2.0, 0.5

    def f(q):
        return layer.fourier_compliance(q, t, E, NU) * np.sinc(q * w / 2 / np.pi) ** 2 / np.pi

    for d in (0.3, 0.7):
        brute = integrate.quad(f, 0, 200, weight="cos", wvar=d, limit=4000)[0]
        brute += integrate.quad(f, 200, np.inf, weight="cos", wvar=d, limlst=400)[0]
        assert layer.line_kernel(d, t, E, NU, w) == pytest.approx(brute, rel=1e-6)


def test_integer_distances_are_distances():
    """Centre distances given as integers (``pitch * np.arange(n)`` with an integer pitch)
    give the kernels of the same distances as floats."""
    d = 4 * np.arange(4)
    np.testing.assert_array_equal(
        layer.line_kernel(d, 5.0, E, NU, 4.0), layer.line_kernel(d.astype(float), 5.0, E, NU, 4.0)
    )
    np.testing.assert_array_equal(
        layer.point_kernel(d, 5.0, E, NU, 1.5), layer.point_kernel(d.astype(float), 5.0, E, NU, 1.5)
    )
