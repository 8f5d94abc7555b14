"""Multirate stepping: near an event only the setae near it take the short steps, the rest
of the array keeps the implicit step's long one.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).

On a rigid backing the plate's motion is prescribed, so the setae are independent systems
that share nothing but that motion: each one's step needs only its own state and the plate's.
A step size can then differ between setae, the multirate idea of Gear & Wells (1984),
"Multirate linear multistep methods", BIT 24(4), 484–502 (doi:10.1007/BF01934907): a slow
component keeps the long step while a fast one takes several short ones over the same
interval. Here the fast components are the setae
:meth:`gecko_agents.model.event_steps.EventSteps.substeps` finds near an event (a snap-off, a
fold, a jump-in, a slip, a released tip's ringing): over one long step dt they take k steps of
dt/k in a pymunk space of their own (:class:`SubWorld`), with the kernels, event location
and energy books of the whole array's located steps; the others take one step of dt. Each
seta's history is then the one it would have had if it were stepped alone, up to rounding,
and an event is resolved as the implicit step's located steps resolve it.

What the plate sees is summed over both: the force on it and its work (the trapezoid of each
seta's pull over its own steps), the dissipation, the releases (each at its own short step's
time and plate position). The whole array's step computes every seta once at dt; the near
setae's share of it is computed again alone from the same state and taken out, so no kernel
needs a mask (:meth:`Multirate.advance`).

Where it does not apply, the whole array takes the located steps as before: a backing that
couples the setae (an elastic strip or layer: their roots move with each other), a continuous
floor (its contact pairs come from pymunk's detection in the array's space), the elastica,
the callback contact path, the explicit step, and a step whose near setae would take more
seta-steps apart than the whole array's k short steps (:meth:`Multirate.near`).
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pymunk
import pymunk.batch as pb

from gecko_agents.backing.rigid import RigidBacking
from gecko_agents.model.state import FX, FY, SetaState
from gecko_agents.model.step_numpy import NumpyStep

__all__ = ["Multirate", "SubWorld", "multirate_applies"]

_FIELDS = pb.BodyFields.BODY_ID | pb.BodyFields.POSITION | pb.BodyFields.VELOCITY
_SET = pb.BodyFields.POSITION | pb.BodyFields.VELOCITY


def multirate_applies(model) -> bool:
    """Whether ``model``'s located steps are multirate (the build step decides:
    ``gecko_agents.model.build.choose_multirate``)."""
    return model.multirate is not None


class SubWorld:
    """A pymunk space for the setae near an event: tip bodies from a pool (grown as needed)
    and a kinematic plate, with the interface of
    :class:`gecko_agents.model.world.World` that a step uses. The floor is each seta's pad
    (heights ``h`` [µm]); a tip is a contact candidate while its sensor circle (radius
    ``sensor_radius`` [µm]) reaches its pad, the overlap full detection finds, decided here
    from the positions at which the step evaluates forces."""

    pads = True
    lazy = False
    pad_slack = math.inf  # the pads are lines here: no window to re-centre

    def __init__(self, world):
        self.sensor_radius = world.sensor_radius
        self.space = pymunk.Space()
        self.plate = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        self.space.add(self.plate)
        self.bodies: list = []
        self._ids = np.zeros(0, dtype=np.uintp)  # the pool's body ids
        self._in_space = 0  # the pool's first bodies are in the space
        self._order_ids = np.zeros(0, dtype=np.uintp)  # the space's body order last seen
        self._buf = pb.Buffer()
        self._force_buf = pb.Buffer()
        self.tip_slice = None

    def load(self, mass, idx, world, rows, state, plate) -> None:
        """Take setae ``idx`` of the array's ``world`` into the space: their pads, roots and
        rest positions, their bodies' positions and velocities ``rows`` ((m, 4): x, y, vx, vy
        [µm, µm/µs]), the sub-state ``state`` whose candidate flags the steps keep, the plate
        at ``plate`` (x, y) [µm]. The space holds exactly m tip bodies from the pool."""
        m, bodies = idx.size, self.bodies
        if len(bodies) < m:  # grow the pool
            new = [
                pymunk.Body(mass, math.inf) for _ in range(max(m, 2 * len(bodies)) - len(bodies))
            ]
            bodies.extend(new)
            self._ids = np.concatenate([self._ids, np.array([b.id for b in new], dtype=np.uintp)])
        if m > self._in_space:
            self.space.add(*bodies[self._in_space : m])
        elif m < self._in_space:
            self.space.remove(*bodies[m : self._in_space])
        self._in_space = m
        self.state, self.n = state, m
        self.h = world.h[idx]
        self.pad_centre = world.pad_centre[idx]
        self.root_dx, self.root_dy = world.root_dx[idx], world.root_dy[idx]
        self.rest_dx, self.rest_dy = world.rest_dx[idx], world.rest_dy[idx]
        self.plate.position = plate
        self.plate.velocity = (0.0, 0.0)
        data = self._get().copy()
        ids = np.frombuffer(self._buf.int_buf(), dtype=np.uintp)
        if ids.size != self._order_ids.size or not np.array_equal(ids, self._order_ids):
            sort = np.argsort(ids)  # each pool body's row in pymunk's order
            self._row_of_body = sort[np.searchsorted(ids, self._ids[:m], sorter=sort)]
            self._order_ids = ids.copy()
        self.order = order = self._row_of_body[:m]
        first = int(order[0]) if m else 0
        contiguous = m and np.array_equal(order, np.arange(first, first + m))
        self.tip_slice = slice(first, first + m) if contiguous else None
        data[order] = rows
        put = pb.Buffer()
        put.set_float_buf(data.reshape(-1))
        pb.set_space_bodies(self.space, _SET, put)
        self.out = np.zeros((ids.size, 2))
        self._force_buf.set_float_buf(self.out.reshape(-1))

    def _get(self) -> np.ndarray:
        """One batch read, rows (x, y, vx, vy) in pymunk's order (a view of the buffer, valid
        until the next read)."""
        self._buf.clear()
        pb.get_space_bodies(self.space, _FIELDS, self._buf)
        return np.frombuffer(self._buf.float_buf()).reshape(-1, 4)

    def read_raw(self) -> np.ndarray:
        """Rows (x, y, vx, vy) of every body of the space, in pymunk's order."""
        return self._get()

    def read(self) -> None:
        """Positions and velocities of the pool's setae into ``state.pv``."""
        np.copyto(self.state.pv, self._get()[self.order].T)

    def rows(self) -> np.ndarray:
        """(m, 4) positions and velocities of the pool's setae, in their order."""
        return self._get()[self.order]

    def write_forces(self, F=None) -> None:
        """Write the tip forces: ``F`` (2, m) in seta order, or ``self.out`` as it is."""
        if F is None:
            pass
        elif self.tip_slice is not None:
            np.copyto(self.out[self.tip_slice], F.T)
        else:
            self.out[self.order] = F.T
        pb.set_space_bodies(self.space, pb.BodyFields.FORCE, self._force_buf)

    def recentre_pads(self, x) -> None:
        """Nothing to move (the pads are lines)."""

    def step(self, dt: float) -> None:
        """The candidate flags at the positions the step evaluates forces at, then one pymunk
        step of ``dt`` [µs]."""
        s = self.state
        np.less(np.abs(s.xy[1] - self.h), self.sensor_radius, out=s.candidate)
        self.space.step(dt)


class Multirate:
    """The multirate located step of a :class:`gecko_agents.model.Model` (module docstring).

    ``n_steps`` counts the multirate steps taken, ``seta_steps`` the seta-steps of their
    near setae besides the whole array's step (their k short steps and the long one whose
    share is taken out)."""

    def __init__(self, model):
        self.m = model
        self.sub_world = SubWorld(model.world)
        self.n_steps = 0
        self.seta_steps = 0
        self._last = None  # the setae whose contact changed in the last multirate step
        self._last_time = math.nan  # and the time it ended [µs]

    def near(self, near: np.ndarray, k: int) -> np.ndarray | None:
        """The setae that take the k short steps of a located step whose ``near`` setae are
        these (bool (N,), :meth:`gecko_agents.model.event_steps.EventSteps.substeps`): they and
        the setae that attached or let go in the multirate step just before, so that an
        event's aftermath (a released tip's ringing, a jumped-in one's settling) is stepped
        short as the whole array's located steps step it (the energy books of
        ``tests/test_event_location.py``'s retraction at 5 explicit steps near events close only
        with it). None where the step is not multirate: its m setae take k + 1 steps of their
        own besides the whole array's one, fewer seta-steps than the whole array's k steps
        only while (k + 1)·m + N < k·N."""
        if self._last is not None and self.m.time == self._last_time:
            near = near | self._last
        count, n = int(np.count_nonzero(near)), near.size
        return near if 0 < count and (k + 1) * count + n < k * n else None

    def _sub(self, idx, saved, dt, k):
        """A model of setae ``idx`` alone in the pool's space, from ``saved`` (their state at
        the step's start), set for k steps of dt/k."""
        m, w = self.m, self.sub_world
        sub = copy.copy(m)
        s = sub.state = SetaState(idx.size)
        np.copyto(s.block, saved["block"])
        for name in ("attached", "slip", "candidate", "candidate_step"):
            np.copyto(getattr(s, name), saved[name])
        s.external_force = saved["ext"]
        w.load(m.mass, idx, m.world, saved["rows"], s, saved["plate"])
        sub.world = w
        sub.n = idx.size
        sub.physics = NumpyStep(sub.constants, m.law, s, w, m.K, m.params.friction)
        sub.backing = RigidBacking(m.setup, w, s, sub.physics, sub.spring_force)
        sub.lost_idx = np.zeros(idx.size, dtype=np.int64)
        sub.gone_idx = np.zeros(idx.size, dtype=np.int64)
        sub.loop_results = np.zeros(7)
        sub.on_plate_prev = saved["on_plate_prev"]
        sub.time = saved["time"]
        sub.implicit_step = m.implicit_step.for_setae(sub, saved["books"], dt / k)
        return sub

    def _gather(self, idx) -> dict:
        """The state of setae ``idx`` at the start of the step (their bodies' positions and
        velocities, ``rows``, come after the whole array's step has read them)."""
        m = self.m
        s = m.state
        return {
            "block": s.block[:, idx],
            "attached": s.attached[idx],
            "slip": s.slip[idx],
            "candidate": s.candidate[idx],
            "candidate_step": s.candidate_step[idx],
            "ext": s.external_force[idx],
            "plate": m.plate_position,
            "books": m.implicit_step.books(idx),
            "on_plate_prev": self._on_plate(idx),
            "time": m.time,
        }

    def _on_plate(self, idx) -> tuple[float, float]:
        """The pull of setae ``idx`` on the plate at the last step [µN]: their springs at the
        step's evaluation positions (:meth:`gecko_agents.model.stepping.Stepping.spring_force`)
        and their dampers, as the step summed them."""
        m = self.m
        root = m.backing.root_positions(m.plate_next)[idx]
        f = m.spring_force(m.state.xy[:, idx].T, root)[0]
        fd = m.state.F_damp_seta[:, idx]
        return float(np.sum(f[:, 0] + fd[0])), float(np.sum(f[:, 1] + fd[1]))

    def advance(self, vp, near: np.ndarray, k: int) -> list:
        """One long step of the model's dt with the ``near`` setae (bool (N,)) taking k steps
        of dt/k; leaves the model as :meth:`gecko_agents.model.stepping.Stepping.advance`
        does (reaction, work, dissipation, state) and returns the releases as (time [µs],
        plate (x, y) [µm], :meth:`gecko_agents.model.stepping.Stepping.pop_releases` list,
        step [µs]) per step they fell in."""
        m = self.m
        idx = np.flatnonzero(near)
        dt = m.dt
        saved = self._gather(idx)
        attached = m.state.attached.copy()
        m.advance(*vp)
        saved["rows"] = m.state.pv[:, idx].T.copy()  # as the step read them from pymunk
        far = [e for e in m.pop_releases() if not near[e[0]]]
        long = self._run(idx, saved, vp, dt, 1)
        short = self._run(idx, saved, vp, dt, k)
        self._scatter(idx, short["sub"], k)
        ph, imp = m.physics, m.implicit_step
        ph.diss += short["diss"] - long["diss"]
        imp.numerical_dissipated += short["numerical"] - long["numerical"]
        m.work_step += short["work"] - long["work"]
        opx, opy = m.on_plate_prev
        lx, ly = long["last"]
        sx, sy = short["last"]
        m.on_plate_prev = (opx - lx + sx, opy - ly + sy)
        m.reaction = (-m.on_plate_prev[0], -m.on_plate_prev[1])
        ph.events = []
        self.n_steps += 1
        self._last = attached != m.state.attached  # the setae that attached or let go
        self._last_time = m.time
        self.seta_steps += (k + 1) * idx.size  # the k short steps and the share taken out
        released = short["released"]
        if far:
            released.append((m.time, m.plate_position, far, dt))
        return released

    def _run(self, idx, saved, vp, dt, k) -> dict:
        """k steps of dt/k of setae ``idx`` alone from ``saved``: their summed plate work,
        dissipation and implicit books [pJ], their last pull on the plate [µN], their
        releases (global seta numbers) and the sub-model."""
        sub = self._sub(idx, saved, dt, k)
        work = diss = 0.0
        released = []
        for _ in range(k):
            sub.advance(*vp)
            work += sub.work_step
            diss += sub.physics.diss
            if sub.physics.events:
                ev = [(int(idx[i]), d, r, f) for i, d, r, f in sub.pop_releases()]
                released.append((sub.time, sub.world.plate.position, ev, sub.dt))
        if sub.warned_linear:
            self.m.warned_linear = True
        return {
            "work": work,
            "diss": diss,
            "numerical": sub.implicit_step.numerical_dissipated,
            "last": sub.on_plate_prev,
            "released": [(t, (p.x, p.y), ev, h) for t, p, ev, h in released],
            "sub": sub,
        }

    def _scatter(self, idx, sub, k) -> None:
        """The near setae's state after their short steps into the model: the state block
        (their force as the model's step reads it, F'·(dt/k)/dt), flags, bodies and the
        implicit step's per-seta books, with their last step dt/k."""
        m = self.m
        s, ss, imp, simp = m.state, sub.state, m.implicit_step, sub.implicit_step
        block = ss.block.copy()
        block[FX] /= k  # the velocity change F·dt/m the recorder reads, at the model's dt
        block[FY] /= k
        s.block[:, idx] = block
        for name in ("attached", "slip", "candidate", "candidate_step"):
            getattr(s, name)[idx] = getattr(ss, name)
        dt_prev = np.full(m.n, m.dt)
        dt_prev[idx] = sub.dt
        imp.take_books(idx, simp, dt_prev)
        w = m.world
        data = w.read_raw().copy()
        data[w.order[idx]] = sub.world.rows()
        put = pb.Buffer()
        put.set_float_buf(data.reshape(-1))
        pb.set_space_bodies(w.space, _SET, put)
