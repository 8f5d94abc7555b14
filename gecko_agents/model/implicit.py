"""The linearly implicit step: each tip's force made implicit in its own springs and dampers.
The default integrator where it is verified (``Model(integrator="auto")``,
:func:`check_integrator`).

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`); sign conventions in
:mod:`gecko_agents.contact`.

pymunk integrates every tip with semi-implicit (symplectic) Euler: it moves the tip to
x₁ = x₀ + v₀·dt, where the model evaluates the force F (seta spring and damping relative to
its root, the contact's normal force and damping, the stick spring), then sets
v₁ = v₀ + F·dt/m. Its step is stable for ω·dt < 2 on the stiffest spring a tip meets: the
contact (JKR 12.9 µN/µm at 5 Fc) and the stick spring (7.4 µN/µm) on the paper's 0.36 ng tip,
far stiffer than the seta (Ka 0.50 µN/µm).

The linearly implicit (Rosenbrock–Euler) step evaluates the force where the step ends instead,
linearised: F(x₁ + v₁·dt, v₁) ≈ F + J_x·(v₁·dt) + J_v·Δv with Δv = v₁ − v₀, J_x = ∂F/∂x and
J_v = ∂F/∂v the tip's 2×2 Jacobians (Hairer & Wanner, Solving Ordinary Differential
Equations II, 2nd ed. 1996, §IV.7, the linearly implicit Euler method; for mechanical
systems, Baraff & Witkin 1998, SIGGRAPH '98 "Large steps in cloth simulation", eq 6). Then

    (m·I − dt·J_v − dt²·J_x)·Δv = dt·[F + dt·J_x·(v₀ − v_root)]       (one 2×2 per tip)

with −J_x = K the sum of the seta's stiffness (the linear seta's K of eq 20–21; the rod's
axial Ka·e eᵀ plus rotary kφ/ℓ²·e⊥e⊥ᵀ plus its tension's Ka(ℓ − L)/ℓ·e⊥e⊥ᵀ clamped ≥ 0), the
contact's normal stiffness dP/dδ·n nᵀ (:meth:`gecko_agents.contact.ContactLaw.stiffness`,
clamped to [0, :meth:`~gecko_agents.contact.ContactLaw.stiffest` at 5 Fc, the flat-punch
bound 2E*a of the radius the branch reaches at that load]: past the load-controlled pull-off
it turns negative and at the end of the JKR branch infinite, where a linearisation would nearly make
the 2×2 singular or freeze the tip) and the stick spring k_t·t tᵀ while the tip sticks (the
spatula: its film's full 2×2 tangent with the front held, its
row along the floor 0 while the pad slides, the tip body's Hertz compression and stick
spring, :meth:`gecko_agents.contact.SpatulaTip.jacobian`); −J_v
the seta's, the normal and (while sticking) the tangential dampers. The seta's part acts on
the tip's motion relative to its root (the root moves with the plate), the contact's on its
motion over the fixed floor. The model hands pymunk the force F' = m·Δv/dt, so pymunk's own
v += F'·dt/m, x += v·dt runs unchanged; with J = 0 it is F, today's explicit step. For one
linear spring the step is exactly backward Euler: stable at any dt, first order, and it damps
what rings faster than 1/dt.

Friction. The stick spring's implicit force, the spring and damper at the step's end, may
exceed the Coulomb cap that the kernel's trial force at the step's start obeyed (at the onset
of a slide, or a tip that holds no shear under the paper's cap in tension): there the tip
slides within the step, its friction at the cap (``ImplicitStep._stick_past_cap``), so
a sticking or sliding tip never holds more than the cap.

Energy books. ΔF = F' − F is a force no spring or damper of the model books. The recorder
books the kinetic energy as ½m·v₀·v₁ and the springs at x₁ (semi-implicit Euler conserves that
sum exactly for a linear spring); its change between two steps is then, for linear forces,
exactly ½dt·v₀·(ΔF_prev + ΔF), so the step books that as dissipated: the scheme's numerical
dissipation (the backward-Euler step's damping of what rings faster than 1/dt) plus the
implicit share of the dampers' work, cumulative in ``ImplicitStep.numerical_dissipated``
and ``meta["implicit_dissipated_pJ"]``. Events, as in the explicit step, change a tip's force
within one step, an error ∝ dt in the books (:data:`gecko_agents.history.ENERGY_RTOL`), k
times the explicit one at a k times longer step: a snap-off's share is booked
(:meth:`ImplicitStep.book_releases`), a jump-in's is not.

Event location. Near an event
(:meth:`~gecko_agents.model.event_steps.EventSteps.substeps`) the runner takes k steps of
dt/k, each no longer than :data:`IMPLICIT_EVENT_FACTOR` explicit steps, so the event and its
share of the books are resolved as the explicit step resolves them; a change of step is
booked exactly (``ImplicitStep._switch_term``). Every body steps with one dt (pymunk), so one
tip's event shortens the whole array's step. With the default ``record_every`` the runner
records by simulated time (:mod:`gecko_agents.model.runner`). What locates a rough array's
steps, the criteria measured and not taken, and the records' spacing: docs/physics.md, "Event
location"; the step's accuracy: :data:`IMPLICIT_DT_FACTOR` and :data:`IMPLICIT_EVENT_FACTOR`.
"""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.backing import backing_class
from gecko_agents.model.event_steps import (
    FREE_RINGING_SHARE,
    IMPLICIT_EVENT_FACTOR,
    IMPLICIT_TRAVEL,
    EventSteps,
    default_event_dt,
    whole_event_steps,
)
from gecko_agents.model.implicit_kernel import clip, pad_solver, past_cap, solve, step_books
from gecko_agents.model.mechanics import MECHANICS, Mechanics
from gecko_agents.physics.friction import friction_cap
from gecko_agents.protocol import DEFAULT_SPEED

__all__ = [
    "INTEGRATORS",
    "IMPLICIT_DT_FACTOR",
    "IMPLICIT_EVENT_FACTOR",
    "IMPLICIT_TRAVEL",
    "FREE_RINGING_SHARE",
    "ImplicitStep",
    "check_integrator",
    "choose_integrator",
    "implicit_time_step",
    "whole_event_steps",
]

INTEGRATORS = ("explicit", "implicit", "auto")

IMPLICIT_DT_FACTOR = 20.0
"""Default implicit step in units of the explicit one (0.75/ω_max) [-], chosen by accuracy, not
stability: the work-precision benchmark (``python -m gecko_agents.bench --work-precision``, one
seta against the explicit step at dt/2) keeps every case within 0.5 % of the reference and its
energy books within :data:`gecko_agents.history.ENERGY_RTOL` at it. The measured table is in
the documentation (explanation, "Performance"); ``tests/test_integrator_convergence.py`` pins
the errors. At the default plate speed :data:`IMPLICIT_TRAVEL` caps it
(:func:`implicit_time_step`)."""


def choose_integrator(integrator, contact: str, mechanics: Mechanics, backing) -> str:
    """The integrator a run takes: ``integrator`` if it is one of
    ``INTEGRATORS`` and goes with the rest; ``"auto"`` is the
    implicit step where it is verified (the batch contact path, a mechanics with its
    Jacobian, a backing measured with it: docs/physics.md, "Time stepping"), the explicit one
    elsewhere. The implicit step is refused, naming both choices, where it is not verified."""
    verified = contact == "batch" and mechanics.jacobian and backing.implicit
    if integrator == "auto":
        return "implicit" if verified else "explicit"
    if integrator not in INTEGRATORS:
        raise ValueError(f"integrator = {integrator!r} must be one of {INTEGRATORS}")
    if integrator == "implicit" and contact != "batch":
        raise ValueError(
            f"integrator = 'implicit' needs contact = 'batch', got {contact!r} (the callback "
            "path adds contact forces after the step's): use 'explicit' or 'auto'"
        )
    if integrator == "implicit" and not mechanics.jacobian:
        raise ValueError(
            f"integrator = 'implicit' with mechanics = {mechanics.name!r}: the implicit step "
            "has no Jacobian of the chain; mechanics = 'elastica' runs with integrator = "
            "'explicit' (or 'auto')"
        )
    if integrator == "implicit" and not backing.implicit:
        raise ValueError(
            f"integrator = 'implicit' with backing.kind = {backing.kind!r}: the {backing.kind} "
            "backing runs with the explicit step (integrator 'explicit' or 'auto'; "
            f"gecko_agents.backing.{backing.kind} says why)"
        )
    return integrator


def check_integrator(integrator, contact: str, params=None) -> str:
    """:func:`choose_integrator` for a model of ``params`` (None: linear setae on the rigid
    plate)."""
    mechanics = MECHANICS["linear" if params is None else params.mechanics]
    backing = backing_class("rigid" if params is None else params.backing.kind)
    return choose_integrator(integrator, contact, mechanics, backing)


def implicit_time_step(dt, omega_max: float, event_dt=None) -> float:
    """The implicit step's dt [µs]: ``dt`` if given (finite, > 0: no stability bound), else
    :data:`IMPLICIT_DT_FACTOR` explicit steps 0.75/ω_max (ω_max [1/µs] of the stiffest spring
    on the tip) or, where that exceeds :data:`IMPLICIT_TRAVEL` of plate travel at the default
    plate speed (:data:`gecko_agents.protocol.DEFAULT_SPEED`), the most whole steps near an
    event (``event_dt`` [µs], default :data:`IMPLICIT_EVENT_FACTOR` explicit steps) within it
    (the travel itself if not one fits), so that the steps near events are as long as allowed,
    not a fraction shorter: where an event falls within the step moves the books' event error
    (a stubby Hertz seta's press-pull at 0.2 µm/µs recorded every step: 2.2 % at 0.1070 µs,
    4.2 % at 0.1053 µs, as the explicit step's 2.5 % and 5.0 %)."""
    if dt is None:
        dt = IMPLICIT_DT_FACTOR * (0.75 / omega_max)  # the explicit steps
        cap = IMPLICIT_TRAVEL / DEFAULT_SPEED
        if dt > cap:
            event = default_event_dt(omega_max) if event_dt is None else event_dt
            dt = whole_event_steps(cap, event) if cap >= event else cap
        return dt
    if not (isinstance(dt, int | float) and math.isfinite(dt) and dt > 0):
        raise ValueError(f"dt = {dt!r} µs must be finite and > 0 (integrator = 'implicit')")
    return float(dt)


class ImplicitStep(EventSteps):
    """The implicit correction of a model's step (see the module docstring).

    Parameters
    ----------
    model : the :class:`gecko_agents.model.Model` (its law, seta stiffnesses, mass, dampers,
        state and physics are read every step).
    default_step : the model's dt is the default :func:`implicit_time_step`, which fast
        segments shorten (:meth:`begin_segment`); a dt the caller chose stands.
    event_dt : the longest step near an event [µs] (default :data:`IMPLICIT_EVENT_FACTOR`
        explicit steps); at or above the model's dt nothing is located.
    """

    def __init__(self, model, default_step: bool = False, event_dt=None):
        self.m = model
        law = model.law
        self.k_cap = float(law.stiffest(5 * model.params.contact.pull_off_force))
        self.normal = None  # (2, N) contact normals of a continuous floor (NumpyStep.contact)
        self.numerical_dissipated = 0.0  # cumulative work of F' − F [pJ]
        n = model.n
        self.dt_full = model.dt  # the step between events [µs]
        self.dt_base = model.dt  # the segment's step between events [µs] (begin_segment)
        self.default_step = default_step  # the step of implicit_time_step(None, …)
        # Near an event: k steps of dt/k, no longer than IMPLICIT_EVENT_FACTOR explicit
        # steps 0.75/ω_max, or the caller's event_dt [µs].
        event = default_event_dt(model.omega_max) if event_dt is None else event_dt
        self.k_event = max(1, math.ceil(model.dt / event - 1e-9))
        self.n_located = 0  # steps taken at dt/k near events
        self.start_books(n, model.dt)
        # A film tip's (the spatula's) contact stiffness is a full 2×2: its kxy [µN/µm].
        self.film = bool(law.film)
        self._pad = False  # the compiled pad kernels (implicit_kernel.pad_solver; not yet)
        # The run's energy scale so far [pJ] (note_energies; the runner resets it per run).
        self.energy_scale = 0.0
        self.near = None  # the setae near an event at the last located step (substeps)

    def for_setae(self, model, books: dict, dt: float) -> ImplicitStep:
        """:meth:`EventSteps.for_setae`, on the numpy kernels (the setae's own pool)."""
        step = super().for_setae(model, books, dt)
        step._pad = False
        return step

    def seta_stiffness(self, rx, ry):
        """The seta's stiffness K = −J_x (kxx, kxy, kyx, kyy) [µN/µm], scalars for the
        linear seta, (N,) arrays for the rod with its root at (rx, ry) + root offset [µm]."""
        m = self.m
        if m.params.mechanics == "linear":
            K = m.K
            return K[0, 0], K[0, 1], K[1, 0], K[1, 1]
        s, w = m.state, m.world
        dx = s.xy[0] - rx - w.root_dx
        dy = s.xy[1] - ry - w.root_dy
        ell = np.sqrt(dx * dx + dy * dy)
        ex, ey = dx / ell, dy / ell
        ka = m.Ka
        # Rotary spring kφ/ℓ² across the rod plus its tension Ka(ℓ − L)/ℓ (clamped ≥ 0).
        kp = m.k_phi / (ell * ell) + np.maximum(ka * (ell - m.L) / ell, 0.0)
        kxy = (ka - kp) * ex * ey
        return ka * ex * ex + kp * ey * ey, kxy, kxy, ka * ey * ey + kp * ex * ex

    def contact_stiffness(self):
        """Normal stiffness k_n [µN/µm] and stick stiffness k_t [µN/µm] of every tip (0 where
        free; k_t 0 where sliding), and the contact dampers c_n, c_t
        [µN·µs/µm] likewise."""
        m = self.m
        s, law = m.state, m.law
        att = s.attached
        kn, kt = self._kn, self._kt
        kn.fill(0.0)
        kt.fill(0.0)
        if self.film:  # the film's off-diagonal stiffness, 0 where free
            self._kxy.fill(0.0)
        idx = att.nonzero()[0]
        k_raw = np.full(att.shape, np.nan)
        if idx.size:
            k = law.stiffness(s.a[idx], s.delta[idx])
            finite = np.isfinite(k)
            k_raw[idx] = np.where(finite, k, -np.inf)
            if self.film:  # the film's own tangent, its front held (SpatulaTip.jacobian)
                kxx, kxy, kyy = law.jacobian(
                    s.xy[0, idx] - s.anchor[0, idx],
                    s.delta[idx],
                    s.s0[idx],
                    s.xi[idx],
                    s.a[idx],
                    s.p0[idx],
                )
                kn[idx], kt[idx] = kyy, kxx
                self._kxy[idx] = kxy
            else:
                kn[idx] = clip(np.where(finite, k, 0.0), 0.0, self.k_cap)
                kt[idx] = np.where(s.slip[idx], 0.0, m.k_t)
        with np.errstate(invalid="ignore"):
            self._k_rate = (k_raw - self._k_raw) / m.dt
        self._k_raw = k_raw
        cn = np.where(att, m.c_n, 0.0)
        if law.tangential and law.damp_sliding:
            ct = np.where(att, m.c_t, 0.0)
        else:
            ct = np.where(kt > 0.0, m.c_t, 0.0)
        return kn, kt, cn, ct

    def correct(self, roots, rebook_damping: bool = False) -> float:
        """Replace ``state.F`` by F' = m·Δv/dt of the linearly implicit step; ``roots`` are
        (rx, ry, rvx, rvy), the seta springs' plate (scalars or (N,) arrays, as
        :meth:`gecko_agents.backing.rigid.RigidBacking.roots`). Returns the energy to book as
        dissipated [pJ]: the work of F' − F on the tips over the step and, with
        ``rebook_damping`` (the per-seta loop booked its dampers at the explicit mid-step
        velocity), the dampers' work on the difference, −dt·Σ F_damp·(F' − F)·dt/(2m)."""
        m = self.m
        s, dt, mass = m.state, m.dt, m.mass
        if self._pad is False:  # the compiled solve where it applies (its first step)
            self._pad = pad_solver(m, self)
        pad = self._pad
        K = self.seta_stiffness(roots[0], roots[1]) if pad is None else None
        kn, kt, cn, ct = self.contact_stiffness()
        vx, vy = s.pv[2], s.pv[3]
        switch = self._switch_term(vx, vy, dt)
        fx, fy = self._solve(K, kn, kt, cn, ct, roots, s.F)
        capped = self._stick_past_cap(fx, fy, kt, ct)
        if capped is not None:  # those tips slide this step, their friction at the cap
            fx, fy = self._solve(K, kn, kt, cn, ct, roots, capped)
        # Work of ΔF = F' − F between the recorder's books at the previous step and this one,
        # ½dt·v₀·(ΔF_prev + ΔF): they book ½m·v₀·v₁, whose change is ½dt·v₀·(F'_prev + F').
        # F := F', and J the impulse of the forces the books pair with the next step's dt.
        books = step_books if pad is None else pad[2]
        e, ed = books(
            vx,
            vy,
            fx,
            fy,
            s.F,
            self._dF,
            s.F_damp_seta,
            s.F_damp_contact,
            self._J,
            dt,
            rebook_damping,
        )
        work = 0.5 * dt * float(np.add.reduce(e))  # np.sum's reduction
        self.numerical_dissipated -= work
        if rebook_damping:
            work += float(np.add.reduce(ed)) * (0.5 * dt / mass) * dt
        self._dt_prev = dt
        return switch - work

    def _solve(self, K, kn, kt, cn, ct, roots, F):
        """F' [µN] (two (N,) arrays) of the linearly implicit step from the explicit forces
        ``F`` (2, N) [µN], the seta's stiffness ``K`` (:meth:`seta_stiffness`), the contact's
        stiffnesses and dampers (:meth:`contact_stiffness`) and the ``roots``
        (rx, ry, rvx, rvy): one 2×2 solve per tip (module docstring); with ``K`` None, the
        same arithmetic compiled (:mod:`gecko_agents.model.implicit_kernel`)."""
        m = self.m
        s, dt, mass = m.state, m.dt, m.mass
        if K is None:
            return solve(self._pad, self, kn, kt, self._kxy, cn, ct, roots, F)
        kxx, kxy, kyx, kyy = K
        vx, vy = s.pv[2], s.pv[3]
        wx, wy = vx - roots[2], vy - roots[3]  # motion relative to the root
        # Seta part: K·(v − v_root).
        gx = kxx * wx + kxy * wy
        gy = kyx * wx + kyy * wy
        if self.normal is None:  # pad floor: n = (0, 1), t = (1, 0)
            gx += kt * vx
            gy += kn * vy
            axx = 1.0 + (dt / mass) * (m.c_seta + ct) + (dt * dt / mass) * (kxx + kt)
            ayy = 1.0 + (dt / mass) * (m.c_seta + cn) + (dt * dt / mass) * (kyy + kn)
            axy = (dt * dt / mass) * kxy
            ayx = (dt * dt / mass) * kyx
            if self.film:  # the film's off-diagonal stiffness (symmetric)
                q = self._kxy
                gx += q * vy
                gy += q * vx
                axy = axy + (dt * dt / mass) * q
                ayx = ayx + (dt * dt / mass) * q
        else:  # n the contact normal, t = (n_y, −n_x)
            nx, ny = self.normal
            cxx = cn * nx * nx + ct * ny * ny
            cxy = (cn - ct) * nx * ny
            cyy = cn * ny * ny + ct * nx * nx
            qxx = kn * nx * nx + kt * ny * ny
            qxy = (kn - kt) * nx * ny
            qyy = kn * ny * ny + kt * nx * nx
            gx += qxx * vx + qxy * vy
            gy += qxy * vx + qyy * vy
            h, h2 = dt / mass, dt * dt / mass
            axx = 1.0 + h * (m.c_seta + cxx) + h2 * (kxx + qxx)
            ayy = 1.0 + h * (m.c_seta + cyy) + h2 * (kyy + qyy)
            axy = h * cxy + h2 * (kxy + qxy)
            ayx = h * cxy + h2 * (kyx + qxy)
        Fx, Fy = F
        bx = Fx - dt * gx
        by = Fy - dt * gy
        det = axx * ayy - axy * ayx
        return (ayy * bx - axy * by) / det, (axx * by - ayx * bx) / det

    def _stick_past_cap(self, fx, fy, kt, ct):
        """The explicit forces to solve again [µN] ((2, N), a copy of ``state.F``), or None:
        sticking tips whose implicit friction would exceed the Coulomb cap slide this step.

        While a tip sticks, its friction in F' is the stick spring and damper at the step's
        end, f = F_t − dt·k_t·v₁ − c_t·(v₁ − v₀) along the tangent (v₁ = v₀ + F'·dt/m,
        F' = (``fx``, ``fy``) [µN]), not the kernel's F_t at the step's start: past
        the onset of a slide f exceeds the cap that F_t still obeyed (by k_t·dt·v₁, 4 % of
        μ|P + 2Fc| on a dragged rod seta at 10 explicit steps), and a tip that may hold no
        shear (the paper's cap μ·max(P, 0) in tension) would hold k_t·dt·v₁. Where |f| > cap
        (:func:`gecko_agents.physics.friction.friction_cap` of the kernel's P), the kernels'
        return mapping (:mod:`gecko_agents.model.step_numpy`) applies to f instead: the tip
        slides, its friction is ±cap (the sign of f), without stick spring or damper in the
        Jacobian (``kt``, ``ct`` [µN/µm, µN·µs/µm] zeroed in place), and it is recorded as
        sliding at that force. The kernel's anchor is kept: the next step's return mapping
        slides it and books its Coulomb work; F' − F is booked as every step's. Laws that
        take the tip's tangential position (the spatula) keep their own friction."""
        m = self.m
        s, law = m.state, m.law
        if law.tangential:
            return None
        if self._pad is not None and not past_cap(self._pad, m, fx, fy, kt, ct):
            return None  # the compiled test (most steps: no tip past its cap)
        i = (kt > 0.0).nonzero()[0]
        if not i.size:
            return None
        h = m.dt / m.mass
        vx, vy = s.pv[2, i], s.pv[3, i]
        if self.normal is None:  # pad floor: t = (1, 0)
            tx, ty = 1.0, 0.0
        else:  # the contact normal n, t = (n_y, −n_x)
            tx, ty = self.normal[1, i], -self.normal[0, i]
        v0t = vx * tx + vy * ty
        v1t = v0t + (fx[i] * tx + fy[i] * ty) * h
        f = s.Ft[i] - m.dt * kt[i] * v1t - ct[i] * (v1t - v0t)
        c = m.constants
        cap = friction_cap(s.P[i], c.Fc, c.mu, c.paper)
        past = np.abs(f) > cap
        if not past.any():
            return None
        j = i[past]
        ft = np.copysign(cap[past], f[past])
        F = s.F.copy()
        dft = ft - s.Ft[j]
        if self.normal is None:
            F[0, j] += dft
        else:
            F[0, j] += dft * self.normal[1, j]
            F[1, j] -= dft * self.normal[0, j]
        kt[j] = 0.0
        ct[j] = 0.0
        s.Ft[j] = ft
        s.slip[j] = True
        return F

    def _switch_term(self, vx, vy, dt) -> float:
        """Energy to book when the step changes from ``dt_prev`` to ``dt`` [pJ]: the recorder's
        kinetic energy ½m·v(n−1)·v(n) changes over a step by ½v(n)·(J(n) + J(n+1)), J the
        impulses F'·dt of the two steps, while every other book (springs at the new position,
        dampers, F' − F) takes both at the new step's dt; the difference
        ½v(n)·F'(n)·(dt_prev − dt) is booked as dissipated (0 at a constant step)."""
        if np.ndim(self._dt_prev) == 0 and dt == self._dt_prev:
            return 0.0
        J = self._J
        Fdt = J * (dt / self._dt_prev)  # F'(n)·dt (per seta after a multirate step)
        out = -0.5 * float(np.add.reduce(vx * (J[0] - Fdt[0]) + vy * (J[1] - Fdt[1])))
        self.numerical_dissipated += out
        return out

    def book_releases(self, events) -> float:
        """Energy to book as dissipated for the tips that let go this step [pJ]: ``events``
        (seta, overlap, last normal force P [µN]) as ``physics.events``. The recorder's
        kinetic energy ½m·v₀·v₁ credits a force switched off at a snap-off with half its
        last value over the step (the trapezoid ½(P_prev + 0)·Δx); the contact's stored
        energy is dissipated at the new position, so the books miss −½·P·(n·v₀)·dt, the work
        of the force the tip last felt over the step's displacement n·v₀·dt. It is ∝ dt, as
        the explicit step's own event error (:data:`gecko_agents.history.ENERGY_RTOL`), which
        this implicit step, ten times longer, books instead of leaving."""
        s, dt = self.m.state, self.m.dt
        out = 0.0
        for i, _, P in events:
            vn = s.pv[3, i] if self.normal is None else s.pv[2:4, i] @ self.normal[:, i]
            out -= 0.5 * P * vn * dt
        return out
