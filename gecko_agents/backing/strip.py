"""The elastic strip of a compliant backing: a chain of rigid links in its own pymunk space,
held together by pivot forces solved directly (:mod:`gecko_agents.backing.pivots`) and bent by
joint springs and dampers this module applies (:class:`Strip`), and the bending length that
sets how fine the chain must be.

The bar-chain discretisation of the Euler–Bernoulli beam and its time-step and size limits are
described in :mod:`gecko_agents.backing.elastic`, which builds the strip under the setae. Units: µm,
µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math

import numpy as np
import pymunk
import pymunk.batch as pb

from gecko_agents.backing.pivots import ChainPivots

__all__ = ["Strip", "bending_length", "OMEGA_DT", "MIN_LINKS"]


MIN_LINKS = 4
"""Fewest links of a default chain (a strip shorter than λ bends little, but still bends)."""

OMEGA_DT = 0.5
"""ω·dt of the chain's stiffest mode after mass scaling (semi-implicit Euler is stable < 2)."""

_READ = (
    pb.BodyFields.BODY_ID
    | pb.BodyFields.POSITION
    | pb.BodyFields.ANGLE
    | pb.BodyFields.VELOCITY
    | pb.BodyFields.ANGULAR_VELOCITY
)


def bending_length(EI: float, k_f: float) -> float:
    """Bending length λ = (4EI/k_f)^(1/4) [µm] of a beam of stiffness EI [µN·µm²] on an elastic
    foundation of stiffness k_f [µN/µm²] (Hetényi 1946, Beams on Elastic Foundation, eq 2.4:
    the load spreads over ~λ)."""
    return (4.0 * EI / k_f) ** 0.25


class Strip:
    """A chain of ``n_links`` rigid links in its own pymunk space, held together at their ends
    by pivot forces and bent by rotary springs and dampers, all of which this class applies
    itself (the pivots solved directly, :class:`gecko_agents.backing.pivots.ChainPivots`; the
    joints so that it can book their energy). pymunk integrates the links; its space has no
    constraints.

    Parameters
    ----------
    x0 : abscissa of the left end [µm]. ell : link length [µm]. n_links : number of links.
    y0 : height of the strip's centre line [µm]. EI : bending stiffness [µN·µm²].
    rho_A : mass per length [ng/µm]. zeta : damping ratio of the rotary springs [-].
    angle : the straight strip is turned by this angle [rad] about its centre (x0 + n·ℓ/2, y0),
        counter-clockwise (a misaligned backing); the joints' rest angles stay 0.

    Stepping (:meth:`step`) is pymunk's semi-implicit Euler: positions with the old
    velocities, then velocities with the forces evaluated at the new positions. The joint
    moments are evaluated there too (angles φ + ω·dt), as pymunk's own ``DampedRotarySpring``
    does; its damping, however, is applied implicitly inside the constraint solver's
    iterations, where its dissipation cannot be read. Here each joint carries an explicit
    damper, moment c·(ω_{j+1} − ω_j) from the velocities at the start of the step, and the
    energy it takes out is booked as the moment times the mid-step relative angular velocity
    ½(ω_n + ω_{n+1}) times dt: the form in which semi-implicit Euler's energy identity closes
    (the same rule as the setae's damping in :mod:`gecko_agents.model.step_numpy`). After a step:

    * :attr:`energy_bending` [pJ]: ½·k_r·Σ(φ_{j+1} − φ_j − rest_j)² at the new angles
      (rest angles 0 but where :meth:`kink_up` laid a leader arm);
    * :attr:`kinetic` [pJ]: Σ ½m·v_n·v_{n+1} + ½I·ω_n·ω_{n+1} (the form semi-implicit Euler
      conserves for a linear spring, as
      :meth:`~gecko_agents.model.stepping.Stepping.kinetic_energy`);
    * :attr:`dissipated` [pJ]: the joint dampers' dissipation in the step;
    * ``rows``: the links' (x, y, φ, vx, vy, ω) after the step (those before it in
      ``rows_before``).

    The pivot forces are not booked: they do no work as long as the pivots hold (their gap,
    :attr:`gap_max` [µm] at the positions each step reaches, stays at the one-step curvature
    term, see :mod:`gecko_agents.backing.pivots`).
    """

    def __init__(self, x0, ell, n_links, y0, EI, rho_A, zeta=0.3, angle=0.0):
        if n_links < 1:
            raise ValueError(f"n_links = {n_links!r} must be ≥ 1")
        self.ell, self.n, self.EI, self.rho_A = float(ell), int(n_links), float(EI), float(rho_A)
        self.space = space = pymunk.Space()
        space.gravity = (0.0, 0.0)
        space.iterations = 1  # no constraints in the space: the pivots are solved here
        self.m = m = rho_A * ell
        self.I_link = inertia = m * ell * ell / 12.0
        self.k_rot = EI / ell  # [pJ/rad]
        self.c_rot = 2.0 * zeta * math.sqrt(self.k_rot * inertia)  # [pJ·µs/rad]
        self.k_clamp = 0.0  # rotary spring of a clamped left end (clamp_left) [pJ/rad]
        self.rest = np.zeros(self.n - 1)  # rest angles of the joints [rad] (kink_up)
        self.x_centre = x0 + (np.arange(self.n) + 0.5) * ell  # rest abscissae of link centres
        self.angle = float(angle)
        self.links = []
        for xc in self.x_centre:
            b = pymunk.Body(m, inertia)
            b.position = self._placed(xc, x0, y0)
            b.angle = self.angle
            space.add(b)
            self.links.append(b)
        self.pivots = ChainPivots(self.n, ell)
        self.x0, self.y0 = float(x0), float(y0)
        ids = np.array([b.id for b in self.links], dtype=np.uintp)
        self._id_sorted, self._id_to_link = np.sort(ids), np.argsort(ids)
        self._ids = None
        self._buf = pb.Buffer()
        self._fbuf = pb.Buffer()
        self.out = np.zeros((self.n, 3))
        self.omega_max = math.sqrt(48.0 * EI / (rho_A * ell**4))
        """Stiffest free mode [rad/µs]: the links' zig-zag, ω² = 48·EI/(ρA·ℓ⁴)."""
        self.rows = self.rows_before = self.read()
        self.energy_bending = self.kinetic = self.dissipated = 0.0

    def _placed(self, x, x0, y0) -> tuple[float, float]:
        """Where the point at abscissa ``x`` [µm] of the straight strip is, turned by
        :attr:`angle` about the centre."""
        if not self.angle:
            return float(x), float(y0)
        c = x0 + 0.5 * self.n * self.ell
        return (
            float(c + (x - c) * math.cos(self.angle)),
            float(y0 + (x - c) * math.sin(self.angle)),
        )

    def clamp_left(self):
        """Clamp the left end to the static body: a pivot and the half-link rotary spring
        2EI/ℓ with damping 2c (the cantilever of the module docstring)."""
        self.pivots.clamp(self._placed(self.x0, self.x0, self.y0))
        self.k_clamp = 2.0 * self.k_rot
        self.rows = self.read()

    def kink_up(self, first: int, psi: float) -> None:
        """Turn links ``first``… (of a level strip) by ``psi`` [rad] about their −x node,
        counter-clockwise, stress-free: the joint there gets the rest angle ψ (a leader arm
        laid out at the peel angle)."""
        if self.angle or not 0 < first < self.n:
            raise ValueError(f"kink_up({first}, …) needs a level strip and 0 < first < {self.n}")
        nx, ny = self.x0 + first * self.ell, self.y0
        c, s = math.cos(psi), math.sin(psi)
        for k, b in enumerate(self.links[first:]):
            r = (k + 0.5) * self.ell
            b.position, b.angle = (nx + r * c, ny + r * s), psi
        self.rest[first - 1] = psi
        self.rows = self.read()

    def scale_inertia(self, mass: float = 1.0, moment: float = 1.0) -> None:
        """Multiply every link's mass by ``mass`` and its moment of inertia by ``mass`` ×
        ``moment`` (the dampers keep their damping ratio on the zig-zag mode)."""
        self.m *= mass
        self.rho_A *= mass
        self.I_link *= mass * moment
        self.c_rot *= math.sqrt(mass * moment)
        for b in self.links:
            b.mass, b.moment = self.m, self.I_link
        self.omega_max /= math.sqrt(mass * moment)

    def read(self) -> np.ndarray:
        """(n, 6) rows (x, y, φ, vx, vy, ω) of the links, in link order (read from pymunk)."""
        buf = self._buf
        buf.clear()
        pb.get_space_bodies(self.space, _READ, buf)
        ids = np.frombuffer(buf.int_buf(), dtype=np.uintp)
        if self._ids is None or not np.array_equal(ids, self._ids):
            # Chipmunk's body order is internal: map rows to links through the body ids.
            where = np.minimum(np.searchsorted(self._id_sorted, ids), self.n - 1)
            rows = np.flatnonzero(self._id_sorted[where] == ids)
            order = np.empty(self.n, dtype=np.int64)
            order[self._id_to_link[where[rows]]] = rows
            self._ids, self._order = ids.copy(), order
            self.out = np.zeros((ids.size, 3))
            self._fbuf.set_float_buf(self.out.reshape(-1))
        data = np.frombuffer(buf.float_buf()).reshape(ids.size, 6)
        return data[self._order]

    def _joint_moments(self, d, dt):
        """Moments [pJ] of the joint springs + dampers on the links, from rows ``d`` at the
        start of a step; sets :attr:`energy_bending` and keeps the dampers' moments."""
        phi = d[:, 2] + d[:, 5] * dt  # the angles the step will reach
        bend = np.diff(phi) - self.rest
        self._w_rel = np.diff(d[:, 5])
        self._m_damp = self.c_rot * self._w_rel
        m = self.k_rot * bend + self._m_damp
        tq = np.zeros(self.n)
        tq[:-1] += m
        tq[1:] -= m
        self.energy_bending = 0.5 * self.k_rot * float(bend @ bend)
        if self.k_clamp:
            # The clamp: rotary spring 2k and damper 2c between the static body and link 0.
            self._m_clamp = 2.0 * self.c_rot * d[0, 5]
            turn = phi[0] - self.angle
            tq[0] -= self.k_clamp * turn + self._m_clamp
            self.energy_bending += 0.5 * self.k_clamp * turn**2
        return tq

    def step(self, dt, fx=0.0, fy=0.0, torque=0.0) -> np.ndarray:
        """One step of ``dt`` [µs] under external forces ``fx``, ``fy`` [µN] and torques
        ``torque`` [pJ] on the links (link order, evaluated at the positions the step
        reaches) besides the joints' own and the pivots'; returns ``rows`` after it."""
        d = self.rows
        n = self.n
        fx = np.broadcast_to(np.asarray(fx, dtype=float), n)
        fy = np.broadcast_to(np.asarray(fy, dtype=float), n)
        tq = self._joint_moments(d, dt) + torque
        # Pivot forces from the velocities the step gives without them (pymunk: v⁺ = d·v +
        # dt·f/m, d = damping^dt) at the positions it reaches (x + v·dt).
        damp = self.space.damping**dt
        pos = (d[:, 0] + d[:, 3] * dt, d[:, 1] + d[:, 4] * dt, d[:, 2] + d[:, 5] * dt)
        a, b = dt / self.m, dt / self.I_link
        vel = (damp * d[:, 3] + a * fx, damp * d[:, 4] + a * fy, damp * d[:, 5] + b * tq)
        px, py, ptq = self.pivots.forces(pos, vel, self.m, self.I_link, dt)
        o = self.out
        o[self._order, 0] = fx + px
        o[self._order, 1] = fy + py
        o[self._order, 2] = tq + ptq
        pb.set_space_bodies(self.space, pb.BodyFields.FORCE | pb.BodyFields.TORQUE, self._fbuf)
        self.space.step(dt)
        new = self.read()
        self.rows_before, self.rows = d, new
        self.kinetic = 0.5 * (
            self.m * float(np.sum(d[:, 3:5] * new[:, 3:5]))
            + self.I_link * float(d[:, 5] @ new[:, 5])
        )
        w_mid = 0.5 * (self._w_rel + np.diff(new[:, 5]))
        self.dissipated = float(self._m_damp @ w_mid) * dt
        if self.k_clamp:
            self.dissipated += self._m_clamp * 0.5 * (d[0, 5] + new[0, 5]) * dt
        return new

    @property
    def gap_max(self) -> float:
        """Largest pivot gap [µm] at the positions the last step reached, before its
        correction (the constraint drift)."""
        return self.pivots.gap_max

    @staticmethod
    def points(data, link, s, dt):
        """World positions at t + dt (x + v·dt, φ + ω·dt) and velocities of the material points
        at abscissa ``s`` [µm] from the centres of links ``link`` (rows of :meth:`read`)."""
        # Per link first (fewer links than points), then gathered: the same numbers.
        phi = data[:, 2] + data[:, 5] * dt
        rx, ry = s * np.cos(phi)[link], s * np.sin(phi)[link]
        px = (data[:, 0] + data[:, 3] * dt)[link] + rx
        py = (data[:, 1] + data[:, 4] * dt)[link] + ry
        w = data[link, 5]
        vx = data[link, 3] - w * ry
        vy = data[link, 4] + w * rx
        return px, py, vx, vy, rx, ry

    def nodes(self, data=None) -> tuple[np.ndarray, np.ndarray]:
        """Positions of the n + 1 nodes (link ends) [µm] of rows ``data`` (default: now)."""
        d = self.rows if data is None else data
        h = 0.5 * self.ell
        cx, sy = h * np.cos(d[:, 2]), h * np.sin(d[:, 2])
        x = np.concatenate([d[:, 0] - cx, d[-1:, 0] + cx[-1:]])
        y = np.concatenate([d[:, 1] - sy, d[-1:, 1] + sy[-1:]])
        return x, y
