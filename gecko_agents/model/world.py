"""Everything pymunk: the space, the plate, the tips, the floor, collision events, batch I/O.

Units: µm, µN, µs, ng (:mod:`gecko_agents.params`).

* Each seta tip is a dynamic pymunk body (a point mass: the tip's rotation plays no part) with a
  **sensor** circle of radius R + |δ_detach| + margin. The backing plate is a kinematic body
  driven by velocity. pymunk integrates every body (semi-implicit Euler: positions with the old
  velocities, then velocities with the forces).
* ``on_collision(TIP, FLOOR)`` ``begin``/``separate`` callbacks keep the table of candidate
  tip–floor pairs; they fire only when a sensor starts or stops overlapping a floor segment.
  An optional ``pre_solve`` callback computes a contact per contact (the reference path).
* Forces are read and written for all bodies at once with ``pymunk.batch``.

Detection (pad floors): ``"full"`` keeps every sensor in the space, so pymunk tests every tip
against its pad every step (~90 % of a step at N = 10⁴ when every tip is pressed). ``"lazy"``
(see :meth:`World.update_sensors`) gives a tip its sensor only while the tip is within a thin
band around the sensor's edge, the only place where a begin or separate can happen; pymunk
delivers those events, and the flags of the other tips follow from where they are. The flags
after every step are the full detection's, so histories are bit-identical.

Floors: with a pad floor (correlation length 0, the paper's eq 28) seta i meets only its own
flat pad at height h_i. A pad is an infinite horizontal line for the contact law, so pymunk
only has to tell when a sensor comes within reach of it: its segment is a short window under
the tip (± sensor radius + slack + 1 µm), re-centred when the tip has slid more than the slack
(wide static pads made every sensor overlap hundreds of pad boxes in the broad phase), and
collision categories (i mod 32) keep a tip from testing its neighbours' pads. Any other floor
is a continuous polyline of segments joined with ``set_neighbors``; a tip meets the nearest
floor point.
"""

from __future__ import annotations

import math

import numpy as np
import pymunk
import pymunk.batch as pb

from gecko_agents import floor
from gecko_agents.physics import beam

__all__ = ["World", "TIP", "FLOOR", "DETECTIONS"]

TIP, FLOOR = 1, 2
DETECTIONS = ("auto", "full", "lazy")
_FIELDS_READ = pb.BodyFields.BODY_ID | pb.BodyFields.POSITION | pb.BodyFields.VELOCITY


class World:
    """The pymunk space of one model.

    Parameters
    ----------
    params : :class:`gecko_agents.params.SetaArray`. n : number of simulated setae.
    state : the :class:`gecko_agents.model.state.SetaState` whose ``candidate`` flags the collision
        events keep. mass : tip mass [ng]. reach : how far below the tip centre contact can
        still exist, R + |δ_detach| [µm]. rng : the run's Generator (draws the floor).
    floor_profile : a given floor (e.g. a measured surface) instead of one drawn from
        ``params.floor``.
    detection : ``"full"`` (every sensor in the space every step: the reference),
        ``"lazy"`` (pad floors only: a sensor only near its edge, :meth:`update_sensors`; the
        same flags on every step) or ``"auto"`` (lazy on a pad floor, else full); the one used
        is ``detection``.
    """

    band = 0.05
    """Rounding margin of lazy detection [µm] (see :meth:`update_sensors`)."""

    def __init__(
        self,
        params,
        n: int,
        state,
        mass: float,
        reach: float,
        rng: np.random.Generator,
        floor_profile: floor.Profile | None = None,
        detection: str = "full",
    ):
        if detection not in DETECTIONS:
            raise ValueError(f"detection = {detection!r} must be one of {DETECTIONS}")
        p = params
        self.state = state
        self.n = n
        self.space = space = pymunk.Space()
        space.gravity = (0.0, 0.0)
        L, theta, R = p.seta.L, p.seta.theta, p.contact.R
        rest_dx, rest_dy = (float(v) for v in beam.rest_tip_offset(L, theta))
        self.root_dx = (np.arange(n) - (n - 1) / 2.0) * p.array.pitch
        self.root_dy = np.zeros(n)
        self.rest_dx, self.rest_dy = self.root_dx + rest_dx, self.root_dy + rest_dy
        self.z_touch = float(beam.touchdown_height(L, theta, R))  # a tip touches h = 0
        touch_x = self.rest_dx.copy()
        margin = 50.0 + 3 * L
        prof = floor.for_array(p.floor, touch_x, p.array.pitch, margin, rng, measured=floor_profile)
        self.profile = prof
        self.pads = prof.pad_heights is not None
        start_gap = 0.5
        self.plate_start = float(np.max(prof.y) + self.z_touch + start_gap)
        self.plate = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        self.plate.position = (0.0, self.plate_start)
        space.add(self.plate)
        self.sensor_radius = reach + 0.5
        if detection == "lazy" and not self.pads:
            raise ValueError(
                "detection='lazy' needs a pad floor (floor.correlation_length = 0); "
                "use detection='full'"
            )
        if detection == "auto":
            detection = "lazy" if self.pads else "full"
        self.lazy = detection == "lazy"
        self.detection = detection
        self._quiet = False  # ignore the separate pymunk fires when lazy detection removes
        self.geometric_flips = 0  # flags lazy detection changed without a pymunk event
        self._build_floor(p, touch_x)
        self._build_tips(mass)
        self.pairs: set[tuple[int, int]] = set()
        self.pairs_dirty = True
        self._pre_solve_fn = None
        space.on_collision(TIP, FLOOR, begin=self._begin, separate=self._separate)
        self._read_buf = pb.Buffer()
        self._force_buf = pb.Buffer()
        self._ids_cached = None

    # ------------------------------------------------------------------ construction
    def _build_floor(self, p, touch_x):
        prof = self.profile
        if self.pads:
            self.h = np.array(prof.pad_heights, dtype=float)
            self.pad_slack = max(2.0, p.array.pitch)
            self.pad_half = self.sensor_radius + self.pad_slack + 1.0
            self.pad_centre = touch_x.copy()
            seg_a = np.column_stack([touch_x - self.pad_half, self.h])
            seg_b = np.column_stack([touch_x + self.pad_half, self.h])
        else:
            self.h = None
            seg_a = np.column_stack([prof.x[:-1], prof.y[:-1]])
            seg_b = np.column_stack([prof.x[1:], prof.y[1:]])
        self.seg_a, self.seg_b = seg_a, seg_b
        self._seg_index = {}
        self._pad_shapes = []
        space = self.space
        for i, (a, b) in enumerate(zip(seg_a, seg_b, strict=True)):
            seg = pymunk.Segment(space.static_body, tuple(a), tuple(b), 0.0)
            seg.collision_type = FLOOR
            if self.pads:
                seg.filter = pymunk.ShapeFilter(categories=1 << (i % 32), mask=1 << (i % 32))
                self._pad_shapes.append(seg)
            else:
                prev = tuple(seg_a[i - 1]) if i > 0 else tuple(a)
                nxt = tuple(seg_b[i + 1]) if i + 1 < len(seg_a) else tuple(b)
                seg.set_neighbors(prev, nxt)
            if not self.lazy:  # lazy: a pad joins the space with its tip's sensor
                space.add(seg)
            self._seg_index[seg] = i

    def _build_tips(self, mass):
        # Point masses with sensor circles; a shared group stops tip–tip detection.
        self.tips, self.sensors, self._tip_index = [], [], {}
        rest = np.column_stack([self.rest_dx, self.rest_dy])
        rest[:, 1] += self.plate_start
        for i in range(self.n):
            body = pymunk.Body(mass, math.inf)
            body.position = tuple(rest[i])
            shape = pymunk.Circle(body, self.sensor_radius)
            shape.sensor = True
            shape.collision_type = TIP
            bit = 1 << (i % 32) if self.pads else pymunk.ShapeFilter.ALL_CATEGORIES()
            shape.filter = pymunk.ShapeFilter(group=1, categories=bit, mask=bit)
            if self.lazy:
                self.space.add(body)  # sensors join while near their edge (update_sensors)
            else:
                self.space.add(body, shape)
            self.tips.append(body)
            self.sensors.append(shape)
            self._tip_index[shape] = i
        self.in_space = np.full(self.n, not self.lazy)
        self._want = np.zeros(self.n, dtype=bool)
        self._g = np.zeros(self.n)
        self._w = np.zeros(self.n)
        self._d = np.zeros(self.n)
        self._primed = False
        # Chipmunk's body order is internal: map batch rows to setae through body ids.
        ids = np.array([b.id for b in self.tips], dtype=np.uintp)
        self._id_sorted = np.sort(ids)
        self._id_to_seta = np.argsort(ids)

    # ------------------------------------------------------------------ collision events
    def _begin(self, arbiter, space, data):
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index[tip_shape], self._seg_index[seg_shape]
        if self.pads:
            if i == j:  # the paper's model: a tip meets only the height drawn for it
                self.state.candidate[i] = True
            return
        self.pairs.add((i, j))
        self.pairs_dirty = True

    def _separate(self, arbiter, space, data):
        if self._quiet:
            return
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index.get(tip_shape), self._seg_index.get(seg_shape)
        if self.pads:
            if i == j and i is not None:
                self.state.candidate[i] = False
            return
        if (i, j) in self.pairs:
            self.pairs.discard((i, j))
            self.pairs_dirty = True

    def on_pre_solve(self, fn):
        """Call ``fn(i, body)`` for every tip i touching its own pad, every step (pad floors)."""
        if not self.pads:
            raise ValueError(
                "contact='callback' (the reference path) needs a pad floor "
                "(floor.correlation_length = 0)"
            )
        if self.lazy:
            raise ValueError("contact='callback' needs detection='full' (a sensor on every tip)")
        self._pre_solve_fn = fn
        self.space.on_collision(
            TIP, FLOOR, begin=self._begin, separate=self._separate, pre_solve=self._pre_solve
        )

    def _pre_solve(self, arbiter, space, data):
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index[tip_shape], self._seg_index[seg_shape]
        if i == j:
            self._pre_solve_fn(i, tip_shape.body)

    def pair_arrays(self):
        """Candidate (tip, segment) pairs of a continuous floor, sorted by tip; and whether a
        tip has several."""
        if self.pairs_dirty:
            pairs = np.array(sorted(self.pairs), dtype=np.int64).reshape(-1, 2)
            self._pair_tip, self._pair_seg = pairs[:, 0], pairs[:, 1]
            self._pair_dup = bool(np.any(pairs[1:, 0] == pairs[:-1, 0]))
            self.pairs_dirty = False
        return self._pair_tip, self._pair_seg, self._pair_dup

    def recentre_pads(self, x):
        """Move the window of every pad whose tip (abscissae ``x``) slid more than the slack
        from it. Changing a static segment's end points keeps its arbiters (no events)."""
        far = np.flatnonzero(np.abs(x - self.pad_centre) > self.pad_slack)
        half = self.pad_half
        for i in far:
            seg, c, h = self._pad_shapes[i], float(x[i]), float(self.h[i])
            seg.unsafe_set_endpoints((c - half, h), (c + half, h))
            if not self.lazy or self.in_space[i]:
                self.space.reindex_shape(seg)
            self.pad_centre[i] = c

    # ------------------------------------------------------------------ batch I/O
    def read_raw(self) -> np.ndarray:
        """One batch read: rows (x, y, vx, vy) of every body in Chipmunk's order."""
        buf = self._read_buf
        buf.clear()
        pb.get_space_bodies(self.space, _FIELDS_READ, buf)
        ids = np.frombuffer(buf.int_buf(), dtype=np.uintp)
        self._check_rows(ids)
        return np.frombuffer(buf.float_buf()).reshape(len(ids), 4)

    def read(self) -> None:
        """Positions and velocities of all tips into ``state.pv``, in seta order."""
        data = self.read_raw()
        if self.tip_slice is not None:
            np.copyto(self.state.pv, data[self.tip_slice].T)
        else:
            np.copyto(self.state.pv, data[self.order].T)

    def _check_rows(self, ids):
        """Chipmunk's body order is internal and changes only when bodies are added or removed
        (the model adds none after construction): remap when the count or an end differs."""
        c = self._ids_cached
        if (
            c is None
            or ids.size != c.size
            or ids[0] != c[0]
            or ids[-1] != c[-1]
            or ids[ids.size // 2] != c[c.size // 2]
        ):
            if c is None or not np.array_equal(ids, c):
                self._map_rows(ids)

    def _map_rows(self, ids):
        """Batch row of every seta, from the body ids."""
        where = np.searchsorted(self._id_sorted, ids)
        ok = (where < self.n) & (self._id_sorted[np.minimum(where, self.n - 1)] == ids)
        rows = np.flatnonzero(ok)
        seta = self._id_to_seta[where[rows]]
        order = np.empty(self.n, dtype=np.int64)
        order[seta] = rows  # batch row of each seta
        self._ids_cached, self.order = ids.copy(), order
        first = int(order[0])
        contiguous = bool(np.array_equal(order, np.arange(first, first + self.n)))
        self.tip_slice = slice(first, first + self.n) if contiguous else None
        # Forces in Chipmunk's body order; rows that are not tips stay zero.
        self.out = np.zeros((ids.size, 2))
        self._force_buf.set_float_buf(self.out.reshape(-1))

    def write_forces(self, F=None) -> None:
        """Write the tip forces: ``F`` (2, N) in seta order, or ``self.out`` as it is."""
        if F is not None:
            if self.tip_slice is not None:
                np.copyto(self.out[self.tip_slice], F.T)
            else:
                self.out[self.order] = F.T
        pb.set_space_bodies(self.space, pb.BodyFields.FORCE, self._force_buf)

    def step(self, dt: float) -> None:
        """One pymunk step of ``dt`` [µs] (lazy detection: :meth:`update_sensors` first)."""
        if self.lazy:
            self.update_sensors(dt)
        self.space.step(dt)

    def update_sensors(self, dt: float) -> None:
        """Lazy detection: before a step of ``dt`` [µs], give sensors to the tips near the
        sensor's edge, take them from the others and set the others' flags.

        Reads ``state.xy`` (2, N) [µm], the positions x + v·dt that pymunk integrates the tips
        to and detects collisions at (the model's step leaves them there), and ``state.pv``.

        Why the flags equal full detection's. A sensor of radius r_s overlaps its pad, a
        horizontal window at height h reaching more than r_s beyond the tip on both sides
        (:meth:`recentre_pads`), exactly when the gap g = |y − h| < r_s: pymunk finds the
        window's closest point (x, h) and tests distance² < r_s². Tip i keeps a sensor this
        step iff |g − r_s| ≤ m_i = ``band`` + 2·|v_y|·dt. Those tips are tested by pymunk as
        under full detection. The others are at least m_i ≥ ``band`` = 0.05 µm from the edge,
        ~10¹⁰ times the rounding of g and of pymunk's distance (µm-sized numbers, relative
        precision 1e-16), so their overlap is decided by the sign of g − r_s and set here:
        True inside (g < r_s − m_i), False outside. A tip whose sensor joins this step starts
        False, so only a begin from pymunk in this step makes it True; a sensor leaving the
        space fires a separate, which is ignored (the flag is set from g as for any tip
        without a sensor). Hence after every step ``state.candidate`` is the overlap of every
        sensor with its pad at the step's positions, as full detection gives it.

        Why pymunk still delivers the events. A flag changes only when g crosses r_s. The
        band's 2·|v_y|·dt term holds a tip moving at up to twice its current vertical speed
        in the band on the step it crosses, so the crossing is seen by pymunk's callbacks;
        a tip that jumps across the whole band in one step is still set right, and is counted
        in ``geometric_flips`` (0 in the tests and benchmarks: see ``tests/test_world.py``).
        """
        s, r_s = self.state, self.sensor_radius
        g, m, want = self._g, self._w, self._want
        np.subtract(s.xy[1], self.h, out=g)
        np.abs(g, out=g)
        np.abs(s.pv[3], out=m)
        m *= 2.0 * dt
        m += self.band
        d = self._d
        np.subtract(g, r_s, out=d)
        inside = d < 0.0
        np.abs(d, out=d)
        np.less_equal(d, m, out=want)
        cand, have = s.candidate, self.in_space
        if not np.array_equal(want, have):
            space, sensors, pads = self.space, self.sensors, self._pad_shapes
            leave = np.flatnonzero(have & ~want)
            join = np.flatnonzero(want & ~have)
            if leave.size:
                self._quiet = True
                try:
                    space.remove(*(sensors[i] for i in leave))
                    space.remove(*(pads[i] for i in leave))
                finally:
                    self._quiet = False
            if join.size:
                cand[join] = False  # a begin in this step makes it True
                space.add(*(pads[i] for i in join))
                space.add(*(sensors[i] for i in join))
            np.copyto(have, want)
        free = ~want
        if self._primed:  # the first step sets the flags pymunk's first begins would
            self.geometric_flips += int(np.count_nonzero((cand != inside) & free))
        self._primed = True
        np.copyto(cand, inside, where=free)

    def skip_free_travel(self, vp, omega: float, dt: float, target=None) -> float:
        """Move plate and tips rigidly along the plate velocity ``vp`` [µm/µs] while nothing
        can touch; returns the travel [µm] (0 if nothing was moved).

        Only when every tip rests relative to the plate: deflection below 1e-3 of the lag
        v/ω of a seta dragged at the plate speed (ω [rad/µs] its slowest free frequency),
        relative velocity below 1e-3 of the plate speed (a free seta then just follows the
        plate, wherever it is). The plate stops where the first sensor circle would reach the
        floor, and a few steps (of ``dt`` [µs]) before ``target`` (x, y) [µm] if given.
        """
        vx, vy = vp
        speed = math.hypot(vx, vy)
        if speed == 0.0:
            return 0.0
        self.read()
        px, py, tvx, tvy = self.state.pv
        pp = self.plate.position
        tol_u, tol_v = 1e-3 * speed / omega, 1e-3 * speed
        if (
            np.abs(px - pp.x - self.rest_dx).max() > tol_u
            or np.abs(py - pp.y - self.rest_dy).max() > tol_u
            or np.abs(tvx - vx).max() > tol_v
            or np.abs(tvy - vy).max() > tol_v
        ):
            return 0.0
        reach = self.sensor_radius + 2.0 * speed * dt
        if self.pads:
            gap = float(np.min(py - self.h)) - reach
        else:
            gap = float(np.min(py)) - self.floor_top() - reach
        travel = math.inf if vy >= 0 else gap * speed / -vy
        if target is not None:
            travel = min(travel, math.hypot(target[0] - pp.x, target[1] - pp.y) - 3.0 * speed * dt)
        if not travel > 20.0 * speed * dt:
            return 0.0
        self.translate(vx / speed * travel, vy / speed * travel, px, py)
        return travel

    def translate(self, sx: float, sy: float, px, py) -> None:
        """Move the plate by (sx, sy) [µm] and put the tips at (px + sx, py + sy)."""
        pp = self.plate.position
        self.plate.position = (pp.x + sx, pp.y + sy)
        for body, x, y in zip(self.tips, px.tolist(), py.tolist(), strict=True):
            body.position = (x + sx, y + sy)

    def floor_top(self) -> float:
        """Highest floor point [µm]."""
        return float(np.max(self.profile.y))
