"""Rough floors: Gaussian heights (eq 28), correlation length, reproducibility."""

import numpy as np
import pytest
from scipy import stats

from gecko_agents import floor


def test_independent_heights_are_gaussian_with_rms_sigma():
    h = floor.seta_heights(200_000, 1.0, np.random.default_rng(1))
    assert abs(np.sqrt(np.mean(h**2)) - 1.0) < 0.01
    assert abs(h.mean()) < 0.01
    assert stats.normaltest(h).pvalue > 1e-3
    # A uniform sample of the same RMS must fail the same test (the test has teeth).
    u = np.sqrt(3) * np.random.default_rng(1).uniform(-1, 1, 200_000)
    assert stats.normaltest(u).pvalue < 1e-6


def _autocorr(y, lag):
    y = y - y.mean()
    return np.mean(y[:-lag] * y[lag:]) / np.mean(y * y)


def test_correlated_profile_rms_and_correlation_length():
    ell, sigma = 5.0, 0.7
    rms, c_ell, c_2ell = [], [], []
    for seed in range(20):
        p = floor.correlated_profile(sigma, ell, 0.0, 2000.0, np.random.default_rng(seed))
        dx = p.x[1] - p.x[0]
        rms.append(np.sqrt(np.mean(p.y**2)))
        c_ell.append(_autocorr(p.y, round(ell / dx)))
        c_2ell.append(_autocorr(p.y, round(2 * ell / dx)))
    assert abs(np.mean(rms) - sigma) < 0.03 * sigma
    assert abs(np.mean(c_ell) - np.exp(-1)) < 0.03  # C(ℓ)/C(0) = e⁻¹
    assert abs(np.mean(c_2ell) - np.exp(-4)) < 0.03  # Gaussian, not exponential
    y = floor.correlated_profile(sigma, ell, 0, 20_000, np.random.default_rng(7)).y
    assert stats.normaltest(y[:: int(16 * 3)]).pvalue > 1e-3


def test_same_seed_same_floor_and_different_seed_differs():
    a = floor.make_profile(1.0, 0.0, 50, 4.0, 4.0 * np.arange(50), 20.0, np.random.default_rng(3))
    b = floor.make_profile(1.0, 0.0, 50, 4.0, 4.0 * np.arange(50), 20.0, np.random.default_rng(3))
    c = floor.make_profile(1.0, 0.0, 50, 4.0, 4.0 * np.arange(50), 20.0, np.random.default_rng(4))
    assert np.array_equal(a.y, b.y) and not np.array_equal(a.y, c.y)
    d = floor.make_profile(1.0, 3.0, 50, 4.0, 4.0 * np.arange(50), 20.0, np.random.default_rng(3))
    e = floor.make_profile(1.0, 3.0, 50, 4.0, 4.0 * np.arange(50), 20.0, np.random.default_rng(3))
    assert np.array_equal(d.y, e.y)


def test_pad_floor_puts_each_height_under_its_seta():
    xc = 4.0 * np.arange(10)
    h = np.linspace(-1, 1, 10)
    p = floor.pad_profile(h, 4.0, xc, margin=30.0)
    assert np.allclose(p.height_at(xc), h)
    assert p.x[0] <= xc[0] - 30 and p.x[-1] >= xc[-1] + 30
    assert np.all(np.diff(p.x) >= 0)


def test_bad_input():
    with pytest.raises(ValueError, match="sigma"):
        floor.seta_heights(3, -1.0, np.random.default_rng(0))
    with pytest.raises(TypeError, match="Generator"):
        floor.seta_heights(3, 1.0, 42)
    with pytest.raises(ValueError, match="correlation_length"):
        floor.correlated_profile(1.0, 0.0, 0, 10, np.random.default_rng(0))
