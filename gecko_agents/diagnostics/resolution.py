"""Validity items of what a run resolved: its records against its steps, and the plate
travel of the steps in which tips let go. Units: µm, µN (:mod:`gecko_agents.params`).

Each function returns ``(value, meaning, source, applies)`` for
:func:`gecko_agents.diagnostics.diagnose`, which adds the item's limit and verdict.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "records",
    "release_step",
    "release_travel_scale",
    "neighbour_distance",
    "pillars_meet",
    "probe_curvature",
    "probe_scale",
]


RUNNER = "the runner's stepped force extremes (gecko_agents.model.runner)"
TIME_STEPPING = "documentation, explanation, 'Time stepping'"
NEIGHBOURS = "gecko_agents.diagnostics.resolution.neighbour_distance"
CURVATURE = "Johnson 1985, Contact Mechanics, §4.2 (two spheres: R_eff = R·R_p/(R + R_p))"
PROBE_FIELD = "the field under the probe: gecko_agents.physics.fibril_probe_halfspace"


def _peak(force_lo: float, force_hi: float) -> float:
    """The run's peak force [µN]: the most tensile if any tension, else the most compressive."""
    return force_lo if force_lo < 0 else force_hi


def records(history) -> tuple:
    """Shortfall of the recorded peak force against the peak at any step, |ΔF|/|F_step| [-].

    The runner sees the total normal force at every step (``meta["stepped_force_normal_
    range_uN"]``); a record cadence (``record_every``) too sparse for the force history misses
    the peak in the series, and every number read off them (``History.peak_pull_off`` reads
    the stepped extreme instead).
    """
    stepped = history.meta.get("stepped_force_normal_range_uN")
    f = np.asarray(history["force_normal_uN"], dtype=float)
    if not stepped or not len(f):
        return None, "not judged: the run did not keep its stepped force range", RUNNER, False
    if stepped[0] < 0 and not len(history.detachments.get("seta", [])):
        # tension with no tip let go: a jump-in's first step (−8/9 Fc for a JKR sphere), not a
        # pull-off; judged once the run pulls a tip off
        return None, "not judged: no tip let go (the tension is not a pull-off)", RUNNER, False
    peak = _peak(*stepped)
    recorded = float(f.min()) if peak < 0 else float(f.max())
    value = abs(peak - recorded) / abs(peak) if peak else 0.0
    meaning = (
        f"the records' peak force {recorded:.4g} µN against {peak:.4g} µN at the step where it "
        f"happened (record_every = {history.meta.get('record_every')} steps): numbers read off "
        "the series are off by as much; record more often (record_every)"
    )
    return value, meaning, RUNNER, True


def release_travel_scale(params, law) -> float:
    """Plate travel over which a tip's force goes from zero to its pull-off [µm]:
    Fc·(1/Ky + 1/k0), the seta (eq 20) and the contact at zero load (the law's
    ``zero_load_stiffness``) in series; 0 without adhesion."""
    Fc = float(law.pull_off_force)
    k0 = float(law.zero_load_stiffness)
    if Fc <= 0 or k0 <= 0:
        return 0.0
    return Fc * (1.0 / float(params.Ky) + 1.0 / k0)


def release_step(history, law) -> tuple:
    """Plate travel of the longest step in which a tip let go, over the travel over which a
    tip's force rises from zero to its pull-off (:func:`release_travel_scale`) [-].

    A release is resolved to one step of plate travel; past a few per cent of that scale the
    force a tip lets go at, and the peak pull-off, are off by up to about the ratio
    (``tests/test_probe_table.py`` pins it on a located and an unlocated step).
    """
    travel = history.meta.get("release_step_travel_um")
    scale = release_travel_scale(history.params, law)
    applies = bool(travel) and scale > 0 and math.isfinite(scale)
    if not applies:
        return None, "not judged: no tip let go, or the tip has no pull-off", TIME_STEPPING, False
    meaning = (
        f"plate travel {travel:.3g} µm of the longest step in which a tip let go, over the "
        f"{scale:.3g} µm over which a tip's force rises from zero to its pull-off Fc·(1/Ky + "
        "1/k0): a release is resolved to one step, so the pull-off is off by about this "
        "ratio; shorten dt (or event_dt) or slow the plate"
    )
    return travel / scale, meaning, TIME_STEPPING, True


def _point_segment(p, a, b) -> np.ndarray:
    """Distance from points p (P, K, 2) to segments a→b (P, M, 2) → (P, K, M) [µm]."""
    ab = (b - a)[:, None, :, :]
    ap = p[:, :, None, :] - a[:, None, :, :]
    t = np.clip(np.sum(ap * ab, -1) / np.maximum(np.sum(ab * ab, -1), 1e-300), 0.0, 1.0)
    return np.hypot(*np.moveaxis(ap - t[..., None] * ab, -1, 0))


def neighbour_distance(nodes) -> float:
    """Smallest distance between neighbouring setae's centre lines [µm]: polylines of joint
    positions (N, K, 2), each seta against the next (the row's order), as the least distance
    from either's joints to the other's links (a link crossing another within half a link of
    a joint is found as a distance below half a link); inf for fewer than two setae."""
    nodes = np.asarray(nodes, dtype=float)
    if len(nodes) < 2:
        return math.inf
    a, b = nodes[:-1], nodes[1:]
    one = _point_segment(a, b[:, :-1], b[:, 1:]).min()
    other = _point_segment(b, a[:, :-1], a[:, 1:]).min()
    return float(min(one, other))


def _tips_apart(history) -> float:
    """Least distance between neighbouring setae's tip nodes over the records [µm] (the row's
    order), from the per-seta tip series; inf where they were not recorded."""
    x, y = history.setae.get("tip_x_um"), history.setae.get("tip_y_um")
    if x is None or y is None or np.ndim(x) != 2 or np.shape(x)[1] < 2 or not len(x):
        return math.inf
    return float(np.min(np.hypot(np.diff(x, axis=1), np.diff(y, axis=1))))


def pillars_meet(history, law) -> tuple:
    """Smallest distance between neighbouring pillars over the records, over the width they
    need [-]: their centre lines over the diameter 2r and, for a flat face wider than its
    stalk (a mushroom's flange, R > r), their tips over the face's diameter 2R (the centre
    lines over 2R where the tips were not recorded). Below 1 they pass through each other,
    which the model does not stop (pillars touch only the floor), so the forces are those of
    pillars, or flanges, that could not be there."""
    gap = history.meta.get("min_neighbour_distance_um")
    if gap is None or not math.isfinite(gap):
        return None, "not judged: one seta, or not an elastica", NEIGHBOURS, False
    d = 2.0 * history.params.seta.r
    value = gap / d
    meaning = (
        f"neighbouring centre lines came {gap:.3g} µm apart, against the pillars' diameter "
        f"{d:.3g} µm: below 1 they pass through each other (no pillar–pillar contact in the "
        "model); space them wider (array.pitch) or press less"
    )
    face = 2.0 * float(law.R)
    if law.flat_face and face > d:
        tips = _tips_apart(history)
        tips = gap if math.isinf(tips) else tips
        if tips / face < value:
            value = tips / face
            meaning = (
                f"neighbouring tips came {tips:.3g} µm apart, against the faces' diameter "
                f"{face:.3g} µm (wider than the stalks' {d:.3g} µm): below 1 the faces overlap "
                "(no contact between them in the model); space them wider (array.pitch), "
                "use smaller faces (contact.R) or press less"
            )
    return value, meaning, NEIGHBOURS, True


def probe_curvature(history, law) -> tuple:
    """How far the tip law's flat floor is from a spherical probe's surface under a tip [-].

    The tip laws take the floor under a tip as flat. On a probe of radius R_p a sphere of
    radius R meets a sphere: JKR and Hertz then hold with R_eff = R·R_p/(R + R_p) (Johnson
    1985, *Contact Mechanics*, §4.2), so a pull-off ∝ R is off by R/(R + R_p): the value is
    R/R_p. A flat face of radius a meets a dome that sags a²/(2R_p) below its edge: the value
    is that sag over the face's snap-off overlap |δc|, the scale on which its force changes.
    """
    p = history.params
    if p.floor.kind != "probe":
        return None, "not judged: the floor is not a probe", CURVATURE, False
    Rp, R = float(p.floor.probe_radius), float(p.contact.R)
    if law.flat_face:
        sag = R * R / (2.0 * Rp)
        stroke = abs(float(law.detach_overlap)) or math.inf
        meaning = (
            f"the probe (R_p = {Rp:g} µm) sags {sag:.3g} µm under the edge of a face of radius "
            f"{R:g} µm, against its snap-off overlap {stroke:.3g} µm: the face law takes the "
            "probe as flat under it; use a larger probe or smaller faces"
        )
        return sag / stroke, meaning, CURVATURE, True
    meaning = (
        f"tip radius {R:g} µm over probe radius {Rp:g} µm: the tip law uses R where two "
        "spheres in contact act with R_eff = R·R_p/(R + R_p), so a pull-off is off by about "
        "this ratio"
    )
    return R / Rp, meaning, CURVATURE, True


def probe_scale(history) -> tuple:
    """``scale_to_array`` = array.count / n_sim of a run under a spherical probe [-].

    The factor scales the simulated setae's forces to the array as if they were a uniform
    patch of it. Under a probe they are not: each pillar meets the sphere at its own height,
    so the scaled force is not the array's. Above 1 it stands for pillars never simulated."""
    if history.params.floor.kind != "probe":
        return None, "not judged: the floor is not a probe", PROBE_FIELD, False
    scale = float(history.meta.get("scale_to_array", 1.0))
    meaning = (
        f"scale_to_array = {scale:g} under a spherical probe (floor.kind = 'probe'): the "
        "simulated row is not a uniform patch of the array (each pillar meets the probe at its "
        "own height), so its forces, scaled, are not the array's; simulate every pillar "
        "(n_sim = array.count), or take the field under the probe from "
        "gecko_agents.physics.fibril_probe_halfspace"
    )
    return scale, meaning, PROBE_FIELD, True
