"""The screen: a design's objectives and constraints from the package's fast models.

A row of ``test.pillars`` pillars on a rigid backing stands over the surface (the floor drawn
as the time-stepped engine draws it, :func:`gecko_agents.floor.for_array` with the run's seed:
a row as long as the engine's meets the very heights its tips meet; a longer row draws a longer
generated floor, whose heights differ), is pressed
to the test's preload (a pressure on the backing, shared over the row's backing area n·s²) and
pulled straight off (these laws are elastic and rate-free: the pull speed is the engine's).
Per tip kind (:data:`~gecko_agents.design.space.TIP_KINDS`):

* a tip with a closed-form release force (flat punch: Kendall's √(8πE*wa³); spatula: the 90°
  peel w·b; Hertz: none) is a linear fibril, the pillar's normal stiffness (eq 20 of the
  paper: axial EπR²/L for a vertical pillar) in series with the bonded contact's (Sneddon's
  2E*a for the punch), letting go at that force:
  :func:`gecko_agents.physics.fibril_probe.probe_pull_off` (the independent-fibril model of
  Noderer et al. 2007, Proc R Soc A, doi:10.1098/rspa.2007.1891);
* the JKR sphere is the quasi-static solver on linear setae
  (:func:`gecko_agents.quasistatic.preload_pull`, the paper's eq 22–27), which finds each
  tip's release at the fold of the spring–contact system;
* on a backing layer (``backing = "layer"``) every tip is the field model's fibril
  (:mod:`gecko_agents.physics.layer_field`: the pillar in series with the contact's
  zero-load stiffness, letting go at the law's pull-off force; for the tips above, the same
  stiffness and release force), the roots coupled through the layer's compliance as the
  engine couples them (:func:`layer_compliance`, the engine's row in plane strain), pressed and
  pulled from event to event (:func:`gecko_agents.physics.fibril_probe_halfspace.probe_test`,
  exact for linear fibrils; with no compliance it is the rigid backing's closed form).

Floor seeds and backing tilts (``test.misalignment_spread_deg``: −spread, 0, +spread; a tilt
adds the ramp x·tan α to the heights) give the spread; ``test.release_tilt_deg`` gives the
release force. Units: µm, µN, MPa; pressures on the backing in kPa.
"""

from __future__ import annotations

import math

import numpy as np

from gecko_agents import floor
from gecko_agents.design.space import (
    KPA,
    TIP_KINDS,
    face_overlap,
    gap_of,
    measured_profile,
    overrides_of,
)
from gecko_agents.params import SetaArray
from gecko_agents.physics import beam, fibril_probe, fibril_probe_halfspace, layer

__all__ = [
    "design_params",
    "row_heights",
    "evaluate",
    "euler_load",
    "measured_profile",
    "layer_compliance",
    "field_fibril",
    "layer_pull_off",
    "fibril_stiffness",
    "full_contact_force",
]


def design_params(spec, values: dict, n: int | None = None) -> SetaArray:
    """The engine's parameter set of one design: the design file's base, the design's knobs,
    ``n`` pillars in the row (default ``test.pillars``)."""
    from gecko_agents.design.schema import base_params

    values = {**spec.fixed, **values}
    p = base_params(spec).replace(**overrides_of(values, spec.material["sigma0_MPa"]))
    return p.replace(**{"array.count": int(n or spec.test["pillars"])})


def measured_offset(spec, profile: floor.Profile, row_length: float, i: int) -> float:
    """Where on the scan the row of floor seed ``i`` starts [µm]: 0 for the first seed, then
    drawn uniformly over the scan's length left beyond the row (seeded by the study's seed)."""
    span = float(profile.x[-1] - profile.x[0]) - row_length
    if i == 0 or span <= 0:
        return 0.0
    return float(np.random.default_rng([spec.seed, i]).uniform(0.0, span))


def crop(profile: floor.Profile, offset: float) -> floor.Profile:
    """The scan from ``offset`` [µm] on, its start moved to x = 0."""
    k = int(np.searchsorted(profile.x, profile.x[0] + offset))
    x = profile.x[k:] - profile.x[k]
    return floor.Profile(x=x, y=profile.y[k:], spacing=profile.spacing, source=profile.source)


def floor_seed(spec, i: int) -> int:
    """The seed of floor ``i`` of a study: ``seed + i`` (also the engine run's seed)."""
    return spec.seed + i


def row_heights(spec, p: SetaArray, i: int) -> np.ndarray:
    """Floor heights [µm] under the row's tips for floor seed ``i``: the profile the engine
    builds (:func:`gecko_agents.floor.for_array`, the same touch-down abscissae and margin)."""
    n, L, theta = p.array.count, p.seta.L, p.seta.theta
    touch_x = (np.arange(n) - (n - 1) / 2.0) * p.array.pitch + float(
        beam.rest_tip_offset(L, theta)[0]
    )
    measured = engine_floor(spec, p, i)
    rng = np.random.default_rng(floor_seed(spec, i))
    prof = floor.for_array(p.floor, touch_x, p.array.pitch, 50.0 + 3 * L, rng, measured=measured)
    if prof.pad_heights is not None:
        return np.asarray(prof.pad_heights, float)
    return np.asarray(prof.height_at(touch_x), float)


def engine_floor(spec, p: SetaArray, i: int) -> floor.Profile | None:
    """The measured profile the engine is given for floor seed ``i`` (None for generated)."""
    if spec.surface["kind"] != "measured":
        return None
    prof = measured_profile(spec.surface["file"])
    row = (p.array.count - 1) * p.array.pitch + 2 * (50.0 + 3 * p.seta.L)
    return crop(prof, measured_offset(spec, prof, row, i))


def euler_load(p: SetaArray, factor: float) -> float:
    """Buckling load c·π²EI/L² of a pillar [µN], I = πr⁴/4 (Euler; the factor c of the end
    condition, :class:`~gecko_agents.design.space.TipKind`)."""
    EI = p.contact.E1 * math.pi * p.seta.r**4 / 4.0
    return factor * math.pi**2 * EI / p.seta.L**2


def fibril_stiffness(p: SetaArray) -> float:
    """Normal stiffness of one pillar and its bonded contact in series [µN/µm]: the pillar's
    eq 20 (Ky of the paper) and the tip law's contact stiffness, if any."""
    k = p.Ky
    kind = TIP_KINDS[p.tip]
    if kind.contact_stiffness is not None:
        k = 1.0 / (1.0 / k + 1.0 / kind.contact_stiffness(p.contact.R, p.contact.E_star))
    return k


def layer_compliance(p: SetaArray) -> np.ndarray | None:
    """The backing layer's compliance between the row's roots [µm/µN] (n, n), None on any
    other backing: the engine's (:mod:`gecko_agents.backing.layer`), a row standing for rows
    one pitch apart with each root's force over a strip one pitch wide,
    :func:`gecko_agents.physics.layer.row_compliance` of the layer t_b, E_b, ν_b."""
    if p.backing.kind != "layer":
        return None
    s, b = p.array.pitch, p.backing
    return layer.row_compliance(s * np.arange(p.array.count), b.t_b, b.E_b, b.nu_b, s, s)


def field_fibril(p: SetaArray) -> tuple[float, float]:
    """(stiffness k [µN/µm], release force F_r [µN]) of one pillar in the field model: the
    screen's linear fibril where the tip law has a closed-form release (:func:`fibril_stiffness`,
    :class:`~gecko_agents.design.space.TipKind`), else the field model's own
    (:meth:`gecko_agents.physics.layer_field.LayerField.from_params`: Ky in series with the
    law's zero-load contact stiffness, released at its pull-off force under fixed load, the
    most a JKR tip on a spring holds)."""
    kind = TIP_KINDS[p.tip]
    if kind.release_force is not None:
        return fibril_stiffness(p), float(kind.release_force(p))
    from gecko_agents.contact import contact_law

    law = contact_law(p)
    return 1.0 / (1.0 / p.Ky + 1.0 / law.zero_load_stiffness), float(law.pull_off_force)


def layer_pull_off(p: SetaArray, heights, preload: float, C) -> tuple[float, float]:
    """(pull-off [µN], a bound on the largest force one pillar carries at the preload [µN])
    of the row on a backing layer of compliance ``C`` [µm/µN] (:func:`layer_compliance`):
    the field model's press to ``preload`` [µN] and pull, event to event. A root only sinks
    under compressive loads, so the highest tip carries at most k·d_max."""
    k, F_r = field_fibril(p)
    h = np.asarray(heights, float) - np.max(heights)
    res = fibril_probe_halfspace.probe_test(h, np.eye(h.size) / k + C, F_r, preload)
    return float(res.pull_off), k * float(res.depth_max)


def full_contact_force(p: SetaArray, heights, C=None) -> float:
    """Force [µN] that brings every tip of the row onto the floor: pressed until the tip over
    the lowest point touches, the others held, f = (I/k + C)⁻¹(h − min h) summed (Σ k·(h_i −
    min h) on a rigid backing; on a layer a lower bound, should the layer lift the lowest
    root further as the others load it)."""
    k = field_fibril(p)[0] if C is not None else fibril_stiffness(p)
    gap = np.asarray(heights, float) - np.min(heights)
    if C is None:
        return float(np.sum(gap)) * k
    return float(np.sum(np.linalg.solve(np.eye(gap.size) / k + C, gap)))


def pull_off(p: SetaArray, heights: np.ndarray, preload: float, C=None) -> tuple[float, float]:
    """(pull-off [µN], largest force one pillar carries at the preload [µN]) of the row over
    ``heights`` pressed to ``preload`` [µN] and pulled straight off; on a backing layer of
    compliance ``C`` by :func:`layer_pull_off`."""
    if C is not None:
        return layer_pull_off(p, heights, preload, C)
    kind = TIP_KINDS[p.tip]
    h = heights - np.max(heights)
    if kind.release_force is None:  # the JKR sphere: the quasi-static solver
        from gecko_agents import quasistatic

        lin = p.replace(mechanics="linear")
        res = quasistatic.preload_pull(lin, heights, preload, record_setae=True)
        return float(res.pull_off), float(np.max(res.per_seta["force"]))
    k = fibril_stiffness(p)
    d_max = fibril_probe.depth_for_preload(preload, h, k)
    F_r = kind.release_force(p)
    return fibril_probe.probe_pull_off(h, k, F_r, d_max), k * d_max


def _tilted(heights: np.ndarray, pitch: float, alpha_deg: float) -> np.ndarray:
    x = (np.arange(heights.size) - (heights.size - 1) / 2.0) * pitch
    return heights + x * math.tan(math.radians(alpha_deg))


def tilts(spec) -> tuple[float, ...]:
    """Backing tilts the spread is taken over [°]: 0, or −spread, 0 and +spread."""
    a = spec.test["misalignment_spread_deg"]
    return (0.0,) if a == 0 else (-a, 0.0, a)


def evaluate(spec, values: dict) -> dict:
    """One design's screen: ``objectives`` (name → value, the units of
    :data:`~gecko_agents.design.space.OBJECTIVES`), ``constraints`` (key → violation, ≤ 0
    where the design keeps the bound, as a fraction of it), ``metrics`` (what the report
    shows) and ``validity`` (the screen's assumptions, each judged for this design)."""
    from gecko_agents.design.schema import base_params

    overlap = face_overlap({**spec.fixed, **values}, base_params(spec))
    if overlap is not None and overlap > 0:
        return _overlapping_faces(overlap)
    p = design_params(spec, values)
    n, s = p.array.count, p.array.pitch
    area = n * s * s
    preload = spec.test["preload_kPa"] * KPA * area
    per_area, peak_pillar, full_touch = [], 0.0, 0.0
    C = layer_compliance(p)
    for i in range(spec.test["floor_seeds"]):
        h = row_heights(spec, p, i)
        for alpha in tilts(spec):
            ht = _tilted(h, s, alpha)
            F, top = pull_off(p, ht, preload, C)
            per_area.append(F / area / KPA)
            peak_pillar = max(peak_pillar, top)
            full_touch = max(full_touch, full_contact_force(p, ht, C) / area / KPA)
    per_area = np.asarray(per_area)
    mean = float(np.mean(per_area))
    h0 = _tilted(row_heights(spec, p, 0), s, spec.test["release_tilt_deg"])
    release = pull_off(p, h0, preload, C)[0] / area / KPA
    kind = TIP_KINDS[p.tip]
    vertical = p.seta.theta_deg == 90.0
    P_E = euler_load(p, kind.euler_factor) if vertical else math.inf
    objectives = {
        "pull_off_per_area": mean,
        "worst_case": float(np.min(per_area)),
        "spread": float(np.std(per_area) / mean) if mean > 0 else 1.0,
        "release_force": float(release),
    }
    metrics = {
        "pitch_um": s,
        "L_um": p.seta.L,
        "gap_um": gap_of(p),
        "fill_fraction": math.pi * p.seta.r**2 / s**2,
        "euler_load_uN": P_E,
        "preload_per_pillar_uN": preload / n,
        "peak_pillar_force_uN": peak_pillar,
        "full_contact_kPa": full_touch,
        "pull_off_std_kPa": float(np.std(per_area)),
    }
    constraints = constraint_values(spec, values, p, metrics)
    if overlap is not None:
        constraints[FACES_FIT] = overlap
    return {
        "objectives": objectives,
        "constraints": constraints,
        "metrics": metrics,
        "validity": validity(spec, p, metrics),
    }


FACES_FIT = "faces_fit_pitch"
"""The constraint every design with a face wider than its stalk keeps: (2R − s)/s ≤ 0, its
neighbouring faces (a mushroom's flanges) apart (the parameters refuse overlapping ones)."""


def _overlapping_faces(overlap: float) -> dict:
    """The screen of a design whose faces overlap: no array holds it, so it holds nothing
    and breaks :data:`FACES_FIT` (its metrics not computed, NaN)."""
    keys = ("pitch_um", "L_um", "gap_um", "fill_fraction", "euler_load_uN",
            "preload_per_pillar_uN", "peak_pillar_force_uN", "full_contact_kPa",
            "pull_off_std_kPa")  # fmt: skip
    return {
        "objectives": {
            "pull_off_per_area": 0.0,
            "worst_case": 0.0,
            "spread": 1.0,
            "release_force": 0.0,
        },
        "constraints": {FACES_FIT: overlap},
        "metrics": dict.fromkeys(keys, math.nan),
        "validity": [],
    }


def constraint_values(spec, values: dict, p: SetaArray, m: dict) -> dict:
    """Each constraint of the design file as a violation, ≤ 0 where the design keeps it (a
    fraction of the bound). The buckling bound is the equal share of the pressure,
    ``no_buckling_below_kPa``·s², against the Euler load (leaning pillars bend rather than
    buckle: no bound)."""
    c, out = spec.constraints, {}
    values = {**spec.fixed, **values}
    if "min_radius_um" in c:
        out["min_radius_um"] = (c["min_radius_um"] - p.seta.r) / c["min_radius_um"]
    if "max_aspect_ratio" in c:
        ar = values["aspect_ratio"]
        out["max_aspect_ratio"] = (ar - c["max_aspect_ratio"]) / c["max_aspect_ratio"]
    if "min_gap_um" in c:
        out["min_gap_um"] = (c["min_gap_um"] - m["gap_um"]) / max(c["min_gap_um"], 1e-9)
    if "no_buckling_below_kPa" in c:
        share = c["no_buckling_below_kPa"] * KPA * p.array.pitch**2
        out["no_buckling_below_kPa"] = (
            (share - m["euler_load_uN"]) / m["euler_load_uN"]
            if math.isfinite(m["euler_load_uN"])
            else -1.0
        )
    if "max_preload_kPa" in c:
        out["max_preload_kPa"] = (m["full_contact_kPa"] - c["max_preload_kPa"]) / c[
            "max_preload_kPa"
        ]
    return out


def validity(spec, p: SetaArray, m: dict) -> list[dict]:
    """The screen's assumptions for this design: ``name``, ``ok`` (True, False, or None where
    it is not judged), ``meaning``."""
    elastic = p.backing.kind == "elastic"
    below = bool(m["peak_pillar_force_uN"] < m["euler_load_uN"])
    return [
        {
            "name": "screen_below_buckling",
            "ok": below,
            "meaning": "the most loaded pillar stays below its Euler load at the test preload "
            "(the screen's pillars are linear springs; a buckled one carries no more)",
        },
        {
            "name": "screen_rigid_backing",
            "ok": not elastic,
            "meaning": "the screen shares the load over a rigid backing or through a backing "
            "layer (the field model); an elastic strip is judged by the engine's confirmation "
            "only",
        },
        {
            "name": "screen_field_release",
            "ok": False
            if p.backing.kind == "layer" and TIP_KINDS[p.tip].release_force is None
            else None,
            "meaning": "on a backing layer a JKR sphere lets go at its pull-off force under "
            "fixed load (the field model's fibril), the most it holds on a spring",
        },
        {
            "name": "screen_small_lean",
            "ok": p.seta.theta_deg == 90.0 or None,
            "meaning": "a leaning pillar is the paper's linear beam (eq 16-21) in the screen and "
            "an elastica in the engine",
        },
    ]
