"""What a run will cost, estimated before it starts: refused when absurd, warned when long.

A run's cost is its seta-steps: the steps it can take at most, times the simulated setae, at
least :data:`STEP_OVERHEAD_SETAE` (a step's fixed cost). Every route to a long run counts:
each segment's longest duration (a force-controlled press down to the deepest plate height, a
pull-off's travel at its angle and its clearance), at least one step per segment, and with
the implicit step each step taken as the located steps near an event (dt/event_dt of them).
About 10⁷ seta-steps per second on one core (numpy path, 100+ setae) sets the two limits.
"""

from __future__ import annotations

import math
import warnings

from gecko_agents._stack import user_stacklevel
from gecko_agents.diagnostics import ValidityWarning

__all__ = [
    "COST_WARN",
    "COST_REFUSE",
    "STEP_OVERHEAD_SETAE",
    "RunCostError",
    "run_cost",
    "check_cost",
]

COST_WARN = 1e9
"""Seta-steps above which a run warns before it starts: about 10⁷ seta-steps per second on one
core (numpy path, 100+ setae) makes this minutes to hours."""
COST_REFUSE = 1e11
"""Seta-steps above which a run is refused before it starts: hours to days on one core; cut
n_sim, the travel or the duration, or raise the speed (checking ``quasi_static``)."""
STEP_OVERHEAD_SETAE = 300
"""A step's fixed cost (the Python step, pymunk's batch I/O, the records) in setae [-]: a
single seta's step costs about as much as 300 setae's share of a large array's."""


class RunCostError(ValueError):
    """A run refused before its first step for what it would cost (an input error)."""


def run_cost(n_setae: int, durations_us, dt_us: float, event_dt_us: float | None = None) -> float:
    """The most seta-steps a run can take [-]: Σ over segments of ⌈duration/dt⌉ (at least one)
    steps, each of up to ⌈dt/event_dt⌉ located steps (implicit step; None: explicit), times
    max(setae, :data:`STEP_OVERHEAD_SETAE`).

    Parameters
    ----------
    n_setae : simulated setae. durations_us : each segment's longest duration [µs].
    dt_us : the step [µs]. event_dt_us : the implicit step near events [µs], or None.
    """
    located = 1.0 if event_dt_us is None else max(1.0, math.ceil(dt_us / event_dt_us - 1e-9))
    steps = sum(
        max(1.0, math.ceil(d / dt_us - 1e-9)) if math.isfinite(d) else d for d in durations_us
    )
    return max(n_setae, STEP_OVERHEAD_SETAE) * steps * located


def check_cost(n_setae: int, durations_us, dt_us: float, event_dt_us=None, names=None) -> float:
    """Refuse (:class:`RunCostError`) a run above :data:`COST_REFUSE` seta-steps (naming dt and
    its range where a step is longer than the whole protocol, the sum of ``durations_us``),
    warn (:class:`ValidityWarning`) above :data:`COST_WARN`; returns the estimate
    (:func:`run_cost`). ``names``: the segments' reprs, to name the longest."""
    durations = [float(d) for d in durations_us]
    total = sum(durations)
    cost = run_cost(n_setae, durations, dt_us, event_dt_us)
    if not cost <= COST_REFUSE and dt_us > total and event_dt_us is not None:
        raise RunCostError(
            f"dt = {dt_us:.3g} µs is longer than the whole protocol (at most ~{total:.3g} µs "
            f"over {len(durations)} segment(s)), and each step would split into up to "
            f"{math.ceil(dt_us / event_dt_us - 1e-9):.3g} located steps near events: the "
            f"allowed range of dt is (0, {total:.3g}] µs; leave dt unset for the "
            "integrator's default"
        )
    longest = max(range(len(durations)), key=durations.__getitem__) if durations else None
    which = f", most of it in {names[longest]}" if names and longest is not None else ""
    sub = (
        f", each up to {math.ceil(dt_us / event_dt_us - 1e-9):.3g} located steps of "
        f"event_dt = {event_dt_us:.3g} µs"
        if event_dt_us is not None and dt_us > event_dt_us
        else ""
    )
    what = (
        f"the run could take ~{total / dt_us:.3g} steps of dt = {dt_us:.3g} µs{sub} over "
        f"~{total:.3g} µs{which} for {n_setae} setae: {cost:.3g} seta-steps"
    )
    fix = (
        "simulate fewer setae (n_sim), a shorter protocol (depth, travel, clearance, hold, a "
        "steeper pull angle) or a faster plate (keeping the validity item quasi_static ≤ "
        "0.05), a dt and event_dt nearer each other, or check the moduli, which set dt"
    )
    if not cost <= COST_REFUSE:
        raise RunCostError(f"{what}, above the limit {COST_REFUSE:.0e}; {fix}")
    if cost > COST_WARN:
        warnings.warn(
            ValidityWarning(f"{what} (above {COST_WARN:.0e}: expect minutes to hours); {fix}"),
            stacklevel=user_stacklevel(),
        )
    return cost
