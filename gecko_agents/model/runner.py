"""Running a protocol on a :class:`gecko_agents.model.Model`: its segments stepped one after
another (each segment gives the plate's velocity, :mod:`gecko_agents.protocol`), the free
approach skipped where nothing can touch, every ``record_every`` steps a recorded row and a
stability check, and at the end the :class:`~gecko_agents.history.History` with its metadata
and validity report.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass

from gecko_agents.contact import bounds as tip_bounds
from gecko_agents.diagnostics import diagnose, model_facts, non_finite_report
from gecko_agents.history import History
from gecko_agents.model.cost import check_cost
from gecko_agents.model.recorder import Recorder
from gecko_agents.model.setup import floor_statistics
from gecko_agents.protocol import Segment
from gecko_agents.provenance import versions

__all__ = ["SimulationUnstable", "run_protocol"]


class SimulationUnstable(RuntimeError):
    """The run blew up (non-finite state or runaway kinetic energy)."""


@dataclass
class _Run:
    """Running totals of one :meth:`Model.run`: plate work and dissipation [pJ], steps, the
    free travel skipped [µm], and the run's settings."""

    recorder: Recorder
    ke_bound: float | None
    max_steps: int
    fast_approach: bool
    work: float = 0.0
    dissipated: float = 0.0
    skipped: float = 0.0
    n_steps: int = 0


def run_protocol(m, protocol, progress, max_steps, ke_bound, fast_approach) -> History:
    """:meth:`gecko_agents.model.Model.run` (its docstring has the arguments)."""
    from tqdm.auto import tqdm

    segments = list(protocol)
    if not segments:
        raise ValueError("protocol is empty: give at least one segment")
    for seg in segments:
        if not isinstance(seg, Segment):
            raise TypeError(f"unknown protocol segment {seg!r}")
    m.reset_state_arrays()
    run = _Run(Recorder(m.record_setae, film=m.law.film), ke_bound, max_steps, fast_approach)
    for seg in segments:
        seg.check(m)  # a depth this plate cannot reach is refused before any step
    est = sum(seg.estimated_duration(m) for seg in segments)
    # refuse or warn before stepping when absurd, force control at its longest
    check_cost(m.n, sum(seg.longest_duration(m) for seg in segments), m.dt)
    # Whole microseconds of simulated time; the total is an estimate and may be exceeded.
    desc = f"gecko_agents (dt = {m.dt:.3g} µs)"
    bar = tqdm(total=max(int(est), 1), unit="µs", disable=not progress, desc=desc,
               mininterval=0.5)  # fmt: skip
    t_wall = time.perf_counter()
    try:
        for seg in segments:
            _run_segment(m, seg, run, bar)
    finally:
        bar.close()
    run.recorder.record(m, run.work, run.dissipated)
    meta = {
        "dt_us": m.dt, "n_steps": run.n_steps, "record_every": m.record_every,
        "n_sim": m.n, "scale_to_array": m.params.array.count / m.n,
        "protocol": [f"{seg!r}" for seg in segments], "contact_path": m.contact_path,
        "kernel": m.kernel, "loop_threads": m.loop_threads,
        "detection": m.world.detection,
        "tip_law": m.law.name, "tip_bounds": tip_bounds(m.law),
        "energy_complete": m.energy_complete,
        "floor_statistics": floor_statistics(m.world.profile, m.params.floor),
        "skipped_travel_um": run.skipped,
        "damping": dataclasses.asdict(m.damping), "mass_ng": m.mass,
        "tangential_stiffness_uN_per_um": m.k_t,
        "wall_time_s": time.perf_counter() - t_wall, "versions": versions(),
        **model_facts(m, segments),
    }  # fmt: skip
    if m.backing.info is not None:
        meta["backing"] = m.backing.info
    w = m.world
    geometry = {"root_dx_um": w.root_dx, "root_dy_um": w.root_dy,
                "floor_x_um": w.profile.x, "floor_y_um": w.profile.y,
                **m.backing.geometry}  # fmt: skip
    history = run.recorder.history(m.params, m.seed, geometry, meta)
    history.meta["validity"] = diagnose(history)
    return history


def _run_segment(m, seg: Segment, run: _Run, bar) -> None:
    """Step through one protocol segment, recording every ``record_every`` steps."""
    state = {"start": m.plate_position, "t0": m.time}
    may_skip = run.fast_approach and seg.skips_free_travel
    every, rec = m.record_every, run.recorder
    e_scale = m.n * max(m.Fc, 1e-300) * abs(m.law.detach_overlap)
    while (vp := seg.velocity(m, state)) is not None:
        if may_skip and run.n_steps % every == 0 and not m.state.attached.any():
            run.skipped += m.skip_free_travel(seg, state, vp)
        m.advance(vp[0], vp[1])
        run.work += m.work_step
        run.dissipated += m.physics.diss
        if m.physics.events:
            rec.note_detachments(m.time, m.plate_position, m.pop_releases())
        run.n_steps += 1
        if run.n_steps % every == 0 or run.n_steps == 1:
            row = rec.record(m, run.work, run.dissipated)
            bound = run.ke_bound
            if bound is None:
                bound = 100 * (e_scale + abs(run.work))
            _check_stable(m, row, bound)
            bar.update(int(m.time) - bar.n)
        if run.n_steps >= run.max_steps:
            raise RuntimeError(f"max_steps = {run.max_steps} reached in segment {seg}")


def _check_stable(m, row, bound):
    if not all(math.isfinite(v) for v in row.values()):
        raise SimulationUnstable(non_finite_report(m, row))
    if row["energy_kinetic_pJ"] > bound:
        raise SimulationUnstable(
            f"kinetic energy {row['energy_kinetic_pJ']:.3g} pJ exceeded {bound:.3g} pJ at "
            f"t = {m.time:.4g} µs: the integration is unstable (reduce dt = "
            f"{m.dt:.3g} µs) or the plate moves too fast for the setae to follow "
            "(lower the protocol speed)"
        )
