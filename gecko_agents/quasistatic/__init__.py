"""The paper's quasi-static contact model (eq 22–27), vectorized over setae: our oracle.

Each seta is a linear spring (the 2×2 beam stiffness K of eq 16–21) between its root on the
plate and a JKR tip (eq 7, 10) on a locally flat floor at height h_i (eq 28). The plate moves
vertically through a list of heights Z; at every plate position every attached seta is put in
static equilibrium

    K·(p − p0) = (F_t, P),    p0 = root + L·(cos θ, −sin θ),    δ = h + R − p_y,

where p is the tip-sphere centre, P = P_JKR(δ) the normal force (positive compressive) and F_t
the tangential contact force. Lateral behaviour, chosen by ``lateral``:

* ``"coupled"`` (default): Coulomb stick/slip with the cap of ``params.friction`` (return
  mapping: try to stick at the previous tip abscissa; if |F_t| exceeds the cap, slide with
  F_t = ±cap). Sliding leaves the normal stiffness Ky of eq 20 plus a friction term; sticking
  gives the stiffer K_yy.
* ``"free"``: the paper's eq 25, F = y2·Ky: the tip is free to move sideways (no friction in
  the normal balance). Eq 26–27 then only describe the lateral bookkeeping.

Contact forms when the free tip touches the floor (δ = 0, jump-in) and is kept along the stable
JKR branch. It lets go where the spring–contact equilibrium ceases to exist: a fold, where the
contact stiffness dP/dδ equals −k with k the seta's effective normal stiffness in its current
stick/slip state (:func:`release_radius`). A soft seta (k → 0) lets go at the load-controlled
point (P = −Fc, a = 0.63 a0), a rigid one at δc (a = 0.303 a0).

Every seta's branch depends on its height only through a shift, so each branch is tabulated
once as a function of the contact radius a and inverted by interpolation plus Newton polishing:
one step costs O(N).

The paper's 10⁷ setae
---------------------
Every seta's history along the plate path depends on its floor height alone, smoothly except
where a discrete decision flips (jump-in, stick or slide, slide direction, release).
:func:`representative_heights` draws and sorts the heights and replaces them by the means of
blocks of consecutive setae, counted with their sizes; given the sorted sample too
(``return_sample=True``, then ``sample=`` to :func:`press_pull`, :func:`preload_pull` or
:func:`solve`), a block that a plate step leaves with such a boundary inside is split there and
both parts re-solved from the block's state before the step. Every block then holds setae with
one discrete history, its mean height represents them to second order, and 2000 blocks give the
curve of all 10⁷ setae solved one by one to ~1e-9 of the peak force (1000 plate positions in
about 1 s with the heights; ``python -m gecko_agents.bench``). Plain block means without the
sample err by about 0.7/n_blocks of the peak: a block crossing a boundary counts all its setae
on one side of it.

Units: µm, µN (see :mod:`gecko_agents.params`). The plate only moves vertically here.

The code lives in one module per concept and this module gathers them, so everything is
importable from here: :mod:`~gecko_agents.quasistatic.branches` (the linear seta's tabulated
branches and release radius), :mod:`~gecko_agents.quasistatic.linear` (one plate position of
linear setae), :mod:`~gecko_agents.quasistatic.blocks` (blocks of a sorted sample split on the
fly), :mod:`~gecko_agents.quasistatic.rod` (the rod seta),
:mod:`~gecko_agents.quasistatic.rod_equilibrium` (the rod's force and its Newton solve per
seta), :mod:`~gecko_agents.quasistatic.solve` (a given plate path; displacement control),
:mod:`~gecko_agents.quasistatic.preload` (force control),
:mod:`~gecko_agents.quasistatic.heights` (representative floor heights),
:mod:`~gecko_agents.quasistatic.state` and :mod:`~gecko_agents.quasistatic.result` (what a
solve carries and returns).
"""

from __future__ import annotations

from gecko_agents.quasistatic.branches import Branches, release_radius, retract_travel
from gecko_agents.quasistatic.heights import (
    plate_start_height,
    quantile_heights,
    representative_heights,
)
from gecko_agents.quasistatic.preload import preload_pull, preload_pulls
from gecko_agents.quasistatic.result import QuasiStaticResult
from gecko_agents.quasistatic.rod import RodSetup, rod_force, rod_retract_travel
from gecko_agents.quasistatic.solve import press_pull, single_seta, solve

__all__ = [
    "release_radius",
    "Branches",
    "QuasiStaticResult",
    "solve",
    "press_pull",
    "retract_travel",
    "rod_force",
    "RodSetup",
    "rod_retract_travel",
    "preload_pull",
    "preload_pulls",
    "representative_heights",
    "quantile_heights",
    "plate_start_height",
    "single_seta",
]
