"""The build step: a run's choices made once, from its parameters and numerics, into one frozen
``Setup`` that the model's parts read.

Each choice comes from a registry, as tip laws do (:data:`gecko_agents.contact.TIP_LAWS`): the
seta mechanics (:data:`MECHANICS`), the backing (:data:`gecko_agents.backing.BACKINGS`, each
class saying what it runs with), the integrator (:data:`INTEGRATORS`) and the per-step kernel
(:data:`gecko_agents.model.setup.KERNELS`). Their compatibility is checked here, once, before
any body is built: a refusal names both choices that do not go together, and a choice that
does not apply (``multirate = True`` where the setae are not independent) is refused, never
ignored.

The derived constants of a seta (its stiffnesses, mass, dampers and the stiffest spring a tip
can meet, eq 16–21 of the source paper, /work/shared/paper notes: Table 1) are named once, in
:class:`SetaConstants`.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from gecko_agents.backing import backing_class
from gecko_agents.contact import ContactLaw, contact_law
from gecko_agents.floor import Profile
from gecko_agents.model.implicit import choose_integrator, implicit_time_step
from gecko_agents.model.mass_damping import DEFAULT_DAMPING, Damping, seta_mass
from gecko_agents.model.mechanics import MECHANICS, Mechanics
from gecko_agents.model.setup import (
    checked_arguments,
    choose_kernel,
    choose_threads,
    detection_mode,
    explicit_time_step,
)
from gecko_agents.model.step_numpy import LoopConstants
from gecko_agents.numerics import Numerics
from gecko_agents.params import SetaArray, check_seed
from gecko_agents.physics import beam
from gecko_agents.protocol import DEFAULT_SPEED

__all__ = [
    "SetaConstants",
    "Setup",
    "build",
    "loop_constants",
    "seta_constants",
]


@dataclass(frozen=True)
class SetaConstants:
    """A seta's derived constants, named once (eq 16–21 of the source paper; damping as
    c = 2ζ√(k·m), :class:`gecko_agents.model.mass_damping.Damping`).

    Attributes
    ----------
    L : seta length [µm]. theta : its angle from the plate [rad]. axis : its unit direction
        (cos θ, −sin θ).
    Ka, Kp : axial and bending stiffness [µN/µm]. K : the linear seta's 2×2 stiffness
        [µN/µm]. k_phi : Kp·L² [pJ/rad²] (the rod's rotary spring).
    mass : the tip's point mass [ng] (:func:`gecko_agents.model.mass_damping.seta_mass`).
    k_t : the law's stick stiffness [µN/µm]. Fc : its pull-off force [µN].
    settle_time : the slowest period of a free seta, 2π√(m/K_y) [µs].
    c_seta, c_n, c_t : seta, normal and tangential dampers [µN·µs/µm].
    k_max : the stiffest spring a tip can meet (seta Ka + contact at 5 Fc + stick) [µN/µm].
    omega_max : √(k_max/m) [1/µs], which sets the explicit step.
    """

    L: float
    theta: float
    axis: np.ndarray
    Ka: float
    Kp: float
    K: np.ndarray
    k_phi: float
    mass: float
    k_t: float
    Fc: float
    settle_time: float
    c_seta: float
    c_n: float
    c_t: float
    k_max: float
    omega_max: float


def seta_constants(params: SetaArray, law: ContactLaw, damping: Damping) -> SetaConstants:
    """The seta's stiffnesses (eq 16–21), mass, damping coefficients and the stiffest spring a
    tip can meet, which sets the time step (units in :class:`SetaConstants`)."""
    s = params.seta
    Ka, Kp = params.axial_stiffness, params.bending_stiffness
    mass = seta_mass(params)
    k_t = law.tangential_stiffness
    # Stiffest spring a tip can meet: seta (Ka) + contact at 5 Fc of compression + stick.
    k_max = Ka + law.stiffest(5 * params.contact.pull_off_force) + k_t
    return SetaConstants(
        L=s.L,
        theta=s.theta,
        axis=np.array([math.cos(s.theta), -math.sin(s.theta)]),
        Ka=Ka,
        Kp=Kp,
        K=beam.stiffness_matrix(Ka, Kp, s.theta),
        k_phi=Kp * s.L**2,
        mass=mass,
        k_t=k_t,
        Fc=law.pull_off_force,
        # Slowest period of a free seta (normal mode, eq 20): the force servo averages over it.
        settle_time=2 * math.pi * math.sqrt(mass / params.Ky),
        c_seta=2 * damping.seta * math.sqrt(params.Ky * mass),
        c_n=2 * damping.normal * math.sqrt(law.zero_load_stiffness * mass),
        c_t=2 * damping.tangential * math.sqrt(k_t * mass),
        k_max=k_max,
        omega_max=math.sqrt(k_max / mass),
    )


@dataclass(frozen=True)
class Setup:
    """A run's choices, made once by :func:`build` (frozen: a run changes its state, never its
    setup).

    Attributes
    ----------
    params, numerics : what was asked. n : setae simulated. seed : the run's seed.
    damping : the :class:`~gecko_agents.model.mass_damping.Damping` ratios.
    floor_profile : a given floor, or None (drawn from ``params.floor``).
    law : the tip's :class:`~gecko_agents.contact.ContactLaw` (:func:`contact_law`).
    mechanics : the :class:`Mechanics` of ``params.mechanics``.
    backing : the backing class of ``params.backing.kind``
        (:data:`gecko_agents.backing.BACKINGS`).
    integrator : "explicit" or "implicit" ("auto" resolved).
    contact : the contact path, "batch" or "callback". detection : "auto", "full" or "lazy".
    pads : the floor is a pad floor (a pad per seta), as the world will build it.
    kernel : the per-step kernel that runs ("auto" resolved); loop : its pad loop (None for
        numpy); loop_threads : the loop's threads.
    seta : the :class:`SetaConstants`.
    dt : the step between events [µs]; default_step : it is the integrator's default.
    event_dt : the implicit step near events [µs], or None (its default).
    record_every : steps between records; record_in_time : records by simulated time (the
        implicit step's default).
    multirate : the implicit step's located steps are multirate
        (:mod:`gecko_agents.model.multirate`).
    """

    params: SetaArray
    numerics: Numerics
    n: int
    seed: int
    damping: Damping
    floor_profile: Profile | None
    law: ContactLaw
    mechanics: Mechanics
    backing: type
    integrator: str
    contact: str
    detection: str
    pads: bool
    kernel: str
    loop: object
    loop_threads: int
    seta: SetaConstants
    dt: float
    default_step: bool
    event_dt: float | None
    record_every: int
    record_in_time: bool
    multirate: bool

    @property
    def fast_pads(self) -> bool:
        """A pad floor with the batch contact path: the case the pad loops cover."""
        return self.pads and self.contact == "batch"

    @property
    def explicit_dt(self) -> float:
        """The explicit step this setup would take [µs] (0.75/ω_max; 0.375/ω_max with crack
        kinetics)."""
        c = self.seta
        return explicit_time_step(None, c.omega_max, c.k_max, c.mass, self.law.rate_dependent)


def build(
    params: SetaArray,
    numerics: Numerics | None = None,
    *,
    n_sim: int | None = None,
    seed=None,
    damping: Damping = DEFAULT_DAMPING,
    floor_profile: Profile | None = None,
) -> Setup:
    """A run's ``Setup`` from its parameters and numerics, every choice checked once
    (arguments as :class:`gecko_agents.model.Model`'s; a refusal names the parameter, its
    value and what it would run with)."""
    numerics = Numerics() if numerics is None else numerics
    if not isinstance(numerics, Numerics):
        raise TypeError(f"numerics must be a Numerics, got {type(numerics).__name__}")
    nu = numerics
    n = checked_arguments(params, n_sim, nu.contact, nu.record_every, nu.kernel, floor_profile)
    mechanics = MECHANICS[params.mechanics]
    backing = backing_class(params.backing.kind)
    integrator = choose_integrator(nu.integrator, nu.contact, mechanics, backing)
    check_kernel(nu.kernel, nu.contact, mechanics, backing)
    threads = choose_threads(nu.threads, n, nu.contact)
    law = contact_law(params)
    seta = seta_constants(params, law, damping)
    dt = time_step(integrator, nu.dt, seta, law.rate_dependent, nu.event_dt)
    pads = pad_floor(params, floor_profile)
    kernel = nu.kernel if backing.loops and mechanics.loops else "numpy"
    fast_pads = pads and nu.contact == "batch"
    kernel, loop, loop_threads = choose_kernel(kernel, fast_pads, n, type(law), threads)
    return Setup(
        params=params,
        numerics=nu,
        n=n,
        seed=run_seed(params, seed),
        damping=damping,
        floor_profile=floor_profile,
        law=law,
        mechanics=mechanics,
        backing=backing,
        integrator=integrator,
        contact=nu.contact,
        detection=detection_mode(nu.detection, nu.contact),
        pads=pads,
        kernel=kernel,
        loop=loop,
        loop_threads=loop_threads,
        seta=seta,
        dt=dt,
        default_step=nu.dt is None,
        event_dt=nu.event_dt,
        record_every=nu.record_every or max(1, round(0.02 / DEFAULT_SPEED / dt)),
        record_in_time=nu.record_every is None,  # the implicit step's default: by time
        multirate=choose_multirate(nu.multirate, integrator, nu.contact, mechanics, backing, pads),
    )


def run_seed(params: SetaArray, seed) -> int:
    """The run's seed: ``seed`` (an integer ≥ 0, checked), one drawn from a
    ``numpy.random.Generator`` (recorded in the history, so the run stays reproducible and
    successive models from one generator differ), or ``params.floor.seed`` (None)."""
    if isinstance(seed, np.random.Generator):
        seed = int(seed.integers(2**63))
    return params.floor.seed if seed is None else check_seed(seed)


def pad_floor(params: SetaArray, floor_profile: Profile | None) -> bool:
    """Whether the world's floor is a pad floor (a pad per seta): a given profile's own
    ``pad_heights``, else a gaussian floor of correlation length 0
    (:func:`gecko_agents.floor.for_array`)."""
    if floor_profile is not None:
        return floor_profile.pad_heights is not None
    fp = params.floor
    return getattr(fp, "kind", "gaussian") == "gaussian" and fp.correlation_length == 0


def check_kernel(kernel: str, contact: str, mechanics: Mechanics, backing) -> None:
    """Refuse a kernel or contact path the mechanics or the backing does not run with, naming
    both choices: the pad loops ("numba", "python") solve the linear and rod setae on the
    rigid plate only; the elastic backings take the batch contact path only."""
    if kernel in ("numba", "python") and not backing.loops:
        raise ValueError(
            f"kernel = {kernel!r}: the {backing.kind} backing (backing.kind = "
            f"{backing.kind!r}) runs with kernel='numpy'"
        )
    if contact not in backing.contacts:
        raise ValueError(
            f"contact = {contact!r}: the {backing.kind} backing (backing.kind = "
            f"{backing.kind!r}) runs with contact='batch'"
        )
    if kernel not in ("auto", "numpy") and not mechanics.loops:
        raise ValueError(
            f"kernel={kernel!r}: mechanics={mechanics.name!r} runs on kernel='numpy' (or 'auto')"
        )
    if mechanics.name not in backing.mechanics:
        raise ValueError(
            f"mechanics = {mechanics.name!r} with backing.kind = {backing.kind!r}: the "
            f"{backing.kind} backing runs with mechanics "
            + " or ".join(repr(m) for m in backing.mechanics)
        )


def time_step(integrator: str, dt, seta: SetaConstants, rate_dependent: bool, event_dt) -> float:
    """The run's step [µs] for its ``integrator``: :func:`explicit_time_step` or
    :func:`gecko_agents.model.implicit.implicit_time_step`. ``event_dt`` [µs], the implicit
    step's near events, is refused for the explicit step (finite and > 0 otherwise)."""
    if event_dt is not None:
        if integrator != "implicit":
            raise ValueError(
                f"event_dt = {event_dt!r} µs sets the implicit step near events; this model "
                f"runs the {integrator} step (integrator = 'implicit' or 'auto' where it is "
                "verified, gecko_agents.model.build.choose_integrator)"
            )
        if not (isinstance(event_dt, int | float) and math.isfinite(event_dt) and event_dt > 0):
            raise ValueError(f"event_dt = {event_dt!r} µs must be finite and > 0")
    if integrator == "implicit":
        return implicit_time_step(dt, seta.omega_max, event_dt)
    return explicit_time_step(dt, seta.omega_max, seta.k_max, seta.mass, rate_dependent)


def choose_multirate(
    multirate, integrator: str, contact: str, mechanics: Mechanics, backing, pads: bool
) -> bool:
    """Whether the implicit step's located steps are multirate
    (:mod:`gecko_agents.model.multirate`): where the setae are independent (the implicit
    step, a rigid backing, a pad floor, the batch contact path, one tip body per seta) unless
    ``multirate`` is False. None: where it applies. True where it does not apply is refused,
    naming the choice that rules it out."""
    if multirate is not None and not isinstance(multirate, bool):
        raise ValueError(f"multirate = {multirate!r} must be True, False or None")
    why = None  # the choice that rules it out, the most basic first
    if not backing.rigid:
        why = (
            f"backing.kind = {backing.kind!r}: the {backing.kind} backing couples the setae "
            "through their roots"
        )
    elif not mechanics.independent:
        why = f"mechanics = {mechanics.name!r}: a seta's chain is not one tip body"
    elif not pads:
        why = (
            "a continuous floor (floor.correlation_length > 0, a self-affine, probe or "
            "measured profile): its contact pairs come from the whole array's space"
        )
    elif contact != "batch":
        why = f"contact = {contact!r}: the callback path adds contact forces after the step's"
    elif integrator != "implicit":
        why = f"integrator = {integrator!r}: only the implicit step locates events"
    if why is not None and multirate:
        raise ValueError(
            f"multirate = True with {why}; multirate steps need independent setae (the "
            "implicit step on a rigid backing over a pad floor): leave multirate at None "
            "(where it applies) or set it False"
        )
    return why is None and multirate is not False


def loop_constants(setup: Setup, dt: float) -> LoopConstants:
    """The per-step kernels' constants record of ``setup`` at the step ``dt`` [µs] (units as in
    :class:`gecko_agents.model.step_numpy.NumpyStep`)."""
    p, c, law = setup.params, setup.seta, setup.law
    K = c.K
    return LoopConstants(
        dt=dt,
        rod=p.mechanics == "rod",
        k00=-K[0, 0],
        k01=-K[0, 1],
        k10=-K[1, 0],
        k11=-K[1, 1],
        L=c.L,
        Ka=c.Ka,
        k_phi=c.k_phi,
        theta=c.theta,
        c_seta=c.c_seta,
        R=p.contact.R,
        detach=law.detach_overlap,
        c_n=c.c_n,
        c_t=c.c_t,
        k_t=c.k_t,
        mu=p.friction.mu,
        paper=p.friction.law == "paper",
        Fc=c.Fc,
        hm=0.5 * dt / c.mass,
        release=law.release_radius,
    )
