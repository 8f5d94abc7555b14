"""Rough floors with Gaussian heights (paper eq 28), generated from an explicit RNG.

Heights are in µm, measured upward from the floor's mean plane. Two kinds:

* correlation length 0 — the paper's model: an independent height h_i ~ N(0, σ²) under every
  seta (a flat pad of one pitch width per seta);
* correlation length ℓ > 0 — a continuous 1-D profile whose heights are Gaussian with RMS σ and
  autocorrelation C(r) = σ²·exp(−r²/ℓ²) (white noise filtered with a Gaussian kernel of standard
  deviation ℓ/2: the self-convolution of that kernel has exactly this autocorrelation).

Either way the result is a polyline (``x``, ``y``) that the pymunk model turns into segments.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Profile", "seta_heights", "correlated_profile", "pad_profile", "make_profile"]


@dataclass(frozen=True)
class Profile:
    """A floor polyline.

    Attributes
    ----------
    x : vertex abscissae [µm], shape (M,), increasing.
    y : vertex heights [µm], shape (M,).
    pad_heights : for a pad floor (correlation length 0), the height under each seta [µm],
        shape (N,); ``None`` for a continuous profile.
    """

    x: np.ndarray
    y: np.ndarray
    pad_heights: np.ndarray | None = None

    def height_at(self, x) -> np.ndarray:
        """Floor height at abscissa(e) x [µm] (linear between vertices) [µm]."""
        return np.interp(x, self.x, self.y)


def _check_rng(rng) -> np.random.Generator:
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator, got {type(rng).__name__}")
    return rng


def seta_heights(n: int, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """Independent floor heights under n setae, h ~ N(0, σ²) (eq 28) [µm].

    Parameters
    ----------
    n : number of setae. sigma : RMS height [µm], ≥ 0. rng : the run's Generator.
    """
    if sigma < 0 or not np.isfinite(sigma):
        raise ValueError(f"sigma = {sigma!r} must be finite and ≥ 0 [µm]")
    return sigma * _check_rng(rng).standard_normal(int(n))


def correlated_profile(sigma: float, correlation_length: float, x_start: float, x_end: float,
                       rng: np.random.Generator, spacing: float | None = None) -> Profile:
    """Continuous Gaussian profile on [x_start, x_end] with RMS σ and correlation length ℓ.

    Parameters
    ----------
    sigma : RMS height [µm], ≥ 0.
    correlation_length : ℓ [µm], > 0; C(r) = σ² exp(−r²/ℓ²).
    x_start, x_end : extent [µm].
    rng : the run's Generator.
    spacing : vertex spacing [µm]; default ℓ/8 (the profile is then smooth between vertices).
    """
    if not correlation_length > 0:
        raise ValueError(f"correlation_length = {correlation_length!r} must be > 0 [µm] here")
    if not x_end > x_start:
        raise ValueError(f"x_end = {x_end!r} must exceed x_start = {x_start!r}")
    dx = correlation_length / 8.0 if spacing is None else float(spacing)
    n = int(np.ceil((x_end - x_start) / dx)) + 1
    x = x_start + dx * np.arange(n)
    s = 0.5 * correlation_length / dx                      # kernel std in vertex units
    half = int(np.ceil(4.0 * s))
    k = np.exp(-0.5 * (np.arange(-half, half + 1) / s) ** 2)
    k /= np.sqrt(np.sum(k * k))                            # unit variance after filtering
    noise = _check_rng(rng).standard_normal(n + 2 * half)
    y = sigma * np.convolve(noise, k, mode="valid")
    return Profile(x=x, y=y)


def pad_profile(heights: np.ndarray, pitch: float, x_centres: np.ndarray,
                margin: float) -> Profile:
    """Pad floor: a flat pad of width ``pitch`` at height h_i centred under x_centres[i].

    The outermost pads are extended by ``margin`` [µm] so tips never run off the floor.
    Vertical steps join neighbouring pads.
    """
    h = np.asarray(heights, dtype=float)
    xc = np.asarray(x_centres, dtype=float)
    left = xc - 0.5 * pitch
    right = xc + 0.5 * pitch
    left[0] -= margin
    right[-1] += margin
    x = np.column_stack([left, right]).ravel()
    y = np.repeat(h, 2)
    return Profile(x=x, y=y, pad_heights=h)


def make_profile(sigma: float, correlation_length: float, n_setae: int, pitch: float,
                 x_centres: np.ndarray, margin: float, rng: np.random.Generator) -> Profile:
    """The floor for an array: pads if ``correlation_length == 0``, else a continuous profile.

    Parameters
    ----------
    sigma : RMS height [µm]. correlation_length : [µm]. n_setae : N. pitch : [µm].
    x_centres : abscissae under which each seta touches down [µm], shape (N,).
    margin : extra floor beyond the outermost tips on each side [µm].
    rng : the run's Generator (the only source of randomness).
    """
    if correlation_length == 0:
        return pad_profile(seta_heights(n_setae, sigma, rng), pitch, x_centres, margin)
    x_centres = np.asarray(x_centres, dtype=float)
    return correlated_profile(sigma, correlation_length, x_centres.min() - margin,
                              x_centres.max() + margin, rng)
