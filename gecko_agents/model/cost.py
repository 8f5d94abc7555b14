"""What a run will cost, estimated before it starts: refused when absurd, warned when long.

A run's cost is its seta-steps, (duration / dt) × simulated setae; about 10⁷ seta-steps per
second on one core (numpy path, 100+ setae) is what sets the two limits below.
"""

from __future__ import annotations

import warnings

from gecko_agents._stack import user_stacklevel
from gecko_agents.diagnostics import ValidityWarning

__all__ = ["COST_WARN", "COST_REFUSE", "run_cost", "check_cost"]

COST_WARN = 1e9
"""Seta-steps (steps × simulated setae) above which a run warns before it starts: about 10⁷
seta-steps per second on one core (numpy path, 100+ setae) makes this minutes to hours."""
COST_REFUSE = 1e11
"""Seta-steps above which a run is refused before it starts: hours to days on one core; cut
n_sim, the travel or the duration, or raise the speed (checking ``quasi_static``)."""


def run_cost(n_setae: int, duration_us: float, dt_us: float) -> float:
    """Estimated seta-steps of a run: (duration / dt) × setae [-]."""
    return n_setae * duration_us / dt_us


def check_cost(n_setae: int, duration_us: float, dt_us: float) -> float:
    """Refuse (ValueError) a run above :data:`COST_REFUSE` seta-steps, warn
    (:class:`ValidityWarning`) above :data:`COST_WARN`; returns the estimate."""
    cost = run_cost(n_setae, duration_us, dt_us)
    steps = duration_us / dt_us
    what = (
        f"the run would take ~{steps:.3g} steps of dt = {dt_us:.3g} µs over ~{duration_us:.3g} "
        f"µs for {n_setae} setae: {cost:.3g} seta-steps"
    )
    fix = (
        "simulate fewer setae (n_sim), a shorter protocol (depth, travel, hold) or a faster "
        "plate (keeping the validity item quasi_static ≤ 0.05), or check the moduli, which set dt"
    )
    if not cost <= COST_REFUSE:
        raise ValueError(f"{what}, above the limit {COST_REFUSE:.0e}; {fix}")
    if cost > COST_WARN:
        warnings.warn(
            ValidityWarning(f"{what} (above {COST_WARN:.0e}: expect minutes to hours); {fix}"),
            stacklevel=user_stacklevel(),
        )
    return cost
