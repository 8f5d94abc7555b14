"""The implicit step's length: the step between events, shortened for fast segments, and the
located steps near an event (:meth:`EventSteps.substeps`), each no longer than
:data:`IMPLICIT_EVENT_FACTOR` explicit steps. What locates a rough array's steps, the criteria
measured and not taken, and the records' spacing: docs/physics.md, "Event location"; the
step's accuracy: :data:`gecko_agents.model.implicit.IMPLICIT_DT_FACTOR` and
:data:`IMPLICIT_EVENT_FACTOR`.

Units: µm, µN, µs, ng, pJ (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import copy
import math

import numpy as np

from gecko_agents.history import ENERGY_RTOL, ENERGY_SCALE_COLUMNS

__all__ = [
    "FREE_RINGING_SHARE",
    "IMPLICIT_EVENT_FACTOR",
    "IMPLICIT_TRAVEL",
    "EventSteps",
    "default_event_dt",
    "whole_event_steps",
]

IMPLICIT_TRAVEL = 0.01
"""Largest plate travel per default implicit step at the default plate speed [µm]."""

FREE_RINGING_SHARE = 0.1 * ENERGY_RTOL
"""Free tips faster than twice the plate count as near an event (:meth:`EventSteps.substeps`)
only while their kinetic energy together exceeds this share of the run's energy scale so far
[-] (:func:`gecko_agents.history.energy_balance_error`'s scale): a tenth of the balance's
tolerance, since long steps book a ringing seta's energy only to within about its size
(``tests/test_event_location.py`` checks both sides)."""

IMPLICIT_EVENT_FACTOR = 1.0
"""The step near an event (:meth:`EventSteps.substeps`) in units of the explicit one
(0.75/ω_max) [-], at most the step between events; ``Model(event_dt=...)`` sets another. Chosen
by accuracy: a located tip lets go a few event steps of plate travel later than at the
explicit step, the scheme's own first-order error, so the event step is the resolution of
every release; longer event steps trade the energy books on a flat floor, where every tip
snaps off in one step, for fewer steps on rough floors (the measured table: documentation,
explanation, "Performance"; ``tests/test_event_location.py``)."""


def whole_event_steps(bound: float, event: float) -> float:
    """The longest whole number of steps ``event`` [µs] within ``bound`` [µs], at least one:
    a step between events that splits into located steps as long as allowed."""
    return event * max(1, math.floor(bound / event + 1e-9))


def default_event_dt(omega_max: float) -> float:
    """The step near an event by default [µs]: :data:`IMPLICIT_EVENT_FACTOR` explicit steps
    0.75/ω_max (ω_max [1/µs] of the stiffest spring on the tip)."""
    return IMPLICIT_EVENT_FACTOR * 0.75 / omega_max


class EventSteps:
    """The length of an implicit step (the part of
    :class:`gecko_agents.model.implicit.ImplicitStep` that sets it): ``dt_full`` the step
    between events [µs], ``dt_base`` the segment's, ``k_event`` the located steps a step takes
    near an event, ``near`` the setae near one at the last located step, ``energy_scale`` the
    run's energy scale so far [pJ]. The step reads its model ``m`` (state, law, mass, dt), its
    contact ``normal`` and the pull-off books ``_k_raw``, ``_k_rate`` of the implicit step.
    A multirate located step (:mod:`gecko_agents.model.multirate`) steps the setae near an
    event apart: :meth:`books`, :meth:`for_setae` and :meth:`take_books` split off their
    per-seta books and join them back."""

    def limit_step(self, dt_max: float) -> None:
        """Shorten the default step between events to at most ``dt_max`` [µs], a whole number
        of event steps (at least one; an event step longer than ``dt_max`` is shortened to
        it); a dt the caller chose stands. For a bound that the model's parts set after the
        step was chosen (the elastic strip's coupling to its setae,
        :class:`gecko_agents.backing.elastic.ElasticBacking`)."""
        if not self.default_step or self.dt_full <= dt_max:
            return
        event = min(self.event_dt, dt_max)
        dt = whole_event_steps(dt_max, event)
        self.k_event = round(dt / event)
        self.dt_full = self.dt_base = self._dt_prev = dt
        self.set_dt(dt)

    @property
    def event_dt(self) -> float:
        """The step taken near an event [µs]: ``dt_full``/k, at most
        :data:`IMPLICIT_EVENT_FACTOR` explicit steps (an elastic strip sub-cycles each of
        them at its own step, :meth:`gecko_agents.backing.elastic.ElasticBacking.roots`)."""
        return self.dt_full / self.k_event

    def begin_segment(self, speed) -> None:
        """Set the segment's step ``dt_base`` [µs] for its plate ``speed`` [µm/µs] (None or
        0: ``dt_full``). With the default step (:func:`implicit_time_step` without a dt), a
        fast segment shortens it so that the plate travels at most :data:`IMPLICIT_TRAVEL`
        per step, to a whole number of the steps taken near events, at least one (the step is
        set for accuracy: plate travel and events per step); below an event step longer than
        the default's (``event_dt``), to the travel itself, at least the default's event step.
        A dt the caller chose stands. The segment asks its plate velocity at this step, so it
        lands on its end point."""
        dt = self.dt_full
        cap = IMPLICIT_TRAVEL / speed if speed else math.inf
        if self.default_step and cap < dt:
            event = self.event_dt
            if cap >= event:
                dt = whole_event_steps(cap, event)
            else:  # one event step at most: the default's (an explicit step), or the travel
                dt = max(cap, min(event, default_event_dt(self.m.omega_max)))
        self.dt_base = dt
        self.set_dt(dt)

    def substeps(self, vp) -> int:
        """How many steps the next step of ``dt_base`` takes [-], with the model's dt set for
        them: k steps of the explicit step's length near an event, else one.

        Near an event means an attached tip running away from its branch (faster than twice
        the plate speed ``vp`` [µm/µs], as the release marks of
        :meth:`gecko_agents.model.step_numpy.NumpyStep.bookkeeping`: past a fold, a crack
        running through, a slip), free tips as fast while their kinetic energy together
        exceeds :data:`FREE_RINGING_SHARE` of the run's energy scale so far, or a tip whose
        overlap δ would cross the law's snap-off
        overlap (attached) or, moving towards the floor, its jump-in overlap (free) within two
        steps at its normal speed, or an attached tip past its load-controlled pull-off
        (dP/dδ < 0, :meth:`gecko_agents.contact.ContactLaw.stiffness`) or reaching it within
        two steps at the rate dP/dδ fell over the last one: from there the seta alone holds
        the tip, up to the fold where dP/dδ = −(the seta's normal stiffness) and the tip
        escapes. Found by its speed alone, the escape started up to a long step late (the
        first releases of a 20-seta retraction at 10 explicit steps: 0.021 µm of plate travel
        behind the explicit step's, 0.011 µm located). A step of the explicit length there
        resolves the event as the explicit step does; between events the long step stands.
        With an elastic backing too: without it a quick pad peel at 30° pulled 8.6 % above the
        explicit step (0.46 µm of plate travel per step), with it 0.7 %."""
        m = self.m
        dt = self.dt_base
        k = math.ceil(dt / self.event_dt - 1e-9)
        if k > 1:
            s = m.state
            v_ref = max(math.hypot(*vp), 1e-4)
            vx, vy = s.pv[2], s.pv[3]
            att = s.attached
            vn = (
                vy
                if self.normal is None
                else np.where(att, vx * self.normal[0] + vy * self.normal[1], vy)
            )
            reach = 2.0 * dt * np.abs(vn)
            d = s.delta
            with np.errstate(invalid="ignore"):
                fast = vx * vx + vy * vy > 4.0 * v_ref * v_ref
                near = att & fast
                near |= self._ringing(fast & ~att, vx, vy)
                near |= att & (d - m.law.detach_overlap < reach)
                near |= ~att & (vn < 0.0) & (m.law.attach_overlap - d < reach)
                # Past the load-controlled pull-off (dP/dδ < 0) or reaching it within two
                # steps at its last rate: the fold, where the tip escapes, lies ahead.
                near |= self._k_raw + 2.0 * dt * np.fmin(self._k_rate, 0.0) < 0.0
            if not near.any():
                k = 1
            self.near = near if k > 1 else None
        else:
            self.near = None
        self.set_dt(dt / k)
        self.n_located += k if k > 1 else 0
        return k

    def _ringing(self, free_fast, vx, vy):
        """``free_fast`` (the free tips faster than twice the plate) where their kinetic energy
        together exceeds :data:`FREE_RINGING_SHARE` of the run's energy scale so far
        (``energy_scale``), else all False: a released tip's ringing is resolved only while
        the long step's books of it could move the balance by a share of its tolerance."""
        if not free_fast.any():
            return free_fast
        ke = 0.5 * self.m.mass * float(np.sum(vx[free_fast] ** 2 + vy[free_fast] ** 2))
        if ke > FREE_RINGING_SHARE * self.energy_scale:
            return free_fast
        return np.zeros_like(free_fast)

    def note_energies(self, row: dict) -> None:
        """Raise ``energy_scale`` [pJ] to a recorded ``row``'s plate work, elastic and
        dissipated energy, as :func:`gecko_agents.history.energy_balance_error` takes it."""
        self.energy_scale = max(self.energy_scale, *(abs(row[c]) for c in ENERGY_SCALE_COLUMNS))

    def set_dt(self, dt: float) -> None:
        """Set the model's step to ``dt`` [µs] (its loop constants too). The recorder's
        kinetic energy reads the last step's velocity change as F'·dt/m with the model's
        dt, so the tips' force is rescaled to keep that change."""
        m = self.m
        if dt == m.dt:
            return
        m.state.F *= m.dt / dt
        m.dt = dt
        m.constants = m.physics.c = m.constants._replace(dt=dt, hm=0.5 * dt / m.mass)

    def start_books(self, n: int, dt: float) -> None:
        """The per-seta books of ``n`` setae at the start, the last step ``dt`` [µs]: the
        impulse F'·dt ``_J`` [µN·µs] and F' − F ``_dF`` [µN] of the last step, the contact's
        normal, stick and (a film tip's) off-diagonal stiffnesses ``_kn``, ``_kt``, ``_kxy``
        [µN/µm], dP/dδ of attached tips ``_k_raw`` (nan where free, −inf where not finite)
        [µN/µm] and its rate over the last step ``_k_rate`` [µN/(µm·µs)] (the pull-off check
        of :meth:`substeps`)."""
        self._J = np.zeros((2, n))
        self._dt_prev = dt
        self._kn = np.zeros(n)
        self._kt = np.zeros(n)
        self._kxy = np.zeros(n)
        self._dF = np.zeros((2, n))
        self._k_raw = np.full(n, np.nan)
        self._k_rate = np.zeros(n)

    def books(self, idx) -> dict:
        """The per-seta books of setae ``idx`` (copies): the last impulse ``J`` [µN·µs], its
        F' − F ``dF`` [µN], dP/dδ ``k_raw`` [µN/µm] and its rate ``k_rate``, the last step
        ``dt_prev`` [µs] (a number, or per seta after a multirate step)."""
        dt_prev = self._dt_prev
        return {
            "J": self._J[:, idx].copy(),
            "dF": self._dF[:, idx].copy(),
            "k_raw": self._k_raw[idx].copy(),
            "k_rate": self._k_rate[idx].copy(),
            "dt_prev": dt_prev if np.ndim(dt_prev) == 0 else dt_prev[idx],
        }

    def for_setae(self, model, books: dict, dt: float) -> EventSteps:
        """This step for ``model``, a model of some of the setae alone (a multirate step's,
        :mod:`gecko_agents.model.multirate`), from their ``books`` (:meth:`books`), with the
        step ``dt`` [µs]."""
        step = copy.copy(self)
        n = books["k_raw"].size
        step.m = model
        step.numerical_dissipated = 0.0
        step.start_books(n, books["dt_prev"])
        step._J, step._dF = books["J"].copy(), books["dF"].copy()
        step._k_raw, step._k_rate = books["k_raw"].copy(), books["k_rate"].copy()
        step.set_dt(dt)
        return step

    def take_books(self, idx, other: EventSteps, dt_prev: np.ndarray) -> None:
        """Take the books of setae ``idx`` from ``other`` (their step alone,
        :meth:`for_setae`), with the last step of every seta ``dt_prev`` [µs]."""
        self._J[:, idx] = other._J
        self._dF[:, idx] = other._dF
        self._k_raw[idx] = other._k_raw
        self._k_rate[idx] = other._k_rate
        self._dt_prev = dt_prev
