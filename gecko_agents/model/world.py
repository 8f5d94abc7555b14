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
against its pad every step (~90 % of a step at N = 10⁴ when every tip is pressed). ``"lazy"`` (see
:meth:`gecko_agents.model.sensors.LazySensors.update`) gives a tip its sensor only while the tip is
within a thin band around the sensor's edge, the only place where a begin or separate can happen;
pymunk delivers those events, and the flags of the other tips follow from where they are. The flags
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
from gecko_agents.model.sensors import LazySensors
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
        ``"lazy"`` (pad floors only: a sensor only near its edge,
        :class:`gecko_agents.model.sensors.LazySensors`; the same flags on every step) or
        ``"auto"`` (lazy on a pad floor, else full); the one used is ``detection``.
    """

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
                self.space.add(body)  # sensors join while near their edge (LazySensors)
            else:
                self.space.add(body, shape)
            self.tips.append(body)
            self.sensors.append(shape)
            self._tip_index[shape] = i
        self.lazy_sensors = None  # the lazy detection's sensors (LazySensors)
        self.in_space = np.full(self.n, True)  # the tips whose sensors are in the space
        if self.lazy:
            self.lazy_sensors = LazySensors(
                self.state, self.h, self.sensor_radius, self.space, self.sensors, self._pad_shapes
            )
            self.in_space = self.lazy_sensors.in_space
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
        if self.lazy_sensors is not None and self.lazy_sensors.removing:
            return  # lazy detection took the sensor out: not a separation
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
        """One pymunk step of ``dt`` [µs] (lazy detection:
        :meth:`gecko_agents.model.sensors.LazySensors.update` first)."""
        if self.lazy:
            self.lazy_sensors.update(dt)
        self.space.step(dt)

    @property
    def geometric_flips(self) -> int:
        """Flags lazy detection changed without a pymunk event (0 with full detection)."""
        return 0 if self.lazy_sensors is None else self.lazy_sensors.geometric_flips

    def floor_top(self) -> float:
        """Highest floor point [µm]."""
        return float(np.max(self.profile.y))
