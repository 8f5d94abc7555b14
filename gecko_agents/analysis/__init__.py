"""Analyses of recorded histories, each defined once (units µm, µN, µs; adhesion > 0 in tension).

* :mod:`~gecko_agents.analysis.drag` — where a drag starts and ends, whether the tip let go in
  it, the seta's lean after it;
* :mod:`~gecko_agents.analysis.pull` — the release point and the pull-off of the pull;
* :mod:`~gecko_agents.analysis.limit_curve` — the frictional-adhesion limit curve and α*;
* :mod:`~gecko_agents.analysis.ratio` — the gripping/releasing pull-off ratio;
* :mod:`~gecko_agents.analysis.convergence` — convergence in the plate speed (slopes, order,
  Richardson limit).
"""
