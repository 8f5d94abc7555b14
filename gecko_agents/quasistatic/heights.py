"""Floor heights under the setae of a quasi-static array, and where the plate starts above them.

Representative heights stand for many setae each (eq 28): drawn and blocked
(:func:`representative_heights`), or a fixed grid of Gaussian quantiles
(:func:`quantile_heights`), optionally entering contact gradually behind a moving contact
front (:func:`contact_front`). Units: µm.
"""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.params import SetaArray
from gecko_agents.physics import beam


def touchdown(params: SetaArray) -> float:
    """Plate height [µm] at which a resting tip touches the floor's mean plane:
    :func:`gecko_agents.physics.beam.touchdown_height`, R + L sin θ."""
    return float(beam.touchdown_height(params.seta.L, params.seta.theta, params.contact.R))


def plate_start_height(params: SetaArray, heights, gap: float = 0.5) -> float:
    """Plate height at which the highest seta's free tip is ``gap`` [µm] above its floor [µm]."""
    return float(np.max(heights) + touchdown(params) + gap)


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
    for :func:`gecko_agents.quasistatic.preload_pulls`'s ``gaussian``.
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


def contact_front(params: SetaArray, h, w, gaussian):
    """Heights and weights as a function of plate height, the start height and the top floor.

    ``gaussian = None``: the fixed heights ``h`` [µm] and weights ``w``; the plate starts 0.5 µm
    above the highest tip's touch-down. ``gaussian = (sigma, edges)``: ``h`` are the slices of
    a Gaussian floor of RMS sigma [µm] between the standard quantiles ``edges`` (n + 1, −∞ …
    +∞); at plate height Z each slice is represented by its part above the contact front
    h_t(Z) = Z − R − L sin θ: weight w·Pr(z > z_t | slice), height σ·E[z | z > z_t, slice]
    (truncated normal). Slices wholly below the front sit at their top edge. The plate starts
    where 0.1 seta is expected above the front.

    Returns
    -------
    (at, Z_start, top): ``at(Z)`` → (heights [µm], weights) at plate height Z [µm]; the start
    height [µm]; the floor heights that bound the retract travel [µm].
    """
    if gaussian is None:

        def fixed(Z):
            return h, w

        return fixed, plate_start_height(params, h, 0.5), h
    from scipy.special import ndtr, ndtri

    g_sigma, edges = float(gaussian[0]), np.asarray(gaussian[1], dtype=float)
    if not (g_sigma > 0 and edges.size == h.size + 1 and np.all(np.diff(edges) > 0)):
        raise ValueError(
            f"gaussian = (sigma {g_sigma!r}, {edges.size} edges) needs sigma > 0 [µm] "
            f"and {h.size + 1} increasing edges for {h.size} heights"
        )
    lo_e, hi_e = edges[:-1], edges[1:]
    p_blk = ndtr(-lo_e) - ndtr(-hi_e)  # upper-tail form: accurate far out
    z_of_touch = touchdown(params)

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
    return h_of, Z_start, np.array([Z_start - 0.5 - z_of_touch])
