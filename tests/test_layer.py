"""The elastic layer's surface compliance (gecko_agents.physics.layer) against closed forms:
its half-space and thin-layer limits, independent quadratures, ContactMechanics' Green's
function where installed, and the rigid flat punch's pressure on a thick layer."""

import math

import extras
import numpy as np
import pytest
from scipy import integrate
from scipy.special import j1

from gecko_agents.physics import fibril_probe_halfspace as halfspace
from gecko_agents.physics import layer, punch

E, NU = 1.413, 0.3  # the paper's polyurethane [MPa], Table 1's ν


def test_factor_limits():
    """g → 1 deep (the half-space); G(q → 0) = t/M thin; q²t³/(3μ) at ν = ½."""
    assert layer.layer_factor(np.array([30.0, 100.0, 1e4]), NU) == pytest.approx(1.0, abs=1e-20)
    t = 10.0
    M = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))
    assert layer.confined_modulus(E, NU) == pytest.approx(M, rel=1e-15)
    assert layer.fourier_compliance(1e-7 / t, t, E, NU) == pytest.approx(t / M, rel=1e-9)
    assert layer.fourier_compliance(0.0, t, E, NU) == pytest.approx(t / M, rel=1e-15)
    mu = E / 3.0  # ν = ½
    for q in (1e-5, 1e-4):
        G = layer.fourier_compliance(q, t, E, 0.5)
        assert G == pytest.approx(q * q * t**3 / (3 * mu), rel=1e-5)
    assert layer.thin_layer_compliance(t, E, 0.5) == 0.0
    assert math.isinf(layer.confined_modulus(E, 0.5))


def test_factor_continuous_across_branches():
    """The series and the e^{−2s} forms meet without a jump."""
    for nu in (0.0, 0.3, 0.49, 0.5):
        for s0 in (0.05, 20.0):
            lo, hi = layer.layer_factor(np.array([s0 * (1 - 1e-9), s0 * (1 + 1e-9)]), nu)
            assert hi == pytest.approx(lo, rel=1e-7)


def test_contact_mechanics_greens_function():
    """The same G(q) as ContactMechanics' finite-thickness PeriodicFFTElasticHalfSpace."""
    cm = extras.require("contactmechanics")
    size, n, t = 64.0, 16, 10.0
    sub = cm.PeriodicFFTElasticHalfSpace((n, n), E, physical_sizes=(size, size),
                                         thickness=t, poisson=NU)  # fmt: skip
    G = np.asarray(sub.greens_function)
    i = np.arange(G.shape[0])[:, None]
    j = np.arange(G.shape[1])[None, :]
    kx, ky = np.where(i <= n // 2, i, n - i), np.where(j <= n // 2, j, n - j)
    q = 2 * np.pi * np.hypot(kx, ky) / size
    np.testing.assert_allclose(layer.fourier_compliance(q, t, E, NU), G.real, rtol=1e-12)


def test_line_kernel_against_quadrature():
    """K(d) = (1/π)∫G·sinc²(qw/2)·cos(qd) dq by adaptive quadrature (QUADPACK's Fourier
    integrals for d > 0, good to ~1e-6 on the oscillating tail)."""
    t, w = 10.0, 4.0

    def f(q):
        return layer.fourier_compliance(q, t, E, NU) * np.sinc(q * w / 2 / np.pi) ** 2 / np.pi

    for d in (0.0, 4.0, 8.0, 20.0, 60.0):
        if d == 0.0:
            brute = integrate.quad(f, 0, 50, limit=2000)[0]
            brute += integrate.quad(f, 50, np.inf, limit=2000)[0]
        else:
            brute = integrate.quad(f, 0, 50, weight="cos", wvar=d, limit=2000)[0]
            brute += integrate.quad(f, 50, np.inf, weight="cos", wvar=d, limlst=200)[0]
        assert layer.line_kernel(d, t, E, NU, w) == pytest.approx(brute, rel=1e-5, abs=1e-8)


def test_point_kernel_self_term_against_quadrature():
    """C(0) = (1/2π)∫G·Λ(qc)²·q dq, the disc's mean under its own uniform load."""
    t, c = 5.0, 1.5

    def f(q):
        lam = 2 * j1(q * c) / (q * c)
        return layer.fourier_compliance(q, t, E, NU) * lam * lam * q / (2 * np.pi)

    brute = (
        integrate.quad(f, 1e-12, 200, limit=4000)[0] + integrate.quad(f, 200, np.inf, limit=4000)[0]
    )
    assert layer.point_kernel(0.0, t, E, NU, c) == pytest.approx(brute, rel=1e-6)


def test_half_space_limit_is_bettscheider():
    """At t = ∞ the field's compliance is the half-space's of the Bettscheider
    re-derivation; at t = 10⁹ µm, and the probe test on it, within 1e-6."""
    x, y = halfspace.square_lattice(4.0, 30.0)
    C_hs = halfspace.halfspace_compliance(x, y, 1.5, E, NU)
    np.testing.assert_allclose(layer.field_compliance(x, y, math.inf, E, NU, 1.5), C_hs, rtol=1e-13)
    C_t = layer.field_compliance(x, y, 1e9, E, NU, 1.5)
    np.testing.assert_allclose(C_t, C_hs, rtol=1e-6)
    h = halfspace.parabolic_heights(x, y, 100.0)
    fib = np.eye(x.size) / 2.0
    a = halfspace.probe_test(h, fib + C_hs, 4.66, 5.0)
    b = halfspace.probe_test(h, fib + C_t, 4.66, 5.0)
    assert b.pull_off == pytest.approx(a.pull_off, rel=1e-6)
    assert b.attached_max == a.attached_max


def test_thin_layer_is_independent_springs():
    """Thin (t ≪ the loaded width): the confined layer's springs. A uniform load on a row
    much wider than t sinks by p·t/M; a fibre's disc of radius c ≫ t is a spring of
    compliance t/(M·πc²), its neighbours untouched; the strip of width w ≫ t, t/(M·w·b)."""
    pitch = 4.0
    M = layer.confined_modulus(E, NU)
    x = (np.arange(201) - 100) * pitch
    w_row = layer.row_compliance(x, 4.0, E, NU, pitch, pitch) @ np.ones(x.size)
    assert w_row[100] == pytest.approx(4.0 / M / pitch**2, rel=1e-6)  # p = 1 µN per cell
    for t in (0.015, 0.0015):  # the edge's share falls as t/c
        C = layer.field_compliance([0.0, pitch], [0.0, 0.0], t, E, NU, 1.5)
        assert C[0, 0] == pytest.approx(t / (M * math.pi * 1.5**2), rel=1.5 * t / 1.5)
        assert C[0, 1] == 0.0
        C = layer.row_compliance([0.0, pitch], t, E, NU, 2.0, pitch)
        assert C[0, 0] == pytest.approx(t / (M * 2.0 * pitch), rel=1.5 * t / 2.0)
        assert C[0, 1] == 0.0


def _punch_loads(C, k):
    """Fibre loads [µN] of stiff fibres (compliance 1/k) pulled 1 µm by the holder together."""
    return np.linalg.solve(C + np.eye(C.shape[0]) / k, -np.ones(C.shape[0]))


def test_stiff_patch_on_thick_layer_is_a_flat_punch():
    """Fibres 10³× stiffer than the layer under them, pulled by the holder, on a layer 100×
    the patch: the loads follow the rigid punch's pressure on a half-space within 1 %
    (plane strain, |x| < 0.8a) and 2 % (a square field, r < 0.7a, discs as wide as a cell)."""
    pitch = 4.0
    x = (np.arange(101) - 50) * pitch
    a = 0.5 * x.size * pitch
    C = layer.row_compliance(x, 100 * a, E, NU, pitch, pitch)
    f = _punch_loads(C, 1e3 / C[0, 0])
    P = f.sum()
    inner = np.abs(x) < 0.8 * a
    p = punch.plane_punch_pressure(x[inner], a, P / pitch)
    np.testing.assert_allclose(f[inner] / pitch**2, p, rtol=0.01)
    xs, ys = halfspace.square_lattice(pitch, 80.0)
    a = math.sqrt(xs.size / math.pi) * pitch  # the patch's area πa²
    C = layer.field_compliance(xs, ys, 100 * a, E, NU, 0.5 * pitch)
    f = _punch_loads(C, 1e3 / C[0, 0])
    r = np.hypot(xs, ys)
    inner = r < 0.7 * a
    p = punch.tilted_punch_pressure(r[inner], 0.0, f.sum(), 0.0, a)
    np.testing.assert_allclose(f[inner] / pitch**2, p, rtol=0.02)


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [({"thickness": 0.0}, "thickness"), ({"thickness": -1.0}, "thickness"),
     ({"modulus": 0.0}, "modulus"), ({"poisson": 0.51}, "poisson"),
     ({"poisson": -0.1}, "poisson")],
)  # fmt: skip
def test_bad_layer_refused(kwargs, field):
    args = {"thickness": 10.0, "modulus": E, "poisson": NU} | kwargs
    with pytest.raises(ValueError, match=field):
        layer.fourier_compliance(1.0, **args)
    with pytest.raises(ValueError, match="thickness"):
        layer.line_kernel(1.0, math.inf, E, NU, 4.0)  # plane strain needs a base
