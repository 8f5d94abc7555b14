"""A rigid spherical probe on independent linear fibrils: the closed form of the probe test.

The textbook model of a fibrillar adhesive under a spherical probe (the fibrils share no load
through the backing, which is rigid; each is a linear spring that attaches where the probe
touches it and lets go at a fixed tension). The spherical-probe models of fibrillar surfaces
(Noderer et al. 2007, Proc R Soc A, doi:10.1098/rspa.2007.1891; Guidoni et al. 2010, J Mech
Phys Solids, doi:10.1016/j.jmps.2010.07.009; Bettscheider, Booth et al.'s open
``sphericalprobe`` code) build on it, adding the backing's compliance. It is the oracle of the
time-stepped probe test where the two coincide: vertical pillars with flat-punch tips (linear
in compression and tension, Kendall's fixed pull-off) on a rigid backing.

Fibril i stands under the probe at height h_i ≤ 0 below the apex
(:func:`gecko_agents.floor.probe.probe_heights`). With the probe pressed a depth d past first
touch, fibril i is compressed
u_i = d + h_i. Pressing to d_max attaches every fibril with u_i > 0 at d_max. On retraction
fibril i carries k·u_i (compression positive) until its tension reaches F_r, at
u_i = −F_r/k; the outermost (lowest h) fibrils let go first. The force on the probe,
F(d) = Σ_attached w_i·k·(d + h_i), is piecewise linear, so the largest tension is reached just
before one of the releases: the pull-off is max_j −F(d_j⁻) over d_j = −F_r/k − h_j.

Weights w_i: 1 for the simulated row through the probe's centre; 2πr_i·n_A·Δr for rings of an
axisymmetric field of fibrils of areal density n_A (:func:`ring_weights`).

Units: µm, µN (k in µN/µm). Sign: F > 0 compressive, the pull-off returned > 0.
"""

from __future__ import annotations

import numpy as np

__all__ = ["depth_for_preload", "probe_force", "probe_pull_off", "ring_weights"]


def _weights(heights, weights):
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.broadcast_to(np.asarray(weights, float), h.shape)
    return h, w


def probe_force(d, heights, k: float, d_max: float, weights=None) -> float:
    """Force on the probe [µN] at depth d [µm] while retracting from d_max [µm] before any
    fibril has let go: Σ over fibrils attached at d_max (d_max + h_i > 0) of w_i·k·(d + h_i).

    Parameters
    ----------
    d : probe depth past first touch [µm]. heights : h_i ≤ 0 [µm]. k : fibril stiffness
    [µN/µm]. d_max : deepest depth of the press [µm]. weights : w_i [-] (default 1).
    """
    h, w = _weights(heights, weights)
    att = d_max + h > 0.0
    return float(np.sum(w[att] * k * (d + h[att])))


def depth_for_preload(preload: float, heights, k: float, weights=None) -> float:
    """Depth d_max [µm] at which the pressed fibrils carry ``preload`` [µN]:
    Σ w_i·k·max(0, d + h_i) = preload, exact (the sum is piecewise linear in d).

    Parameters
    ----------
    preload : compressive force [µN], > 0. heights : h_i ≤ 0 [µm]. k : [µN/µm].
    weights : w_i [-].
    """
    h, w = _weights(heights, weights)
    order = np.argsort(-h)  # touched first: highest fibril
    hs, ws = h[order], w[order]
    # With the first m fibrils touched, F(d) = k·(W_m·d + S_m); solve and keep the d that lies
    # between the m-th and the (m+1)-th touch-down depths −h.
    W = np.cumsum(ws)
    S = np.cumsum(ws * hs)
    d = (preload / k - S) / W
    nxt = np.append(-hs[1:], np.inf)
    ok = (d >= -hs) & (d <= nxt)
    return float(d[np.argmax(ok)])


def probe_pull_off(heights, k: float, release_force: float, d_max: float, weights=None) -> float:
    """Largest tension on the probe during retraction from d_max [µN] (0 if none).

    Parameters
    ----------
    heights : h_i ≤ 0 [µm]. k : fibril stiffness [µN/µm]. release_force : tension F_r at
    which a fibril lets go [µN]. d_max : deepest depth of the press [µm]. weights : w_i [-].
    """
    h, w = _weights(heights, weights)
    att = d_max + h > 0.0
    h, w = h[att], w[att]
    best = 0.0
    for hj in np.unique(h):  # just before fibrils at height hj let go
        dj = -release_force / k - hj
        held = h >= hj
        best = max(best, -float(np.sum(w[held] * k * (dj + h[held]))))
    return best


def ring_weights(radii, areal_density: float, ring_width: float) -> np.ndarray:
    """Weights 2πr·n_A·Δr [-] of rings of fibrils at radii r [µm] of an axisymmetric field of
    areal density n_A [1/µm²], rings Δr [µm] wide (the row's pitch): the row's fibrils, each
    standing for its ring, make the field under a sphere.

    Parameters
    ----------
    radii : ring radii r ≥ 0 [µm]. areal_density : fibrils per µm². ring_width : Δr [µm].
    """
    return 2.0 * np.pi * np.abs(np.asarray(radii, float)) * areal_density * ring_width
