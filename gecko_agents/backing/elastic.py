"""A compliant backing: an elastic strip under the setae, pulled through a handle spring.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`); parameters in
:class:`gecko_agents.params.backing.Backing`.

The strip (plane strain, as wide as the row spacing b = ``array.pitch``) is a chain of rigid
links of length ℓ, each a pymunk body of mass m = ρ_b·b·t_b·ℓ [ng] and moment of inertia
mℓ²/12, joined at the nodes by pivot joints and rotary springs (with dampers; both applied by
:class:`Strip` itself, so that their energy is booked) of stiffness

    k_r = EI/ℓ [pJ/rad],   EI = E_b·b·t_b³ / (12(1 − ν_b²)) [µN·µm²]

(the bar-chain discretisation of the Euler–Bernoulli beam, Hencky 1921; a joint's rotation
θ = M·ℓ/EI is the curvature M/EI integrated over one link). A clamped end carries the
half-link stiffness 2EI/ℓ, which makes a cantilever's end deflection under an end load P

    δ = P·ℓ³/EI·[n²/2 + Σ_{m=1}^{n−1} m²] = P·L³/(3EI)·(1 + 1/(2n²))

against Euler–Bernoulli's P·L³/(3EI) (Timoshenko & Gere 1972, Mechanics of Materials, §7.3).
The links are inextensible (the pivots hold them): the axial stiffness E_b·b·t_b/ℓ is 10³–10⁵
times a seta's, so axial springs would only shorten the time step.

Seta roots ride on the links (:class:`ElasticBacking`): the root of seta i sits on link j(i) at
the abscissa it has on a straight strip, so it turns and moves with the link; the seta spring
and damping act between the tip and that root (position and velocity of the root's material
point), and the reaction goes onto the link as a force and a torque. A linear seta keeps its
rest direction in the floor's frame (small strip rotations). The strip is driven through the
handle, the kinematic body that the protocol moves (``World.plate``), by a linear spring of
total stiffness k_h (``drive = "uniform"``: k_h/n on every link centre; ``"peel_end"``: k_h on
the +x end), damped at ``damping_ratio``. With a rigid, stiff strip this is the rigid plate of
the paper (equal load sharing); a soft one concentrates load where it is pulled (Hui,
Glassmaker, Tang & Jagota 2004, J R Soc Interface 1:35; Bacca, Booth, Turner & McMeeking 2016,
J Mech Phys Solids 96:428).

Time step: the chain's stiffest mode is the zig-zag of links turning about their centres,
ω² = 4k_r/I = 48·EI/(ρA·ℓ⁴); the handle spring on a link end adds ω² = k/m_eff with
m_eff = 1/(1/m + (ℓ/2)²/I). The model's time step is set by the setae; when the chain is
stiffer, the links' moment of inertia is scaled up until the zig-zag has ω·dt = 0.5
(rotary-inertia scaling, as explicit beam codes do: bending waves longer than a link,
ω² = EI·q⁴/ρA, keep the true mass), recorded as ``meta["backing"]["moment_scale"]``; then, if
the handle is still too fast, the links' mass (``mass_scale``). Mass scaling is not harmless:
a heavy strip's inertia shares the load it is pulled with (8 setae peeled at 0.05 µm/µs,
β = 0.31: pull-off 0.44 N·Fc with the mass ×105 of whole-link scaling, 0.41 with ×27 for a
1000 µN/µm handle, 0.34 with a 50 µN/µm handle and ×1.4, the same as at a quarter of the
speed); keep the handle no stiffer than it needs to be (≫ k_f·λ for a peel).

Under the implicit step (:mod:`gecko_agents.model.implicit`; its default step shortened to
ω_c·dt ≤ :data:`COUPLING_OMEGA_DT` of the setae on a link,
:meth:`ElasticBacking.coupling_omega`) the strip keeps its own step h, the explicit step the
model would take (:func:`strip_step`), for which its inertia is scaled as above, and sub-cycles
each tips' step dt in k = ⌈dt/h⌉ steps of dt/k before the tips take it
(:meth:`ElasticBacking.roots`): in that step the tips move from x₀ to x₀ + v₀·dt whatever their
forces (semi-implicit Euler), so each sub-step's seta springs pull the root points where the
sub-step takes them towards the tips' point on that path (the dampers' force of the last step
held), and the tips' step then takes its roots where the strip went. Scaled for the long step
instead (ω·dt = 0.5 at dt), the links were 100× heavier and a stiff strip pulled off 14 % above
the rigid plate. Stepped after the tips under their held forces, the strip rang at two steps'
period and diverged in the misalignment study (200 setae; the setae under a link have ω·dt =
1.2–1.3 on its mass): the nearly massless tips follow the strip a step behind, and a velocity
change of the strip returns as a force against the next one, (ω·dt)² times as large.

Energy: the history's energy columns hold the strip too. Elastic = setae + contacts + the
strip's joints + the handle spring; kinetic = tips + links; dissipated = the setae's and
contacts' + the joint dampers + the handle's damper, so that the plate (handle) work balances
them within the history invariant's tolerance (:func:`gecko_agents.history.energy_balance_error`;
measured 0.2–0.3 % of the run's energy in ``tests/test_backing.py``). The dampers' dissipation
is computed from the damping forces and moments this module applies (pymunk's
``DampedRotarySpring`` damps inside the constraint solver, where it cannot be read).

Pivots: the links' ends are held together by pivot forces solved directly each step, one
banded solve, O(n) in the links (:mod:`gecko_agents.backing.pivots`; Baraff 1996), so any
length of strip can be built; pymunk integrates the links, its space has no constraints.
"""

from __future__ import annotations

import math

import numpy as np

from gecko_agents.backing.handle import HandleSpring
from gecko_agents.backing.strip import MIN_LINKS, OMEGA_DT, Strip, bending_length

__all__ = [
    "COUPLING_OMEGA_DT",
    "Strip",
    "ElasticBacking",
    "STRIP_COLUMNS",
    "STRIP_ARRAYS",
    "bending_length",
    "strip_step",
    "OMEGA_DT",
    "MIN_LINKS",
]


STRIP_COLUMNS = ("strip_front_x_um", "strip_setae_force_x_uN", "strip_setae_force_y_uN")
"""Columns the strip adds to ``history.csv`` after
:data:`~gecko_agents.history.SCALAR_COLUMNS`: the detachment front, the material abscissa [µm]
on the straight strip of the attached seta nearest the pulled side (NaN while none is
attached), and the total seta spring + damping force on the tips [µN], the force the setae
pull the strip with, free of the strip's inertia. The force on the handle is the plate's
(``plate_force_*_uN``)."""

STRIP_ARRAYS = ("strip_node_x_um", "strip_node_y_um")
"""Per-record arrays of the strip in ``History.backing`` (``setae.npz``), shape (n_records,
n_links + 1): its nodes (link ends, −x end first) in the floor's frame [µm]. Their material
abscissae [µm] on the straight strip (the roots' frame, the pad centred on 0; a leader arm's
nodes lie beyond ``length_um``/2) are ``History.geometry["strip_node_abscissa_um"]``, the
strip's static figures ``History.meta["backing"]``."""


COUPLING_OMEGA_DT = 1.0
"""Largest ω_c·dt of the implicit step with the strip (:meth:`ElasticBacking.coupling_omega`):
the tips take their roots where the strip went and the strip its forces from where the tips
were, so a link's setae couple explicitly to its mass. Measured (a 30° pad peel's preload, 40
linear setae, 3 per link): stable at ω_c·dt = 1.49 (10 explicit steps), diverging at 2.24 (15)
and 2.98 (20); half the explicit bound ω·dt < 2 keeps a margin, as the explicit step's 0.75."""


def strip_step(setup) -> float:
    """The strip's own step [µs] in a run of ``setup`` (a
    ``gecko_agents.model.build.Setup``, or a :class:`gecko_agents.model.Model`): the run's
    dt with the explicit integrator (the strip steps with the tips); with the implicit one,
    the explicit step the run would take (0.75/ω_max of the tips' stiffest spring,
    ``explicit_dt``), or its dt if shorter. The links' inertia is scaled for this step
    (:class:`ElasticBacking`), and the strip sub-cycles the tips' step in steps no longer than
    it (:meth:`ElasticBacking.roots`)."""
    if setup.integrator != "implicit":
        return setup.dt
    return min(setup.explicit_dt, setup.dt)


def start_turned(world, lift: float, alpha: float) -> None:
    """A misaligned start: raise the handle of ``world`` by ``lift`` [µm] (the strip's lowest
    edge starts where a level strip would) and put every tip at rest below its root on the
    strip turned by ``alpha`` [rad] about the handle."""
    w = world
    pp = w.plate.position
    w.plate.position = (pp.x, pp.y + lift)
    w.plate_start = pp.y + lift
    c, s = math.cos(alpha), math.sin(alpha)
    dx = w.root_dx * (c - 1.0)
    dy = w.root_dx * s + lift
    for body, ddx, ddy in zip(w.tips, dx.tolist(), dy.tolist(), strict=True):
        p = body.position
        body.position = (p.x + ddx, p.y + ddy)


class ElasticBacking:
    """The elastic strip of ``params.backing`` under the setae, held by the handle
    (``world.plate``) through the handle spring; the backing of a
    :class:`gecko_agents.model.Model` with ``params.backing.kind == "elastic"`` (its
    ``model.backing``; the interface is :class:`gecko_agents.backing.rigid.RigidBacking`'s).
    The numpy kernel only; the free approach is stepped (no rigid skip: the strip is not
    rigid).

    Parameters
    ----------
    setup, world, state, physics, spring_force : as
        :class:`gecko_agents.backing.rigid.RigidBacking`'s. ``params.backing.leader_arm``
        [µm] > 0 (with ``drive = "peel_end"``) adds a pre-peeled arm of that length beyond the
        pad's +x edge: links of the same strip with no setae under them, laid out at
        ``params.backing.peel_angle_deg`` from the floor (+x, the pulled side; 90 = straight
        up), stress-free in that shape (the kink's joint has that rest angle); the handle
        holds the arm's end, so pulling the handle along the same angle peels the pad at a
        steady angle (a handle pulled from the end of a flat strip drags it instead).

    Attributes
    ----------
    strip : the :class:`Strip`. info : its static figures (``meta["backing"]``).
    setae_force : (x, y) [µN] total seta spring + damping force on the tips at the last step.
    """

    kind = "elastic"
    rigid = False
    implicit = True
    loops = False
    contacts = ("batch",)
    mechanics = ("linear", "rod", "elastica")

    def __init__(self, setup, world, state, physics, spring_force):
        bk = setup.params.backing  # its leader_arm and peel_angle_deg, checked there
        self.leader_arm, self.peel_angle_deg = float(bk.leader_arm), float(bk.peel_angle_deg)
        self.params, self.world, self.state = setup.params, world, state
        self.physics, self.n, self.spring_force = physics, setup.n, spring_force
        self.Ka = setup.seta.Ka
        self.tips_implicit = setup.integrator == "implicit"  # the tips' step
        self.dt = strip_step(setup)
        self._build_strip()
        self.setae_force = (0.0, 0.0)
        self._roots = (np.zeros(self.n), np.zeros(self.n))
        self._k, self._handle_force = 1, (0.0, 0.0)  # sub-steps of the step (roots)

    def _build_strip(self):
        p, w, bk = self.params, self.world, self.params.backing
        pitch = p.array.pitch
        EI = bk.bending_stiffness(pitch)
        length = self.n * pitch
        k_f = p.Ky / pitch  # the setae as an elastic foundation [µN/µm²]
        lam = bending_length(EI, k_f)
        # Default: the coarsest chain that resolves λ (the stiffest mode ∝ 1/ℓ² sets the mass
        # scaling), and at least MIN_LINKS links.
        spacing = bk.spacing or min(0.25 * lam, length / MIN_LINKS)
        if spacing > 0.25 * lam:
            raise ValueError(
                f"Backing.spacing = {spacing:.4g} µm (0 = the pitch) is too coarse to resolve "
                f"the strip's bending length λ = (4EI/k_f)^(1/4) = {lam:.4g} µm (EI = "
                f"{EI:.4g} µN·µm², k_f = Ky/pitch = {k_f:.4g} µN/µm²): use spacing ≤ λ/4 = "
                f"{0.25 * lam:.4g} µm"
            )
        n_links = max(1, math.ceil(length / spacing - 1e-9))
        ell = length / n_links
        rho_A = bk.density * pitch * bk.t_b
        alpha = math.radians(bk.misalignment_deg)
        if alpha:
            start_turned(self.world, 0.5 * length * abs(math.sin(alpha)), alpha)
        n_arm = math.ceil(self.leader_arm / ell - 1e-9)  # links of the leader arm
        strip = Strip(
            -0.5 * length,
            ell,
            n_links + n_arm,
            w.plate.position.y,
            EI,
            rho_A,
            bk.damping_ratio,
            angle=alpha,
        )
        if n_arm:
            strip.kink_up(n_links, math.radians(self.peel_angle_deg))
        self.handle = HandleSpring(strip, self.world, bk, n_links, n_arm, length, alpha)
        k_each = self.handle.k
        # Rotary inertia first: the zig-zag mode is the links turning about their centres
        # (ω² = 4k_r/I), slowed to ω·dt = OMEGA_DT by the links' moment of inertia alone,
        # which leaves the bending waves longer than a link (ω² = EI·q⁴/ρA) at the true mass.
        moment = max(1.0, (strip.omega_max * self.dt / OMEGA_DT) ** 2)
        strip.scale_inertia(moment=moment)
        # Then the handle spring on a link end, effective mass 1/(1/m + (ℓ/2)²/I) (m/4 for
        # an unscaled link), by the translational mass where it is still too fast.
        m_eff = 1.0 / (1.0 / strip.m + 0.25 * ell**2 / strip.I_link)
        mass = max(1.0, k_each / m_eff * (self.dt / OMEGA_DT) ** 2)
        strip.scale_inertia(mass=mass)
        m_eff *= mass
        # Damping ratio on the link end's effective mass (explicit: c·dt/m_eff = 2ζ·ω·dt).
        self.handle.c = 2.0 * bk.damping_ratio * math.sqrt(k_each * m_eff)
        self.strip = strip
        # Roots: link and abscissa from its centre on a straight strip.
        rx = w.root_dx
        self._r_link = np.clip(((rx + 0.5 * length) // ell).astype(np.int64), 0, n_links - 1)
        self._r_s = rx - strip.x_centre[self._r_link]
        self.geometry = {"strip_node_abscissa_um": -0.5 * length + ell * np.arange(strip.n + 1)}
        """Static arrays for ``History.geometry``: the nodes' abscissae on the straight strip
        [µm] (the roots' frame, the pad centred on 0: a leader arm's nodes lie beyond
        ``length_um``/2)."""
        self.info = {
            "EI_uN_um2": EI,
            "width_um": pitch,
            "length_um": length,
            "n_links": strip.n,
            "pad_links": n_links,
            "leader_arm_um": n_arm * ell,
            "peel_angle_deg": self.peel_angle_deg if n_arm else None,
            "link_um": ell,
            "bending_length_um": lam,
            "foundation_uN_per_um2": k_f,
            "mass_scale": mass,
            "moment_scale": moment,
            "handle_stiffness_each_uN_per_um": k_each,
        }

    # ------------------------------------------------------------------ stepping
    def coupling_omega(self) -> float:
        """ω_c [1/µs] of the setae on the link that carries most of them: √(n·Ka/m), n the
        setae on it, Ka the seta's stiffest spring (its axial stiffness, eq 17; the seta's
        share of the model's ``k_max``) [µN/µm], m the link's mass as scaled [ng]."""
        n = int(np.bincount(self._r_link, minlength=self.strip.n).max())
        return math.sqrt(n * self.Ka / self.strip.m)

    def step_limit(self) -> float | None:
        """The longest step between events the implicit step may take [µs]: the tips follow
        the links a step behind, so ω_c·dt ≤ :data:`COUPLING_OMEGA_DT`; None with the explicit
        step (the strip steps with the tips)."""
        return COUPLING_OMEGA_DT / self.coupling_omega() if self.tips_implicit else None

    def roots(self, hx, hy, vpx, vpy, dt):
        """Where the roots' material points on the links will be at the end of the step and
        how fast they move, as per-seta "plates" for the seta springs (root minus the root
        offset, since :meth:`~gecko_agents.model.step_numpy.NumpyStep.spring_damp` adds it);
        the handle reaches (``hx``, ``hy``) [µm] at the step's end, moving at (``vpx``,
        ``vpy``) [µm/µs], the tips' step ``dt`` [µs]. Where the tips' step is longer than the
        strip's own (the implicit step), the strip takes its sub-steps first (``_subcycle``)
        and the roots are where they took it; else they are predicted, x + v·dt, where the
        strip's step after the tips' (:meth:`advance`) takes them."""
        w, st = self.world, self.strip
        self._k = max(1, math.ceil(dt / self.dt - 1e-9))
        if self._k > 1:
            self._subcycle(dt, self._k, hx, hy, vpx, vpy)
            dt = 0.0
        rx, ry, rvx, rvy, ox, oy = st.points(st.rows, self._r_link, self._r_s, dt)
        self._roots, self._arms = (rx, ry), (ox, oy)
        return rx - w.root_dx, ry - w.root_dy, rvx, rvy

    def _subcycle(self, dt, k, hx, hy, vpx, vpy) -> None:
        """The strip's k sub-steps of ``dt``/k [µs] over the tips' step, before it: the tips
        move from x₀ to x₁ = x₀ + v₀·dt in it whatever their forces (pymunk's semi-implicit
        Euler; ``state.pv``, ``state.xy``), so each sub-step's seta springs pull the root
        points where the sub-step takes them towards the tips' point on that path
        (:meth:`~gecko_agents.model.stepping.Stepping.spring_force`),
        with the seta dampers' force of the
        last step; the handle spring as in :meth:`advance`. Books what :meth:`advance` books
        (the seta dampers' share at the root points' velocities; the handle's share is booked
        by :meth:`advance` with this step's damper forces); keeps the force on the handle."""
        s, st = self.state, self.strip
        nl, link = st.n, self._r_link
        Fdx, Fdy = s.F_damp_seta
        damp = np.bincount(link, Fdx, nl), np.bincount(link, Fdy, nl)
        (x0, y0), (x1, y1) = s.pv[:2], s.xy
        h = dt / k
        for j in range(k):
            a = (j + 1) / k
            rx, ry, _, _, ox, oy = st.points(st.rows, link, self._r_s, h)
            tips = np.column_stack((x0 + a * (x1 - x0), y0 + a * (y1 - y0)))
            F = self.spring_force(tips, np.column_stack((rx, ry)))[0]
            fs = (F[:, 0] + Fdx, F[:, 1] + Fdy)
            back = (k - 1 - j) * h  # the handle's time to the step's end [µs]
            self._handle_force = self._substep(
                h,
                (hx - vpx * back, hy - vpy * back),
                (vpx, vpy),
                (0.0, 0.0),
                (-np.bincount(link, fs[0], nl), -np.bincount(link, fs[1], nl)),
                (ox, oy),
                damp,
                fs,
            )

    def hold(self, state) -> None:
        """Keep the seta spring + damping forces on the tips (``state.F`` before the contacts
        add to it, without the external force): their reaction loads the links."""
        fsx, fsy = state.F[0].copy(), state.F[1].copy()
        if state.external_force.any():
            fsx -= state.external_force[:, 0]
            fsy -= state.external_force[:, 1]
        self._fs = (fsx, fsy)

    def advance(self, dt, hx, hy, vpx, vpy, on_plate):
        """The strip's step after the tips' step ``dt`` [µs], under the setae's reactions and
        the handle spring, the handle at (``hx``, ``hy``) [µm] at the step's end, moving at
        (``vpx``, ``vpy``) [µm/µs]; called after the setae's bookkeeping. Returns the force on
        the handle [µN] (``on_plate``, the setae's pull on a rigid plate, is not it). Where
        the strip took its sub-steps before the tips' step (:meth:`roots`), it only books the
        seta dampers' share and returns the handle's force at the last sub-step.

        Energy: besides the setae's own bookkeeping, the step books the strip's joints
        (:meth:`Strip.step`), the handle spring's energy ½k_h·|Δ|² at the positions the step
        reaches, and the dissipation of the dampers that act on the strip (seta damping and
        the handle's damper), each as force × mid-step velocity of the link it acts on
        (v and ω averaged over the step: the work it does in semi-implicit Euler)."""
        s, st = self.state, self.strip
        fsx, fsy = self._fs
        Fdx, Fdy = s.F_damp_seta
        self.setae_force = (float(fsx.sum()), float(fsy.sum()))
        if self._k > 1:
            # Sub-cycled (roots): the setae's bookkeeping booked this step's seta damping
            # against the handle's velocity; the sub-steps booked it at the roots'.
            self.physics.diss -= (vpx * float(Fdx.sum()) + vpy * float(Fdy.sum())) * dt
            return self._handle_force
        # Reactions on the links: −F at the root (force; its torque r × F in _substep) and
        # the seta dampers' share of it, for their dissipation.
        nl, link = st.n, self._r_link
        f = (-np.bincount(link, fsx, nl), -np.bincount(link, fsy, nl))
        damp = np.bincount(link, Fdx, nl), np.bincount(link, Fdy, nl)
        return self._substep(dt, (hx, hy), (vpx, vpy), (vpx, vpy), f, self._arms, damp, self._fs)

    def _substep(self, dt, handle, vp, vd, f, arms, damp, fs):
        """One step ``dt`` [µs] of the strip, the handle at ``handle`` [µm] at its end moving
        at ``vp`` [µm/µs], the reactions ``f`` (x, y) [µN] on its links (added to in place)
        of the seta forces ``fs`` [µN] on the tips, the roots' lever ``arms`` [µm] and the
        seta dampers' force ``damp`` [µN] on the links; books the dissipation
        (:meth:`advance`; the seta dampers' against the velocity ``vd`` [µm/µs] taken out)
        and returns the force on the handle [µN]."""
        ph, st, s = self.physics, self.strip, self.state
        data = st.rows
        (hx, hy), (vpx, vpy), (fx, fy) = handle, vp, f
        fsx, fsy = fs
        ox, oy = arms
        nl, link = st.n, self._r_link
        tq = -np.bincount(link, ox * fsy - oy * fsx, nl)
        Fdx, Fdy = s.F_damp_seta
        dfx, dfy = damp
        dtq = np.bincount(link, ox * Fdy - oy * Fdx, nl)
        hl = self.handle.link
        Fhx, Fhy, Fcx, Fcy, qox, qoy = self.handle.forces(data, hx, hy, vpx, vpy, fx, fy, tq, dt)
        new = st.step(dt, fx, fy, tq)
        # Mid-step velocities of the links: what a force on a link works against.
        vmx, vmy = 0.5 * (data[:, 3] + new[:, 3]), 0.5 * (data[:, 4] + new[:, 4])
        wm = 0.5 * (data[:, 5] + new[:, 5])
        # Seta damping dissipates −Fd·(v_tip − v_root): the setae's bookkeeping books it
        # against the handle's velocity, the correction moves it onto the roots' (and keeps
        # the release detection's reference speed, the handle's).
        root_power = float(vmx @ dfx + vmy @ dfy + wm @ dtq)
        ph.diss += (root_power - vd[0] * float(Fdx.sum()) - vd[1] * float(Fdy.sum())) * dt
        # The handle's damper: plate work at the handle minus the work done on the link.
        hl_power = float(Fcx @ vmx[hl] + Fcy @ vmy[hl] + (qox * Fcy - qoy * Fcx) @ wm[hl])
        handle_power = vpx * float(Fcx.sum()) + vpy * float(Fcy.sum())
        ph.diss += (handle_power - hl_power) * dt + st.dissipated
        return float(Fhx.sum()), float(Fhy.sum())

    # ------------------------------------------------------------------ state
    def front_x(self) -> float:
        """Detachment front [µm]: root abscissa (straight strip) of the attached seta nearest
        the pulled side (+x for a peel; the outermost attached seta for a uniform pull); NaN
        when none is attached. The strip moves sideways by no more than the setae's
        deflection while setae hold it, so it also marks the front on the drawn strip."""
        att = np.flatnonzero(self.state.attached)
        if not att.size:
            return math.nan
        x = self.world.root_dx[att]
        if self.params.backing.drive == "peel_end":
            return float(x.max())
        return float(x[np.argmax(np.abs(x))])

    def root_positions(self, handle) -> np.ndarray:
        """Root positions (N, 2) [µm] on the links where the last step evaluated the forces
        (``handle``, the handle's position, is not needed)."""
        return np.column_stack(self._roots)

    def energy(self) -> float:
        """Elastic energy of the strip's joints and the handle spring [pJ] at the last step's
        evaluation positions."""
        return self.strip.energy_bending + self.handle.energy

    def kinetic_energy(self, tips: float) -> float:
        """Kinetic energy of the tips (``tips`` [pJ]) and of the strip's links [pJ] (both in
        the form ½m·v(n−½)·v(n+½) of
        :meth:`~gecko_agents.model.stepping.Stepping.kinetic_energy`)."""
        return tips + self.strip.kinetic

    def record(self) -> tuple[dict, dict]:
        """(scalar columns, per-record arrays) at a record: the front and the setae's pull
        (:data:`STRIP_COLUMNS`), the nodes' positions (:data:`STRIP_ARRAYS`)."""
        scalars = dict(zip(STRIP_COLUMNS, (self.front_x(), *self.setae_force), strict=True))
        return scalars, dict(zip(STRIP_ARRAYS, self.strip.nodes(), strict=True))
