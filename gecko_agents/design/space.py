"""The design search's tables: the material, the tip kinds it can choose, the knobs of the
search space, the objectives and the constraints. Adding a tip law, a backing parameter or a
material property to the search is one entry in :data:`TIP_KINDS`, :data:`KNOBS` or
:data:`MATERIAL`; nothing else changes.

Units: µm, µN, MPa (= µN/µm²), µN/µm for the work of adhesion; pressures on the backing in kPa
(1 kPa = 1e-3 µN/µm²), the unit pull-off per area of fibre arrays is published in.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass

from gecko_agents.params import SetaArray
from gecko_agents.params.checks import MODULUS_RANGE, SURFACE_ENERGY_MAX
from gecko_agents.params.tips import FLAT_FACE_TIPS
from gecko_agents.physics import flaw_tolerance, punch

__all__ = [
    "face_overlap",
    "in_use",
    "KPA",
    "MATERIAL",
    "MATERIAL_DEFAULTS",
    "TipKind",
    "TIP_KINDS",
    "Knob",
    "KNOBS",
    "EXCLUSIVE_KNOBS",
    "CATEGORIES",
    "OBJECTIVES",
    "CONSTRAINTS",
    "pitch_of",
    "gap_of",
    "overrides_of",
]

KPA = 1e-3
"""1 kPa in µN/µm² (MPa = µN/µm²)."""


MATERIAL: dict[str, tuple[tuple[float, float], str]] = {
    "E_MPa": (MODULUS_RANGE, "contact.E1"),
    "nu": ((0.0, 0.5), "contact.nu1"),
    "w_J_per_m2": ((0.0, 2 * SURFACE_ENERGY_MAX), "contact.w"),
    "sigma0_MPa": ((0.0, math.inf), "contact.sigma0"),
}
"""``[material]`` key → (allowed range, the :class:`~gecko_agents.params.SetaArray`
parameter it sets). A material property a new tip law needs is one entry here."""

MATERIAL_DEFAULTS = {"sigma0_MPa": math.inf}
"""``[material]`` keys a design file may leave out, with the value they take: the interface
strength σ₀ [MPa], unbounded (Kendall's punch) unless given."""


@dataclass(frozen=True)
class TipKind:
    """A tip law the search can choose.

    Attributes
    ----------
    tip : ``SetaArray.tip`` of the law (:data:`gecko_agents.params.TIPS`).
    release_force : the design's parameter set → the force [µN] at which one tip
        lets go under a straight pull, from the law's closed form; None where the screen uses
        the quasi-static solver instead (the JKR sphere, whose release depends on the
        pillar's stiffness, :mod:`gecko_agents.quasistatic`).
    contact_stiffness : (a, E*) → the bonded contact's normal stiffness [µN/µm] (in series
        with the pillar), or None for a contact much stiffer than its pillar.
    euler_factor : c in the pillar's buckling load c·π²EI/L² for the end condition the tip
        holds (4: clamped–clamped, the punch's face held flat; 2.046: clamped–pinned, a tip
        free to turn; Timoshenko & Gere 1961, Theory of Elastic Stability, §2.5).
    floors : the surface kinds the law stands on in the time-stepped engine.
    source : the law's source, for the report.
    """

    tip: str
    release_force: Callable[[SetaArray], float] | None
    contact_stiffness: Callable[[float, float], float] | None
    euler_factor: float
    floors: tuple[str, ...]
    source: str


def _law_pull_off(p) -> float:
    """The pull-off force [µN] of the tip law of parameter set ``p`` (its contact law's)."""
    from gecko_agents.contact import contact_law

    return float(contact_law(p).pull_off_force)


ALL_FLOORS = ("measured", "gaussian", "self_affine", "flat", "probe")

TIP_KINDS: dict[str, TipKind] = {
    "flat_punch": TipKind(
        "flat_punch",
        lambda p: float(
            flaw_tolerance.punch_pull_off(
                p.contact.R, p.contact.work_of_adhesion, p.contact.E_star, p.contact.sigma0
            )
        ),
        lambda a, E: float(punch.punch_stiffness(a, E)),
        4.0,
        ALL_FLOORS,
        "Kendall 1971, J Phys D 4:1186 (pull-off), capped by σ₀ (Tang, Hui & Glassmaker 2005, "
        "J R Soc Interface 2:505); Sneddon 1965, Int J Eng Sci 3:47",
    ),
    "sphere": TipKind(
        "sphere", None, None, 2.046, ALL_FLOORS, "Johnson, Kendall & Roberts 1971, Proc R Soc A"
    ),
    "hertz": TipKind("hertz", lambda p: 0.0, None, 2.046, ALL_FLOORS, "Hertz 1882 (no adhesion)"),
    "spatula": TipKind(
        "spatula",
        lambda p: 2.0 * p.contact.R * p.contact.work_of_adhesion,  # a film as wide as the pillar
        None,
        2.046,
        ("gaussian", "flat"),
        "Kendall 1975, J Phys D 8:1449 (90° peel, F = w·b, b = 2r)",
    ),
    "mushroom": TipKind(
        "mushroom",
        lambda p: _law_pull_off(p),
        lambda a, E: float(punch.punch_stiffness(a, E)),
        4.0,
        ALL_FLOORS,
        "the package's mushroom tip (rim and centre modes; Aksak, Şahin & Sitti 2014, Beilstein "
        "J Nanotechnol 5:630): a flange of radius flange_ratio·r",
    ),
}
"""Tip kind → :class:`TipKind`."""


@dataclass(frozen=True)
class Knob:
    """A searchable design parameter: its design-file key, unit, allowed range, whether the
    search samples it on a log scale, and what it sets.

    ``apply(value, values) -> {dotted SetaArray parameter: value}``; ``values`` holds the
    design's other knobs (the stalk radius, for an aspect ratio).
    """

    key: str
    unit: str
    bounds: tuple[float, float]
    log: bool
    apply: Callable[[float, dict], dict]
    doc: str


def pitch_of(values: dict) -> float:
    """Centre-to-centre spacing of the square lattice [µm]: ``spacing_um``, or from the fill
    fraction f = πr²/s² (the share of the backing the pillars' sections cover)."""
    if "spacing_um" in values:
        return float(values["spacing_um"])
    return values["radius_um"] * math.sqrt(math.pi / values["fill_fraction"])


def gap_of(p: SetaArray) -> float:
    """The gap between neighbouring pillars of parameter set ``p`` [µm]: the pitch less the
    widest part of two pillars (a tip wider than its stalk, a mushroom's flange, counts)."""
    return p.array.pitch - 2 * max(p.seta.r, p.contact.R)


KNOBS: dict[str, Knob] = {
    "radius_um": Knob(
        "radius_um",
        "µm",
        (0.05, 100.0),
        True,
        lambda v, d: {"seta.r": v, "contact.R": v, "spatula.b": 2.0 * v},
        "stalk radius r; the tip (sphere, punch face) has the same radius",
    ),
    "aspect_ratio": Knob(
        "aspect_ratio",
        "-",
        (0.5, 50.0),
        False,
        lambda v, d: {"seta.L": 2.0 * d["radius_um"] * v},
        "L/(2r): pillar length over diameter",
    ),
    "lean_deg": Knob(
        "lean_deg",
        "°",
        (10.0, 90.0),
        False,
        lambda v, d: {"seta.theta_deg": v},
        "angle between the pillar and the backing; 90 is vertical",
    ),
    "fill_fraction": Knob(
        "fill_fraction",
        "-",
        (0.001, 0.78),
        True,
        lambda v, d: {"array.pitch": pitch_of(d)},
        "πr²/s² on a square lattice (at most π/4: touching pillars)",
    ),
    "spacing_um": Knob(
        "spacing_um",
        "µm",
        (0.2, 1000.0),
        True,
        lambda v, d: {"array.pitch": v},
        "centre-to-centre spacing s",
    ),
    "flange_ratio": Knob(
        "flange_ratio",
        "-",
        (1.0, 5.0),
        False,
        lambda v, d: {"contact.R": v * d["radius_um"]} if d["tip"] == "mushroom" else {},
        "flange radius over stalk radius of a mushroom tip (other tips: not used)",
    ),
    "rim_angle_deg": Knob(
        "rim_angle_deg",
        "°",
        (1.0, 135.0),
        False,
        lambda v, d: {"mushroom.rim_angle_deg": v} if d["tip"] == "mushroom" else {},
        "edge angle of a sharp mushroom rim (mushroom_rim = 'sharp'; at 45° or less not singular)",
    ),
    "backing_thickness_um": Knob(
        "backing_thickness_um",
        "µm",
        (1.0, 5000.0),
        True,
        lambda v, d: {"backing.t_b": v},
        "thickness of the elastic backing strip or layer (backing = 'elastic' or 'layer')",
    ),
    "backing_modulus_MPa": Knob(
        "backing_modulus_MPa",
        "MPa",
        (0.01, 1e4),
        True,
        lambda v, d: {"backing.E_b": v},
        "modulus of the elastic backing strip or layer (backing = 'elastic' or 'layer')",
    ),
}
"""Design-file key in ``[space]`` → :class:`Knob`."""

EXCLUSIVE_KNOBS = (("fill_fraction", "spacing_um"),)
"""Knobs of which a design file gives exactly one."""

CATEGORIES: dict[str, tuple[str, ...]] = {
    "tip": tuple(TIP_KINDS),
    "backing": ("rigid", "elastic", "layer"),
    "mushroom_rim": ("flawed", "sharp"),
}
"""Categorical knobs in ``[space]``: a name or a list of names to choose from."""

BACKING_KNOBS = ("backing_thickness_um", "backing_modulus_MPa")


def in_use(values: dict) -> dict:
    """The knobs of one design that act on it: those whose :class:`Knob` sets a parameter for
    this design and that :func:`overrides_of` applies (a backing's thickness and modulus only
    off a rigid backing), a mushroom's rim only on a mushroom tip, and its rim angle only on a
    sharp rim (a flawed rim lets go at its flaw, whatever its angle)."""
    mushroom = values.get("tip") == "mushroom"
    rigid = values.get("backing", "rigid") == "rigid"

    def acts(key, value) -> bool:
        if key == "mushroom_rim":
            return mushroom
        if key == "rim_angle_deg" and values.get("mushroom_rim", "flawed") != "sharp":
            return False
        if key in BACKING_KNOBS and rigid:
            return False
        return key not in KNOBS or bool(KNOBS[key].apply(value, values))

    return {k: v for k, v in values.items() if acts(k, v)}


def overrides_of(values: dict, sigma0: float = math.inf) -> dict:
    """The dotted :class:`~gecko_agents.params.SetaArray` overrides of one design; the
    interface strength ``sigma0`` [MPa] goes to a flat face's tip (it acts on no other)."""
    out = {"tip": values["tip"], "backing.kind": values.get("backing", "rigid")}
    if out["backing.kind"] == "layer":  # the engine's layer holds linear or rod pillars
        out["mechanics"] = "rod"
    if values["tip"] in FLAT_FACE_TIPS:
        out["contact.sigma0"] = sigma0
    if values["tip"] == "mushroom":
        out["mushroom.rim"] = values.get("mushroom_rim", "flawed")
    for key, knob in KNOBS.items():
        if key in values and not (key in BACKING_KNOBS and out["backing.kind"] == "rigid"):
            out |= knob.apply(values[key], values)
    return out


def face_overlap(values: dict, base) -> float | None:
    """(2R − s)/s [-] of a design (its knobs ``values``, the design file's fixed ones
    included; ``base`` the :class:`~gecko_agents.params.SetaArray` they override) whose flat
    face of radius R is wider than its stalk r, s the pitch: > 0 where neighbouring faces
    (a mushroom's flanges) overlap; None for other designs."""
    o = overrides_of(values)
    R = o.get("contact.R", base.contact.R)
    r, s = o.get("seta.r", base.seta.r), o.get("array.pitch", base.array.pitch)
    if o["tip"] not in FLAT_FACE_TIPS or R <= r:
        return None
    return (2.0 * R - s) / s


OBJECTIVES: dict[str, tuple[str, str, str]] = {
    "pull_off_per_area": (
        "maximize",
        "kPa",
        "mean pull-off over the backing area, over floor seeds and tilts",
    ),
    "worst_case": ("maximize", "kPa", "smallest pull-off per area over floor seeds and tilts"),
    "spread": (
        "minimize",
        "-",
        "relative spread of the pull-off, std/mean over floor seeds and tilts "
        "(1 for a design that holds nothing)",
    ),
    "release_force": (
        "minimize",
        "kPa",
        "pull-off per area with the backing tilted by test.release_tilt_deg "
        "(a gripper lets go by tilting)",
    ),
}
"""Objective name → (direction, unit, meaning)."""

CONSTRAINTS: dict[str, tuple[str, str]] = {
    "min_radius_um": ("µm", "smallest stalk radius the process makes"),
    "max_aspect_ratio": ("-", "largest aspect ratio L/(2r) the process makes"),
    "min_gap_um": ("µm", "smallest gap s − 2r between neighbouring pillars"),
    "no_buckling_below_kPa": (
        "kPa",
        "pillars carry this pressure on the backing, shared equally, below their Euler load",
    ),
    "max_preload_kPa": (
        "kPa",
        "largest pressure on the backing the user can apply: every pillar of the row "
        "touches the surface at or below it",
    ),
}
"""Constraint key in ``[constraints]`` → (unit, meaning); each is a bound a design must keep."""


@functools.cache
def measured_profile(path: str):
    """The measured scan of a design file, a :class:`gecko_agents.floor.Profile` (read once
    per process)."""
    from gecko_agents.floor import readers

    return readers.load(path)
