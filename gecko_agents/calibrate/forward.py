"""The quasi-static forward model of :mod:`gecko_agents.calibrate`: what the model predicts
for each observation of a data set.

Heights on a fixed grid of Gaussian quantiles with a moving contact front, one shared approach
for all preloads of a σ and batched retracts, the peak refined by bisection
(:func:`gecko_agents.quasistatic.preload_pulls`), so the model is a smooth function of the
parameters. Units: µm, µN.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from gecko_agents import quasistatic as qs
from gecko_agents.calibrate.data import Data
from gecko_agents.params import SetaArray
from gecko_agents.physics.beam import touchdown_height


@dataclass
class Forward:
    """How the model is evaluated. The defaults are set by the forward model's noise (see
    :func:`gecko_agents.calibrate.fit`).

    Attributes
    ----------
    kind : ``"quasistatic"`` (default; :mod:`quasistatic` on representative heights) or
        ``"agent"`` (the pymunk model on an ``n_sim`` patch, scaled to the array; slow, for a
        final check of a fitted point).
    n_blocks : representative heights per array, on the fixed Gaussian quantile grid of
        :func:`quasistatic.quantile_heights` (no random draw: the model is a smooth function of
        σ and of every other parameter).
    retract_steps : plate steps of each retract (the travel of :func:`quasistatic.preload_pull`
        divided by this; an array pulls off within about the first half of it).
    n_sim : agent patch size.
    dz : approach step [µm] (the turning point is bisected exactly; the result does not depend
        on it, measured: 0.0072 and 0.02 µm give the same pull-offs to 5 digits).
    retract_dz : largest retract step [µm] (the step is travel/retract_steps or this, the
        smaller); the peak is refined by bisection (``preload_pulls(refine_peak=True)``).
    """

    kind: str = "quasistatic"
    n_blocks: int = 64
    retract_steps: int = 400
    n_sim: int = 20
    dz: float = 0.05
    retract_dz: float | None = 0.25

    def __post_init__(self):
        if self.kind not in ("quasistatic", "agent"):
            raise ValueError(f"forward = {self.kind!r} must be 'quasistatic' or 'agent'")
        for name, lo in (("n_blocks", 1), ("retract_steps", 10), ("n_sim", 1)):
            v = getattr(self, name)
            if not isinstance(v, int) or v < lo:
                raise ValueError(f"Forward.{name} = {v!r} must be an integer ≥ {lo}")


def _heights(p: SetaArray, sigma: float, n_blocks: int):
    """Heights [µm], weights and the ``gaussian`` front argument of the fixed quantile grid."""
    if p.array.count == 1 or sigma == 0 or n_blocks == 1:
        return np.zeros(1), np.array([float(p.array.count)]), None
    h, w, e = qs.quantile_heights(
        p.array.count, sigma, min(n_blocks, p.array.count), return_edges=True
    )
    return h, w, (sigma, e)


def predict_quasistatic(
    data: Data, params: SetaArray, stiffness_scale: float, forward: Forward
) -> np.ndarray:
    """Quasi-static model values for each observation of ``data`` [µN, µm] (see
    ``gecko_agents.calibrate.predict``)."""
    if data.kind == "preload":
        return _pull_offs(data, params, stiffness_scale, forward)
    c = data.columns
    z_touch = float(touchdown_height(params.seta.L, params.seta.theta, params.contact.R))
    h, w, _ = _heights(params, params.floor.sigma, forward.n_blocks)
    depth = 0.5
    if data.kind == "curve":
        depth = max(0.5, -float(np.min(c["displacement"])))
    r = qs.press_pull(
        params,
        h,
        depth,
        weights=w,
        stiffness_scale=stiffness_scale,
        n_retract=forward.retract_steps * 2,
    )
    if data.kind == "curve":
        t = r.turn_index
        z = r.plate_y[t:] - z_touch
        return np.interp(
            c["displacement"], z, r.force_normal[t:], left=r.force_normal[t], right=0.0
        )
    last = max((i for i, _, _ in r.releases), default=len(r.plate_y) - 1)
    return np.array([r.pull_off, r.plate_y[last] - z_touch])


def _pull_offs(data: Data, params: SetaArray, stiffness_scale: float, forward: Forward):
    """Pull-off [µN] at each row's preload; rows of one σ share one approach."""
    c = data.columns
    out = np.empty(data.n)
    sig = c.get("sigma", np.full(data.n, params.floor.sigma))
    for s in np.unique(sig):
        rows = np.flatnonzero(sig == s)
        h, w, g = _heights(params, float(s), forward.n_blocks)
        res = qs.preload_pulls(
            params,
            h,
            c["preload"][rows],
            weights=w,
            stiffness_scale=stiffness_scale,
            retract_steps=forward.retract_steps,
            dz=forward.dz,
            retract_dz=forward.retract_dz,
            gaussian=g,
            refine_peak=True,
        )
        out[rows] = [r.pull_off for r in res]
    return out
