"""Quasi-static histories along a given plate path: :func:`solve`, and displacement control.

The seta model is chosen by ``params.mechanics`` (:func:`setup`): the linear seta's tabulated
branches or the rod. :func:`press_pull` presses to a depth and retracts. Units: µm, µN (see
:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from gecko_agents._stack import user_stacklevel
from gecko_agents.diagnostics import ValidityWarning
from gecko_agents.history import STATE_FREE as FREE
from gecko_agents.params import SetaArray
from gecko_agents.physics import jkr
from gecko_agents.quasistatic.blocks import Blocks
from gecko_agents.quasistatic.branches import Branches, retract_travel
from gecko_agents.quasistatic.heights import plate_start_height
from gecko_agents.quasistatic.linear import step as linear_step
from gecko_agents.quasistatic.result import QuasiStaticResult, Recorder
from gecko_agents.quasistatic.rod import RodSetup, RodState, rod_retract_travel, rod_step
from gecko_agents.quasistatic.state import State


def setup(
    params: SetaArray, lateral: str, stiffness_scale: float, tangential_stiffness: float
) -> Branches | RodSetup:
    """The seta model of ``params.mechanics``: :class:`Branches` (linear) or :class:`RodSetup`.
    The solver's tip is the paper's elastic JKR sphere: other tip laws are refused."""
    require_paper_tip(params)
    if params.mechanics not in ("linear", "rod"):
        raise ValueError(
            f"the quasi-static solver models mechanics 'linear' and 'rod': mechanics = "
            f"{params.mechanics!r} runs in the time-stepped Model"
        )
    if params.mechanics == "rod":
        return RodSetup.from_params(params, lateral, stiffness_scale, tangential_stiffness)
    return Branches.from_params(params, lateral, stiffness_scale, tangential_stiffness)


def require_paper_tip(params: SetaArray) -> None:
    """Refuse, naming the field, a parameter set whose tip the quasi-static solver does not
    model: it solves the elastic JKR sphere (eq 1–15) whose radius follows the overlap alone."""
    c = params.contact
    checks = (
        ("tip", params.tip, params.tip == "sphere", "'sphere'"),
        ("contact.crack_speed", c.crack_speed, math.isinf(c.crack_speed), "inf (elastic)"),
        ("contact.shear_coupling", c.shear_coupling, c.shear_coupling == "none", "'none'"),
    )
    for name, value, ok, allowed in checks:
        if not ok:
            raise ValueError(
                f"the quasi-static solver models the elastic JKR sphere only: {name} = "
                f"{value!r} must be {allowed}; run the time-stepped Model for this tip"
            )


def travel_up(params: SetaArray, br: Branches | RodSetup, heights, Z_from: float) -> float:
    """:func:`retract_travel` or :func:`rod_retract_travel`, as the seta model is [µm]."""
    travel = rod_retract_travel if isinstance(br, RodSetup) else retract_travel
    return travel(params, br, heights, Z_from)


def blocks_of(sample, weights, heights, rod: bool, record_setae: bool) -> Blocks | None:
    """The :class:`Blocks` that split on the fly with a ``sample`` (None without one, or for
    the rod, whose decision boundaries are not linear in h)."""
    if sample is None:
        return None
    if record_setae:
        raise ValueError("record_setae is not available with a sample (blocks split)")
    return None if rod else Blocks(sample, weights, heights)


def solve(
    params: SetaArray,
    heights,
    plate_y,
    *,
    weights=None,
    lateral: str = "coupled",
    stiffness_scale: float = 1.0,
    tangential_stiffness: float = math.inf,
    record_setae: bool = False,
    branches: Branches | None = None,
    stop_when_free_after: int | None = None,
    sample=None,
) -> QuasiStaticResult:
    """Quasi-static history of setae over floor heights along a vertical plate path.

    Parameters
    ----------
    params : the array (its contact, seta and friction parts are used).
    heights : floor height under each seta [µm], (N,).
    plate_y : plate heights above the floor's mean plane, in order [µm], (n,).
    weights : setae each entry stands for (default 1 each).
    lateral : ``"coupled"`` (stick/slip friction) or ``"free"`` (eq 25).
    stiffness_scale : multiplies Ka and Kp (large → rigid setae).
    tangential_stiffness : stick spring of the contact [µN/µm] (∞: rigid stick).
    record_setae : keep per-seta force, overlap, state and lateral offset.
    branches : prebuilt :class:`Branches` (or :class:`RodSetup` for ``mechanics == "rod"``;
        ``lateral`` and ``stiffness_scale`` are then unused).
    stop_when_free_after : stop at the first step past this index where no seta is attached.
    sample : the sorted heights of every seta [µm] when ``heights``/``weights`` are block
        means and sizes of consecutive setae of it (``representative_heights(...,
        return_sample=True)``). Blocks are then split wherever a plate step puts a jump-in,
        stick/slide or release boundary inside one (see
        :class:`~gecko_agents.quasistatic.blocks.Blocks`),
        so the blocks reproduce the force curve of all the setae to ~1e-9 of its peak instead of
        ~0.7/n_blocks; the result's ``heights``/``weights`` are the final blocks and
        ``releases`` index the blocks of their step. Not with ``record_setae``. With
        ``mechanics == "rod"`` the blocks are not split (the rod's decision boundaries are not
        linear in h): plain block means, an error of about 0.7/n_blocks of the peak.

    ``params.mechanics == "rod"`` solves the large-rotation rod of :func:`rod_force` instead of
    the linear spring (:func:`~gecko_agents.quasistatic.rod.rod_step`); the friction and release
    laws
    are the same.
    """
    rod = params.mechanics == "rod"
    br = branches or setup(params, lateral, stiffness_scale, tangential_stiffness)
    h = np.asarray(heights, dtype=float)
    w = np.ones_like(h) if weights is None else np.asarray(weights, dtype=float)
    Zs = np.asarray(plate_y, dtype=float)
    if not np.all(np.isfinite(Zs)):
        raise ValueError("plate_y must be finite")
    blocks = blocks_of(sample, w, h, rod, record_setae)
    st = RodState(h.size) if rod else State(h.size)
    out = Recorder(Zs.size, h.size, record_setae)
    for i, Z in enumerate(Zs):
        if rod:
            P, Ft, d, rel, rel_d = rod_step(br, st, Z, h)
        elif blocks is None:
            P, Ft, d, rel, rel_d = linear_step(br, st, Z, h)
        else:
            P, Ft, d, rel, rel_d = blocks.step(br, st, Z)
            h, w = blocks.h, blocks.w
        out.record(i, P, Ft, d, st, w, rel, rel_d)
        if (
            stop_when_free_after is not None
            and i > stop_when_free_after
            and not np.any(st.state != FREE)
        ):
            return out.result(Zs, w, h, keep=i + 1)
    return out.result(Zs, w, h)


def press_pull(
    params: SetaArray,
    heights,
    depth: float,
    *,
    n_approach: int = 500,
    n_retract: int = 2000,
    start_gap: float = 0.5,
    lateral: str = "coupled",
    stiffness_scale: float = 1.0,
    tangential_stiffness: float = math.inf,
    weights=None,
    record_setae: bool = False,
    sample=None,
) -> QuasiStaticResult:
    """Displacement control: approach to ``depth`` [µm], then retract.

    ``depth`` is measured from the plate height at which a resting tip touches the floor's
    mean plane (h = 0), so it does not depend on the highest asperity of a sample. The plate
    starts ``start_gap`` [µm] above the highest tip's touch-down and moves down to that depth
    in ``n_approach`` equal steps; it then retracts in ``n_retract`` equal
    steps over :func:`retract_travel`, stopping early once every seta has let go (a seta still
    attached at its end raises RuntimeError: the travel is a bound on every release). Equilibria
    are exact at every step; the step only sets how finely the curve and the release points
    are sampled. A tip that slides one way per leg takes the same path at any step; one that
    sticks and slips by turns (a stiff seta near its release) can change state between two
    samples, so its path converges with the step (first order, as its release height); so
    does the position of a rod tip's slip, taken at the first step past its onset.

    ``weights`` and ``sample``: see :func:`solve`. With a sample, the start height is set by
    the highest seta of the sample rather than the highest block mean.

    The paper's 10⁷ setae (σ = 1 µm, 1000 plate positions, < 1 s besides drawing the
    heights): ``h, w, s = representative_heights(10**7, 1.0, rng, 2000, return_sample=True)``
    then ``press_pull(PAPER_ARRAY, h, 1.0, weights=w, sample=s, n_approach=333,
    n_retract=667)``: 2000 blocks of 5000 setae, split on the fly wherever a jump-in,
    stick/slide or release boundary crosses one (a few hundred splits over the curve), which
    reproduces the curve of every seta solved on its own to ~1e-9 of the peak (tested against
    brute force on 10⁴ setae in tests/test_quasistatic.py).
    """
    if not depth > 0:
        raise ValueError(f"depth = {depth!r} must be > 0 [µm]")
    br = setup(params, lateral, stiffness_scale, tangential_stiffness)
    top = heights if sample is None else sample[-1:]
    Z0 = plate_start_height(params, top, start_gap)
    Zmin = plate_start_height(params, [0.0], 0.0) - depth
    if Zmin >= Z0:
        raise ValueError(
            f"depth = {depth!r} µm does not reach the highest floor point "
            f"({np.max(top):.3g} µm above the mean plane)"
        )
    up = travel_up(params, br, top, Zmin)
    Zs = np.concatenate(
        [np.linspace(Z0, Zmin, n_approach + 1), Zmin + up * np.arange(1, n_retract + 1) / n_retract]
    )
    res = solve(
        params,
        heights,
        Zs,
        weights=weights,
        record_setae=record_setae,
        branches=br,
        stop_when_free_after=n_approach,
        sample=sample,
    )
    if res.n_attached[-1] > 0:  # the curve would end before its last release: refuse it
        raise RuntimeError(
            f"{res.n_attached[-1]:.6g} setae still attached after the retract's {up:.6g} µm "
            "of travel, which bounds every seta's release: the pull-off curve is incomplete "
            "(a defect of the travel bound for these parameters)"
        )
    _warn_pressed_releases(params, res)
    return res


def _warn_pressed_releases(params: SetaArray, res: QuasiStaticResult) -> None:
    """Warn where a seta let go while its contact was compressed: its last overlap at or above
    JKR's zero-load overlap δ0 = a0²/3R (eq 10 at P = 0), i.e. P ≥ 0 on the stable branch,
    or it let go a second time (it touched again after letting go, so the plate was still
    pressing it). A compressed contact cannot open; the solver found no equilibrium for the
    seta there (a rod whose stick spring k_t is far softer than the contact's), and the curve
    misses its force."""
    a0 = jkr.zero_load_contact_radius(*params.contact.jkr_args())
    zero_load = a0**2 / (3 * params.contact.R)
    seen: set = set()
    pressed = 0
    for _, j, d in res.releases:
        pressed += d >= zero_load or j in seen
        seen.add(j)
    if pressed:
        warnings.warn(
            ValidityWarning(
                f"{pressed} of {len(res.releases)} releases were of setae whose contact was "
                f"compressed (overlap at or above JKR's zero-load {zero_load:.3g} µm, or let go "
                "again): no equilibrium "
                "was found for them there, and their force is missing from the curve at those "
                "steps (a stick spring far softer than the contact's: raise "
                "tangential_stiffness)"
            ),
            stacklevel=user_stacklevel(),
        )


def single_seta(params: SetaArray, plate_y, height: float = 0.0, **kw) -> QuasiStaticResult:
    """One seta (eq 22–27) over a floor at ``height`` [µm] along plate heights ``plate_y``."""
    return solve(params, np.array([float(height)]), plate_y, record_setae=True, **kw)
