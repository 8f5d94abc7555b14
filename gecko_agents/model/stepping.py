"""One time step of a :class:`gecko_agents.model.Model`'s world and what it reads back: the
seta springs, the tip contacts, pymunk's step, the backing's, the plate's reaction and work,
and the energies the recorder books. :class:`Stepping` is the part of :class:`Model` that steps;
the model's construction, configuration and runs are in :mod:`gecko_agents.model`.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from gecko_agents._stack import user_stacklevel
from gecko_agents.model.step_loop import PadArrays, PlateStep
from gecko_agents.physics import beam

__all__ = ["Stepping"]


class Stepping:
    """Stepping and the readings of a step, for :class:`gecko_agents.model.Model` (which
    builds every attribute these methods use: ``state``, ``world``, ``physics``, ``backing``,
    ``law``, the stiffnesses and the step ``dt``).

    After each step: ``reaction`` (the plate's, [µN]), ``work_step`` (the plate's work over the
    step [pJ]), ``on_plate_prev`` (the setae's pull on the plate [µN]), ``plate_next`` (the
    plate where the step evaluated forces [µm]); ``warned_linear``: a seta deflected beyond
    0.1 L under the linear beam model (warned once)."""

    def spring_force(self, x, root):
        """Seta spring force on the tips [µN], elastic energies [pJ] and (linear) deflections.

        Parameters
        ----------
        x : tip positions (N, 2) [µm]. root : root positions (N, 2) [µm].
        """
        d = x - root
        if self.params.mechanics == "linear":
            u = d - self.L * self.axis
            return (*beam.linear_spring_force(u, self.K), u)
        if self.physics.chain is not None:
            return (*self.physics.chain.peek(d), None)
        return (*beam.rod_spring_force(d, self.L, self.Ka, self.k_phi, self.theta), None)

    def spring_energies(self) -> np.ndarray:
        """Elastic energy of every seta [pJ] at the last step's evaluation positions (as
        :meth:`spring_force`'s, without its forces)."""
        root = self.backing.root_positions(self.plate_next)
        if self.physics.chain is not None:  # the elastica's chain
            return self.spring_force(self.state.xy.T, root)[1]
        dx, dy = self.state.xy - root.T
        if self.params.mechanics == "linear":
            ux, uy = self.L * self.axis
            return beam.linear_spring_energy(dx - ux, dy - uy, self.K)
        return beam.rod_spring_energy(dx, dy, self.L, self.Ka, self.k_phi, self.theta)

    def backing_energy(self) -> float:
        """Elastic energy of the backing [pJ] (0 for the rigid plate)."""
        return self.backing.energy()

    def contact_energies(self) -> np.ndarray:
        """Energy stored in each contact at the last step (0 for free tips) [pJ]."""
        U = np.zeros(self.n)
        idx = self.state.attached.nonzero()[0]
        if idx.size:
            U[idx] = self.physics.contact_energy(idx)
        return U

    def kinetic_energy(self) -> float:
        """Kinetic energy of the tips and the backing at the recorded positions [pJ]:
        ½m·v(n−½)·v(n+½), the form that semi-implicit Euler conserves exactly for a linear
        spring."""
        v = self.state.pv[2:4]
        dv = self.state.F * (self.dt / self.mass)
        tips = 0.5 * self.mass * float(np.add.reduce(v * (v + dv), None))
        return self.backing.kinetic_energy(tips)

    def damping_half_step(self) -> float:
        """Share of the dampers' work [pJ] to add to the dissipated energy a record books:
        ½dt·Σ F_d·v(n+½), F_d the setae's and contacts' damping forces of the last step [µN]
        and v(n+½) = v + F·dt/m. The step books the dampers' work at the mid-step velocity,
        F_d(n)·½(v(n−½) + v(n+½))·dt, while :meth:`kinetic_energy`'s ½m·v(n−½)·v(n+½) changes
        by ½v(n−½)·(F(n−1) + F(n))·dt; the two differ by a sum that telescopes to this term,
        so the books balance at every record, also while a released seta rings down (where
        −½dt·c·v² reached 5 % of a punch's energy), not only once the motion has stopped
        (semi-implicit Euler's discrete energy identity, Hairer, Lubich & Wanner 2006,
        Geometric Numerical Integration, §I.1). 0 under the implicit step, whose books of
        F' − F and of the dampers (:meth:`~gecko_agents.model.implicit.ImplicitStep.correct`)
        close its own step."""
        if self.implicit_step is not None:
            return 0.0
        s = self.state
        v_next = s.pv[2:4] + s.F * (self.dt / self.mass)
        Fd = s.F_damp_seta + s.F_damp_contact
        return 0.5 * self.dt * float(np.add.reduce(Fd * v_next, None))

    def overlaps(self) -> np.ndarray:
        """Overlap δ of every tip with a candidate floor at the last step, NaN elsewhere."""
        if self.fast_pads:
            return np.where(self.state.candidate_step, self.state.delta, np.nan)
        return self.state.delta.copy()

    # ------------------------------------------------------------------ stepping
    def _pre_solve(self, i, body):
        """Reference path: the contact force of one tip, computed and applied per contact."""
        pos = body.position
        s = self.state
        fx, fy = self.physics.contact(
            np.array([i]),
            np.array([pos.x]),
            np.array([pos.y]),
            s.pv[2, i : i + 1],
            s.pv[3, i : i + 1],
            np.array([i]),
        )
        body.force = (body.force.x + float(fx[0]), body.force.y + float(fy[0]))

    def advance(self, vpx: float, vpy: float) -> None:
        """One time step with the plate (handle) at velocity (``vpx``, ``vpy``) [µm/µs]; leaves
        the step's reaction, work and dissipation in ``reaction`` [µN],
        ``work_step`` [pJ] and ``physics.diss`` [pJ], the tips that let go in
        ``physics.events`` (:meth:`pop_releases`). The backing (:attr:`backing`) gives the
        roots the setae pull on and steps after the tips."""
        dt, s, ph, w, bk = self.dt, self.state, self.physics, self.world, self.backing
        w.plate.velocity = (vpx, vpy)
        pp = w.plate.position
        pnx, pny = pp.x + vpx * dt, pp.y + vpy * dt
        self.plate_next = (pnx, pny)
        ph.events = []
        ph.diss = 0.0
        if self.loop is not None:
            opx, opy = self._advance_loop(pnx, pny, vpx, vpy)
        else:
            w.read()
            x, y = s.xy
            np.multiply(s.pv[2], dt, out=x)
            x += s.pv[0]  # where pymunk will evaluate forces
            np.multiply(s.pv[3], dt, out=y)
            y += s.pv[1]
            roots = bk.roots(pnx, pny, vpx, vpy, dt)
            opx, opy = ph.spring_damp(*roots)
            bk.hold(s)
            if self.params.mechanics == "linear":
                self._check_linear(ph.max_u2)
            if self.fast_pads:
                ph.contact_pads()
            elif self.contact_path == "batch":
                ph.contact_general()
            else:
                s.F_damp_contact.fill(0.0)
                s.delta.fill(np.nan)
                ph.any_contact_damping = True
            if self.implicit_step is not None:
                ph.diss += self.implicit_step.correct(roots)
            w.write_forces(s.F)
            if self.contact_path == "callback":
                # Tips that lost their candidate while attached (no pre_solve will come).
                np.copyto(s.candidate_step, s.candidate)
                ph.lost(s.candidate_step)
        if w.pads and (self.loop is None or self.loop_results[6] > w.pad_slack):
            w.recentre_pads(s.xy[0])
        w.step(dt)
        self.time += dt
        if self.loop is None:
            ph.bookkeeping(vpx, vpy)
        if self.implicit_step is not None and ph.events:
            ph.diss += self.implicit_step.book_releases(ph.events)
        opx, opy = bk.advance(dt, pnx, pny, vpx, vpy, (opx, opy))
        ppx, ppy = self.on_plate_prev
        self.work_step = (0.5 * (opx + ppx) * vpx + 0.5 * (opy + ppy) * vpy) * dt
        self.on_plate_prev = (opx, opy)
        self.reaction = (-opx, -opy)

    def _advance_loop(self, pnx, pny, vpx, vpy):
        s, w, ph = self.state, self.world, self.physics
        data = w.read_raw()
        np.copyto(s.candidate_step, s.candidate)
        res = self.loop_results
        ext = s.external_force
        arrays = PadArrays(
            data,
            w.order,
            w.out,
            w.h,
            s.candidate_step,
            s.attached,
            s.slip,
            s.block,
            ext,
            w.pad_centre,
            ph.rest,
            ph.root,
            self.lost_idx,
            self.gone_idx,
            res,
        )
        plate = PlateStep(pnx, pny, vpx, vpy, max(math.hypot(vpx, vpy), 1e-4), bool(ext.any()))
        self.loop(arrays, plate, self.constants, self.law.constants)
        if self.implicit_step is not None:
            ph.diss += self.implicit_step.correct((pnx, pny, vpx, vpy), rebook_damping=True)
            w.write_forces(s.F)
        else:
            w.write_forces()
        ph.diss += float(res[2])
        n_lost, n_gone = int(res[3]), int(res[4])
        if n_lost or n_gone:
            lost, gone = self.lost_idx[:n_lost].copy(), self.gone_idx[:n_gone].copy()
            d, P = s.delta, s.P
            ph.events.extend((int(i), -np.inf, float(P[i])) for i in lost)
            ph.events.extend((int(i), float(d[i]), float(P[i])) for i in gone)
            idx = np.concatenate([lost, gone])
            P[idx] = 0.0
            s.Ft[idx] = 0.0
            s.slip[idx] = False
        if not self.constants.rod:
            self._check_linear(float(res[5]))
        ph.any_contact_damping = True
        return float(res[0]), float(res[1])

    def pop_releases(self) -> list:
        """The tips that let go in the last step (``physics.events``), each as (seta, overlap
        [µm], release overlap [µm], force [µN]): the release overlap is where the tip started
        to run away from its equilibrium (its overlap at the step if it never did); the force
        is the law's at δ_detach for a tip that passed it
        (:meth:`~gecko_agents.contact.base.ContactLaw.release_force`, not the step's
        overshoot), else its last force. Clears
        those tips' release marks (``state.jump``), so each release is reported once."""
        jump = self.state.jump
        located = self.law.release_force()
        out = []
        for i, d, force in self.physics.events:
            j = jump[i]
            if -math.inf < d < self.law.detach_overlap and not math.isnan(located):
                force = located
            out.append((i, d, d if np.isnan(j) else float(j), force))
            jump[i] = np.nan
        return out

    def _check_linear(self, max_u2):
        if max_u2 > (0.1 * self.L) ** 2 and not self.warned_linear:
            self.warned_linear = True
            warnings.warn(
                f"a seta deflected by {math.sqrt(max_u2) / self.L:.2f} L under the linear beam "
                "model (eq 16–21 assume small deflection); mechanics='rod' stays physical",
                stacklevel=user_stacklevel(),
            )

    def step(self, plate_velocity):
        """Advance one time step with the plate moving at ``plate_velocity`` (vx, vy) [µm/µs].

        Returns the plate's reaction (force of the setae on the plate) [µN], the work the
        plate did on the system during the step [pJ], the elastic energy of every seta [pJ]
        and the tip positions (N, 2) at which the forces were evaluated [µm].
        """
        vx, vy = (float(v) for v in plate_velocity)
        self.advance(vx, vy)
        return (
            np.array(self.reaction),
            self.work_step,
            self.spring_energies(),
            self.state.xy.T.copy(),
        )

    def reset_state_arrays(self):
        """Start the energy and force bookkeeping afresh (as at the start of :meth:`run`)."""
        self.on_plate_prev = (0.0, 0.0)
        self.state.P[:] = 0.0
        # Nothing stored in the contacts counts as dissipated at a first-step snap-off.
        self.state.a[:] = self.law.jump_radius
        self.state.xi[:] = 0.0
