"""The rigid backing of the paper: every seta root fixed to the plate, the kinematic body the
protocol moves (``World.plate``).

It is also the reference for the interface every backing offers
:class:`gecko_agents.model.Model` (the elastic strip, :mod:`gecko_agents.backing.elastic`,
offers the same). Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import numpy as np

__all__ = ["RigidBacking"]


class RigidBacking:
    """The rigid plate: the seta roots ride on the handle (``world.plate``) at their offsets
    (``world.root_dx``, ``world.root_dy``), and the setae pull on it directly.

    :class:`gecko_agents.model.Model` holds one backing (``model.backing``), built from
    ``params.backing.kind``, and calls it at these points of a step (the numpy kernel; the
    compiled pad loop, :mod:`gecko_agents.model.step_loop`, is the rigid plate's alone):

    1. :meth:`roots` — where the roots are and how fast they move, as the seta springs and
       dampers see them (:meth:`gecko_agents.model.step_numpy.NumpyStep.spring_damp`);
    2. :meth:`hold` — once the seta forces are in ``state.F``, before the contacts add to it;
    3. :meth:`advance` — after the tips' step and their bookkeeping: the backing steps itself,
       adds its dissipation to ``physics.diss`` and returns the force on the handle.

    Besides: :meth:`root_positions` (for the setae's elastic energy), :meth:`energy` and
    :meth:`kinetic_energy` (the energy columns), :meth:`record` (what the
    :class:`~gecko_agents.model.recorder.Recorder` writes per record), :attr:`geometry` and
    :attr:`info` (static, for the History), :attr:`rigid` (the roots move with the plate: the
    compiled pad loop and the skip of the free approach apply); and what it runs with, which
    the build step (:func:`gecko_agents.model.build`) checks: :attr:`implicit`,
    :attr:`loops`, :attr:`contacts`, :attr:`mechanics`.

    Parameters
    ----------
    setup : the run's ``gecko_agents.model.build.Setup`` (its parameters, seta constants
        and steps). world : the :class:`gecko_agents.model.world.World` (the handle, the
        roots' offsets). state : the per-seta state. physics : the step's forces
        (:class:`gecko_agents.model.step_numpy.NumpyStep`). spring_force : the setae's
        springs, ``spring_force(tips, roots)`` → (forces (N, 2) [µN], energies [pJ], …)
        (:meth:`gecko_agents.model.stepping.Stepping.spring_force`).
    """

    kind = "rigid"
    rigid = True
    implicit = True
    """The implicit step is verified with this backing (docs/physics.md, "Time stepping")."""
    loops = True
    """The pad loops (:mod:`gecko_agents.model.step_loop`) step the setae on it."""
    contacts = ("batch", "callback")
    """The contact paths it runs with."""
    mechanics = ("linear", "rod", "elastica")
    """The seta mechanics it holds."""
    info = None
    """Static figures for ``meta["backing"]`` (none for the rigid plate)."""

    def __init__(self, setup, world, state, physics, spring_force):
        self.world = world
        self.geometry = {}
        """Static arrays for ``History.geometry`` (none for the rigid plate)."""

    def roots(self, hx: float, hy: float, vpx: float, vpy: float, dt: float):
        """The plate the seta springs are measured from: the handle at (``hx``, ``hy``) [µm],
        where the step of ``dt`` [µs] evaluates forces, moving at (``vpx``, ``vpy``)
        [µm/µs]."""
        return hx, hy, vpx, vpy

    def hold(self, state) -> None:
        """Nothing to keep: the plate takes the setae's pull as it is."""

    def advance(self, dt, hx, hy, vpx, vpy, on_plate):
        """The plate moves as the protocol says; the force on it is the setae's ``on_plate``
        (x, y) [µN]."""
        return on_plate

    def root_positions(self, handle) -> np.ndarray:
        """Root positions (N, 2) [µm] with the handle at ``handle`` (x, y) [µm]."""
        return np.asarray(handle) + np.column_stack([self.world.root_dx, self.world.root_dy])

    def step_limit(self) -> float | None:
        """The longest step between events the backing allows the implicit step [µs] (None:
        no bound of its own)."""
        return None

    def energy(self) -> float:
        """Elastic energy of the backing [pJ]: none in a rigid plate."""
        return 0.0

    def kinetic_energy(self, tips: float) -> float:
        """Kinetic energy [pJ] of the tips (``tips``) and the backing: the plate's motion is
        prescribed, so the tips' alone."""
        return tips

    def record(self) -> tuple[dict, dict]:
        """(scalar columns, per-record arrays) of the backing at a record: none."""
        return {}, {}
