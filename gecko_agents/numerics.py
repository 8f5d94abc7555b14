"""How a run is computed, apart from what is simulated: the integrator and its steps, the
records, the compute path. Changing one changes a history only to the integrator's accuracy
(or not at all: kernel, threads, detection), never its physics.

Units: µs for steps (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import dataclasses
import warnings
from dataclasses import dataclass

from gecko_agents._stack import user_stacklevel

__all__ = ["Numerics", "NUMERICS_FIELDS", "BACKING_OPTIONS", "older_spellings", "split_options"]


@dataclass(frozen=True)
class Numerics:
    """The numerical settings of a :class:`gecko_agents.model.Model` (each checked, with the
    allowed values named, when the model is built).

    Attributes
    ----------
    integrator : ``"auto"`` (default: the implicit step where it is verified,
        :func:`gecko_agents.model.implicit.check_integrator`), ``"explicit"`` or ``"implicit"``.
    dt : time step [µs]; None: the integrator's default (explicit 0.75/ω_max, refused at or
        above 2/ω_max; implicit :func:`gecko_agents.model.implicit.implicit_time_step`).
    event_dt : the implicit step near an event (snap, fold, slip) [µs]; None: one explicit
        step. Longer: fewer steps on rough floors, each release later by about as many
        explicit steps of plate travel. Refused with the explicit step.
    record_every : record every this many steps; None: every 0.02 µm of plate travel at the
        default speed (by simulated time under the implicit step).
    kernel : ``"auto"``, ``"numba"``, ``"numpy"`` or ``"python"``: how a pad floor's step is
        computed (the same history to rounding; ``meta["kernel"]``).
    contact : ``"batch"`` (default) or ``"callback"`` (the per-contact reference path).
    detection : ``"auto"``, ``"full"`` or ``"lazy"``: how pymunk finds contact candidates
        (the same history).
    threads : numba threads of the pad loop; None: from the model's size and the idle cores.
    multirate : near an event, only the setae near it take the implicit step's short steps,
        the rest the long one, where the setae are independent
        (:mod:`gecko_agents.model.multirate`). None (default): where it applies; True: asked
        for, refused where it does not apply (naming what rules it out,
        ``gecko_agents.model.build.choose_multirate``); False: the whole array takes them.
    """

    integrator: str = "auto"
    dt: float | None = None
    event_dt: float | None = None
    record_every: int | None = None
    kernel: str = "auto"
    contact: str = "batch"
    detection: str = "auto"
    threads: int | None = None
    multirate: bool | None = None

    def replace(self, **changes) -> Numerics:
        """A copy with ``changes`` (field → value)."""
        return dataclasses.replace(self, **changes)


NUMERICS_FIELDS = tuple(f.name for f in dataclasses.fields(Numerics))
"""The field names of :class:`Numerics` (also ``Model``'s older keyword arguments)."""


BACKING_OPTIONS = ("leader_arm", "peel_angle_deg")
"""``Model``'s older keyword arguments that are now ``params.backing`` fields."""


def older_spellings(params, numerics: Numerics | None, older: dict):
    """(params, numerics) with ``Model``'s older keyword arguments folded in, one
    DeprecationWarning naming them: :class:`Numerics` fields (``Model(dt=…)``) and the
    backing's ``leader_arm``/``peel_angle_deg`` (now ``params.backing`` fields, so run files
    and metadata carry them). An unknown keyword is a TypeError naming it."""
    unknown = sorted(set(older) - set(NUMERICS_FIELDS) - set(BACKING_OPTIONS))
    if unknown:
        raise TypeError(f"Model() got unexpected keyword arguments {unknown}")
    if numerics is not None and not isinstance(numerics, Numerics):
        raise TypeError(f"numerics must be a Numerics, got {type(numerics).__name__}")
    num = {k: v for k, v in older.items() if k in NUMERICS_FIELDS}
    if num and numerics is not None:
        raise TypeError(f"give {sorted(num)} inside numerics=Numerics(...), not beside it")
    backing = {k: v for k, v in older.items() if k in BACKING_OPTIONS}
    if older:
        hint = []
        if num:
            hint.append(f"numerics=Numerics({', '.join(f'{k}=…' for k in num)})")
        if backing:
            hint.append(
                f"params.replace(backing={{{', '.join(repr(k) + ': …' for k in backing)}}})"
            )
        warnings.warn(
            f"Model({', '.join(f'{k}=…' for k in older)}) is deprecated and goes in 0.3: pass "
            + " and ".join(hint),
            DeprecationWarning,
            stacklevel=user_stacklevel(),
        )
    if backing:
        params = params.replace(backing=backing)
    return params, Numerics(**num) if numerics is None else numerics


def split_options(options: dict) -> tuple[dict, dict]:
    """``options`` for a ``Model`` as (its :class:`Numerics` fields, the rest): for helpers
    that take a model's keyword arguments and build it with ``numerics=Numerics(**first)``."""
    num = {k: v for k, v in options.items() if k in NUMERICS_FIELDS}
    return num, {k: v for k, v in options.items() if k not in NUMERICS_FIELDS}
