"""The point functions a sweep file may name (:data:`POINT_FUNCTIONS`).

* :func:`analytic_point` — a closed-form result row (microseconds per point), the point the
  sweep tests and the ``gecko-agents sweep`` examples use;
* :func:`cpu_bound_point` — a fixed amount of arithmetic per point, for timing workers;
* :func:`quasistatic_preload_point` — a force-controlled press to a preload and pull-off of a
  whole array with the quasi-static solver (Fig 11a/11b);
* :func:`agent_preload_point` — the same on a patch of the agent model, scaled to the array.

A point function takes ``(params, seed, **kwargs)`` and returns a flat dict of numbers; the
preload is a protocol quantity, swept with the grid name ``"fn.preload_uN"``. Units are those
of :mod:`gecko_agents.params` (µm, µN).
"""

from __future__ import annotations

import functools

import numpy as np

from gecko_agents import quasistatic
from gecko_agents.model import Model
from gecko_agents.params import SetaArray
from gecko_agents.protocol import Press, PullOff

__all__ = [
    "POINT_FUNCTIONS",
    "analytic_point",
    "cpu_bound_point",
    "quasistatic_preload_point",
    "agent_preload_point",
]


def analytic_point(params: SetaArray, seed: int) -> dict[str, float]:
    """A cheap closed-form result row (for tests and demos); the seed draws the floor.

    Returns
    -------
    ``pull_off_single_uN`` JKR pull-off of one tip Fc [µN]; ``snap_off_overlap_um`` δc [µm]
    (< 0); ``pull_off_ideal_array_uN`` N·Fc, all setae letting go together [µN];
    ``mean_floor_height_um`` mean of 1000 floor heights drawn with
    ``numpy.random.default_rng(seed)`` and σ = ``params.floor.sigma`` [µm].
    """
    from gecko_agents.floor import seta_heights

    fc = params.contact.pull_off_force
    heights = seta_heights(1000, params.floor.sigma, np.random.default_rng(seed))
    return {
        "pull_off_single_uN": fc,
        "snap_off_overlap_um": params.contact.snap_off_overlap,
        "pull_off_ideal_array_uN": params.array.count * fc,
        "mean_floor_height_um": float(np.mean(heights)),
    }


def cpu_bound_point(
    params: SetaArray, seed: int, *, repeats: int = 300, n_overlaps: int = 10_000
) -> dict[str, float]:
    """A CPU-bound point for benchmarks: ``repeats`` JKR force curves of ``n_overlaps`` overlaps.

    Each repeat evaluates :func:`gecko_agents.physics.jkr.force_from_overlap` on overlaps drawn
    uniformly in [δc, 1 µm] with ``numpy.random.default_rng(seed)`` (≈ 1.5 ms per repeat for
    10⁴ overlaps on one core; arrays that small stay in cache, so the work is arithmetic, not
    memory traffic). Returns the mean force [µN] and the most tensile force [µN].
    """
    from gecko_agents.physics import jkr

    rng = np.random.default_rng(seed)
    args = params.contact.jkr_args()
    lo = params.contact.snap_off_overlap
    total, lowest = 0.0, np.inf
    for _ in range(int(repeats)):
        force = jkr.force_from_overlap(rng.uniform(lo, 1.0, int(n_overlaps)), *args)
        total += float(force.mean())
        lowest = min(lowest, float(force.min()))
    return {"mean_force_uN": total / max(int(repeats), 1), "min_force_uN": lowest}


# Preload-and-pull points (Fig 11a/11b) ------------------------------------------------------

CURVE_STRIDE = 64
"""The longest move of a curve's press and of its retracts, in plate steps, where no seta
changes state (``approach_stride`` and ``retract_stride`` of
:func:`gecko_agents.quasistatic.preload_pulls`): the paper's soft setae press ~5000 short
steps deep and retract ~1000 each; with it a curve of 12 preloads takes ×6–8 less CPU for
the same turning points (to 1e-12) and the same sampled pull-offs and releases."""


def quasistatic_preload_point(
    params: SetaArray,
    seed: int,
    *,
    preload_uN: float,
    n_blocks: int = 1000,
    retract_steps: int | None = None,
    lateral: str = "coupled",
    curve_uN: tuple | list | None = None,
) -> dict[str, float]:
    """Force-controlled press and pull-off of the whole array with the quasi-static solver.

    The ``params.array.count`` floor heights (σ = ``params.floor.sigma``, drawn with
    ``numpy.random.default_rng(seed)``) are reduced to ``n_blocks`` weighted
    representative heights (:func:`gecko_agents.quasistatic.representative_heights`; 1000
    blocks reproduce 20 000 to < 0.2 % for the paper's array) and pressed until the total
    normal force is ``preload_uN`` [µN] (:func:`gecko_agents.quasistatic.preload_pull`), then pulled
    off in up to ``retract_steps`` plate steps (default 4000; for the paper's array 2000 changes
    the pull-off by < 0.05 %, 500 by < 0.3 %).

    ``curve_uN``: the preloads [µN] of the whole curve this point is one of (``preload_uN``
    among them). The point is then read off one :func:`gecko_agents.quasistatic.preload_pulls`
    over them all — one shared approach and the retracts batched into one vectorized solve,
    both in moves of up to ``CURVE_STRIDE`` plate steps where no seta changes state — that
    this process computes once per parameter set and seed (``_preload_curve``) and serves
    the curve's other points from. Its turning points are bisected as without ``curve_uN``,
    so each point equals the one press-and-pull to the solver's 1e-9.

    Returns
    -------
    ``preload_uN`` compressive force reached [µN]; ``pull_off_uN`` maximum tensile force [µN];
    ``pull_off_per_seta_uN`` the same per seta of the array [µN]; ``pull_off_over_ideal``
    pull-off / (N·Fc) [-]; ``attached_fraction`` largest fraction of setae attached [-].
    """
    if curve_uN is not None:
        curve = tuple(float(c) for c in curve_uN)
        if float(preload_uN) not in curve:
            raise ValueError(f"preload_uN = {preload_uN!r} is not one of curve_uN = {curve}")
        rows = _preload_curve(params, seed, curve, n_blocks, retract_steps, lateral)
        return dict(rows[curve.index(float(preload_uN))])
    n = params.array.count
    rng = np.random.default_rng(seed)
    heights, weights = quasistatic.representative_heights(n, params.floor.sigma, rng, n_blocks)
    res = quasistatic.preload_pull(
        params,
        heights,
        float(preload_uN),
        weights=weights,
        lateral=lateral,
        retract_steps=retract_steps,
    )
    return _preload_row(params, res)


@functools.lru_cache(maxsize=4)
def _preload_curve(params, seed, curve, n_blocks, retract_steps, lateral) -> tuple:
    """The rows of :func:`quasistatic_preload_point` at every preload of ``curve`` [µN], from
    one :func:`gecko_agents.quasistatic.preload_pulls` on the floor of ``seed``."""
    rng = np.random.default_rng(seed)
    n = params.array.count
    heights, weights = quasistatic.representative_heights(n, params.floor.sigma, rng, n_blocks)
    results = quasistatic.preload_pulls(
        params,
        heights,
        curve,
        weights=weights,
        lateral=lateral,
        retract_steps=retract_steps,
        approach_stride=CURVE_STRIDE,
        retract_stride=CURVE_STRIDE,
        turning="bisect",
    )
    return tuple(_preload_row(params, res) for res in results)


def _preload_row(params: SetaArray, res) -> dict[str, float]:
    """A quasi-static press-and-pull result as :func:`quasistatic_preload_point`'s row."""
    n = params.array.count
    return {
        "preload_uN": res.preload,
        "pull_off_uN": res.pull_off,
        "pull_off_per_seta_uN": res.pull_off / n,
        "pull_off_over_ideal": res.pull_off / (n * params.contact.pull_off_force),
        "attached_fraction": float(res.n_attached.max()) / n,
    }


def agent_preload_point(
    params: SetaArray, seed: int, *, preload_uN: float, n_sim: int = 16, speed: float = 0.02
) -> dict[str, float]:
    """Force-controlled press and pull-off of an ``n_sim``-seta patch with the agent model.

    ``preload_uN`` is the preload on the whole array of ``params.array.count`` setae [µN]; the
    patch gets its share, ``preload_uN · n_sim / count``, and its pull-off is scaled back by
    ``count / n_sim``. The patch's floor is drawn from ``seed``. Protocol:
    :class:`~gecko_agents.protocol.Press` to the patch preload at ``speed`` [µm/µs], then a
    vertical :class:`~gecko_agents.protocol.PullOff` at the same speed.

    Returns
    -------
    ``preload_patch_uN`` target on the patch [µN]; ``preload_held_uN`` force at the deepest
    plate position [µN] (a small patch cannot hit a preload finer than one contact's jump-in);
    ``pull_off_patch_uN`` peak tensile force of the patch [µN]; ``pull_off_array_uN`` that ×
    count / n_sim [µN]; ``pull_off_per_seta_uN`` [µN]; ``attached_fraction`` largest fraction
    of the patch attached [-]; ``n_steps`` time steps; ``max_kinetic_to_elastic`` peak kinetic
    / peak elastic energy (quasi-static if ≪ 1).
    """
    count = params.array.count
    target = preload_uN * n_sim / count
    model = Model(params, n_sim=n_sim, seed=seed)
    hist = model.run([Press(target, speed), PullOff(speed)], progress=False)
    y = hist["plate_y_um"]
    held = float(hist["force_normal_uN"][np.flatnonzero(y <= y.min())[-1]])
    peak = hist.peak_pull_off
    return {
        "preload_patch_uN": target,
        "preload_held_uN": held,
        "pull_off_patch_uN": peak,
        "pull_off_array_uN": peak * count / n_sim,
        "pull_off_per_seta_uN": peak / n_sim,
        "attached_fraction": float(hist["n_attached"].max()) / n_sim,
        "n_steps": int(hist.meta["n_steps"]),
        "max_kinetic_to_elastic": float(hist.meta["max_kinetic_to_elastic"]),
    }


POINT_FUNCTIONS = {
    f.__name__: f
    for f in (analytic_point, cpu_bound_point, quasistatic_preload_point, agent_preload_point)
}
"""The point functions a sweep file may name (``point = "<name>"``)."""
