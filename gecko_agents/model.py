"""The time-stepped agent model: setae on a moving plate over a rough floor, in pymunk.

Units: µm, µN, µs, ng (see :mod:`gecko_agents.params`); a seta's mass is then O(0.1–1).

What pymunk does and what we do
-------------------------------
* Each seta tip is a dynamic pymunk body (a point mass: the tip's rotation plays no part) with a
  **sensor** circle of radius R + |δc| + margin. The floor is a set of static segments. The
  backing plate is a kinematic body driven by velocity. pymunk integrates every body
  (semi-implicit Euler: positions with the old velocities, then velocities with the forces).
* ``on_collision(TIP, FLOOR)`` ``begin``/``separate`` callbacks keep the table of candidate
  tip–segment pairs; they fire only when a sensor starts or stops overlapping a segment.
* Every step, all forces are computed at once at the positions pymunk is about to integrate
  velocities with (x + v·dt), and written back with one ``pymunk.batch`` call:
  the seta spring (``linear``: −K·(x − x_rest) with the 2×2 stiffness of eq 20–21;
  ``rod``: a rigid rod pivoting at its root on a rotary spring Kp·L² with an axial spring Ka),
  damping relative to the plate, and the contact (JKR normal force from
  :func:`jkr.force_from_overlap`, a stick spring with a Coulomb cap tangentially).
* ``contact="callback"`` computes the contact force instead in a per-contact ``pre_solve``
  callback (pad floors only): the slow reference the fast path is tested against.

Contact state machine per tip: free → attached when the overlap δ ≥ 0 (jump-in; no long-range
force), attached → free when δ < δc (the end of the JKR branch). A soft seta leaves its
equilibrium earlier (at the fold of the spring–contact system, see :mod:`quasistatic`) and then
runs to δc by itself; the overlap where its tip started to jump away is recorded as
``release_overlap_um``.

Floors: with correlation length 0 each seta has its own flat pad at its own height and its tip
meets only that pad (the paper's model, eq 28); otherwise the floor is a continuous polyline
(segments joined with ``set_neighbors``) and each tip meets the nearest floor point.

Performance
-----------
* A pad is an infinite horizontal line for the contact law, so pymunk only has to tell when a
  sensor comes within reach of it. Its pymunk segment is a short window under the tip
  (± sensor radius + a few µm) that is re-centred under the tip whenever the tip has slid a
  few µm: wide static pads (a soft seta can slide hundreds of µm) made every sensor overlap
  hundreds of pad boxes in pymunk's broad phase, which cost more than everything else.
* Per-seta state lives in one preallocated ``(rows, N)`` float block (positions, velocities,
  forces, anchors, contact radius, …) so the hot path allocates little and works on contiguous
  rows. Pad floors take a special path (the normal is vertical, every tip has its own pad) that
  works on the whole array when every tip is attached and gathers the attached ones otherwise.
* Stored energies (spring, contact) are computed only when a row is recorded; the step keeps
  the contact radius and stick stretch of each attached tip, from which the energy a snap-off
  dissipates is evaluated when it happens. Dissipation and plate work are accumulated every
  step.
* ``kernel="numba"`` (default when numba is installed, pad floors and the batch path) runs the
  whole per-seta update of a step in one compiled loop; the numpy path is the fallback and both
  give the same history to rounding.
* :meth:`Model.run` skips the free approach: while no tip is attached and every tip follows the
  plate at rest relative to it (a free seta's dynamics do not depend on where it is), the plate
  and tips are moved rigidly up to where the first sensor would reach the floor.
"""

from __future__ import annotations

import dataclasses
import math
import time
import warnings
from dataclasses import dataclass

import numpy as np
import pymunk
import pymunk.batch as pb

from . import beam, floor, jkr
from .history import (
    PER_SETA_FIELDS,
    SCALAR_COLUMNS,
    STATE_FREE,
    STATE_SLIP,
    STATE_STICK,
    History,
    versions,
)
from .params import SetaArray
from .protocol import DEFAULT_SPEED, Hold, Move, Press, PressTo, PullOff

__all__ = ["Damping", "Model", "SimulationUnstable", "numba_available", "seta_mass",
           "tangential_stiffness"]

TIP, FLOOR = 1, 2
_FIELDS_READ = pb.BodyFields.BODY_ID | pb.BodyFields.POSITION | pb.BodyFields.VELOCITY
KERNELS = ("auto", "numpy", "numba", "python")
_PYTHON_MAX_N = 6   # below this many setae the interpreted kernel beats numpy's call overhead

# Rows of the per-seta state block Model._S (shape (_NROWS, N)).
(_PX, _PY, _VX, _VY, _X, _Y, _FX, _FY, _DMPX, _DMPY, _AX, _AY, _AC, _XI, _P, _FT, _DELTA,
 _JUMP, _UX, _UY, _FDX, _FDY) = range(22)
_NROWS = 22
# Entries of the numba kernel's parameter vector.
(_K_DT, _K_PNX, _K_PNY, _K_VPX, _K_VPY, _K_ROD, _K_K00, _K_K01, _K_K10, _K_K11, _K_L, _K_KA,
 _K_KPHI, _K_THETA, _K_CS, _K_R, _K_DC, _K_CN, _K_CT, _K_KT, _K_MU, _K_LAW, _K_FC, _K_AC,
 _K_VREF, _K_EXT, _K_HM, _K_W, _K_ES) = range(29)


class SimulationUnstable(RuntimeError):
    """The run blew up (non-finite state or runaway kinetic energy)."""


@dataclass(frozen=True)
class Damping:
    """Damping ratios [-] (fractions of critical damping c = 2ζ√(k·m)).

    seta : isotropic damping of the tip relative to the plate, on the seta's softest
        stiffness Ky; 1 = critical, so a free seta follows the plate without ringing and a
        tip moving with the plate feels none.
    normal : on the normal contact velocity, on the contact stiffness at zero load 2E*a0.
    tangential : on the tangential velocity of a sticking tip, on the stick stiffness.
    """

    seta: float = 1.0
    normal: float = 0.1
    tangential: float = 0.5

    def __post_init__(self):
        for name in ("seta", "normal", "tangential"):
            v = getattr(self, name)
            if not (math.isfinite(v) and v >= 0):
                raise ValueError(f"Damping.{name} = {v!r} must be finite and ≥ 0")


def seta_mass(params: SetaArray) -> float:
    """Tip point mass [ng]: the sphere plus the cantilever rod's effective share 33/140.

    33/140 is Rayleigh's effective mass of a cantilever loaded at its tip (Timoshenko, Vibration
    Problems in Engineering, §1.10): the rod's kinetic energy when it swings in its first mode.
    """
    rho, R = params.seta.density, params.contact.R
    rod = math.pi * params.seta.r**2 * params.seta.L * rho
    return 4.0 / 3.0 * math.pi * R**3 * rho + 33.0 / 140.0 * rod


def tangential_stiffness(params: SetaArray) -> float:
    """Stick-spring stiffness of the contact k_t = 8G*·a0 [µN/µm] (Mindlin 1949).

    G* = ((2−ν1)/G1 + (2−ν2)/G2)⁻¹, G = E/(2(1+ν)), at the zero-load JKR radius a0.
    """
    c = params.contact
    G1, G2 = c.E1 / (2 * (1 + c.nu1)), c.E2 / (2 * (1 + c.nu2))
    G_star = 1.0 / ((2 - c.nu1) / G1 + (2 - c.nu2) / G2)
    return 8.0 * G_star * float(jkr.zero_load_contact_radius(*c.jkr_args()))


def numba_available() -> bool:
    """Whether the optional numba kernel can be used (``pip install gecko_agents[fast]``)."""
    return _numba_kernel() is not None


class Model:
    """A pymunk world of ``n_sim`` setae on a kinematic plate above a Gaussian rough floor.

    Parameters
    ----------
    params : the array. ``params.array.count`` is the physical array; the model simulates
        ``n_sim`` setae of it (default: all of them, refused above 20 000) in one row at
        ``params.array.pitch`` and reports ``scale = count / n_sim`` in the metadata.
    seed : seed of the run's single ``numpy.random.Generator`` (default ``params.floor.seed``).
    dt : time step [µs]; default 0.75/ω_max from the stiffest spring and the tip mass. A dt at
        or above the stability bound 2/ω_max is refused.
    contact : ``"batch"`` (fast, default) or ``"callback"`` (per-contact reference path).
    damping : :class:`Damping` ratios.
    record_every : record every this many steps (default: every 0.02 µm of plate travel at the
        default speed, about 20 steps).
    record_setae : also record per-seta arrays (needed for animations).
    verbose : print the chosen time step.
    kernel : how a pad-floor step with the batch contact path is computed: ``"numba"`` (one
        compiled loop; needs numba, ``pip install 'gecko_agents[fast]'``), ``"numpy"``
        (vectorized) or ``"python"`` (the numba loop run by the interpreter: fastest without
        numba for a handful of setae). ``"auto"`` (default): numba if installed, else python
        up to 6 setae and numpy above; other floors and paths always use numpy. All give the
        same history to rounding; the one used is ``meta["kernel"]`` of the history.
    """

    def __init__(self, params: SetaArray, *, n_sim: int | None = None, seed: int | None = None,
                 dt: float | None = None, contact: str = "batch",
                 damping: Damping = Damping(), record_every: int | None = None,
                 record_setae: bool = False, verbose: bool = False, kernel: str = "auto"):
        if not isinstance(params, SetaArray):
            raise TypeError(f"params must be a SetaArray, got {type(params).__name__}")
        n = params.array.count if n_sim is None else n_sim
        if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= 20_000:
            raise ValueError(f"n_sim = {n!r} must be an integer in [1, 20000]; simulate a patch "
                             "of a large array with n_sim (the quasi-static solver does 10⁷)")
        if contact not in ("batch", "callback"):
            raise ValueError(f"contact = {contact!r} must be 'batch' or 'callback'")
        if record_every is not None and (not isinstance(record_every, int) or record_every < 1):
            raise ValueError(f"record_every = {record_every!r} must be an integer ≥ 1")
        if kernel not in KERNELS:
            raise ValueError(f"kernel = {kernel!r} must be one of {KERNELS}")
        self.params, self.n, self.contact_path = params, int(n), contact
        self.seed = params.floor.seed if seed is None else int(seed)
        self.rng = np.random.default_rng(self.seed)
        self.damping = damping
        self.record_setae = record_setae
        c, s = params.contact, params.seta
        self.R, self.w, self.E_star = c.jkr_args()
        self.Fc = c.pull_off_force
        self.delta_c = c.snap_off_overlap
        self.L, self.theta = s.L, s.theta
        self.axis = np.array([math.cos(self.theta), -math.sin(self.theta)])
        self.Ka, self.Kp = params.axial_stiffness, params.bending_stiffness
        self.K = beam.stiffness_matrix(self.Ka, self.Kp, self.theta)
        self.k_phi = self.Kp * self.L**2
        self.mass = seta_mass(params)
        self.k_t = tangential_stiffness(params)
        # Slowest period of a free seta (normal mode, eq 20): the force servo averages over it.
        self.settle_time = 2 * math.pi * math.sqrt(self.mass / params.Ky)
        a0 = float(jkr.zero_load_contact_radius(self.R, self.w, self.E_star))
        self.c_seta = 2 * damping.seta * math.sqrt(params.Ky * self.mass)
        self.c_n = 2 * damping.normal * math.sqrt(2 * self.E_star * a0 * self.mass)
        self.c_t = 2 * damping.tangential * math.sqrt(self.k_t * self.mass)
        # Stiffest spring a tip can meet: seta (Ka) + contact at 5 Fc of compression + stick.
        a_ref = float(jkr.contact_radius_from_force(5 * self.Fc, self.R, self.w, self.E_star))
        self.k_max = self.Ka + 2 * self.E_star * a_ref + self.k_t
        self.omega_max = math.sqrt(self.k_max / self.mass)
        bound = 2.0 / self.omega_max
        if dt is None:
            dt = 0.75 / self.omega_max
        elif not (isinstance(dt, int | float) and math.isfinite(dt) and 0 < dt < bound):
            raise ValueError(f"dt = {dt!r} µs is outside the stable range (0, {bound:.4g}) µs: "
                             f"the stiffest spring ({self.k_max:.3g} µN/µm) on a tip of "
                             f"{self.mass:.3g} ng needs ω·dt < 2")
        self.dt = float(dt)
        if verbose:
            print(f"gecko_agents: dt = {self.dt:.4g} µs (ω_max·dt = {self.omega_max * dt:.2f}; "
                  f"stable below {bound:.4g} µs)")
        self.record_every = record_every or max(1, round(0.02 / DEFAULT_SPEED / self.dt))
        # JKR constants of the hot path (the same formulas as jkr.radius_from_overlap etc.).
        self._ac = float(jkr.snap_off_radius(self.R, self.w, self.E_star))
        self._a_jump = float(np.cbrt((math.sqrt(2 * math.pi * self.w / self.E_star)
                                      * self.R) ** 2))   # U(a_jump) = 0: δ = 0
        self._build_world()
        self._fast_pads = self.pads and contact == "batch"
        if kernel in ("numba", "python") and not self._fast_pads:
            raise ValueError(f"kernel={kernel!r} covers pad floors "
                             "(floor.correlation_length = 0) with contact='batch'")
        if kernel == "auto":
            kernel = "numpy"
            if self._fast_pads:
                kernel = ("numba" if _numba_kernel() is not None
                          else "python" if self.n <= _PYTHON_MAX_N else "numpy")
        self._kernel = None
        if kernel == "numba":
            self._kernel = _numba_kernel()
            if self._kernel is None:
                raise ValueError("kernel='numba' needs numba (pip install "
                                 "'gecko_agents[fast]'); use kernel='numpy'")
        elif kernel == "python":
            self._kernel = _pads_kernel
        self.kernel = kernel

    # ------------------------------------------------------------------ construction
    def _build_world(self):
        p, n = self.params, self.n
        self.space = space = pymunk.Space()
        space.gravity = (0.0, 0.0)
        self.root_dx = (np.arange(n) - (n - 1) / 2.0) * p.array.pitch
        self.root_dy = np.zeros(n)
        self.z_touch = self.R + self.L * math.sin(self.theta)   # plate height: tip on h = 0
        touch_x = self.root_dx + self.L * math.cos(self.theta)
        margin = 50.0 + 3 * self.L
        prof = floor.for_array(p.floor, touch_x, p.array.pitch, margin, self.rng)
        self.profile = prof
        self.pads = prof.pad_heights is not None
        start_gap = 0.5
        self.plate_start = float(np.max(prof.y) + self.z_touch + start_gap)
        self.plate = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        self.plate.position = (0.0, self.plate_start)
        space.add(self.plate)
        self.sensor_radius = self.R + abs(self.delta_c) + 0.5
        # Floor segments. Pads: seta i meets a flat floor at its own height h_i (the paper's
        # model treats it as a plane), so pymunk only needs a window of it under the tip:
        # ± (sensor radius + slack + 1 µm) around a centre that is moved under the tip
        # whenever the tip is more than `slack` from it (_recentre_pads). Collision
        # categories (i mod 32) keep a tip from testing its neighbours' pads.
        # Continuous profile: one segment per polyline edge, joined with set_neighbors.
        if self.pads:
            self._h = np.array(prof.pad_heights, dtype=float)
            self._pad_slack = max(2.0, p.array.pitch)
            self._pad_half = self.sensor_radius + self._pad_slack + 1.0
            self._pad_c = touch_x.copy()
            seg_a = np.column_stack([touch_x - self._pad_half, self._h])
            seg_b = np.column_stack([touch_x + self._pad_half, self._h])
        else:
            seg_a = np.column_stack([prof.x[:-1], prof.y[:-1]])
            seg_b = np.column_stack([prof.x[1:], prof.y[1:]])
        self.seg_a, self.seg_b = seg_a, seg_b
        self._seg_index = {}
        self._pad_shapes = []
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
            space.add(seg)
            self._seg_index[seg] = i
        # Tips: point masses with sensor circles; a shared group stops tip–tip detection.
        self.tips, self._tip_index = [], {}
        rest = np.column_stack([self.root_dx, self.root_dy]) + self.L * self.axis
        rest[:, 1] += self.plate_start
        for i in range(n):
            body = pymunk.Body(self.mass, math.inf)
            body.position = tuple(rest[i])
            shape = pymunk.Circle(body, self.sensor_radius)
            shape.sensor = True
            shape.collision_type = TIP
            bit = 1 << (i % 32) if self.pads else pymunk.ShapeFilter.ALL_CATEGORIES()
            shape.filter = pymunk.ShapeFilter(group=1, categories=bit, mask=bit)
            space.add(body, shape)
            self.tips.append(body)
            self._tip_index[shape] = i
        # Chipmunk's body order is internal: map batch rows to setae through body ids.
        ids = np.array([b.id for b in self.tips], dtype=np.uintp)
        self._id_sorted = np.sort(ids)
        self._id_to_seta = np.argsort(ids)
        # Candidate tip–floor pairs: a flag per tip for pads (a tip meets only its own pad),
        # a set of (tip, segment) pairs for a continuous floor.
        self._cand = np.zeros(n, dtype=bool)
        self._pairs: set[tuple[int, int]] = set()
        self._pairs_dirty = True
        space.on_collision(TIP, FLOOR, begin=self._begin, separate=self._separate,
                           pre_solve=self._pre_solve if self.contact_path == "callback" else None)
        if self.contact_path == "callback" and not self.pads:
            raise ValueError("contact='callback' (the reference path) needs a pad floor "
                             "(floor.correlation_length = 0)")
        self._read_buf = pb.Buffer()
        self._ids_cached = None
        self._force_buf = pb.Buffer()
        # Per-seta state and per-step buffers: one block, one row per quantity (see _S rows).
        self._S = S = np.zeros((_NROWS, n))
        self._pv, self._xy, self._F = S[_PX:_VY + 1], S[_X:_Y + 1], S[_FX:_FY + 1]
        self._Fdmp, self._anchor = S[_DMPX:_DMPY + 1], S[_AX:_AY + 1]
        self._Fd, self._u = S[_FDX:_FDY + 1], S[_UX:_UY + 1]
        self._P, self._Ft, self._delta = S[_P], S[_FT], S[_DELTA]
        self._a_c, self._xi_c = S[_AC], S[_XI]
        self.jump_overlap = S[_JUMP]
        self.jump_overlap[:] = np.nan
        self._delta[:] = np.nan
        self._a_c[:] = self._a_jump
        self._tmp = np.zeros((6, n))
        self.attached = np.zeros(n, dtype=bool)
        self._slip = np.zeros(n, dtype=bool)
        self._cand_step = np.zeros(n, dtype=bool)
        self._lost_idx = np.zeros(n, dtype=np.int64)
        self._gone_idx = np.zeros(n, dtype=np.int64)
        self._res = np.zeros(8)
        self._prm = np.zeros(29)
        self.time = 0.0
        self._warned_linear = False
        self.external_force = np.zeros((n, 2))  # extra force on each tip [µN] (probing/tests)
        self._root_offset = np.column_stack([self.root_dx, self.root_dy])
        self._rest_dx = self.root_dx + self.L * self.axis[0]
        self._rest_dy = self.root_dy + self.L * self.axis[1]
        self._root = np.vstack([self.root_dx, self.root_dy])
        self._rest = np.vstack([self._rest_dx, self._rest_dy])
        self._pnext = (0.0, self.plate_start)
        self._reaction = (0.0, 0.0)
        self._work_step = self._diss_step = 0.0
        self._events = []
        self._any_contact_damping = False
        self.reset_state_arrays()

    # ------------------------------------------------------------------ callbacks
    def _begin(self, arbiter, space, data):
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index[tip_shape], self._seg_index[seg_shape]
        if self.pads:
            if i == j:   # the paper's model: a tip meets only the height drawn for it
                self._cand[i] = True
            return
        self._pairs.add((i, j))
        self._pairs_dirty = True

    def _separate(self, arbiter, space, data):
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index.get(tip_shape), self._seg_index.get(seg_shape)
        if self.pads:
            if i == j and i is not None:
                self._cand[i] = False
            return
        if (i, j) in self._pairs:
            self._pairs.discard((i, j))
            self._pairs_dirty = True

    def _pre_solve(self, arbiter, space, data):
        """Reference path: the contact force of one tip, computed and applied per contact."""
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index[tip_shape], self._seg_index[seg_shape]
        if i != j:
            return
        body = tip_shape.body
        pos = body.position
        fx, fy = self._contact(np.array([i]), np.array([pos.x]), np.array([pos.y]),
                               self._pv[2, i:i + 1], self._pv[3, i:i + 1], np.array([j]))
        body.force = (body.force.x + float(fx[0]), body.force.y + float(fy[0]))

    def _recentre_pads(self):
        """Move the pymunk window of every pad whose tip slid more than the slack from it.

        Changing a static segment's end points keeps its arbiters (no begin/separate)."""
        x = self._xy[0]
        far = np.flatnonzero(np.abs(x - self._pad_c) > self._pad_slack)
        half = self._pad_half
        for i in far:
            seg, c, h = self._pad_shapes[i], float(x[i]), float(self._h[i])
            seg.unsafe_set_endpoints((c - half, h), (c + half, h))
            self.space.reindex_shape(seg)
            self._pad_c[i] = c

    # ------------------------------------------------------------------ physics
    def _read(self):
        """Positions and velocities of all tips into ``self._pv`` (rows x, y, vx, vy), in seta
        order, from one batch call."""
        buf = self._read_buf
        buf.clear()
        pb.get_space_bodies(self.space, _FIELDS_READ, buf)
        ids = np.frombuffer(buf.int_buf(), dtype=np.uintp)
        data = np.frombuffer(buf.float_buf()).reshape(len(ids), 4)
        self._check_rows(ids)
        if self._tip_slice is not None:
            np.copyto(self._pv, data[self._tip_slice].T)
        else:
            np.copyto(self._pv, data[self._order].T)
        return data

    def _check_rows(self, ids):
        """Chipmunk's body order is internal and changes only when bodies are added or removed
        (the model adds none after construction): remap when the count or an end differs."""
        c = self._ids_cached
        if (c is None or ids.size != c.size or ids[0] != c[0] or ids[-1] != c[-1]
                or ids[ids.size // 2] != c[c.size // 2]):
            if c is None or not np.array_equal(ids, c):
                self._map_rows(ids)

    def _map_rows(self, ids):
        """Batch row of every seta, from the body ids."""
        where = np.searchsorted(self._id_sorted, ids)
        ok = (where < self.n) & (self._id_sorted[np.minimum(where, self.n - 1)] == ids)
        rows = np.flatnonzero(ok)
        seta = self._id_to_seta[where[rows]]
        order = np.empty(self.n, dtype=np.int64)
        order[seta] = rows                      # batch row of each seta
        self._ids_cached, self._order = ids.copy(), order
        first = int(order[0])
        contiguous = bool(np.array_equal(order, np.arange(first, first + self.n)))
        self._tip_slice = slice(first, first + self.n) if contiguous else None
        # Forces in Chipmunk's body order; rows that are not tips stay zero.
        self._out = np.zeros((ids.size, 2))
        self._force_buf.set_float_buf(self._out.reshape(-1))

    def _write_forces(self):
        if self._tip_slice is not None:
            np.copyto(self._out[self._tip_slice], self._F.T)
        else:
            self._out[self._order] = self._F.T
        pb.set_space_bodies(self.space, pb.BodyFields.FORCE, self._force_buf)

    @property
    def _vel_now(self):
        """Tip velocities (N, 2) at the start of the last step [µm/µs]."""
        return np.column_stack([self._pv[2], self._pv[3]])

    def spring_force(self, x, root):
        """Seta spring force on the tips [µN], elastic energies [pJ] and (linear) deflections.

        Parameters
        ----------
        x : tip positions (N, 2) [µm]. root : root positions (N, 2) [µm].
        """
        d = x - root
        if self.params.mechanics == "linear":
            u = d - self.L * self.axis
            K = self.K                  # F = −K·u, written out (no BLAS call per record)
            F = np.column_stack([-(u[:, 0] * K[0, 0] + u[:, 1] * K[0, 1]),
                                 -(u[:, 0] * K[1, 0] + u[:, 1] * K[1, 1])])
            energy = -0.5 * (u[:, 0] * F[:, 0] + u[:, 1] * F[:, 1])
            return F, energy, u
        ell = np.hypot(d[:, 0], d[:, 1])
        e = d / ell[:, None]
        dphi = np.arctan2(d[:, 1], d[:, 0]) + self.theta
        dphi = (dphi + math.pi) % (2 * math.pi) - math.pi
        e_perp = np.column_stack([-e[:, 1], e[:, 0]])
        F = (-self.Ka * (ell - self.L))[:, None] * e - (self.k_phi * dphi / ell)[:, None] * e_perp
        energy = 0.5 * self.Ka * (ell - self.L) ** 2 + 0.5 * self.k_phi * dphi**2
        return F, energy, None

    def _spring_energy(self):
        """Elastic energy of every seta [pJ] at the last step's evaluation positions."""
        root = np.asarray(self._pnext) + self._root_offset
        return self.spring_force(self._xy.T, root)[1]

    def _spring_damp(self, pnx, pny, vpx, vpy):
        """Seta spring + damping into ``self._F`` (rows fx, fy); returns their sums."""
        x, y = self._xy
        Fx, Fy = self._F
        t0, t1 = self._tmp[0], self._tmp[1]
        if self.params.mechanics == "linear":
            ux, uy = self._u
            np.subtract(x, pnx, out=ux)
            ux -= self._rest_dx
            np.subtract(y, pny, out=uy)
            uy -= self._rest_dy
            K = self.K
            np.multiply(ux, -K[0, 0], out=Fx)
            np.multiply(uy, -K[0, 1], out=t0)
            Fx += t0
            np.multiply(ux, -K[1, 0], out=Fy)
            np.multiply(uy, -K[1, 1], out=t0)
            Fy += t0
            if not self._warned_linear:
                np.multiply(ux, ux, out=t0)
                np.multiply(uy, uy, out=t1)
                t0 += t1
                self._check_linear(float(t0.max()))
        else:
            dx, dy = self._u
            np.subtract(x, pnx, out=dx)
            dx -= self.root_dx
            np.subtract(y, pny, out=dy)
            dy -= self.root_dy
            ell, dphi, t2 = self._tmp[2], self._tmp[3], self._tmp[4]
            np.multiply(dx, dx, out=ell)
            np.multiply(dy, dy, out=t0)
            ell += t0
            np.sqrt(ell, out=ell)
            np.arctan2(dy, dx, out=dphi)
            dphi += self.theta + math.pi
            np.remainder(dphi, 2 * math.pi, out=dphi)
            dphi -= math.pi
            # F = −Ka(ℓ − L)·e − (kφ·Δφ/ℓ)·e⊥, e = d/ℓ, e⊥ = (−e_y, e_x)
            np.subtract(ell, self.L, out=t0)
            t0 *= -self.Ka
            t0 /= ell                          # −Ka(ℓ − L)/ℓ
            np.multiply(dphi, self.k_phi, out=t1)
            t1 /= ell
            t1 /= ell                          # kφ·Δφ/ℓ²
            np.multiply(t0, dx, out=Fx)
            np.multiply(t1, dy, out=t2)
            Fx += t2
            np.multiply(t0, dy, out=Fy)
            np.multiply(t1, dx, out=t2)
            Fy -= t2
        vx, vy = self._pv[2], self._pv[3]
        Fdx, Fdy = self._Fd
        np.subtract(vx, vpx, out=Fdx)
        Fdx *= -self.c_seta
        np.subtract(vy, vpy, out=Fdy)
        Fdy *= -self.c_seta
        Fx += Fdx
        Fy += Fdy
        on_plate = (float(Fx.sum()), float(Fy.sum()))
        if self.external_force.any():
            self._F += self.external_force.T
        return on_plate

    def _check_linear(self, max_u2):
        if max_u2 > (0.1 * self.L) ** 2 and not self._warned_linear:
            self._warned_linear = True
            most = math.sqrt(max_u2) / self.L
            warnings.warn(f"a seta deflected by {most:.2f} L under the linear beam model "
                          "(eq 16–21 assume small deflection); mechanics='rod' stays physical",
                          stacklevel=5)

    def _radius(self, delta):
        """:func:`jkr.radius_from_overlap` for this contact, with fewer temporaries."""
        ac = self._ac
        d = delta * (self.R / (ac * ac))
        np.maximum(d, -3.0, out=d)
        disc = d * d
        disc *= d
        disc *= 1.0 / 27.0
        disc += 1.0
        np.sqrt(disc, out=disc)
        disc += 1.0
        A = np.cbrt(disc, out=disc)
        Bp = d / (3.0 * A)
        den = A * A
        den += d * (1.0 / 3.0)                # A·Bp = d/3
        den += Bp * Bp
        m = np.divide(2.0, den, out=den)
        inner = np.divide(2.0, m, out=Bp)
        np.sqrt(inner, out=inner)
        inner *= 4.0
        inner -= 2.0 * m
        np.maximum(inner, 0.0, out=inner)
        np.sqrt(inner, out=inner)
        m *= 2.0
        u = np.sqrt(m, out=m)
        u += inner
        u *= 0.5
        # One Newton step on u⁴ − 4u − d where 4u³ − 4 > 1e-3 (as jkr.radius_from_overlap).
        u2 = u * u
        f = u2 * u2
        f -= 4.0 * u
        f -= d
        fp = np.multiply(u2, u, out=u2)
        fp -= 1.0
        fp *= 4.0
        if fp.min() > 1e-3:
            f /= fp
            u -= f
        else:
            safe = fp > 1e-3
            u = np.where(safe, u - f / np.where(safe, fp, 1.0), u)
        np.maximum(u, 1.0, out=u)
        u *= u
        u *= ac
        return u

    def _force(self, a):
        """:func:`jkr.force_from_radius` for this contact."""
        a3 = a * a
        a3 *= a
        root = np.multiply(a3, 8.0 * math.pi * self.w * self.E_star)
        np.sqrt(root, out=root)
        a3 *= 4.0 * self.E_star / (3.0 * self.R)
        a3 -= root
        return a3

    def _energy(self, idx):
        """Energy stored in the contacts of tips ``idx`` [pJ]: JKR branch + stick spring."""
        xi = self._xi_c[idx]
        return (jkr.contact_energy(self._a_c[idx], self.R, self.w, self.E_star)
                + 0.5 * self.k_t * xi * xi)

    def _detach(self, lost, gone, delta):
        """Tips that let go this step: ``lost`` (no candidate segment left, overlap −∞) and
        ``gone`` (overlap past δc). Books the energy their contacts stored as dissipated."""
        idx = np.concatenate([lost, gone])
        self._events.extend((int(i), -np.inf, float(self._P[i])) for i in lost)
        self._events.extend((int(i), float(delta[i]), float(self._P[i])) for i in gone)
        self._diss_step += float(np.sum(self._energy(idx)))
        self.attached[idx] = False
        self._P[idx] = 0.0
        self._Ft[idx] = 0.0
        self._slip[idx] = False

    def _geometry(self, ps, x, y):
        """Nearest floor point (qx, qy), unit normal (nx, ny) from floor to tip and overlap δ
        of tip centres (x, y) (each (k,)) against floor segments ``ps`` [µm]."""
        if self.pads:  # horizontal pads: the normal is vertical
            qy = self._h[ps]
            return x, qy, np.zeros(ps.size), np.ones(ps.size), self.R - (y - qy)
        A, B = self.seg_a[ps], self.seg_b[ps]
        abx, aby = B[:, 0] - A[:, 0], B[:, 1] - A[:, 1]
        t = ((x - A[:, 0]) * abx + (y - A[:, 1]) * aby) / (abx * abx + aby * aby)
        t = np.clip(t, 0.0, 1.0)
        qx, qy = A[:, 0] + t * abx, A[:, 1] + t * aby
        dx, dy = x - qx, y - qy
        dist = np.sqrt(dx * dx + dy * dy)
        inv = 1.0 / np.maximum(dist, 1e-300)
        return qx, qy, dx * inv, dy * inv, self.R - dist

    def _contact(self, tips, x, y, vx, vy, ps):
        """Contact of ``tips`` (positions x, y, velocities vx, vy, each (k,)) with segments
        ``ps``: the general (and reference) form, any floor, one or many tips.

        Updates the attach/detach state, stick anchors and per-seta records of those tips and
        adds the contact force to ``self._F``; returns it (fx, fy). Tangent t = (n_y, −n_x).
        """
        qx, qy, nx, ny, delta = self._geometry(ps, x, y)
        att0 = self.attached[tips]
        new = ~att0 & (delta >= 0.0)
        gone = att0 & (delta < self.delta_c)
        att = (att0 | new) & ~gone
        self._delta[tips] = delta
        if np.any(gone):
            self._detach(tips[:0], tips[gone], self._delta)
        if np.any(new):
            self._anchor[0, tips[new]] = qx[new]
            self._anchor[1, tips[new]] = qy[new]
        k = tips.size
        fx, fy = np.zeros(k), np.zeros(k)
        i = np.flatnonzero(att)
        if i.size:
            ti = tips[i]
            n_x, n_y = nx[i], ny[i]
            a = jkr.radius_from_overlap(delta[i], self.R, self.w, self.E_star)
            Pi = jkr.force_from_radius(a, self.R, self.w, self.E_star)
            vn = vx[i] * n_x + vy[i] * n_y
            vt = vx[i] * n_y - vy[i] * n_x
            ax, ay = self._anchor[0, ti], self._anchor[1, ti]
            xi = (qx[i] - ax) * n_y - (qy[i] - ay) * n_x
            cap = self.params.friction.cap(Pi, self.Fc)
            trial = -self.k_t * xi
            sl = np.abs(trial) > cap
            xi_new = np.where(sl, np.sign(xi) * cap / self.k_t, xi)
            # Return mapping: slide the anchor so the stick spring holds exactly the cap.
            self._anchor[0, ti] = qx[i] - xi_new * n_y
            self._anchor[1, ti] = qy[i] + xi_new * n_x
            # Coulomb work of the slip: the anchor slides |ξ − ξ_new| against the cap.
            self._diss_step += float(np.sum(cap * np.abs(xi - xi_new)))
            dn = -self.c_n * vn
            dt_ = np.where(sl, 0.0, -self.c_t * vt)
            ft = np.where(sl, -self.k_t * xi_new, trial) + dt_
            fn = Pi + dn
            fx[i] = fn * n_x + ft * n_y
            fy[i] = fn * n_y - ft * n_x
            self._Fdmp[0, ti] += dn * n_x + dt_ * n_y
            self._Fdmp[1, ti] += dn * n_y - dt_ * n_x
            self._P[ti], self._Ft[ti], self._slip[ti] = Pi, ft, sl
            self._a_c[ti], self._xi_c[ti] = a, xi_new
            # Jump-in starts the branch at U(δ ≥ 0) ≈ 0: book the difference.
            jumped = ti[new[i]]
            if jumped.size:
                self._diss_step -= float(np.sum(self._energy(jumped)))
        self.attached[tips] = att
        self._F[0, tips] += fx
        self._F[1, tips] += fy
        return fx, fy

    def _pair_arrays(self):
        if self._pairs_dirty:
            pairs = np.array(sorted(self._pairs), dtype=np.int64).reshape(-1, 2)
            self._pair_tip, self._pair_seg = pairs[:, 0], pairs[:, 1]
            self._pair_dup = bool(np.any(pairs[1:, 0] == pairs[:-1, 0]))   # sorted by tip
            self._pairs_dirty = False
        return self._pair_tip, self._pair_seg

    def _lost(self, cand):
        """Tips that lost every candidate while attached are beyond δc: they let go."""
        lost = np.flatnonzero(self.attached & ~cand)
        if lost.size:
            self._detach(lost, lost[:0], self._delta)

    def _contact_general(self):
        """Continuous floor: the contact of every tip that has a candidate segment, in bulk."""
        self._Fdmp.fill(0.0)
        self._any_contact_damping = True
        self._delta.fill(np.nan)
        pt, ps = self._pair_arrays()
        cand = self._cand_step
        cand.fill(False)
        cand[pt] = True
        self._lost(cand)
        if pt.size == 0:
            return
        x, y = self._xy
        if self._pair_dup:
            # Several candidate segments: keep each tip's nearest floor point.
            delta = self._geometry(ps, x[pt], y[pt])[4]
            order = np.lexsort((-delta, pt))
            keep = order[np.unique(pt[order], return_index=True)[1]]
            pt, ps = pt[keep], ps[keep]
        self._contact(pt, x[pt], y[pt], self._pv[2, pt], self._pv[3, pt], ps)

    def _contact_pads(self):
        """Pad floor, batch path: every tip against its own horizontal pad, in bulk.

        The same physics as :meth:`_contact` with n = (0, 1), t = (1, 0), q = (x, h): works on
        whole rows when every tip is attached and gathers the attached tips otherwise."""
        n = self.n
        x, y = self._xy
        d = self._delta
        np.subtract(y, self._h, out=d)
        np.subtract(self.R, d, out=d)             # δ = R − (y − h)
        cand = self._cand_step
        np.copyto(cand, self._cand)
        att = self.attached
        all_att, all_cand = bool(att.all()), bool(cand.all())
        lo = d < self.delta_c
        gone = lo if all_att else lo & att
        if all_cand:
            lost = None
        else:
            lost = att & ~cand
            gone &= cand
        if gone.any() or (lost is not None and lost.any()):
            self._detach(np.flatnonzero(lost) if lost is not None else np.zeros(0, np.int64),
                         np.flatnonzero(gone), d)
            all_att = False
        new = None
        if not all_att:
            new = d >= 0.0
            new &= cand
            new &= ~att
            if new.any():
                att |= new
                self._anchor[0, new] = x[new]
                self._anchor[1, new] = self._h[new]
            else:
                new = None
        n_att = n if all_att else int(np.count_nonzero(att))
        Fdmp = self._Fdmp
        if n_att == 0:
            if self._any_contact_damping:
                Fdmp.fill(0.0)
                self._any_contact_damping = False
            return
        vx, vy = self._pv[2], self._pv[3]
        if n_att == n:
            ia = None
            da, xa, vta, vna, anc = d, x, vx, vy, self._anchor[0]
        else:
            ia = np.flatnonzero(att)
            da, xa, vta, vna, anc = d[ia], x[ia], vx[ia], vy[ia], self._anchor[0, ia]
        a = self._radius(da)
        P = self._force(a)
        xi = xa - anc
        k_t = self.k_t
        if self.params.friction.law == "paper":
            cap = np.maximum(P, 0.0)
            cap *= self.params.friction.mu
        else:
            cap = P + 2.0 * self.Fc
            np.abs(cap, out=cap)
            cap *= self.params.friction.mu
        trial = xi * -k_t
        sl = np.abs(trial) > cap
        any_sl = bool(sl.any())
        dtg = vta * -self.c_t
        if any_sl:
            xi_new = np.where(sl, np.copysign(cap / k_t, xi), xi)
            # Coulomb work of the slip: the anchor slides |ξ − ξ_new| against the cap.
            self._diss_step += float(np.sum((cap * np.abs(xi - xi_new))[sl]))
            dtg[sl] = 0.0
            ft = np.where(sl, -k_t * xi_new, trial)
            ft += dtg
        else:
            xi_new = xi
            ft = trial
            ft += dtg
        dn = vna * -self.c_n
        if ia is None:
            np.subtract(x, xi_new, out=self._anchor[0])
            self._F[0] += ft
            self._F[1] += P + dn
            Fdmp[0], Fdmp[1] = dtg, dn
            self._P[:], self._Ft[:], self._a_c[:], self._xi_c[:] = P, ft, a, xi_new
            self._slip[:] = sl
        else:
            self._anchor[0, ia] = xa - xi_new
            self._F[0, ia] += ft
            self._F[1, ia] += P + dn
            Fdmp.fill(0.0)
            Fdmp[0, ia], Fdmp[1, ia] = dtg, dn
            self._P[ia], self._Ft[ia], self._a_c[ia], self._xi_c[ia] = P, ft, a, xi_new
            self._slip[ia] = sl
        self._any_contact_damping = True
        if new is not None:   # jump-in starts the branch at U(δ ≥ 0) ≈ 0: book the difference
            self._diss_step -= float(np.sum(self._energy(np.flatnonzero(new))))

    def _bookkeeping(self, vpx, vpy):
        """After the forces are known: damping dissipation and the release bookkeeping."""
        hm = 0.5 * self.dt / self.mass
        vm = self._tmp[0:2]
        np.multiply(self._F, hm, out=vm)
        vm += self._pv[2:4]                       # mid-step velocity ½(v + v_next)
        Fd = self._Fd
        # −dt·[Σ Fd·(v_mid − vp) + Σ F_contact_damping·v_mid]. (Products and sums rather than
        # np.dot/vdot: BLAS threads that spin-wait on a busy machine cost milliseconds.)
        prod = self._tmp[3:5]
        if self._any_contact_damping:
            np.add(Fd, self._Fdmp, out=prod)
            prod *= vm
        else:
            np.multiply(Fd, vm, out=prod)
        s = float(prod.sum()) - vpx * float(Fd[0].sum()) - vpy * float(Fd[1].sum())
        self._diss_step -= s * self.dt
        # Release bookkeeping: where a tip began to run away from the plate.
        # A tip following its branch moves slower than the plate; past the fold it runs away.
        att = self.attached
        if not att.any():
            return
        v_ref = max(math.hypot(vpx, vpy), 1e-4)
        s2 = self._tmp[2]
        vx, vy = self._pv[2], self._pv[3]
        np.multiply(vx, vx, out=s2)
        s2 += vy * vy
        fast = s2 > 4.0 * v_ref * v_ref
        fast &= att
        jump = self.jump_overlap
        jn = np.isnan(jump)
        set_ = fast & jn
        if set_.any():
            jump[set_] = self._delta[set_]
        if not jn.all():
            slow = s2 < v_ref * v_ref
            slow &= att
            jump[slow] = np.nan

    def _advance(self, vpx, vpy):
        """One time step with the plate at velocity (vpx, vpy) [µm/µs]; leaves the step's
        reaction, work and dissipation in ``_reaction``, ``_work_step``, ``_diss_step``."""
        dt = self.dt
        self.plate.velocity = (vpx, vpy)
        pp = self.plate.position
        pnx, pny = pp.x + vpx * dt, pp.y + vpy * dt
        self._pnext = (pnx, pny)
        self._events = []
        self._diss_step = 0.0
        if self._kernel is not None:
            opx, opy = self._advance_kernel(pnx, pny, vpx, vpy)
        else:
            self._read()
            x, y = self._xy
            np.multiply(self._pv[2], dt, out=x)
            x += self._pv[0]                       # where pymunk will evaluate forces
            np.multiply(self._pv[3], dt, out=y)
            y += self._pv[1]
            opx, opy = self._spring_damp(pnx, pny, vpx, vpy)
            if self._fast_pads:
                self._contact_pads()
            elif self.contact_path == "batch":
                self._contact_general()
            else:
                self._Fdmp.fill(0.0)
                self._delta.fill(np.nan)
                self._any_contact_damping = True
            self._write_forces()
            if self.contact_path == "callback":
                # Tips that lost their candidate while attached (no pre_solve will come).
                np.copyto(self._cand_step, self._cand)
                self._lost(self._cand_step)
        if self.pads and (self._kernel is None or self._res[6] > self._pad_slack):
            self._recentre_pads()
        self.space.step(dt)
        self.time += dt
        if self._kernel is None:
            self._bookkeeping(vpx, vpy)
        ppx, ppy = self._on_plate_prev
        self._work_step = (0.5 * (opx + ppx) * vpx + 0.5 * (opy + ppy) * vpy) * dt
        self._on_plate_prev = (opx, opy)
        self._reaction = (-opx, -opy)

    def _advance_kernel(self, pnx, pny, vpx, vpy):
        data = self._read_raw()
        prm = self._prm
        prm[_K_PNX], prm[_K_PNY], prm[_K_VPX], prm[_K_VPY] = pnx, pny, vpx, vpy
        prm[_K_VREF] = max(math.hypot(vpx, vpy), 1e-4)
        prm[_K_EXT] = 1.0 if self.external_force.any() else 0.0
        np.copyto(self._cand_step, self._cand)
        res = self._res
        self._kernel(data, self._order, self._out, prm, self._h, self._cand_step, self.attached,
                     self._slip, self._S, self.external_force, self._pad_c, self._rest,
                     self._root, self._lost_idx, self._gone_idx, res)
        pb.set_space_bodies(self.space, pb.BodyFields.FORCE, self._force_buf)
        self._diss_step += float(res[2])
        n_lost, n_gone = int(res[3]), int(res[4])
        if n_lost or n_gone:
            lost, gone = self._lost_idx[:n_lost].copy(), self._gone_idx[:n_gone].copy()
            d, P = self._delta, self._P
            self._events.extend((int(i), -np.inf, float(P[i])) for i in lost)
            self._events.extend((int(i), float(d[i]), float(P[i])) for i in gone)
            idx = np.concatenate([lost, gone])
            P[idx] = 0.0
            self._Ft[idx] = 0.0
            self._slip[idx] = False
        if not self._warned_linear and self.params.mechanics == "linear":
            self._check_linear(float(res[5]))
        self._any_contact_damping = True
        return float(res[0]), float(res[1])

    def _read_raw(self):
        """The batch read of ids, positions and velocities (rows in Chipmunk's order)."""
        buf = self._read_buf
        buf.clear()
        pb.get_space_bodies(self.space, _FIELDS_READ, buf)
        ids = np.frombuffer(buf.int_buf(), dtype=np.uintp)
        self._check_rows(ids)
        return np.frombuffer(buf.float_buf()).reshape(len(ids), 4)

    # ------------------------------------------------------------------ stepping
    def step(self, plate_velocity):
        """Advance one time step with the plate moving at ``plate_velocity`` (vx, vy) [µm/µs].

        Returns the plate's reaction (force of the setae on the plate) [µN], the work the
        plate did on the system during the step [pJ], the elastic energy of every seta [pJ]
        and the tip positions (N, 2) at which the forces were evaluated [µm].
        """
        vx, vy = (float(v) for v in plate_velocity)
        self._advance(vx, vy)
        return (np.array(self._reaction), self._work_step, self._spring_energy(),
                self._xy.T.copy())

    def reset_state_arrays(self):
        """Start the energy and force bookkeeping afresh (as at the start of :meth:`run`)."""
        self._on_plate_prev = (0.0, 0.0)
        self._P[:] = 0.0
        # Nothing stored in the contacts counts as dissipated at a first-step snap-off.
        self._a_c[:] = self._a_jump
        self._xi_c[:] = 0.0
        prm = self._prm
        K = self.K
        prm[_K_DT] = self.dt
        prm[_K_ROD] = 1.0 if self.params.mechanics == "rod" else 0.0
        prm[_K_K00], prm[_K_K01], prm[_K_K10], prm[_K_K11] = -K[0, 0], -K[0, 1], -K[1, 0], -K[1, 1]
        prm[_K_L], prm[_K_KA], prm[_K_KPHI], prm[_K_THETA] = self.L, self.Ka, self.k_phi, self.theta
        prm[_K_CS], prm[_K_R], prm[_K_DC] = self.c_seta, self.R, self.delta_c
        prm[_K_CN], prm[_K_CT], prm[_K_KT] = self.c_n, self.c_t, self.k_t
        prm[_K_MU] = self.params.friction.mu
        prm[_K_LAW] = 1.0 if self.params.friction.law == "paper" else 0.0
        prm[_K_FC], prm[_K_AC], prm[_K_HM] = self.Fc, self._ac, 0.5 * self.dt / self.mass
        prm[_K_W], prm[_K_ES] = self.w, self.E_star

    # ------------------------------------------------------------------ protocol runner
    def run(self, protocol, *, progress: bool = True, max_steps: int = 50_000_000,
            ke_bound: float | None = None, fast_approach: bool = True) -> History:
        """Run a protocol (list of :mod:`protocol` segments) and return its :class:`History`.

        Parameters
        ----------
        protocol : list of Move / PressTo / Press / Hold / PullOff segments.
        progress : tqdm progress bar over simulated time.
        max_steps : hard cap on time steps.
        ke_bound : kinetic energy [pJ] beyond which the run is declared unstable (default:
            100 × the adhesion energy of all setae, N·Fc·|δc|, plus the plate work so far).
        fast_approach : in Move, PressTo and Press segments, while no tip is attached and
            every tip rests relative to the plate (within 1e-3 of the plate speed and of the
            lag that speed causes), move plate and tips rigidly to where the first sensor
            reaches the floor (:meth:`_skip_free_travel`) instead of stepping there. A free
            seta's motion does not depend on where it is, so the history is the same but for
            the skipped rows; the travel skipped is ``meta["skipped_travel_um"]``.
        """
        from tqdm.auto import tqdm

        segments = list(protocol)
        if not segments:
            raise ValueError("protocol is empty: give at least one segment")
        for s in segments:
            if not isinstance(s, Move | PressTo | Press | Hold | PullOff):
                raise TypeError(f"unknown protocol segment {s!r}")
        self.reset_state_arrays()
        rec = _Recorder(self)
        e_scale = self.n * self.Fc * abs(self.delta_c)
        work = dissipated = skipped = 0.0
        n_steps = 0
        every = self.record_every
        est = sum(self._estimate_duration(s) for s in segments)
        # Whole microseconds of simulated time; the total is an estimate and may be exceeded.
        bar = tqdm(total=max(int(est), 1), unit="µs", disable=not progress,
                   desc=f"gecko_agents (dt = {self.dt:.3g} µs)",
                   mininterval=0.5)
        t_wall = time.perf_counter()
        try:
            for seg in segments:
                pos = self.plate.position
                state = {"start": (pos.x, pos.y), "t0": self.time, "all_free": None}
                may_skip = fast_approach and isinstance(seg, Move | PressTo | Press)
                while True:
                    vp, done = self._segment_velocity(seg, state)
                    if done:
                        break
                    if may_skip and n_steps % every == 0 and not self.attached.any():
                        skipped += self._skip_free_travel(seg, state, vp)
                    self._advance(vp[0], vp[1])
                    work += self._work_step
                    dissipated += self._diss_step
                    if self._events:
                        rec.note_events(self)
                    n_steps += 1
                    if n_steps % every == 0 or n_steps == 1:
                        row = rec.record(self, work, dissipated)
                        bound = ke_bound if ke_bound is not None else 100 * (e_scale + abs(work))
                        self._check_stable(row, bound)
                        bar.update(int(self.time) - bar.n)
                    if n_steps >= max_steps:
                        raise RuntimeError(f"max_steps = {max_steps} reached in segment {seg}")
        finally:
            bar.close()
        rec.record(self, work, dissipated)
        wall = time.perf_counter() - t_wall
        meta = {"dt_us": self.dt, "n_steps": n_steps, "record_every": self.record_every,
                "n_sim": self.n, "scale_to_array": self.params.array.count / self.n,
                "protocol": [f"{s!r}" for s in segments], "contact_path": self.contact_path,
                "kernel": self.kernel, "skipped_travel_um": skipped,
                "damping": dataclasses.asdict(self.damping),
                "mass_ng": self.mass, "tangential_stiffness_uN_per_um": self.k_t,
                "wall_time_s": wall, "versions": versions()}
        return rec.history(self, meta)

    def _skip_free_travel(self, seg, state, vp) -> float:
        """Move plate and tips rigidly along ``vp`` while nothing can touch; returns the travel.

        Only when no tip is attached and every tip rests relative to the plate: deflection
        below 1e-3 of the lag v/ω of a seta dragged at the plate speed, relative velocity below
        1e-3 of the plate speed (a free seta then just follows the plate, wherever it is). The
        plate stops where the first sensor circle would reach the floor, and a few steps
        before the end of a Move or PressTo.
        """
        vx, vy = vp
        speed = math.hypot(vx, vy)
        if speed == 0.0 or self.attached.any():
            return 0.0
        self._read()
        px, py, tvx, tvy = self._pv
        pp = self.plate.position
        omega = math.sqrt(self.params.Ky / self.mass)
        tol_u, tol_v = 1e-3 * speed / omega, 1e-3 * speed
        if (np.abs(px - pp.x - self._rest_dx).max() > tol_u
                or np.abs(py - pp.y - self._rest_dy).max() > tol_u
                or np.abs(tvx - vx).max() > tol_v or np.abs(tvy - vy).max() > tol_v):
            return 0.0
        reach = self.sensor_radius + 2.0 * speed * self.dt
        if self.pads:
            gap = float(np.min(py - self._h)) - reach
        else:
            gap = float(np.min(py)) - float(np.max(self.profile.y)) - reach
        travel = math.inf if vy >= 0 else gap * speed / -vy
        if isinstance(seg, Move | PressTo):
            if isinstance(seg, PressTo):
                tx, ty = state["start"][0], self.z_touch - seg.depth
            else:
                tx, ty = state["start"][0] + seg.dx, state["start"][1] + seg.dy
            travel = min(travel, math.hypot(tx - pp.x, ty - pp.y) - 3.0 * speed * self.dt)
        if not travel > 20.0 * speed * self.dt:
            return 0.0
        sx, sy = vx / speed * travel, vy / speed * travel
        self.plate.position = (pp.x + sx, pp.y + sy)
        for body, x, y in zip(self.tips, px.tolist(), py.tolist(), strict=True):
            body.position = (x + sx, y + sy)
        self.time += travel / speed
        return travel

    def _estimate_duration(self, seg) -> float:
        if isinstance(seg, Move):
            return math.hypot(seg.dx, seg.dy) / seg.speed
        if isinstance(seg, PressTo):
            return max(self.plate_start - (self.z_touch - seg.depth), 0.0) / seg.speed
        if isinstance(seg, Press):
            return 2.0 / seg.speed
        if isinstance(seg, Hold):
            return seg.duration
        return (self.Fc / self.params.Ky if self.params.mechanics == "linear"
                else self.L) / seg.speed

    def _segment_velocity(self, seg, state):
        """Plate velocity (vx, vy) for the next step of a segment, and whether it is over."""
        pos = self.plate.position
        px, py = pos.x, pos.y
        dt = self.dt
        if isinstance(seg, Move | PressTo):
            if isinstance(seg, PressTo):
                tx, ty = state["start"][0], self.z_touch - seg.depth
            else:
                tx, ty = state["start"][0] + seg.dx, state["start"][1] + seg.dy
            rx, ry = tx - px, ty - py
            dist = math.hypot(rx, ry)
            if dist <= 1e-12:
                return None, True
            if dist < seg.speed * dt:
                return (rx / dt, ry / dt), False
            return (rx / dist * seg.speed, ry / dist * seg.speed), False
        if isinstance(seg, Press):
            # Servo on the force averaged over the seta's slowest period: a fresh contact's
            # ring-down can push the instantaneous force past the target before the static
            # force gets there.
            force = float(self._P.sum())
            avg = state.setdefault("force_avg", force)
            avg += (force - avg) * min(1.0, dt / self.settle_time)
            state["force_avg"] = avg
            if avg >= seg.preload:
                return None, True
            frac = (seg.preload - avg) / (seg.band * seg.preload)
            return (0.0, -seg.speed * min(1.0, max(frac, 0.02))), False
        if isinstance(seg, Hold):
            return ((0.0, 0.0), False) if self.time - state["t0"] < seg.duration - 1e-9 * dt \
                else (None, True)
        # PullOff
        sx, sy = state["start"]
        travel = math.hypot(px - sx, py - sy)
        attached = bool(self.attached.any())
        if seg.max_travel is not None and travel >= seg.max_travel:
            if attached:
                warnings.warn(f"PullOff stopped at max_travel = {seg.max_travel} µm with "
                              f"{int(self.attached.sum())} setae still attached", stacklevel=4)
            return None, True
        if not attached:
            if state["all_free"] is None:
                state["all_free"] = (px, py)
            elif math.hypot(px - state["all_free"][0], py - state["all_free"][1]) \
                    >= seg.clearance:
                return None, True
        else:
            state["all_free"] = None
        ang = math.radians(seg.angle_deg)
        return (seg.speed * math.cos(ang), seg.speed * math.sin(ang)), False

    def _check_stable(self, row, bound):
        if not all(math.isfinite(v) for v in row.values()):
            raise SimulationUnstable(
                f"non-finite state at t = {self.time:.4g} µs: the time step dt = {self.dt:.3g} µs "
                "is too large for the contact stiffness reached; pass a smaller dt or a "
                "shallower depth/preload")
        if row["energy_kinetic_pJ"] > bound:
            raise SimulationUnstable(
                f"kinetic energy {row['energy_kinetic_pJ']:.3g} pJ exceeded {bound:.3g} pJ at "
                f"t = {self.time:.4g} µs: the integration is unstable (reduce dt = "
                f"{self.dt:.3g} µs) or the plate moves too fast for the setae to follow "
                "(lower the protocol speed)")

    # ------------------------------------------------------------------ recorded quantities
    def _overlaps(self):
        """Overlap δ of every tip with a candidate floor at the last step, NaN elsewhere."""
        if self._fast_pads:
            return np.where(self._cand_step, self._delta, np.nan)
        return self._delta.copy()

    def _contact_energies(self):
        """Energy stored in each contact at the last step (0 for free tips) [pJ]."""
        U = np.zeros(self.n)
        idx = np.flatnonzero(self.attached)
        U[idx] = self._energy(idx)
        return U


class _Recorder:
    """Collects rows every ``record_every`` steps; separate from the stepping."""

    def __init__(self, model: Model):
        self.rows = {c: [] for c in SCALAR_COLUMNS}
        self.per = {f: [] for f in PER_SETA_FIELDS} if model.record_setae else {}
        self.det = {k: [] for k in ("seta", "time_us", "plate_x_um", "plate_y_um",
                                    "overlap_um", "release_overlap_um", "force_uN")}
        self.max_ke = self.max_el = 0.0

    def record(self, m: Model, work, dissipated):
        pos = m.plate.position
        # Kinetic energy at the recorded positions: ½m·v(n−½)·v(n+½), the form that
        # semi-implicit Euler conserves exactly for a linear spring.
        v = m._pv[2:4]
        ke = 0.5 * m.mass * float(np.sum(v * (v + m._F * (m.dt / m.mass))))
        U = m._contact_energies()
        el = float(np.sum(m._spring_energy()) + np.sum(U))
        reaction = m._reaction
        row = {
            "time_us": m.time, "plate_x_um": pos.x, "plate_y_um": pos.y,
            "force_normal_uN": float(m._P.sum()), "force_tangential_uN": float(m._Ft.sum()),
            "plate_force_x_uN": float(reaction[0]), "plate_force_y_uN": float(reaction[1]),
            "n_attached": int(m.attached.sum()), "n_sliding": int((m._slip & m.attached).sum()),
            "energy_elastic_pJ": el, "energy_kinetic_pJ": ke,
            "energy_dissipated_pJ": dissipated, "work_plate_pJ": work,
        }
        for k, val in row.items():
            self.rows[k].append(val)
        self.max_ke = max(self.max_ke, ke)
        self.max_el = max(self.max_el, el)
        if self.per:
            state = np.where(m.attached, np.where(m._slip, STATE_SLIP, STATE_STICK), STATE_FREE)
            vals = {"tip_x_um": m._xy[0], "tip_y_um": m._xy[1], "force_normal_uN": m._P,
                    "force_tangential_uN": m._Ft, "overlap_um": m._overlaps(),
                    "state": state.astype(np.int8)}
            for f in PER_SETA_FIELDS:
                self.per[f].append(np.array(vals[f]))
        return row

    def note_events(self, m: Model):
        pos = m.plate.position
        for i, d, force in m._events:
            self.det["seta"].append(i)
            self.det["time_us"].append(m.time)
            self.det["plate_x_um"].append(pos.x)
            self.det["plate_y_um"].append(pos.y)
            self.det["overlap_um"].append(d)
            j = m.jump_overlap[i]
            self.det["release_overlap_um"].append(d if np.isnan(j) else j)
            self.det["force_uN"].append(force)
            m.jump_overlap[i] = np.nan

    def history(self, m: Model, meta: dict) -> History:
        scalars = {k: np.asarray(v, dtype=float) for k, v in self.rows.items()}
        setae = {k: np.asarray(v) for k, v in self.per.items()}
        geometry = {"root_dx_um": m.root_dx, "root_dy_um": m.root_dy,
                    "floor_x_um": m.profile.x, "floor_y_um": m.profile.y}
        det = {k: np.asarray(v) for k, v in self.det.items()}
        # Quasi-static measure: peak kinetic over peak elastic energy of the run.
        meta = dict(meta, max_kinetic_to_elastic=self.max_ke / max(self.max_el, 1e-300))
        return History(m.params, m.seed, scalars, setae, geometry, det, meta)


# ---------------------------------------------------------------------- optional numba kernel
# The per-seta update of a pad-floor step as one loop: the same formulas and the same order of
# operations as Model._spring_damp + Model._contact_pads + Model._bookkeeping. Compiled on
# first use when numba is installed (the `fast` extra); the numpy path is the fallback.

def _s_radius(delta, R, ac):
    """Scalar :func:`jkr.radius_from_overlap` (as Model._radius)."""
    d = delta * (R / (ac * ac))
    if d < -3.0:
        d = -3.0
    disc = math.sqrt(d * d * d * (1.0 / 27.0) + 1.0)
    A = np.cbrt(disc + 1.0)
    Bp = d / (3.0 * A)
    m = 2.0 / (A * A + d * (1.0 / 3.0) + Bp * Bp)
    inner = math.sqrt(2.0 / m) * 4.0 - 2.0 * m
    if inner < 0.0:
        inner = 0.0
    u = (math.sqrt(m * 2.0) + math.sqrt(inner)) * 0.5
    u2 = u * u
    fp = (u2 * u - 1.0) * 4.0
    if fp > 1e-3:
        u -= (u2 * u2 - 4.0 * u - d) / fp
    if u < 1.0:
        u = 1.0
    return (u * u) * ac


def _s_energy(a, xi, R, w, E, k_t, Uj):
    """Scalar :func:`jkr.contact_energy` + stick-spring energy ½k_t·ξ²."""
    A = 4.0 * E / (3.0 * R)
    B = math.sqrt(8.0 * math.pi * w * E)
    C = math.sqrt(2.0 * math.pi * w / E)
    U = (2.0 * A * a**5 / (5.0 * R) - (A * C / 7.0 + 4.0 * B / (7.0 * R)) * a**3.5
         + math.pi * w * a * a)
    return U - Uj + 0.5 * k_t * xi * xi


def _pads_kernel(data, rows, out, prm, h, cand, attached, slip, S, ext, pad_c, rest, root,
                 lost_idx, gone_idx, res):
    """One pad-floor step of every seta: reads the batch rows ``data`` (x, y, vx, vy; seta i
    in row ``rows[i]``), writes the forces into ``out`` and the state block ``S`` (rows as the
    ``_PX`` … ``_FDY`` constants), the detached tips into ``lost_idx``/``gone_idx`` and into
    ``res``: plate force (x, y), dissipation, #lost, #gone, max |u|², max pad-window drift.
    ``prm`` holds the scalars in the order of the ``_K_*`` constants."""
    n = S.shape[1]
    dt, pnx, pny, vpx, vpy = prm[0], prm[1], prm[2], prm[3], prm[4]
    rod = prm[5] > 0.0
    k00, k01, k10, k11 = prm[6], prm[7], prm[8], prm[9]
    L, Ka, kphi, theta = prm[10], prm[11], prm[12], prm[13]
    cs, R, dc, cn, ct, kt = prm[14], prm[15], prm[16], prm[17], prm[18], prm[19]
    mu, paper, Fc, ac, vref = prm[20], prm[21] > 0.0, prm[22], prm[23], prm[24]
    has_ext, hm, w, E = prm[25] > 0.0, prm[26], prm[27], prm[28]
    c1 = 4.0 * E / (3.0 * R)
    c2 = 8.0 * math.pi * w * E
    Cj = math.sqrt(2.0 * math.pi * w / E)
    Uj = _s_energy(np.cbrt((Cj * R) ** 2), 0.0, R, w, E, kt, 0.0)
    fast2, slow2 = 4.0 * vref * vref, vref * vref
    opx = opy = diss = dd = sfdx = sfdy = max_u2 = drift = 0.0
    nl = ng = 0
    # Three passes over blocks of setae: (1) springs, damping, overlaps, contact state
    # changes; (2) contact radius; (3) contact forces and bookkeeping. The contact radius is a
    # long chain of dependent sqrt/cbrt/divisions that overlaps between setae only in a short
    # loop of its own; blocks keep the data of the three passes in cache.
    for b0 in range(0, n, 128):
        b1 = min(n, b0 + 128)
        # Pass 1: springs, damping, overlaps and contact state changes.
        for i in range(b0, b1):
            r = rows[i]
            px, py, vx, vy = data[r, 0], data[r, 1], data[r, 2], data[r, 3]
            S[0, i], S[1, i], S[2, i], S[3, i] = px, py, vx, vy
            x = vx * dt + px
            y = vy * dt + py
            S[4, i], S[5, i] = x, y
            if rod:
                dx = (x - pnx) - root[0, i]
                dy = (y - pny) - root[1, i]
                ell = math.sqrt(dx * dx + dy * dy)
                dphi = math.atan2(dy, dx) + (theta + math.pi)
                dphi = dphi % (2.0 * math.pi) - math.pi
                t0 = (ell - L) * -Ka / ell
                t1 = dphi * kphi / ell / ell
                fx = t0 * dx + t1 * dy
                fy = t0 * dy - t1 * dx
            else:
                ux = (x - pnx) - rest[0, i]
                uy = (y - pny) - rest[1, i]
                S[18, i], S[19, i] = ux, uy
                fx = ux * k00 + uy * k01
                fy = ux * k10 + uy * k11
                u2 = ux * ux + uy * uy
                if u2 > max_u2:
                    max_u2 = u2
            fdx = (vx - vpx) * -cs
            fdy = (vy - vpy) * -cs
            S[20, i], S[21, i] = fdx, fdy
            sfdx += fdx
            sfdy += fdy
            fx += fdx
            fy += fdy
            opx += fx
            opy += fy
            if has_ext:
                fx += ext[i, 0]
                fy += ext[i, 1]
            S[6, i], S[7, i] = fx, fy
            # Contact with the tip's own pad: n = (0, 1), t = (1, 0), q = (x, h).
            d = R - (y - h[i])
            S[16, i] = d
            if attached[i]:
                gone = False
                if not cand[i]:
                    lost_idx[nl] = i
                    nl += 1
                    gone = True
                elif d < dc:
                    gone_idx[ng] = i
                    ng += 1
                    gone = True
                if gone:   # snap-off: what the contact stored is dissipated
                    attached[i] = False
                    diss += _s_energy(S[12, i], S[13, i], R, w, E, kt, Uj)
            elif cand[i] and d >= 0.0:
                attached[i] = True
                S[10, i], S[11, i] = x, h[i]
                S[13, i] = np.inf           # marks a jump-in for pass 3
        # Pass 2: contact radius on the JKR branch.
        for i in range(b0, b1):
            if attached[i]:
                S[12, i] = _s_radius(S[16, i], R, ac)
        # Pass 3: contact forces, stick/slip, release bookkeeping, dissipation, force write.
        for i in range(b0, b1):
            vx, vy, x = S[2, i], S[3, i], S[4, i]
            fx, fy, fdx, fdy = S[6, i], S[7, i], S[20, i], S[21, i]
            dmpx = dmpy = 0.0
            if attached[i]:
                new = S[13, i] == np.inf
                a = S[12, i]
                a3 = a * a * a
                P = a3 * c1 - math.sqrt(a3 * c2)
                xi = x - S[10, i]
                if paper:
                    cap = (P if P > 0.0 else 0.0) * mu
                else:
                    cap = abs(P + 2.0 * Fc) * mu
                trial = xi * -kt
                dtg = vx * -ct
                if abs(trial) > cap:
                    xin = math.copysign(cap / kt, xi)
                    diss += cap * abs(xi - xin)   # Coulomb work of the slip
                    dtg = 0.0
                    ft = -kt * xin + dtg
                    sl = True
                else:
                    xin = xi
                    ft = trial + dtg
                    sl = False
                S[10, i] = x - xin
                dn = vy * -cn
                fx += ft
                fy += P + dn
                dmpx, dmpy = dtg, dn
                S[14, i], S[15, i], S[13, i] = P, ft, xin
                slip[i] = sl
                if new:   # jump-in starts the branch at U(δ ≥ 0) ≈ 0
                    diss -= _s_energy(a, xin, R, w, E, kt, Uj)
                s2 = vx * vx + vy * vy
                if s2 > fast2:
                    if math.isnan(S[17, i]):
                        S[17, i] = S[16, i]
                elif s2 < slow2:
                    S[17, i] = np.nan
            S[6, i], S[7, i], S[8, i], S[9, i] = fx, fy, dmpx, dmpy
            r = rows[i]
            out[r, 0], out[r, 1] = fx, fy
            vmx = fx * hm + vx
            vmy = fy * hm + vy
            dd += (fdx + dmpx) * vmx + (fdy + dmpy) * vmy
            dr = abs(x - pad_c[i])
            if dr > drift:
                drift = dr
    res[0], res[1] = opx, opy
    res[2] = diss - (dd - vpx * sfdx - vpy * sfdy) * dt
    res[3], res[4], res[5], res[6] = nl, ng, max_u2, drift


_KERNEL: list = []


def _numba_kernel():
    """The compiled pad-floor kernel, or None without numba (compiled once, cached on disk)."""
    if not _KERNEL:
        try:
            import numba
        except ImportError:
            _KERNEL.append(None)
            return None
        jit = numba.njit(cache=True, error_model="numpy")
        g = globals()
        for name in ("_s_radius", "_s_energy"):
            g[name] = jit(g[name])
        _KERNEL.append(jit(_pads_kernel))
    return _KERNEL[0]
