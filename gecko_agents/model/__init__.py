"""The time-stepped agent model: setae on a moving plate over a rough floor, in pymunk.

Units: µm, µN, µs, ng (:mod:`gecko_agents.params`); a seta's mass is then O(0.1–1). Sign
conventions: :mod:`gecko_agents.contact` and ``docs/physics.md``.

:class:`Model` is a façade: :func:`gecko_agents.model.build` makes every choice of the
run once (a frozen ``gecko_agents.model.build.Setup``, compatibility checked there), the
model assembles the parts from it and runs a protocol once into a History; the pieces live in
their own modules:

* :mod:`gecko_agents.model.world` — the pymunk space (tips, plate, floor, collision events,
  batch I/O);
* :mod:`gecko_agents.model.state` — per-seta state as named arrays;
* :mod:`gecko_agents.contact` — the tip law (JKR sphere by default), chosen by ``params.tip``;
* :mod:`gecko_agents.model.step_numpy`, :mod:`gecko_agents.model.step_loop` — the per-step
  forces (numpy, or one loop compiled by numba);
* :mod:`gecko_agents.backing` — what holds the seta roots (``model.backing``, chosen by
  ``params.backing.kind``): the rigid plate, or an elastic strip pulled through a handle spring;
* :mod:`gecko_agents.protocol` — what the plate does; :mod:`gecko_agents.model.recorder` — what is
  recorded into a :class:`~gecko_agents.history.History`.

Contact state machine per tip: free → attached when the overlap δ ≥ δ_attach (0 for the JKR
sphere: it jumps in, no long-range force), attached → free when δ < δ_detach (δc, the end of the
JKR branch). A soft seta leaves its equilibrium earlier (at the fold of the spring–contact
system, see :mod:`gecko_agents.quasistatic`) and then runs to δc by itself; the overlap where
its tip started to jump away is recorded as ``release_overlap_um``.

:meth:`Model.run` skips the free approach: while no tip is attached and every tip follows the
plate at rest relative to it (a free seta's dynamics do not depend on where it is), the plate
and tips are moved rigidly up to where the first sensor would reach the floor.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from gecko_agents.floor import Profile
from gecko_agents.history import History
from gecko_agents.model.build import SetaConstants, Setup, build, loop_constants
from gecko_agents.model.free_travel import skip_free_travel
from gecko_agents.model.implicit import ImplicitStep
from gecko_agents.model.mass_damping import DEFAULT_DAMPING, Damping, seta_mass
from gecko_agents.model.multirate import Multirate
from gecko_agents.model.runner import SimulationUnstable, run_protocol
from gecko_agents.model.setup import KERNELS, numba_available
from gecko_agents.model.state import SetaState
from gecko_agents.model.step_numpy import NumpyStep
from gecko_agents.model.stepping import Stepping
from gecko_agents.model.world import World
from gecko_agents.numerics import BACKING_OPTIONS, Numerics, older_spellings, split_options
from gecko_agents.params import SetaArray
from gecko_agents.physics.elastica import Elastica

__all__ = [
    "Damping",
    "Model",
    "Numerics",
    "SimulationUnstable",
    "numba_available",
    "seta_mass",
    "KERNELS",
]


class Model(Stepping):
    """A pymunk world of ``n_sim`` setae on a kinematic plate above a rough floor.

    Parameters
    ----------
    params : the array. ``params.array.count`` is the physical array; the model simulates
        ``n_sim`` setae of it (default: all of them; refused above ``array.count`` or
        ``gecko_agents.model.setup.MAX_N``) in one row at
        ``params.array.pitch`` and reports ``scale = count / n_sim`` in the metadata.
    seed : seed of the run's single ``numpy.random.Generator`` (default ``params.floor.seed``):
        an integer ≥ 0 (Python or numpy; bool, float and str are refused, naming ``seed``), or
        a ``numpy.random.Generator`` from which the seed is drawn (recorded in the history).
    numerics : how the run is computed (:class:`Numerics`: integrator, dt, event_dt,
        record_every, kernel, contact path, detection, threads); default ``Numerics()``. Its
        fields were keyword arguments of ``Model`` itself: those spellings still work, with a
        DeprecationWarning, until 0.3.
    damping : :class:`Damping` ratios.
    record_setae : also record per-seta arrays (needed for animations).
    floor_profile : a given floor (:class:`gecko_agents.floor.Profile`, e.g. a measured
        surface from :func:`gecko_agents.floor.from_profile`) instead of one drawn from
        ``params.floor``.
    verbose : print the chosen time step.

    Attributes
    ----------
    setup : the run's ``gecko_agents.model.build.Setup`` (its choices and the seta's
        constants, also attributes of the model by their names: ``mass``, ``K``, ``Fc``, …).
    backing : what holds the seta roots, built from ``params.backing``
        (:mod:`gecko_agents.backing`): the rigid plate, an elastic strip or layer.
    implicit_step : the :class:`~gecko_agents.model.implicit.ImplicitStep`, or None.
    multirate : the :class:`~gecko_agents.model.multirate.Multirate` step, or None.
    constants : the per-step kernels' constants record (at the current ``dt``).
    """

    energy_complete = True
    """Whether the energy columns book every energy of the world (plate work = elastic +
    kinetic + dissipated); a model with parts whose energy it does not book says False and
    its histories skip the energy-balance invariant."""

    def __init__(
        self,
        params: SetaArray,
        *,
        n_sim: int | None = None,
        seed: int | None = None,
        numerics: Numerics | None = None,
        damping: Damping = DEFAULT_DAMPING,
        record_setae: bool = False,
        floor_profile: Profile | None = None,
        verbose: bool = False,
        **older,
    ):
        params, numerics = older_spellings(params, numerics, older)
        setup = build(
            params,
            numerics,
            n_sim=n_sim,
            seed=seed,
            damping=damping,
            floor_profile=floor_profile,
        )
        self.setup = setup
        self.params, self.numerics, self.n, self.seed = params, numerics, setup.n, setup.seed
        self.contact_path, self.integrator = setup.contact, setup.integrator
        self.rng = np.random.default_rng(self.seed)
        self.damping = damping
        self.record_setae = record_setae
        self.law = setup.law
        for f in dataclasses.fields(SetaConstants):  # the seta's constants, by their names
            setattr(self, f.name, getattr(setup.seta, f.name))
        self.dt = setup.dt
        if verbose:
            print(
                f"gecko_agents: {self.integrator} step dt = {self.dt:.4g} µs (ω_max·dt = "
                f"{self.omega_max * self.dt:.2f}; explicit stable below 2)"
            )
        self.record_every, self.record_in_time = setup.record_every, setup.record_in_time
        self.state = SetaState(self.n)
        self.world = World(
            params,
            self.n,
            self.state,
            self.mass,
            params.contact.R + abs(self.law.detach_overlap),
            self.rng,
            floor_profile,
            setup.detection,
        )
        self.constants = loop_constants(setup, self.dt)
        self.physics = NumpyStep(
            self.constants, self.law, self.state, self.world, self.K, params.friction
        )
        if self.contact_path == "callback":
            self.world.on_pre_solve(self._pre_solve)
        self._set_step_parts(setup)
        self.fast_pads = setup.fast_pads
        self.kernel, self.loop, self.loop_threads = setup.kernel, setup.loop, setup.loop_threads
        self._start_books()
        self.backing = setup.backing(setup, self.world, self.state, self.physics, self.spring_force)
        limit = self.backing.step_limit()
        if self.implicit_step is not None and limit is not None:
            self.implicit_step.limit_step(limit)
        self.multirate = Multirate(self) if setup.multirate else None

    def _start_books(self) -> None:
        """The clock, the step's scratch arrays and the books a run starts from."""
        self.time = 0.0
        self._ran = False
        self.warned_linear = False
        self.lost_idx = np.zeros(self.n, dtype=np.int64)
        self.gone_idx = np.zeros(self.n, dtype=np.int64)
        self.loop_results = np.zeros(7)
        self.plate_next = (0.0, self.world.plate_start)
        self.reaction = (0.0, 0.0)
        self.work_step = 0.0
        self.reset_state_arrays()

    @classmethod
    def from_options(cls, params: SetaArray, **options) -> Model:
        """A model from one flat set of keyword options: :class:`Numerics` fields (``dt``,
        ``integrator``, …), ``params.backing`` fields (``leader_arm``, ``peel_angle_deg``) and
        the model's own arguments (``n_sim``, ``seed``, …), for helpers and run files that
        pass options through."""
        num, rest = split_options(options)
        backing = {k: rest.pop(k) for k in BACKING_OPTIONS if k in rest}
        if backing:
            params = params.replace(backing=backing)
        numerics = rest.pop("numerics", None) or Numerics()
        return cls(params, numerics=numerics.replace(**num), **rest)

    def _set_step_parts(self, setup: Setup) -> None:
        """The implicit step (``implicit_step``, :class:`ImplicitStep`, where chosen) and the
        elastica's chains."""
        self.implicit_step = None
        if self.integrator == "implicit":
            self.implicit_step = ImplicitStep(
                self, default_step=setup.default_step, event_dt=setup.event_dt
            )
            if not self.world.pads:  # the contact normals NumpyStep.contact keeps
                self.implicit_step.normal = self.physics.normal
        if setup.mechanics.name == "elastica":
            params = setup.params
            self.physics.chain = Elastica.of(params, self.n)
            self.physics.chain_axis = self.axis
            self.physics.chain_damping_ratio = math.sqrt(self.Kp / params.Ky)

    # Older private spellings, kept for code written against them.
    @property
    def _implicit(self):
        return self.implicit_step

    @property
    def _multirate(self):
        return self.multirate

    @property
    def _constants(self):
        return self.constants

    # ------------------------------------------------------------------ public state
    @property
    def plate(self):
        """The plate's pymunk body (kinematic)."""
        return self.world.plate

    @property
    def plate_position(self) -> tuple[float, float]:
        """Plate (x, y) [µm]."""
        pos = self.world.plate.position
        return pos.x, pos.y

    @property
    def attached(self) -> np.ndarray:
        """Which tips are attached (bool (N,))."""
        return self.state.attached

    @property
    def external_force(self) -> np.ndarray:
        """Extra force on each tip (N, 2) [µN] (probing and tests); the plate does not see it."""
        return self.state.external_force

    @property
    def explicit_dt(self) -> float:
        """The explicit step this model would take [µs] (0.75/ω_max; 0.375/ω_max with crack
        kinetics): the elastic strip's own step under the implicit step."""
        return self.setup.explicit_dt

    @property
    def event_dt(self) -> float:
        """The step near events [µs]: the implicit step's located step, or dt."""
        return self.dt if self.implicit_step is None else self.implicit_step.event_dt

    @property
    def profile(self) -> Profile:
        """The floor under the array."""
        return self.world.profile

    @property
    def deepest(self) -> float:
        """Deepest plate height a press may reach [µm]: −(L + R), the root a seta length and a
        tip radius below the floor's mean plane, seta and tip wholly under it."""
        return -(self.L + self.params.contact.R)

    @property
    def z_touch(self) -> float:
        """Plate height at which a resting tip touches the floor's mean plane h = 0 [µm]."""
        return self.world.z_touch

    @property
    def plate_start(self) -> float:
        """Plate height at the start of a run [µm]."""
        return self.world.plate_start

    @property
    def root_dx(self) -> np.ndarray:
        """Root abscissae relative to the plate [µm]."""
        return self.world.root_dx

    @property
    def tips(self) -> list:
        """The tips' pymunk bodies, in seta order."""
        return self.world.tips

    @property
    def space(self):
        """The pymunk space."""
        return self.world.space

    @property
    def pull_travel(self) -> float:
        """Plate travel a pull-off typically needs [µm] (progress estimates)."""
        if self.params.mechanics == "linear":
            return self.Fc / self.params.Ky
        return self.L

    def normal_force(self) -> float:
        """Total normal contact force [µN] (> 0 compressive)."""
        return float(self.state.P.sum())

    def n_attached(self) -> int:
        return int(self.state.attached.sum())

    # ------------------------------------------------------------------ protocol runner
    def run(
        self,
        protocol,
        *,
        progress: bool = True,
        max_steps: int = 50_000_000,
        ke_bound: float | None = None,
        fast_approach: bool = True,
    ) -> History:
        """Run a protocol (list of :mod:`protocol` segments) and return its :class:`History`.

        Parameters
        ----------
        protocol : list of :class:`~gecko_agents.protocol.Segment` (Move, PressTo, Press,
            Hold, PullOff, or your own).
        progress : tqdm progress bar over simulated time.
        max_steps : hard cap on time steps.
        ke_bound : kinetic energy [pJ] beyond which the run is declared unstable (default:
            100 × the adhesion energy of all setae, N·Fc·|δ_detach|, plus the plate work).
        fast_approach : in segments that allow it (Move, PressTo, Press), while no tip is
            attached and every tip rests relative to the plate (within 1e-3 of the plate speed
            and of the lag that speed causes), move plate and tips rigidly to where the first
            sensor reaches the floor (:meth:`skip_free_travel`) instead of stepping there. A
            free seta's motion does not depend on where it is, so the history is the same but
            for the skipped rows; the travel skipped is ``meta["skipped_travel_um"]``.

        A model runs once: a second call is refused (RuntimeError), since its world is at the
        first run's end state, which the parameters, seed and protocol of a history do not
        reproduce. Build a new :class:`Model` for each run.
        """
        if self._ran:
            raise RuntimeError(
                "Model.run was already called on this model: its world is at that run's end "
                "state, which the parameters, seed and protocol in a history's metadata do not "
                "reproduce; build a new Model(params, seed=...) for each run"
            )
        self._ran = True
        h = run_protocol(self, protocol, progress, max_steps, ke_bound, fast_approach)
        if self.implicit_step is not None:
            h.meta["implicit_dissipated_pJ"] = self.implicit_step.numerical_dissipated
        return h

    def skip_free_travel(self, seg, state, vp) -> float:
        """Move plate and tips rigidly along ``vp`` (plate velocity [µm/µs]) towards where
        segment ``seg`` (its running ``state``) lets the first sensor reach the floor, while
        nothing can touch (:func:`gecko_agents.model.free_travel.skip_free_travel`); returns
        the travel [µm]: 0 while a tip is attached or with a backing that is not rigid."""
        if self.state.attached.any() or not self.backing.rigid:
            return 0.0
        target = seg.target(self, state)
        omega = math.sqrt(self.params.Ky / self.mass)
        travel = skip_free_travel(self.world, vp, omega, self.dt, target)
        self.time += travel / math.hypot(*vp) if travel else 0.0
        return travel
