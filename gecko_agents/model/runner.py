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

import numpy as np

from gecko_agents.contact import bounds as tip_bounds
from gecko_agents.diagnostics import diagnose, model_facts
from gecko_agents.diagnostics.resolution import neighbour_distance
from gecko_agents.history import History
from gecko_agents.model.cost import check_cost
from gecko_agents.model.recorder import Recorder
from gecko_agents.model.setup import floor_statistics
from gecko_agents.protocol import Segment
from gecko_agents.provenance import versions

__all__ = ["SimulationUnstable", "SegmentBar", "run_protocol"]


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
    t_record: float = 0.0  # the next record's time with records by time [µs]
    force_lo: float = math.inf  # most tensile total normal force at any step [µN]
    force_hi: float = -math.inf  # most compressive [µN]
    release_travel: float = 0.0  # longest plate travel of a step in which a tip let go [µm]
    neighbours: float = math.inf  # least distance of neighbouring pillars' centre lines [µm]


def run_protocol(m, protocol, progress, max_steps, ke_bound, fast_approach) -> History:
    """:meth:`gecko_agents.model.Model.run` (its docstring has the arguments)."""
    segments = list(protocol)
    if not segments:
        raise ValueError("protocol is empty: give at least one segment")
    for seg in segments:
        if not isinstance(seg, Segment):
            raise TypeError(f"unknown protocol segment {seg!r}")
    m.reset_state_arrays()
    if m.implicit_step is not None:
        m.implicit_step.energy_scale = 0.0  # the run's own (History.energy_balance_error)
    run = _Run(
        Recorder(m.record_setae, film=m.law.film, mode=m.law.release_mode),
        ke_bound,
        max_steps,
        fast_approach,
    )
    for seg in segments:
        seg.check(m)  # a depth this plate cannot reach is refused before any step
    # refuse or warn before stepping when absurd, force control at its longest
    check_cost(
        m.n,
        [seg.longest_duration(m) for seg in segments],
        m.dt,
        None if m.implicit_step is None else m.event_dt,
        [repr(seg) for seg in segments],
    )
    t_wall = time.perf_counter()
    for i, seg in enumerate(segments, 1):
        bar = SegmentBar(m, seg, f"{i}/{len(segments)}", progress)
        try:
            _run_segment(m, seg, run, bar)
            bar.finish()
        finally:
            bar.close()
    run.recorder.record(m, run.work, run.dissipated)
    meta = {
        "dt_us": m.dt,
        "n_steps": run.n_steps,
        "record_every": m.record_every,
        "n_sim": m.n,
        "scale_to_array": m.params.array.count / m.n,
        "protocol": [f"{seg!r}" for seg in segments],
        "contact_path": m.contact_path,
        "kernel": m.kernel,
        "loop_threads": m.loop_threads,
        "detection": m.world.detection,
        "tip_law": m.law.name,
        "tip_bounds": tip_bounds(m.law),
        "energy_complete": m.energy_complete,
        "floor_statistics": floor_statistics(m.world.profile, m.params.floor),
        "skipped_travel_um": run.skipped,
        "damping": dataclasses.asdict(m.damping),
        "mass_ng": m.mass,
        "tangential_stiffness_uN_per_um": m.k_t,
        "wall_time_s": time.perf_counter() - t_wall,
        "versions": versions(),
        "numerics": dataclasses.asdict(m.numerics),
        "stepped_force_normal_range_uN": [run.force_lo, run.force_hi] if run.n_steps else None,
        "release_step_travel_um": run.release_travel,
        "min_neighbour_distance_um": run.neighbours if math.isfinite(run.neighbours) else None,
        "multirate_steps": 0 if m.multirate is None else m.multirate.n_steps,
        "multirate_seta_substeps": 0 if m.multirate is None else m.multirate.seta_steps,
        **model_facts(m, segments),
    }
    if m.backing.info is not None:
        meta["backing"] = m.backing.info
    w = m.world
    geometry = {
        "root_dx_um": w.root_dx,
        "root_dy_um": w.root_dy,
        "floor_x_um": w.profile.x,
        "floor_y_um": w.profile.y,
        **m.backing.geometry,
    }
    history = run.recorder.history(m.params, m.seed, geometry, meta)
    history.meta["validity"] = diagnose(history)
    return history


class SegmentBar:
    """The progress bar of one protocol segment, over simulated time in whole µs.

    A segment that ends at a fixed time or point (:class:`~gecko_agents.protocol.Hold`,
    :class:`~gecko_agents.protocol.PressTo`, :class:`~gecko_agents.protocol.Move`) gets a bar
    whose total is its duration from where the plate stands (travel / speed, or the hold's
    duration), never passed and filled to exactly 100 % when the segment ends (it ends within
    a step of that total). One that ends on a measured condition (a
    :class:`~gecko_agents.protocol.Press` to a preload, a
    :class:`~gecko_agents.protocol.PullOff` until every tip let go) has no total while it
    runs: a spinner counting µs, whose total is set to what it ran when it ends.
    """

    def __init__(self, m, seg: Segment, label: str, progress: bool):
        from tqdm.auto import tqdm

        self.m, self.t0 = m, m.time
        total = _segment_total(m, seg)
        desc = f"gecko_agents {label} {type(seg).__name__} (dt = {m.dt:.3g} µs)"
        self.bar = tqdm(total=total, unit="µs", disable=not progress, desc=desc, mininterval=0.5)

    def update(self) -> None:
        """Advance to the segment's elapsed simulated time [whole µs], never past the total."""
        n = int(self.m.time - self.t0)
        if self.bar.total is not None:
            n = min(n, int(self.bar.total))
        if n > self.bar.n:
            self.bar.update(n - self.bar.n)

    def finish(self) -> None:
        """The segment ended: a bar fills to exactly its total, a spinner gets one."""
        if self.bar.total is None:
            self.bar.total = max(int(self.m.time - self.t0), self.bar.n)
        self.bar.update(int(self.bar.total) - self.bar.n)
        self.bar.refresh()

    def close(self) -> None:
        self.bar.close()


def _segment_total(m, seg: Segment) -> int | None:
    """Whole µs a segment that ends at a fixed time or point runs from now (None: it ends on
    a measured condition)."""
    duration = getattr(seg, "duration", None)
    if duration is not None:
        return max(round(duration), 1)
    target = seg.target(m, {"start": m.plate_position, "t0": m.time})
    speed = getattr(seg, "speed", None)
    if target is None or not speed:
        return None
    px, py = m.plate_position
    return max(round(math.hypot(target[0] - px, target[1] - py) / speed), 1)


def _run_segment(m, seg: Segment, run: _Run, bar: SegmentBar) -> None:
    """Step through one protocol segment, recording every ``record_every`` steps, or, with
    the implicit step's default (``Model.record_in_time``), every ``record_every`` full steps
    of simulated time: its steps shorten for fast segments and near events, and records
    every so many of them would sample those densely (the energy books' transients at events
    included, which the explicit step's records sample as sparsely as the rest)."""
    state = {"start": m.plate_position, "t0": m.time}
    may_skip = run.fast_approach and seg.skips_free_travel
    every, rec = m.record_every, run.recorder
    e_scale = m.n * max(m.Fc, 1e-300) * abs(m.law.detach_overlap)
    implicit = m.implicit_step
    interval = None
    if implicit is not None:
        implicit.begin_segment(getattr(seg, "speed", None))
        interval = every * implicit.dt_full if m.record_in_time else None
    while (vp := seg.velocity(m, state)) is not None:
        if may_skip and run.n_steps % every == 0 and not m.state.attached.any():
            run.skipped += m.skip_free_travel(seg, state, vp)
        if implicit is not None:  # a hold ends on its duration, not a whole step past it
            left = seg.time_left(m, state)
            if left is not None and 0 < left < implicit.dt_base:
                implicit.dt_base = left
        # The implicit step takes k steps of dt/k near an event (ImplicitStep.substeps),
        # only the setae near it where they are independent (multirate).
        k = 1 if implicit is None else implicit.substeps(vp)
        multi = m.multirate
        near = None
        if k > 1 and multi is not None and run.n_steps and implicit.near is not None:
            near = multi.near(implicit.near, k)
        if near is not None:
            implicit.set_dt(implicit.dt_base)  # the long step; the near setae take k
            released = multi.advance(vp, near, k)
            steps = 1
        else:
            released, steps = None, k
        for _ in range(steps):
            if released is None:
                m.advance(vp[0], vp[1])
            _account(m, run, vp, released)
            if interval is None:
                due = run.n_steps % every == 0
            else:
                due = m.time >= run.t_record - 1e-9 * interval
                if due:
                    run.t_record = (math.floor(m.time / interval + 1e-9) + 1) * interval
            if due or run.n_steps == 1:
                row = rec.record(m, run.work, run.dissipated)
                _note_neighbours(m, run)
                if implicit is not None:
                    implicit.note_energies(row)
                bound = run.ke_bound
                if bound is None:
                    bound = 100 * (e_scale + abs(run.work))
                _check_stable(m, row, bound)
                bar.update()
            if run.n_steps >= run.max_steps:
                raise RuntimeError(f"max_steps = {run.max_steps} reached in segment {seg}")
        if k > 1:
            implicit.set_dt(implicit.dt_base)
    if implicit is not None:  # a fast segment's shorter step ends with it
        implicit.set_dt(implicit.dt_full)


def _account(m, run: _Run, vp, released) -> None:
    """Book one step of the whole array: its work, dissipation and force extremes, and its
    releases: ``released`` as :meth:`gecko_agents.model.multirate.Multirate.advance` gives
    them (time, plate position, releases, step), or None for the model's own step."""
    run.work += m.work_step
    run.dissipated += m.physics.diss
    force = np.add.reduce(m.state.P)  # what the records may step over
    if force < run.force_lo:
        run.force_lo = float(force)
    if force > run.force_hi:
        run.force_hi = float(force)
    if released is None and m.physics.events:
        released = [(m.time, m.plate_position, m.pop_releases(), m.dt)]
    for t, plate, events, dt in released or ():
        run.release_travel = max(run.release_travel, math.hypot(*vp) * dt)
        run.recorder.note_detachments(t, plate, events)
    run.n_steps += 1


def _note_neighbours(m, run: _Run) -> None:
    """The least distance between neighbouring elastica pillars' centre lines so far [µm]
    (the validity item ``pillars_meet``)."""
    chain = m.physics.chain
    if chain is None or m.n < 2:
        return
    px, py = m.plate_position
    roots = np.column_stack([px + m.world.root_dx, py + m.world.root_dy])
    run.neighbours = min(run.neighbours, neighbour_distance(chain.nodes(roots)))


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


def non_finite_report(model, row: dict) -> str:
    """Say what went non-finite in a model's state and where (which quantity, which setae),
    and whether an input (an external force) or the integration is to blame."""
    from gecko_agents.model.state import ROWS

    s = model.state
    t = f"t = {model.time:.4g} µs"
    ext = np.asarray(s.external_force)
    bad_ext = np.flatnonzero(~np.isfinite(ext).all(axis=1))
    if bad_ext.size:
        return (
            f"non-finite external force {ext[bad_ext[0]].tolist()} µN on seta(s) "
            f"{bad_ext[:10].tolist()} at {t}: it was given to the model (Model.external_force), "
            "not produced by the integration; pass finite forces"
        )
    found = []
    for name in ROWS:
        if name in ("delta", "jump"):  # NaN by design (no candidate floor, not running away)
            continue
        row_vals = s.block[ROWS.index(name)]
        idx = np.flatnonzero(~np.isfinite(row_vals))
        if idx.size:
            found.append(f"{name} (setae {idx[:10].tolist()})")
    cols = [k for k, v in row.items() if not math.isfinite(v)]
    where = "; ".join(found) if found else "no per-seta quantity"
    return (
        f"non-finite state at {t}: per-seta {where}; recorded columns {cols}. "
        f"The inputs were finite, so the integration diverged: the time step dt = "
        f"{model.dt:.3g} µs (ω_max·dt = {model.omega_max * model.dt:.2f}) may be too large for "
        "the contact stiffness reached; pass a smaller dt or a shallower depth/preload"
    )
