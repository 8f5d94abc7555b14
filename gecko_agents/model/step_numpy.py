"""The per-step force computation of the time-stepped model.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`); sign conventions in
:mod:`gecko_agents.contact`.

Every step, all forces are computed at the positions pymunk is about to integrate velocities
with (x + v·dt): the seta spring (``linear``: −K·u with eq 20–21's 2×2 stiffness; ``rod``: a
rigid rod on a rotary spring Kp·L² plus an axial spring Ka,
``gecko_agents.physics.beam.rod_spring_force``),
damping relative to the plate, and the contact (the normal force of the tip law,
:mod:`gecko_agents.contact`; a stick spring with a Coulomb cap tangentially). Two ways:

* :class:`NumpyStep` — vectorized over setae; any floor, and the per-contact reference path;
* :func:`gecko_agents.model.step_loop.pad_loop` — pad floors: the same formulas and the same
  order of operations as one loop over setae, compiled with numba when installed
  (``kernel="numba"``) or run by the interpreter (``kernel="python"``, the fastest for a handful
  of setae). Built once per contact law by a factory; both give the numpy path's history to
  rounding.

Stick/slip (return mapping): the trial stretch ξ of the stick spring k_t is the tip's
tangential displacement from its anchor (on a continuous floor: the tip centre's displacement
along the floor's tangent, ``FloorContact._trial_stretch``); if k_t|ξ| exceeds the cap, the
anchor slides so that the spring holds exactly the cap, and the slip |ξ − ξ_new| dissipates
the Coulomb work cap·|ξ − ξ_new|.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from gecko_agents.model.face_opening import FaceOpening
from gecko_agents.model.step_floor import FloorContact
from gecko_agents.model.step_pads import PadContact

__all__ = ["LoopConstants", "NumpyStep"]


class LoopConstants(NamedTuple):
    """Fixed scalars of the per-seta loop (units as in :class:`NumpyStep`)."""

    dt: float
    rod: bool
    k00: float  # −K[0, 0] … −K[1, 1] [µN/µm] (linear seta)
    k01: float
    k10: float
    k11: float
    L: float
    Ka: float
    k_phi: float  # Kp·L² [pJ/rad²]
    theta: float
    c_seta: float
    R: float
    detach: float  # δ below which a tip lets go [µm]
    c_n: float
    c_t: float
    k_t: float
    mu: float
    paper: bool  # friction cap μ·max(P, 0) (eq 27) instead of μ|P + 2Fc|
    Fc: float
    hm: float  # dt / (2m) [µs/ng]
    release: float  # a rate-dependent tip lets go at a ≤ this radius [µm]


class NumpyStep(PadContact, FloorContact):
    """Vectorized forces of one step on a :class:`~gecko_agents.model.state.SetaState`.

    Parameters
    ----------
    c : :class:`LoopConstants`. law : the :class:`~gecko_agents.contact.ContactLaw`.
    state : per-seta state. world : the :class:`~gecko_agents.model.world.World` (floor geometry).
    K : the linear seta's 2×2 stiffness [µN/µm]. friction : ``params.friction``.
    """

    def __init__(self, c: LoopConstants, law, state, world, K, friction):
        self.c, self.law, self.s, self.world, self.K, self.friction = (
            c,
            law,
            state,
            world,
            K,
            friction,
        )
        n = state.n
        self.tmp = np.zeros((6, n))
        self.root = np.vstack([world.root_dx, world.root_dy])
        self.rest = np.vstack([world.rest_dx, world.rest_dy])
        self.any_contact_damping = False
        self.diss = 0.0  # energy dissipated in the current step [pJ]
        self.events = []  # (seta, overlap, force) of the tips that let go this step
        self.max_u2 = 0.0  # largest |u|² of a linear seta this step [µm²]
        self.chain = None  # the elastica of mechanics="elastica" (physics.elastica.Elastica)
        self.holds_tip = law.flat_face  # a bonded flat face keeps the tip's direction
        # contact.edge_opening: the faces' detachment moves with their moment (face_opening)
        self.opening = FaceOpening(law, n) if getattr(law, "edge_opening", False) else None
        # (2, N): each tip's contact normal at its last contact step (NumpyStep.contact's
        # stick spring carries ξ over from it; the implicit step reads it).
        self.normal = np.zeros((2, n))
        self.normal[1] = 1.0

    # ------------------------------------------------------------------ seta springs
    def spring_damp(self, pnx, pny, vpx, vpy):
        """Seta spring + damping into ``state.F``; returns their sums (the force on the
        plate's setae) [µN]."""
        s, c = self.s, self.c
        x, y = s.xy
        Fx, Fy = s.F
        t0, t1 = self.tmp[0], self.tmp[1]
        if self.chain is not None:
            dx, dy = s.u
            np.subtract(x, pnx, out=dx)
            dx -= self.world.root_dx
            np.subtract(y, pny, out=dy)
            dy -= self.world.root_dy
            held = s.attached if self.holds_tip else False
            if self.opening is not None:  # an opened face no longer holds its direction
                held = held & ~self.opening.opened
            F = self.chain.solve(np.column_stack([dx, dy]), held)[0]
            self.diss += self.chain.released  # a bonded face let go: its clamp's energy
            if self.opening is not None:
                self.opening.update(self.chain.face_moment())
            Fx[:], Fy[:] = F[:, 0], F[:, 1]
        elif not c.rod:
            ux, uy = s.u
            np.subtract(x, pnx, out=ux)
            ux -= self.world.rest_dx
            np.subtract(y, pny, out=uy)
            uy -= self.world.rest_dy
            K = self.K
            np.multiply(ux, -K[0, 0], out=Fx)
            np.multiply(uy, -K[0, 1], out=t0)
            Fx += t0
            np.multiply(ux, -K[1, 0], out=Fy)
            np.multiply(uy, -K[1, 1], out=t0)
            Fy += t0
            np.multiply(ux, ux, out=t0)
            np.multiply(uy, uy, out=t1)
            t0 += t1
            self.max_u2 = float(t0.max())
        else:
            dx, dy = s.u
            np.subtract(x, pnx, out=dx)
            dx -= self.world.root_dx
            np.subtract(y, pny, out=dy)
            dy -= self.world.root_dy
            ell, dphi, t2 = self.tmp[2], self.tmp[3], self.tmp[4]
            np.multiply(dx, dx, out=ell)
            np.multiply(dy, dy, out=t0)
            ell += t0
            np.sqrt(ell, out=ell)
            np.arctan2(dy, dx, out=dphi)
            dphi += c.theta + math.pi
            np.remainder(dphi, 2 * math.pi, out=dphi)
            dphi -= math.pi
            # F = −Ka(ℓ − L)·e − (kφ·Δφ/ℓ)·e⊥, e = d/ℓ, e⊥ = (−e_y, e_x)
            np.subtract(ell, c.L, out=t0)
            t0 *= -c.Ka
            t0 /= ell  # −Ka(ℓ − L)/ℓ
            np.multiply(dphi, c.k_phi, out=t1)
            t1 /= ell
            t1 /= ell  # kφ·Δφ/ℓ²
            np.multiply(t0, dx, out=Fx)
            np.multiply(t1, dy, out=t2)
            Fx += t2
            np.multiply(t0, dy, out=Fy)
            np.multiply(t1, dx, out=t2)
            Fy -= t2
        vx, vy = s.pv[2], s.pv[3]
        Fdx, Fdy = s.F_damp_seta
        np.subtract(vx, vpx, out=Fdx)
        Fdx *= -c.c_seta
        np.subtract(vy, vpy, out=Fdy)
        Fdy *= -c.c_seta
        if self.chain is not None:
            self._damp_across(Fdx, Fdy)
        Fx += Fdx
        Fy += Fdy
        on_plate = (float(Fx.sum()), float(Fy.sum()))
        if s.external_force.any():
            s.F += s.external_force.T
        return on_plate

    def _damp_across(self, Fdx, Fdy):
        """The elastica's damper across its rest axis n: c_seta·(Kp/Ky)^½, critical for the
        bending mode as c_seta is for the axial one (one isotropic damper overdamps a pillar's
        bending by √(Ka/Kp) ≈ L/r and stalls its buckling). Along n it stays c_seta."""
        nx, ny = self.chain_axis
        along = Fdx * nx + Fdy * ny
        across_x, across_y = Fdx - along * nx, Fdy - along * ny
        f = self.chain_damping_ratio - 1.0
        Fdx += f * across_x
        Fdy += f * across_y

    # ------------------------------------------------------------------ contact
    def contact_energy(self, idx):
        """Energy stored in the contacts of tips ``idx`` [pJ]: tip law + stick spring (a
        tangential law keeps its own in ``state.uc``)."""
        if self.law.tangential:
            return self.s.uc[idx]
        xi = self.s.xi[idx]
        return self.law.energy(self.s.a[idx], self.s.delta[idx]) + 0.5 * self.c.k_t * xi * xi

    def detach(self, lost, gone, delta):
        """Tips that let go this step: ``lost`` (no candidate floor left, overlap −∞) and
        ``gone`` (overlap past δ_detach). Books the energy their contacts stored as dissipated."""
        s = self.s
        idx = np.concatenate([lost, gone])
        self.events.extend((int(i), -np.inf, float(s.P[i])) for i in lost)
        self.events.extend((int(i), float(delta[i]), float(s.P[i])) for i in gone)
        self.diss += float(np.sum(self.contact_energy(idx)))
        s.attached[idx] = False
        s.P[idx] = 0.0
        s.Ft[idx] = 0.0
        s.slip[idx] = False

    def lost(self, cand):
        """Tips that lost every candidate while attached are beyond δ_detach: they let go."""
        lost = np.flatnonzero(self.s.attached & ~cand)
        if lost.size:
            self.detach(lost, lost[:0], self.s.delta)

    def bookkeeping(self, vpx, vpy):
        """Damping dissipation and the release bookkeeping, once the forces are known."""
        s, c = self.s, self.c
        vm = self.tmp[0:2]
        np.multiply(s.F, c.hm, out=vm)
        vm += s.pv[2:4]  # mid-step velocity ½(v + v_next)
        Fd = s.F_damp_seta
        # −dt·[Σ Fd·(v_mid − vp) + Σ F_contact_damping·v_mid]. (Products and sums rather than
        # np.dot/vdot: BLAS threads that spin-wait on a busy machine cost milliseconds.)
        prod = self.tmp[3:5]
        if self.any_contact_damping:
            np.add(Fd, s.F_damp_contact, out=prod)
            prod *= vm
        else:
            np.multiply(Fd, vm, out=prod)
        sm = float(prod.sum()) - vpx * float(Fd[0].sum()) - vpy * float(Fd[1].sum())
        self.diss -= sm * c.dt
        # Release bookkeeping: where a tip began to run away from the plate.
        # A tip following its branch moves slower than the plate; past the fold it runs away.
        att = s.attached
        if not att.any():
            return
        v_ref = max(math.hypot(vpx, vpy), 1e-4)
        s2 = self.tmp[2]
        vx, vy = s.pv[2], s.pv[3]
        np.multiply(vx, vx, out=s2)
        s2 += vy * vy
        fast = s2 > 4.0 * v_ref * v_ref
        fast &= att
        jump = s.jump
        jn = np.isnan(jump)
        set_ = fast & jn
        if set_.any():
            jump[set_] = s.delta[set_]
        if not jn.all():
            slow = s2 < v_ref * v_ref
            slow &= att
            jump[slow] = np.nan
