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
* Every step, all forces are computed at once in numpy at the positions pymunk is about to
  integrate velocities with (x + v·dt), and written back with one ``pymunk.batch`` call:
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

__all__ = ["Damping", "Model", "SimulationUnstable", "seta_mass", "tangential_stiffness"]

TIP, FLOOR = 1, 2
_FIELDS_READ = pb.BodyFields.BODY_ID | pb.BodyFields.POSITION | pb.BodyFields.VELOCITY


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
    """

    def __init__(self, params: SetaArray, *, n_sim: int | None = None, seed: int | None = None,
                 dt: float | None = None, contact: str = "batch",
                 damping: Damping = Damping(), record_every: int | None = None,
                 record_setae: bool = False, verbose: bool = False):
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
        self._build_world()

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
        prof = floor.make_profile(p.floor.sigma, p.floor.correlation_length, n, p.array.pitch,
                                  touch_x, margin, self.rng)
        self.profile = prof
        self.pads = prof.pad_heights is not None
        start_gap = 0.5
        self.plate_start = float(np.max(prof.y) + self.z_touch + start_gap)
        self.plate = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        self.plate.position = (0.0, self.plate_start)
        space.add(self.plate)
        # Floor segments. Pads: seta i meets a flat floor at its own height h_i (the paper's
        # model treats it as a plane), so its pad segment reaches past any lateral travel of
        # the tip; collision categories (i mod 32) keep a tip from testing most other pads.
        # Continuous profile: one segment per polyline edge, joined with set_neighbors.
        if self.pads:
            half = 0.5 * p.array.pitch + self._lateral_reach()
            xc = 0.5 * (prof.x[0::2] + prof.x[1::2])
            xc[0], xc[-1] = touch_x[0], touch_x[-1]
            seg_a = np.column_stack([xc - half, prof.pad_heights])
            seg_b = np.column_stack([xc + half, prof.pad_heights])
        else:
            seg_a = np.column_stack([prof.x[:-1], prof.y[:-1]])
            seg_b = np.column_stack([prof.x[1:], prof.y[1:]])
        self.seg_a, self.seg_b = seg_a, seg_b
        self._seg_index = {}
        for i, (a, b) in enumerate(zip(seg_a, seg_b, strict=True)):
            seg = pymunk.Segment(space.static_body, tuple(a), tuple(b), 0.0)
            seg.collision_type = FLOOR
            if self.pads:
                seg.filter = pymunk.ShapeFilter(categories=1 << (i % 32), mask=1 << (i % 32))
            else:
                prev = tuple(seg_a[i - 1]) if i > 0 else tuple(a)
                nxt = tuple(seg_b[i + 1]) if i + 1 < len(seg_a) else tuple(b)
                seg.set_neighbors(prev, nxt)
            space.add(seg)
            self._seg_index[seg] = i
        # Tips: point masses with sensor circles; a shared group stops tip–tip detection.
        self.sensor_radius = self.R + abs(self.delta_c) + 0.5
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
        # Contact state per tip.
        self.attached = np.zeros(n, dtype=bool)
        self.anchor = np.zeros((n, 2))
        self.jump_overlap = np.full(n, np.nan)
        self.time = 0.0
        self._warned_linear = False
        self._zeros, self._ones = np.zeros(n), np.ones(n)
        self.external_force = np.zeros((n, 2))  # extra force on each tip [µN] (probing/tests)
        self._root_offset = np.column_stack([self.root_dx, self.root_dy])

    def _lateral_reach(self) -> float:
        """How far [µm] a tip can slide sideways from its touch-down point (pad half-width).

        linear: the free tip moves |K_xy/K_xx| per unit of normal stretch, and a seta stretches
        by up to ~Fc/Ky before it lets go; rod: at most the rod length on each side.
        """
        if self.params.mechanics == "rod":
            return 2.0 * self.L + 10.0
        stretch = 1.5 * self.Fc / self.params.Ky
        return stretch * abs(self.K[0, 1] / self.K[0, 0]) + self.L + 10.0

    # ------------------------------------------------------------------ callbacks
    def _begin(self, arbiter, space, data):
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index[tip_shape], self._seg_index[seg_shape]
        if self.pads and i != j:
            return  # the paper's model: a tip meets only the height drawn for it
        self._pairs.add((i, j))
        self._pairs_dirty = True

    def _separate(self, arbiter, space, data):
        tip_shape, seg_shape = arbiter.shapes
        key = (self._tip_index.get(tip_shape), self._seg_index.get(seg_shape))
        if key in self._pairs:
            self._pairs.discard(key)
            self._pairs_dirty = True

    def _pre_solve(self, arbiter, space, data):
        """Reference path: the contact force of one tip, computed and applied per contact."""
        tip_shape, seg_shape = arbiter.shapes
        i, j = self._tip_index[tip_shape], self._seg_index[seg_shape]
        if i != j:
            return
        body = tip_shape.body
        x = np.array([[body.position.x, body.position.y]])
        v = self._vel_now[i:i + 1]
        out = self._contact(np.array([i]), x, v, np.array([j]))
        fx, fy = out["force"][0]
        body.force = (body.force.x + fx, body.force.y + fy)
        self._F[i] += out["force"][0]
        self._store_contact(np.array([i]), out)

    # ------------------------------------------------------------------ physics
    def _read(self):
        """Positions and velocities of all tips (N, 2), in seta order, in one batch call."""
        buf = self._read_buf
        buf.clear()
        pb.get_space_bodies(self.space, _FIELDS_READ, buf)
        ids = np.frombuffer(buf.int_buf(), dtype=np.uintp)
        data = np.frombuffer(buf.float_buf()).reshape(len(ids), 4)
        if self._ids_cached is None or not np.array_equal(ids, self._ids_cached):
            # Chipmunk's order is internal and changes only when bodies are added/removed.
            where = np.searchsorted(self._id_sorted, ids)
            ok = (where < self.n) & (self._id_sorted[np.minimum(where, self.n - 1)] == ids)
            rows = np.flatnonzero(ok)
            seta = self._id_to_seta[where[rows]]
            order = np.empty(self.n, dtype=np.int64)
            order[seta] = rows                      # batch row of each seta
            self._ids_cached, self._rows, self._order = ids.copy(), rows, order
            self._rows_seta = seta
        sel = data[self._order]
        return sel[:, 0:2], sel[:, 2:4], ids.size, self._rows, self._rows_seta

    def spring_force(self, x, root):
        """Seta spring force on the tips [µN], elastic energies [pJ] and (linear) deflections.

        Parameters
        ----------
        x : tip positions (N, 2) [µm]. root : root positions (N, 2) [µm].
        """
        d = x - root
        if self.params.mechanics == "linear":
            u = d - self.L * self.axis
            F = -u @ self.K.T
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

    def _geometry(self, ps, x):
        """Nearest floor point (qx, qy), unit normal (nx, ny) from floor to tip and overlap δ
        of tip centres x (k, 2) against floor segments ``ps`` [µm]."""
        if self.pads:  # horizontal pads: the normal is vertical
            qy = self.seg_a[ps, 1]
            return x[:, 0], qy, self._zeros[: ps.size], self._ones[: ps.size], \
                self.R - (x[:, 1] - qy)
        A, B = self.seg_a[ps], self.seg_b[ps]
        abx, aby = B[:, 0] - A[:, 0], B[:, 1] - A[:, 1]
        t = ((x[:, 0] - A[:, 0]) * abx + (x[:, 1] - A[:, 1]) * aby) / (abx * abx + aby * aby)
        t = np.clip(t, 0.0, 1.0)
        qx, qy = A[:, 0] + t * abx, A[:, 1] + t * aby
        dx, dy = x[:, 0] - qx, x[:, 1] - qy
        dist = np.hypot(dx, dy)
        inv = 1.0 / np.maximum(dist, 1e-300)
        return qx, qy, dx * inv, dy * inv, self.R - dist

    def _contact(self, tips, x, v, ps):
        """Contact of ``tips`` (positions x, velocities v, each (k, 2)) with segments ``ps``.

        Updates the attach/detach state and stick anchors of those tips; returns the force on
        each tip and what the history records. Tangent t = (n_y, −n_x).
        """
        qx, qy, nx, ny, delta = self._geometry(ps, x)
        att0 = self.attached[tips]
        new = ~att0 & (delta >= 0.0)
        gone = att0 & (delta < self.delta_c)
        att = (att0 | new) & ~gone
        if np.any(new):
            self.anchor[tips[new], 0] = qx[new]
            self.anchor[tips[new], 1] = qy[new]
        k = tips.size
        P, Ft, U = np.zeros(k), np.zeros(k), np.zeros(k)
        slip = np.zeros(k, dtype=bool)
        force, damp = np.zeros((k, 2)), np.zeros((k, 2))   # damp: the viscous part of force
        diss = 0.0
        i = np.flatnonzero(att)
        if i.size:
            ti = tips[i]
            n_x, n_y = nx[i], ny[i]
            a = jkr.radius_from_overlap(delta[i], self.R, self.w, self.E_star)
            Pi = jkr.force_from_radius(a, self.R, self.w, self.E_star)
            vx, vy = v[i, 0], v[i, 1]
            vn = vx * n_x + vy * n_y
            vt = vx * n_y - vy * n_x
            xi = (qx[i] - self.anchor[ti, 0]) * n_y - (qy[i] - self.anchor[ti, 1]) * n_x
            cap = self.params.friction.cap(Pi, self.Fc)
            trial = -self.k_t * xi
            sl = np.abs(trial) > cap
            xi_new = np.where(sl, np.sign(xi) * cap / self.k_t, xi)
            # Return mapping: slide the anchor so the stick spring holds exactly the cap.
            self.anchor[ti, 0] = qx[i] - xi_new * n_y
            self.anchor[ti, 1] = qy[i] + xi_new * n_x
            diss += float(np.sum(0.5 * self.k_t * (xi * xi - xi_new * xi_new)))
            dn = -self.c_n * vn
            dt_ = np.where(sl, 0.0, -self.c_t * vt)
            ft = np.where(sl, -self.k_t * xi_new, trial) + dt_
            fn = Pi + dn
            force[i, 0] = fn * n_x + ft * n_y
            force[i, 1] = fn * n_y - ft * n_x
            damp[i, 0] = dn * n_x + dt_ * n_y
            damp[i, 1] = dn * n_y - dt_ * n_x
            P[i], Ft[i], slip[i] = Pi, ft, sl
            U[i] = jkr.contact_energy(a, self.R, self.w, self.E_star) + 0.5 * self.k_t * xi_new**2
        # Energy bookkeeping at state changes: jump-in starts the branch at U(δ ≥ 0) ≈ 0,
        # snap-off loses what the contact stored.
        diss -= float(np.sum(U[new & att]))
        diss += float(np.sum(self._U_prev[tips[gone]]))
        self.attached[tips] = att
        return {"force": force, "P": P, "Ft": Ft, "U": U, "delta": delta, "slip": slip,
                "new": new, "gone": gone, "diss": diss, "damp": damp}

    def _store_contact(self, tips, out):
        self._P[tips] = out["P"]
        self._Ft[tips] = out["Ft"]
        self._U[tips] = out["U"]
        self._delta[tips] = out["delta"]
        self._slip[tips] = out["slip"]
        self._diss_step += out["diss"]
        self._Fdamp[tips] += out["damp"]
        for i, d in zip(tips[out["gone"]], out["delta"][out["gone"]], strict=True):
            self._events.append((int(i), d))

    def _pair_arrays(self):
        if self._pairs_dirty:
            pairs = np.array(sorted(self._pairs), dtype=np.int64).reshape(-1, 2)
            self._pair_tip, self._pair_seg = pairs[:, 0], pairs[:, 1]
            self._pairs_dirty = False
        return self._pair_tip, self._pair_seg

    def _contact_all(self, x, v):
        """Fast path: the contact of every tip that has a candidate segment, in bulk."""
        pt, ps = self._pair_arrays()
        # Tips that lost every candidate while attached are beyond δc: they let go.
        cand = np.zeros(self.n, dtype=bool)
        cand[pt] = True
        lost = np.flatnonzero(self.attached & ~cand)
        if lost.size:
            self.attached[lost] = False
            self._diss_step += float(np.sum(self._U_prev[lost]))
            self._events.extend((int(i), -np.inf) for i in lost)
        if pt.size == 0:
            return
        if not self.pads and pt.size != np.unique(pt).size:
            # Several candidate segments: keep each tip's nearest floor point.
            delta = self._geometry(ps, x[pt])[4]
            order = np.lexsort((-delta, pt))
            keep = order[np.unique(pt[order], return_index=True)[1]]
            pt, ps = pt[keep], ps[keep]
        out = self._contact(pt, x[pt], v[pt], ps)
        self._F[pt] += out["force"]
        self._store_contact(pt, out)

    # ------------------------------------------------------------------ stepping
    def step(self, plate_velocity):
        """Advance one time step with the plate moving at ``plate_velocity`` (vx, vy) [µm/µs].

        Returns the plate's reaction (force of the setae on the plate) [µN] and the work the
        plate did on the system during the step [pJ].
        """
        dt = self.dt
        vp = np.asarray(plate_velocity, dtype=float)
        self.plate.velocity = (float(vp[0]), float(vp[1]))
        pos, vel, n_rows, rows, seta = self._read()
        self._vel_now = vel
        plate_next = np.array(self.plate.position) + vp * dt
        x = pos + vel * dt                              # where pymunk will evaluate forces
        root = plate_next + self._root_offset
        Fs, Es, strain = self.spring_force(x, root)
        if strain is not None and not self._warned_linear and (
                np.max(strain[:, 0] ** 2 + strain[:, 1] ** 2) > (0.1 * self.L) ** 2):
            self._warned_linear = True
            most = np.sqrt(np.max(strain[:, 0] ** 2 + strain[:, 1] ** 2)) / self.L
            warnings.warn(f"a seta deflected by {most:.2f} L under the linear beam model "
                          "(eq 16–21 assume small deflection); mechanics='rod' stays physical",
                          stacklevel=3)
        Fd = -self.c_seta * (vel - vp)
        self._F = Fs + Fd + self.external_force
        self._P_prev = self._P
        self._P = np.zeros(self.n)
        self._Ft = np.zeros(self.n)
        self._U = np.zeros(self.n)
        self._delta = np.full(self.n, np.nan)
        self._slip = np.zeros(self.n, dtype=bool)
        self._diss_step = 0.0
        self._Fdamp = np.zeros((self.n, 2))
        self._events = []
        if self.contact_path == "batch":
            self._contact_all(x, vel)
        # Write forces in Chipmunk's body order (rows that are not tips get zero).
        out = np.zeros((n_rows, 2))
        out[rows] = self._F[seta]
        self._force_buf.set_float_buf(out.ravel())
        pb.set_space_bodies(self.space, pb.BodyFields.FORCE, self._force_buf)
        if self.contact_path == "callback":
            # Tips that lost their candidate while attached (no pre_solve will come).
            cand = np.zeros(self.n, dtype=bool)
            pt, _ = self._pair_arrays()
            cand[pt] = True
            lost = np.flatnonzero(self.attached & ~cand)
            self.attached[lost] = False
            self._diss_step += float(np.sum(self._U_prev[lost]))
            self._events.extend((int(i), -np.inf) for i in lost)
        self.space.step(dt)
        self.time += dt
        # Energy bookkeeping consistent with semi-implicit Euler: the step's velocity change
        # is F·dt/m, and a force acting during the step moves with the mean velocity.
        self._vel_next = vel + self._F * (dt / self.mass)
        v_mid = 0.5 * (vel + self._vel_next)
        self._diss_step -= float(np.sum(Fd * (v_mid - vp)) + np.sum(self._Fdamp * v_mid)) * dt
        on_plate = np.sum(Fs + Fd, axis=0)      # what the plate pushes on the roots with
        reaction = -on_plate
        work = float(np.dot(0.5 * (on_plate + self._on_plate_prev), vp) * dt)
        self._on_plate_prev = on_plate
        # Release bookkeeping: where a tip began to run away from the plate.
        # A tip following its branch moves slower than the plate; past the fold it runs away.
        speed = np.hypot(vel[:, 0], vel[:, 1])
        v_ref = max(math.hypot(vp[0], vp[1]), 1e-4)
        fast = self.attached & (speed > 2 * v_ref)
        self.jump_overlap = np.where(fast & np.isnan(self.jump_overlap), self._delta,
                                     self.jump_overlap)
        self.jump_overlap[self.attached & (speed < v_ref)] = np.nan
        self._U_prev = np.where(self.attached, self._U, 0.0)
        return reaction, work, Es, x

    def reset_state_arrays(self):
        self._U_prev = np.zeros(self.n)
        self._on_plate_prev = np.zeros(2)
        self._P = np.zeros(self.n)

    # ------------------------------------------------------------------ protocol runner
    def run(self, protocol, *, progress: bool = True, max_steps: int = 50_000_000,
            ke_bound: float | None = None) -> History:
        """Run a protocol (list of :mod:`protocol` segments) and return its :class:`History`.

        Parameters
        ----------
        protocol : list of Move / PressTo / Press / Hold / PullOff segments.
        progress : tqdm progress bar over simulated time.
        max_steps : hard cap on time steps.
        ke_bound : kinetic energy [pJ] beyond which the run is declared unstable (default:
            100 × the adhesion energy of all setae, N·Fc·|δc|, plus the plate work so far).
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
        work = dissipated = 0.0
        last_normal = 0.0
        n_steps = 0
        est = sum(self._estimate_duration(s) for s in segments)
        bar = tqdm(total=est, unit="µs", disable=not progress, desc="gecko_agents",
                   mininterval=0.5, bar_format="{l_bar}{bar}| {n:.0f}/{total:.0f} µs "
                   "[{elapsed}<{remaining}]")
        t_wall = time.perf_counter()
        try:
            for seg in segments:
                state = {"start": np.array(self.plate.position), "t0": self.time, "all_free": None}
                while True:
                    vp, done = self._segment_velocity(seg, state, last_normal)
                    if done:
                        break
                    reaction, dwork, Es, x = self.step(vp)
                    work += dwork
                    dissipated += self._diss_step
                    if self._events:
                        rec.note_events(self)
                    last_normal = float(self._P.sum())
                    n_steps += 1
                    if n_steps % self.record_every == 0 or n_steps == 1:
                        row = rec.record(self, reaction, Es, x, work, dissipated)
                        bound = ke_bound if ke_bound is not None else 100 * (e_scale + abs(work))
                        self._check_stable(row, bound)
                        bar.update(self.time - bar.n)
                    if n_steps >= max_steps:
                        raise RuntimeError(f"max_steps = {max_steps} reached in segment {seg}")
        finally:
            bar.close()
        rec.record(self, reaction, Es, x, work, dissipated)
        wall = time.perf_counter() - t_wall
        meta = {"dt_us": self.dt, "n_steps": n_steps, "record_every": self.record_every,
                "n_sim": self.n, "scale_to_array": self.params.array.count / self.n,
                "protocol": [f"{s!r}" for s in segments], "contact_path": self.contact_path,
                "damping": dataclasses.asdict(self.damping),
                "mass_ng": self.mass, "tangential_stiffness_uN_per_um": self.k_t,
                "wall_time_s": wall, "versions": versions()}
        return rec.history(self, meta)

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

    def _segment_velocity(self, seg, state, normal_force):
        """Plate velocity for the next step of a segment, and whether the segment is over."""
        pos = np.array(self.plate.position)
        dt = self.dt
        if isinstance(seg, Move | PressTo):
            if isinstance(seg, PressTo):
                target = np.array([state["start"][0], self.z_touch - seg.depth])
            else:
                target = state["start"] + np.array([seg.dx, seg.dy])
            rem = target - pos
            dist = math.hypot(*rem)
            if dist <= 1e-12:
                return None, True
            v = rem / dist * seg.speed
            if dist < seg.speed * dt:
                v = rem / dt
            return v, False
        if isinstance(seg, Press):
            if normal_force >= seg.preload:
                return None, True
            frac = (seg.preload - normal_force) / (seg.band * seg.preload)
            return np.array([0.0, -seg.speed * min(1.0, max(frac, 0.02))]), False
        if isinstance(seg, Hold):
            return (np.zeros(2), False) if self.time - state["t0"] < seg.duration - 1e-9 * dt \
                else (None, True)
        # PullOff
        travel = math.hypot(*(pos - state["start"]))
        if seg.max_travel is not None and travel >= seg.max_travel:
            if np.any(self.attached):
                warnings.warn(f"PullOff stopped at max_travel = {seg.max_travel} µm with "
                              f"{int(self.attached.sum())} setae still attached", stacklevel=4)
            return None, True
        if not np.any(self.attached):
            if state["all_free"] is None:
                state["all_free"] = pos.copy()
            elif math.hypot(*(pos - state["all_free"])) >= seg.clearance:
                return None, True
        else:
            state["all_free"] = None
        ang = math.radians(seg.angle_deg)
        return seg.speed * np.array([math.cos(ang), math.sin(ang)]), False

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


class _Recorder:
    """Collects rows every ``record_every`` steps; separate from the stepping."""

    def __init__(self, model: Model):
        self.rows = {c: [] for c in SCALAR_COLUMNS}
        self.per = {f: [] for f in PER_SETA_FIELDS} if model.record_setae else {}
        self.det = {k: [] for k in ("seta", "time_us", "plate_x_um", "plate_y_um",
                                    "overlap_um", "release_overlap_um", "force_uN")}
        self.max_ke = self.max_el = 0.0

    def record(self, m: Model, reaction, Es, x, work, dissipated):
        pos = m.plate.position
        # Kinetic energy at the recorded positions: ½m·v(n−½)·v(n+½), the form that
        # semi-implicit Euler conserves exactly for a linear spring.
        ke = 0.5 * m.mass * float(np.sum(m._vel_now * m._vel_next))
        el = float(np.sum(Es) + np.sum(m._U))
        row = {
            "time_us": m.time, "plate_x_um": pos.x, "plate_y_um": pos.y,
            "force_normal_uN": float(m._P.sum()), "force_tangential_uN": float(m._Ft.sum()),
            "plate_force_x_uN": float(reaction[0]), "plate_force_y_uN": float(reaction[1]),
            "n_attached": int(m.attached.sum()), "n_sliding": int((m._slip & m.attached).sum()),
            "energy_elastic_pJ": el, "energy_kinetic_pJ": ke,
            "energy_dissipated_pJ": dissipated, "work_plate_pJ": work,
        }
        for k, v in row.items():
            self.rows[k].append(v)
        self.max_ke = max(self.max_ke, ke)
        self.max_el = max(self.max_el, el)
        if self.per:
            state = np.where(m.attached, np.where(m._slip, STATE_SLIP, STATE_STICK), STATE_FREE)
            vals = {"tip_x_um": x[:, 0], "tip_y_um": x[:, 1], "force_normal_uN": m._P,
                    "force_tangential_uN": m._Ft, "overlap_um": m._delta,
                    "state": state.astype(np.int8)}
            for f in PER_SETA_FIELDS:
                self.per[f].append(np.array(vals[f]))
        return row

    def note_events(self, m: Model):
        for i, d in m._events:
            self.det["seta"].append(i)
            self.det["time_us"].append(m.time)
            self.det["plate_x_um"].append(m.plate.position.x)
            self.det["plate_y_um"].append(m.plate.position.y)
            self.det["overlap_um"].append(d)
            j = m.jump_overlap[i]
            self.det["release_overlap_um"].append(d if np.isnan(j) else j)
            self.det["force_uN"].append(m._P_prev[i])
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
