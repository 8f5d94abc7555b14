"""Validity diagnostics: does a run mean what its numbers seem to say?

Every :meth:`gecko_agents.model.Model.run` ends with :func:`diagnose`, which writes the result
into the history's metadata under ``"validity"`` and warns once (:class:`ValidityWarning`) per
violated item. A run whose result cannot mean anything (the plate went past the floor but no tip
ever touched it) raises :class:`MeaninglessRunError` instead. :func:`validity_table` summarises
the diagnostics of several runs as a markdown table (for ``renders/paper_comparison.md``).

:func:`diagnose` reads the :class:`~gecko_agents.history.History` alone: its parameters, series,
floor (``geometry["floor_y_um"]``) and the facts of the live model that the run recorded into
its metadata (:data:`MODEL_FACTS`, written by :func:`model_facts`). A run loaded from disk
(:func:`gecko_agents.history.load_history`) is therefore diagnosed exactly as it was when it
ran; one whose metadata lacks a fact is refused with an error naming the key.

Units: µm, µN, µs, ng (:mod:`gecko_agents.params`). Each item is a dict::

    {"value": float, "limit": float, "ok": bool | None, "rule": "value ≤ limit", "meaning": str,
     "source": str}

``ok`` is ``None`` where the item does not apply to the run (an adhesion measure for the Hertz
tip, the beam's range for the rod, the crack number for elastic contact). The items:

The contact items (``a_over_R``, ``tabor``) apply to sphere tips that touched (not a punch).

``a_over_R``
    Largest contact radius over tip radius, a/R, with a the larger of the zero-load JKR radius
    a0 and the radius at the largest tip compression reached. JKR (like Hertz) treats the
    sphere as a paraboloid on a half-space, which needs a ≪ R (Johnson 1985, *Contact
    Mechanics*, §4.2 and §5.5); Maugis 1995 (Langmuir 11:679, "Extension of the JKR theory of
    the elastic contact of spheres to large contact radii") gives the large-radius correction,
    which grows beyond a few per cent above a/R ≈ 0.1. Limit 0.1. The paper's tip (R = 4 µm,
    E* = 1.55 MPa, w = 0.165 J/m²) has a0/R = 0.72: its JKR numbers are the formula's, not
    the sphere's.
``tabor``
    Tabor's parameter μ = (R·w²/(E*²·z0³))^(1/3) (Tabor 1977, J Colloid Interface Sci 58:2),
    the ratio of the elastic neck height at pull-off to the range of the surface forces. JKR
    holds for μ ≳ 5 (Johnson & Greenwood 1997, J Colloid Interface Sci 192:326, "An adhesion
    map for the contact of elastic spheres"); below it Maugis–Dugdale or DMT apply. z0 is the
    equilibrium separation of the surfaces (the ε of the Lennard-Jones law in Greenwood 1997,
    Proc R Soc A 453:1277); :data:`Z0_UM` = 0.3 nm, an interatomic spacing. A smaller z0 (e.g.
    Israelachvili's 0.165 nm contact separation) gives a larger μ, so 0.3 nm is the cautious
    choice. Limit: μ ≥ 5.
``linear_deflection``
    Largest tip deflection of a linear seta over its length, |u|/L (``mechanics="linear"``
    only). Eq 16–21 are small-deflection beam theory; a cantilever's tip deflection departs
    from it by ~1 % at 0.1 L and grows fast beyond (Bisshopp & Drucker 1945, Q Appl Math
    3:272). Limit 0.1, the same as the model's own warning. ``ok`` comes from the model's own
    check, which sees every step (``model_warned``); ``value`` is measured on the recorded tip
    positions when per-seta arrays were recorded (``record_setae=True``), else None.
``quasi_static``
    q = ζ·Ky·v·T/(π·Fc): the force a moving plate costs a held tip, over the tip's pull-off
    force. The seta's damper (ζ of critical on Ky, relative to the plate: ``meta["damping"]``)
    has c = 2ζ√(Ky·m) = ζ·Ky·T/π with T = 2π√(m/Ky) the free seta's period
    (``Model.settle_time``); while a tip is held and the plate moves at v it carries c·v, so a
    force–displacement curve sits c·v off the quasi-static one (equivalently, the seta lags
    by c·v/K; docs/physics.md, "Time stepping"). v is the plate speed [µm/µs] where the
    peak force happened (the pull-off if the run pulled, else the largest compression), read
    off the recorded plate positions; Fc the tip law's pull-off force (JKR 3πwR/2, Kendall's
    w·b for the spatula). Halving the speed moves the pull's force curve by q/2 of Fc
    (``tests/test_frontend.py`` measures it for linear and rod setae with sphere tips); a JKR
    sphere's peak pull-off, limited by the contact, moves much less. Limit 0.05. Not judged
    for a tip without adhesion (Hertz: Fc = 0) nor for a peeling film (the spatula, whose
    contact damping adds its own rate dependence: its curve moved 4–6 × q/2). The recorded
    peak kinetic/elastic energy ratio is given beside it.
``time_step``
    ω·dt with ω = √(k/m) of the stiffest spring a tip met (seta + contact at the largest
    compression reached, at least the model's design point 5 Fc, + stick spring), dt the step
    taken at events (``meta["event_dt_us"]``). Semi-implicit Euler is stable for ω·dt < 2 and
    books a jump event's energy to a fraction ~ω·dt (docs/physics.md, "Time stepping" and
    "Energy bookkeeping"; Hairer, Lubich & Wanner, *Geometric Numerical Integration*, §I.1).
    Limit 1 (the model's default is 0.75). The implicit step is stable at any step; near an
    event it takes steps of the explicit length
    (:meth:`gecko_agents.model.event_steps.EventSteps.substeps`), and those are judged; where it
    cannot locate events (the elastic backing) its whole step is.
``touched``
    Whether any tip ever attached. 1 if so, 0 if not. A run in which the plate never went past
    the height at which the tip over the highest floor point touches (a pull-off alone, free
    travel) may legitimately touch nothing: ``ok`` is then None. If the plate did go past it
    and no tip touched, the plate outran the setae and the run measured nothing:
    :class:`MeaninglessRunError`.
``crack_deborah``
    For rate-dependent contact (``params.contact.crack_speed`` v* < ∞): De = (v/|δc|)/(v*/a0),
    the loading rate of a contact over the crack's relaxation rate (Maugis & Barquins 1978,
    J Phys D 11:1989; Greenwood & Johnson 1981, Phil Mag A 43:697). De ≪ 1: the crack keeps
    up, elastic JKR; De ~ 1: rate-dependent. With the kinetic law G/w − 1 = (v/v*)^n the
    crack must run at ~De·v*, i.e. G/w ≈ 1 + De^n. Viscoelastic enhancement cannot exceed the
    ratio of glassy to rubbery modulus, ~10²–10³ for elastomers (Greenwood & Johnson 1981), so
    the power law is extrapolated beyond its physics when De^n > 100. Limit: De^n ≤ 100.
``records``
    The recorded peak force's shortfall against the peak at any step (the runner keeps the
    total normal force's extremes over every step): a record cadence too sparse for the force
    history misses the peak in the series and what is read off them (``History.peak_pull_off``
    reads the stepped extreme, which no cadence misses). Limit 5 %.
``release_step``
    Plate travel of the longest step in which a tip let go, over Fc·(1/Ky + 1/k0), the travel
    over which a tip's force rises from zero to its pull-off (seta and zero-load contact in
    series): a release is resolved to one step, so the pull-off is off by about this ratio
    (:mod:`gecko_agents.diagnostics.resolution`). Limit 0.02.
``pillars_meet``
    For elastica pillars in a row: the smallest distance between neighbouring centre lines
    over the records, over the diameter 2r, and for flat faces wider than their stalks
    (mushroom flanges) between neighbouring tips over the face's diameter 2R. The model has no
    pillar–pillar contact, so below 1 buckled pillars, or flanges, pass through each other.
    Limit ≥ 1.
``probe_curvature``
    On a spherical probe (``floor.kind = "probe"``), how far the tip laws' flat floor is from
    the probe under a tip: a sphere's R/R_p (two spheres in contact act with
    R_eff = R·R_p/(R + R_p), Johnson 1985 §4.2, so a pull-off is off by about the ratio); a flat
    face's sag a²/(2R_p) over its snap-off overlap. Limit 0.1.
``probe_scale``
    On a spherical probe, ``scale_to_array`` = array.count / n_sim, the factor that scales the
    simulated setae's forces to the array. It takes them as a uniform patch of the array;
    under a probe each pillar meets the sphere at its own height, so only a run of every
    pillar (n_sim = array.count) gives the array's force. Limit 1.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

import numpy as np

from gecko_agents._stack import user_stacklevel
from gecko_agents.contact import contact_law
from gecko_agents.diagnostics import resolution
from gecko_agents.diagnostics.limits import LIMITS
from gecko_agents.diagnostics.table import validity_table
from gecko_agents.physics import jkr

__all__ = [
    "ValidityWarning",
    "MeaninglessRunError",
    "Z0_UM",
    "LIMITS",
    "MODEL_FACTS",
    "diagnose",
    "model_facts",
    "validity_table",
]

Z0_UM = 3.0e-4
"""Equilibrium separation z0 of Tabor's parameter [µm] (0.3 nm; module docstring, ``tabor``)."""


MODEL_FACTS = {
    "dt_us": "the time step dt [µs]",
    "mass_ng": "the tip mass m [ng]",
    "axial_stiffness_uN_per_um": "the seta's axial stiffness Ka [µN/µm]",
    "tangential_stiffness_uN_per_um": "the tip law's stick stiffness k_t [µN/µm]",
    "omega_max_per_us": "the model's design-point ω_max = √(k_max/m) [1/µs]",
    "settle_time_us": "the free seta's period T = 2π√(m/Ky) [µs] (Model.settle_time)",
    "z_touch_um": "the plate height at which a resting tip touches the floor's mean plane [µm]",
    "tip_law": "the name of the tip law the model ran (rebuilt from the parameters)",
    "linear_deflection_warned": "whether the model's every-step linear-deflection check fired",
    "protocol_speed_um_per_us": "the largest plate speed of the protocol's segments [µm/µs]",
}
"""Keys of ``history.meta`` that :func:`diagnose` reads → what they hold: what the live model
knew and the history's series do not say. :meth:`gecko_agents.model.Model.run` records them
(:func:`model_facts`, beside ``dt_us``, ``mass_ng``, ``tangential_stiffness_uN_per_um`` and
``tip_law``, which its metadata carries anyway)."""


class ValidityWarning(UserWarning):
    """A run left the range in which its model holds (see :mod:`gecko_agents.diagnostics`)."""


class MeaninglessRunError(RuntimeError):
    """A run whose result cannot mean anything; ``history`` holds what it recorded."""

    def __init__(self, message: str, history=None):
        super().__init__(message)
        self.history = history


def _item(name: str, value: float | None, meaning: str, source: str, applies: bool = True):
    rel, limit = LIMITS[name]
    if value is None or not applies:
        ok = None
    elif rel == "≤":
        ok = bool(value <= limit)
    else:
        ok = bool(value >= limit)
    return {
        "value": None if value is None else float(value),
        "limit": limit,
        "ok": ok,
        "rule": f"value {rel} {limit:g}",
        "meaning": meaning,
        "source": source,
    }


def _tip_forces(history) -> tuple[np.ndarray, np.ndarray]:
    """Per-tip normal and tangential contact forces [µN]: per seta if recorded, else the mean
    over attached tips of every record (a lower bound of the largest)."""
    setae = history.setae
    if setae and "force_normal_uN" in setae and "force_tangential_uN" in setae:
        return np.asarray(setae["force_normal_uN"]), np.asarray(setae["force_tangential_uN"])
    n = np.maximum(np.asarray(history["n_attached"], dtype=float), 1.0)
    return history["force_normal_uN"] / n, history["force_tangential_uN"] / n


def model_facts(model, segments) -> dict:
    """What :func:`diagnose` needs of a live model beyond the metadata every run carries
    (:data:`MODEL_FACTS`), for ``history.meta``.

    Parameters
    ----------
    model : the :class:`~gecko_agents.model.Model` at the end of its run.
    segments : the protocol's segments (their ``speed`` [µm/µs], 0 for a segment without one).

    Returns
    -------
    dict of the :data:`MODEL_FACTS` the run's metadata does not carry anyway, in their units.
    """
    speeds = [float(getattr(s, "speed", 0.0) or 0.0) for s in segments]
    return {
        "axial_stiffness_uN_per_um": float(model.Ka),
        "omega_max_per_us": float(model.omega_max),
        "settle_time_us": float(model.settle_time),
        "z_touch_um": float(model.z_touch),
        "linear_deflection_warned": bool(model.warned_linear),
        "protocol_speed_um_per_us": max(speeds, default=0.0),
        # Read with defaults (explicit, dt) so runs saved before they were kept still load.
        "integrator": model.integrator,
        "event_dt_us": float(model.event_dt),
    }


def _model_facts(history) -> dict:
    """The :data:`MODEL_FACTS` of ``history.meta``, or a ValueError naming every one missing."""
    missing = [k for k in MODEL_FACTS if k not in history.meta]
    if missing:
        what = "; ".join(f"{k!r}: {MODEL_FACTS[k]}" for k in missing)
        raise ValueError(
            f"history.meta lacks {what}, which diagnose needs: the run was recorded before "
            "the model kept it, or its metadata was edited; re-run it"
        )
    return {k: history.meta[k] for k in MODEL_FACTS}


@dataclass(frozen=True)
class _Run:
    """What the items are measured from, read once from the history: its parameters, series
    and floor, and the model facts it recorded (:data:`MODEL_FACTS`)."""

    R: float  # tip radius [µm]
    w: float  # work of adhesion [µN/µm]
    E: float  # effective modulus E* [MPa = µN/µm²]
    adhesive: bool  # a JKR sphere with w > 0
    P_comp: float  # largest compression of a tip [µN]
    touched: bool  # any tip ever attached
    a0: float  # zero-load JKR contact radius [µm] (0 if not adhesive)
    v: float  # largest plate speed [µm/µs]
    v_peak: float  # plate speed where the peak force happened [µm/µs]
    Fc: float  # the tip law's pull-off force [µN] (0 without adhesion)
    Ky: float  # the seta's stiffness Ky [µN/µm] (eq 20), the damper's scale
    zeta: float  # the seta's damping ratio (meta["damping"]["seta"], 1 if not recorded)
    film: bool  # the tip law peels a film (the spatula)
    flat_face: bool  # the tip is a flat punch (a = R by construction)
    stroke: float | None  # |δc|, the JKR snap-off overlap [µm] (None if not adhesive)
    floor_top: float  # highest floor point [µm]
    reached: bool  # the plate went below the height at which the highest resting tip touches
    z_touch: float  # plate height at which a resting tip touches h = 0 [µm]
    settle_time: float  # free seta period T [µs]
    dt: float  # time step [µs]
    event_dt: float  # the step taken where a tip snaps, slips or lets go [µs]
    implicit: bool  # the run's integrator is the linearly implicit step
    mass: float  # tip mass [ng]
    k_max: float  # seta + contact at the largest compression (≥ 5 Fc) + stick [µN/µm]
    omega_max: float  # the model's design-point ω_max [1/µs]
    warned_linear: bool  # the model's every-step linear-deflection check fired


def _law(history, tip_law: str):
    """The tip law the run used, rebuilt from its parameters (refused if it is not
    ``tip_law``, the law the run recorded)."""
    law = contact_law(history.params)
    if law.name != tip_law:
        raise ValueError(
            f"history.meta['tip_law'] = {tip_law!r}, but the history's parameters give the "
            f"tip law {law.name!r}: the parameters or the metadata were edited; re-run it"
        )
    return law


def _speed_at_peak(history) -> float:
    """Plate speed [µm/µs] at the record of the peak force (the most tensile if any tension,
    else the most compressive), from the recorded plate positions either side of it."""
    f = np.asarray(history["force_normal_uN"])
    if not len(f):
        return 0.0
    i = int(np.argmin(f)) if f.min() < 0 else int(np.argmax(f))
    j0, j1 = max(i - 1, 0), min(i + 1, len(f) - 1)
    t = history["time_us"]
    if t[j1] <= t[j0]:
        return 0.0
    dx = history["plate_x_um"][j1] - history["plate_x_um"][j0]
    dy = history["plate_y_um"][j1] - history["plate_y_um"][j0]
    return float(math.hypot(dx, dy) / (t[j1] - t[j0]))


def _facts(history) -> _Run:
    m = _model_facts(history)
    p = history.params
    c = p.contact
    R, w, E = c.jkr_args()
    adhesive = p.tip == "sphere" and w > 0
    P_tip, _ = _tip_forces(history)
    P_comp = float(np.max(P_tip, initial=0.0))
    if "floor_y_um" not in history.geometry:
        raise ValueError("history.geometry lacks 'floor_y_um' (the floor), which diagnose needs")
    floor_y = np.asarray(history.geometry["floor_y_um"])
    floor_top = float(np.max(floor_y)) if len(floor_y) else 0.0
    z_touch = float(m["z_touch_um"])
    law = _law(history, m["tip_law"])
    k_contact = law.stiffest(max(P_comp, 5 * c.pull_off_force))
    k_max = m["axial_stiffness_uN_per_um"] + k_contact + m["tangential_stiffness_uN_per_um"]
    return _Run(
        R=R,
        w=w,
        E=E,
        adhesive=adhesive,
        P_comp=P_comp,
        touched=bool(np.max(history["n_attached"], initial=0) > 0),
        a0=float(jkr.zero_load_contact_radius(R, w, E)) if adhesive else 0.0,
        v=float(m["protocol_speed_um_per_us"]),
        v_peak=_speed_at_peak(history),
        Fc=float(law.pull_off_force),
        Ky=float(p.Ky),
        flat_face=bool(law.flat_face),
        zeta=float((history.meta.get("damping") or {}).get("seta", 1.0)),
        film=bool(law.film),
        stroke=abs(c.snap_off_overlap) if adhesive else None,
        floor_top=floor_top,
        reached=float(np.min(history["plate_y_um"], initial=np.inf)) <= z_touch + floor_top,
        z_touch=z_touch,
        settle_time=float(m["settle_time_us"]),
        dt=float(m["dt_us"]),
        event_dt=float(history.meta.get("event_dt_us", m["dt_us"])),
        implicit=history.meta.get("integrator") == "implicit",
        mass=float(m["mass_ng"]),
        k_max=k_max,
        omega_max=float(m["omega_max_per_us"]),
        warned_linear=bool(m["linear_deflection_warned"]),
    )


def _a_over_R(f: _Run) -> dict:
    if f.adhesive:
        a_load = float(jkr.contact_radius_from_force(f.P_comp, f.R, f.w, f.E))
    else:
        a_load = float(jkr.hertz_contact_radius(f.P_comp, f.R, f.E))
    a_max = max(f.a0, a_load)
    return _item(
        "a_over_R",
        a_max / f.R,
        f"largest contact radius {a_max:.3g} µm over tip radius {f.R:g} µm (JKR and Hertz "
        "treat the sphere as a paraboloid on a half-space: a ≪ R)",
        "Johnson 1985 Contact Mechanics §4.2, §5.5; Maugis 1995 Langmuir 11:679",
        applies=a_max > 0 and f.touched and not f.flat_face,
    )


def _tabor(f: _Run) -> dict:
    mu_t = (f.R * f.w**2 / (f.E**2 * Z0_UM**3)) ** (1 / 3) if f.adhesive else None
    return _item(
        "tabor",
        mu_t,
        f"Tabor parameter (R·w²/(E*²·z0³))^(1/3) with z0 = {Z0_UM * 1e3:g} nm; JKR needs "
        "μ ≳ 5, below it Maugis–Dugdale/DMT",
        "Tabor 1977 J Colloid Interface Sci 58:2; Johnson & Greenwood 1997 J Colloid "
        "Interface Sci 192:326; z0 as ε of Greenwood 1997 Proc R Soc A 453:1277",
        applies=f.adhesive and f.touched,
    )


def _linear_deflection(history, f: _Run) -> dict:
    p = history.params
    linear = p.mechanics == "linear"
    warned = f.warned_linear
    dev = None
    if linear and history.setae and "tip_x_um" in history.setae:
        g = history.geometry
        L, th = p.seta.L, p.seta.theta
        ux = (
            history.setae["tip_x_um"]
            - history["plate_x_um"][:, None]
            - np.asarray(g["root_dx_um"])[None, :]
            - L * math.cos(th)
        )
        uy = (
            history.setae["tip_y_um"]
            - history["plate_y_um"][:, None]
            - np.asarray(g["root_dy_um"])[None, :]
            + L * math.sin(th)
        )
        dev = float(np.max(np.hypot(ux, uy), initial=0.0)) / L
    item = _item(
        "linear_deflection",
        dev,
        "largest linear-seta tip deflection / L (eq 16–21 are small-deflection theory; "
        "mechanics='rod' stays physical); value from the recorded tip positions, ok also from "
        "the model's check on every step",
        "Bisshopp & Drucker 1945 Q Appl Math 3:272; docs/physics.md 'Seta mechanics'",
        applies=linear,
    )
    if linear:  # the model's in-run check sees every step: it decides
        item["ok"] = bool(not warned and (dev is None or dev <= 0.1))
    item["model_warned"] = warned
    return item


def _quasi_static(history, f: _Run) -> dict:
    """The force the seta's damper costs a held tip at the peak's plate speed, over Fc."""
    lag_force = f.zeta * f.Ky * f.v_peak * f.settle_time / math.pi
    judged = f.Fc > 0 and not f.film
    if judged:
        meaning = (
            f"force a moving plate costs a held tip, ζ·Ky·v·T/π = {lag_force:.3g} µN (plate "
            f"speed {f.v_peak:.3g} µm/µs where the peak force happened, free seta period "
            f"{f.settle_time:.3g} µs), over the pull-off force Fc = {f.Fc:.3g} µN: halving the "
            "speed moves the force curve by half of it"
        )
    else:  # no force scale (Hertz), or a film whose own dampers add to the seta's
        meaning = (
            f"not judged: tip = {history.params.tip!r} "
            + (
                "peels a film whose contact damping adds to the seta's (measured: 4–6 × q/2)"
                if f.film
                else "has no pull-off force"
            )
            + f"; halve the plate speed ({f.v_peak:.3g} µm/µs at the peak) until the forces "
            "stop moving (a spatula's pull-off is first order in the speed: the "
            "frictional-adhesion study's plate-speed table)"
        )
    item = _item(
        "quasi_static",
        lag_force / f.Fc if judged else None,
        meaning,
        "docs/physics.md 'Time stepping' (seta damping, settle period)",
        applies=judged and f.touched,
    )
    item["plate_speed_um_per_us"] = f.v_peak
    item["max_kinetic_to_elastic"] = history.meta.get("max_kinetic_to_elastic")
    return item


def _time_step(f: _Run) -> dict:
    """ω·dt of the stiffest spring a tip met (seta + contact at the largest compression
    reached, at least the design point 5 Fc, + stick spring), at the step taken at events:
    the explicit step's dt, or the implicit step's located step dt/k."""
    k = f.k_max
    omega = max(math.sqrt(k / f.mass), f.omega_max)
    if f.implicit:
        what = (
            f"dt = {f.event_dt:.3g} µs, the implicit step's step at events (dt = {f.dt:.3g} µs "
            "between them, stable at any step); energy of jump events booked to ~ω·dt"
        )
    else:
        what = f"dt = {f.dt:.3g} µs); stable below 2, energy of jump events booked to ~ω·dt"
    return _item(
        "time_step",
        omega * f.event_dt,
        f"ω·dt with ω = √(k/m) of the stiffest spring met (k = {k:.3g} µN/µm, m = "
        f"{f.mass:.3g} ng, " + what,
        "docs/physics.md 'Time stepping'; Hairer, Lubich & Wanner, Geometric Numerical "
        "Integration §I.1",
    )


def _touched(f: _Run) -> dict:
    return _item(
        "touched",
        1.0 if f.touched else 0.0,
        "whether any tip ever attached; a run whose plate never reached the floor (pull-off "
        "only, free travel) need not touch",
        "a plate that outruns its setae measures nothing (MeaninglessRunError)",
        applies=f.touched or f.reached,
    )


def _crack_deborah(contact, f: _Run) -> dict:
    """Rate-dependent contact: De^n against the glassy/rubbery modulus ratio."""
    v_star = float(getattr(contact, "crack_speed", math.inf))
    n_exp = float(getattr(contact, "crack_exponent", 0.5) or 0.5)
    rate = math.isfinite(v_star) and f.adhesive and f.stroke
    De = (f.v / f.stroke) / (v_star / f.a0) if rate else None
    item = _item(
        "crack_deborah",
        De**n_exp if De is not None else None,
        "De^n with De = (v/|δc|)/(v*/a0), the loading rate over the crack's relaxation rate: "
        "G/w ≈ 1 + De^n must stay below the glassy/rubbery modulus ratio ~10²",
        "Maugis & Barquins 1978 J Phys D 11:1989; Greenwood & Johnson 1981 Phil Mag A 43:697",
        applies=bool(rate),
    )
    item["deborah"] = De
    return item


def _refuse_if_meaningless(history, f: _Run) -> None:
    """MeaninglessRunError if the plate went past the floor and no tip ever touched it."""
    if not (f.reached and not f.touched):
        return
    past = f.z_touch + f.floor_top - float(np.min(history["plate_y_um"]))
    lag = f.v * f.settle_time / math.pi
    v_ok = abs(history.params.contact.snap_off_overlap) / f.settle_time
    raise MeaninglessRunError(
        f"no tip ever touched the floor although the plate went {past:.3g} µm past the "
        f"height at which the highest resting tip touches it: at {f.v:.3g} µm/µs the setae "
        f"(free period {f.settle_time:.3g} µs) lag the plate by ~{lag:.3g} µm, so the "
        f"run measured nothing; lower the plate speed below {v_ok:.3g} µm/µs (a lag "
        "of |δc|/π) or press deeper (the recorded history is the exception's .history)",
        history,
    )


def _warn_violations(items: dict, violations: list[str]) -> None:
    """One ValidityWarning per violated item, attributed to the user's line that ran the model."""
    for name in violations:
        it = items[name]
        if name == "linear_deflection" and it["model_warned"]:
            continue  # the model already warned during the run
        warnings.warn(
            ValidityWarning(
                f"validity: {name} = {_fmt(it['value'])} violates {it['rule']}: "
                f"{it['meaning']} [{it['source']}]"
            ),
            stacklevel=user_stacklevel(),
        )


def diagnose(history, *, warn: bool = True) -> dict:
    """Validity of one run (module docstring): ``{"ok", "violations", "items"}``.

    Reads the history alone (its parameters, series, floor and :data:`MODEL_FACTS`), so a run
    loaded with :func:`gecko_agents.history.load_history` gives what the live run gave.

    Parameters
    ----------
    history : :class:`~gecko_agents.history.History`
        A run of :meth:`gecko_agents.model.Model.run`, live or loaded.
    warn : bool
        Issue one :class:`ValidityWarning` per violated item.

    Returns
    -------
    dict
        ``"ok"`` (bool), ``"violations"`` (item names) and ``"items"`` (name → item dict).

    Raises
    ------
    ValueError
        If ``history.meta`` lacks a :data:`MODEL_FACTS` key (named), or its ``tip_law`` is
        not the law of its parameters.
    MeaninglessRunError
        If the plate went past the floor and no tip ever touched it.
    """
    f = _facts(history)
    items = {
        "a_over_R": _a_over_R(f),
        "tabor": _tabor(f),
        "linear_deflection": _linear_deflection(history, f),
        "quasi_static": _quasi_static(history, f),
        "time_step": _time_step(f),
        "touched": _touched(f),
        "crack_deborah": _crack_deborah(history.params.contact, f),
        "records": _item("records", *resolution.records(history)),
        "release_step": _item(
            "release_step", *resolution.release_step(history, contact_law(history.params))
        ),
        "pillars_meet": _item(
            "pillars_meet", *resolution.pillars_meet(history, contact_law(history.params))
        ),
        "probe_curvature": _item(
            "probe_curvature",
            *resolution.probe_curvature(history, contact_law(history.params)),
        ),
        "probe_scale": _item("probe_scale", *resolution.probe_scale(history)),
    }
    violations = [name for name, it in items.items() if it["ok"] is False]
    _refuse_if_meaningless(history, f)
    if warn:
        _warn_violations(items, violations)
    return {"ok": not violations, "violations": violations, "items": items}


def _fmt(value) -> str:
    return "?" if value is None else f"{value:.3g}"
