"""The history a quasi-static solve returns, and the recorder that sums it step by step.

Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from gecko_agents.history import STATE_FREE as FREE


@dataclass
class QuasiStaticResult:
    """Quasi-static history of an array (n = number of plate positions, N = number of
    (representative) setae).

    Attributes
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


class Recorder:
    """Weighted sums (and optionally per-seta rows) of each plate step's equilibria."""

    def __init__(self, n, N, per_seta):
        self.F = np.zeros(n)
        self.T = np.zeros(n)
        self.na = np.zeros(n)
        self.per = (
            (
                {k: np.zeros((n, N)) for k in ("force", "overlap", "tip_dx")}
                | {"state": np.zeros((n, N), dtype=np.int8)}
            )
            if per_seta
            else {}
        )
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
        return QuasiStaticResult(
            Zs[sl],
            self.F[sl],
            self.T[sl],
            self.na[sl],
            w,
            h,
            {k: v[sl] for k, v in self.per.items()},
            self.releases,
        )
