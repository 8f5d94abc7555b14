"""Design files: reading and checking them entirely before any trial runs.

The format is described in :mod:`gecko_agents.design`. Every error is a
:class:`~gecko_agents.runfiles.schema.RunFileError` naming the file, the key, the value and the
allowed range (the command line exits with 2 and runs nothing).
"""

from __future__ import annotations

import hashlib
import itertools
import math
from dataclasses import dataclass, field
from pathlib import Path

from gecko_agents.data import DEKTAK_PROFILE
from gecko_agents.design.space import (
    CATEGORIES,
    CONSTRAINTS,
    EXCLUSIVE_KNOBS,
    KNOBS,
    MATERIAL,
    MATERIAL_DEFAULTS,
    OBJECTIVES,
    TIP_KINDS,
    face_overlap,
    gap_of,
    overrides_of,
)
from gecko_agents.params import PAPER_ARRAY, SetaArray
from gecko_agents.runfiles.schema import Ctx, read_toml, sub_table

__all__ = ["DesignSpec", "load_design", "base_params", "PACKAGED_SCANS", "SEED_MAX"]

PACKAGED_SCANS = {"dektak": DEKTAK_PROFILE}
"""Names a design file may give as ``surface.file`` for a scan shipped with the package."""

SEED_MAX = 2**32 - 1
"""The largest study seed: Optuna's samplers seed numpy's legacy RandomState, which takes
seeds in [0, 2³² − 1]."""

_TOP = {"description", "seed", "trials", "confirm", "objectives"}
_TABLES = ("material", "surface", "test", "space", "constraints")
_QUICK = {"trials", "confirm", "test"}
_SURFACES = ("measured", "gaussian", "self_affine", "flat")
_SURFACE_NUM = {
    "sigma_um": (0.0, 100.0),
    "correlation_length_um": (0.0, 100.0),
    "hurst": (0.0, 1.0),
    "short_cutoff_um": (1e-3, 1e4),
    "long_cutoff_um": (1e-3, 1e7),
}
_TEST_NUM = {
    "probe_radius_um": (1.0, 1e5),
    "preload_kPa": (1e-3, 1e4),
    "pull_speed_um_per_us": (1e-4, 1.0),
    "misalignment_spread_deg": (0.0, 5.0),
    "release_tilt_deg": (0.0, 10.0),
}
_TEST_INT = {
    "floor_seeds": (1, 50),
    "pillars": (2, 2000),
    "engine_pillars": (1, 40),
    "engine_seeds": (1, 10),
}
_TEST_DEFAULTS = {
    "probe": "flat",
    "probe_radius_um": 100.0,
    "pull_speed_um_per_us": 0.05,
    "misalignment_spread_deg": 0.0,
    "release_tilt_deg": 1.0,
    "floor_seeds": 3,
    "pillars": 20,
    "engine_pillars": 5,
    "engine_seeds": 2,
}


@dataclass(frozen=True)
class DesignSpec:
    """A checked design file.

    Attributes
    ----------
    path, text : the file and its bytes; ``sha256`` their digest (names the study).
    quick : whether the ``[quick]`` variant was taken.
    seed : the study's seed (sampler and floor seeds); ``trials``: screening trials;
        ``confirm``: designs confirmed with the engine.
    material : E_MPa, nu, w_J_per_m2. surface : kind and its statistics (``file``: the scan's
        path). test : probe, preload, speeds, seeds and pillar counts (defaults filled in).
    fixed : knob → value; ``ranges``: knob → (lo, hi) searched; ``choices``: category →
        names searched or fixed (one name).
    objectives : names of :data:`~gecko_agents.design.space.OBJECTIVES`, in order.
    constraints : key of :data:`~gecko_agents.design.space.CONSTRAINTS` → bound.
    """

    path: Path
    text: bytes
    sha256: str
    quick: bool
    description: str
    seed: int
    trials: int
    confirm: int
    material: dict
    surface: dict
    test: dict
    fixed: dict
    ranges: dict
    choices: dict
    objectives: tuple[str, ...]
    constraints: dict
    resolved: dict = field(default_factory=dict)

    @property
    def directions(self) -> list[str]:
        return [OBJECTIVES[o][0] for o in self.objectives]


def base_params(spec: DesignSpec) -> SetaArray:
    """The parameter set every design of ``spec`` starts from: the paper's array with the
    design file's material, elastica pillars and the surface's floor statistics."""
    m, s = spec.material, spec.surface
    # σ₀ acts on a flat face only: set with the design's tip (screen.design_params)
    over = {param: m[key] for key, (_, param) in MATERIAL.items() if param != "contact.sigma0"}
    over |= {"mechanics": "elastica", "floor.sigma": 0.0}
    if spec.test["probe"] == "sphere":
        over |= {"floor.kind": "probe", "floor.probe_radius": spec.test["probe_radius_um"]}
    elif s["kind"] == "gaussian":
        over |= {
            "floor.sigma": s.get("sigma_um", 0.0),
            "floor.correlation_length": s.get("correlation_length_um", 0.0),
        }
    elif s["kind"] == "self_affine":
        over |= {"floor.kind": "self_affine", "floor.sigma": s.get("sigma_um", 0.0)}
        for k, p in (
            ("hurst", "hurst"),
            ("short_cutoff_um", "short_cutoff"),
            ("long_cutoff_um", "long_cutoff"),
        ):
            if k in s:
                over[f"floor.{p}"] = s[k]
    return PAPER_ARRAY.replace(**over)


def _number(ctx: Ctx, where: str, value, lo: float, hi: float, integer=False):
    v = ctx.type_(where, value, int if integer else float)
    if not (lo <= v <= hi) or (not integer and math.isinf(v) and math.isfinite(hi)):
        shown = f"[{lo}, {hi}]" if integer else f"[{lo:g}, {hi:g}]"
        raise ctx.error(where, f"{value!r} is outside the allowed range {shown}")
    return v


def _material(ctx: Ctx, t: dict) -> dict:
    ctx.keys("[material]", t, MATERIAL)
    out = {}
    for key, ((lo, hi), _) in MATERIAL.items():
        if key not in t and key in MATERIAL_DEFAULTS:
            out[key] = MATERIAL_DEFAULTS[key]
            continue
        if key not in t:
            raise ctx.error("[material]", f"missing key {key!r} (range [{lo:g}, {hi:g}])")
        out[key] = _number(ctx, f"[material] {key}", t[key], lo, hi)
        if key == "nu" and out[key] >= 0.5:
            raise ctx.error("[material] nu", f"{t[key]!r} is outside the allowed range [0, 0.5)")
    return out


def _surface(ctx: Ctx, t: dict) -> dict:
    ctx.keys("[surface]", t, {"kind", "file", *_SURFACE_NUM})
    kind = ctx.type_("[surface] kind", t.get("kind", "flat"), str)
    if kind not in _SURFACES:
        raise ctx.error("[surface] kind", f"{kind!r} must be one of {', '.join(_SURFACES)}")
    out: dict = {"kind": kind}
    for key, (lo, hi) in _SURFACE_NUM.items():
        if key in t:
            if kind in ("measured", "flat"):
                raise ctx.error(f"[surface] {key}", f"applies to a generated floor, not {kind!r}")
            out[key] = _number(ctx, f"[surface] {key}", t[key], lo, hi)
    if kind == "measured":
        name = ctx.type_("[surface] file", t.get("file", ""), str)
        path = PACKAGED_SCANS.get(name) or (ctx.path.parent / name)
        if not name or not Path(path).is_file():
            raise ctx.error(
                "[surface] file",
                f"{name!r} is not a readable file; give a scan's path (relative to the design "
                f"file) or one of {', '.join(PACKAGED_SCANS)}",
            )
        out["file"] = str(Path(path).resolve())
        out["name"] = name
    elif "file" in t:
        raise ctx.error("[surface] file", f"applies to kind = 'measured', not {kind!r}")
    return out


def _test(ctx: Ctx, t: dict, quick_t: dict) -> dict:
    ctx.keys("[test]", t, {"probe", *_TEST_NUM, *_TEST_INT})
    out = dict(_TEST_DEFAULTS)
    for key, value in t.items():
        where = f"[{'quick.' if key in quick_t else ''}test] {key}"
        if key == "probe":
            out[key] = ctx.type_(where, value, str)
            if out[key] not in ("flat", "sphere"):
                raise ctx.error(where, f"{value!r} must be 'flat' or 'sphere'")
        elif key in _TEST_NUM:
            out[key] = _number(ctx, where, value, *_TEST_NUM[key])
        else:
            out[key] = _number(ctx, where, value, *_TEST_INT[key], integer=True)
    if "preload_kPa" not in out:
        raise ctx.error("[test]", "missing key 'preload_kPa' (pressure on the backing [kPa])")
    return out


def _space(ctx: Ctx, t: dict) -> tuple[dict, dict, dict]:
    ctx.keys("[space]", t, {*KNOBS, *CATEGORIES})
    fixed, ranges, choices = {}, {}, {}
    for cat, allowed in CATEGORIES.items():
        value = t.get(cat, allowed[0] if cat != "tip" else None)
        if value is None:
            raise ctx.error("[space]", f"missing key {cat!r} (one or a list of {allowed})")
        names = [value] if isinstance(value, str) else value
        if not isinstance(names, list) or not names:
            raise ctx.error(f"[space] {cat}", f"{value!r} must be a name or a list of names")
        for n in names:
            if n not in allowed:
                raise ctx.error(f"[space] {cat}", f"{n!r} must be one of {', '.join(allowed)}")
        choices[cat] = tuple(dict.fromkeys(names))
    for key, knob in KNOBS.items():
        if key not in t:
            continue
        lo, hi = knob.bounds
        where = f"[space] {key}"
        v = t[key]
        if isinstance(v, list):
            if len(v) != 2:
                raise ctx.error(where, f"{v!r} must be a number or a range [low, high]")
            a = _number(ctx, where, v[0], lo, hi)
            b = _number(ctx, where, v[1], lo, hi)
            if not a < b:
                raise ctx.error(where, f"{v!r}: low must be below high")
            ranges[key] = (a, b)
        else:
            fixed[key] = _number(ctx, where, v, lo, hi)
    for need in ("radius_um", "aspect_ratio"):
        if need not in fixed and need not in ranges:
            lo, hi = KNOBS[need].bounds
            raise ctx.error(
                "[space]", f"missing key {need!r} (a number or a range in [{lo:g}, {hi:g}])"
            )
    for group in EXCLUSIVE_KNOBS:
        given = [k for k in group if k in fixed or k in ranges]
        if len(given) != 1:
            raise ctx.error(
                "[space]", f"give exactly one of {', '.join(group)} (got {given or 'none'})"
            )
    if choices["backing"] == ("rigid",):
        for key in ("backing_thickness_um", "backing_modulus_MPa"):
            if key in fixed or key in ranges:
                raise ctx.error(f"[space] {key}", "applies to backing = 'elastic' or 'layer'")
    return fixed, ranges, choices


def _constraints(ctx: Ctx, t: dict) -> dict:
    ctx.keys("[constraints]", t, CONSTRAINTS)
    return {k: _number(ctx, f"[constraints] {k}", v, 0.0, 1e7) for k, v in t.items()}


def _objectives(ctx: Ctx, value) -> tuple[str, ...]:
    names = [value] if isinstance(value, str) else value
    if not isinstance(names, list) or not names:
        raise ctx.error(
            "objectives", f"{value!r} must be a name or a list of {', '.join(OBJECTIVES)}"
        )
    for n in names:
        if n not in OBJECTIVES:
            raise ctx.error("objectives", f"{n!r} must be one of {', '.join(OBJECTIVES)}")
    if len(set(names)) != len(names):
        raise ctx.error("objectives", f"{names!r} names an objective twice")
    return tuple(names)


def _cross_checks(ctx: Ctx, spec: DesignSpec) -> None:
    """What the tables decide together: every tip stands on the surface, the fabrication bounds
    leave some of the space, and every corner of the space is a valid parameter set."""
    floor = "probe" if spec.test["probe"] == "sphere" else spec.surface["kind"]
    for tip in spec.choices["tip"]:
        if floor not in TIP_KINDS[tip].floors:
            raise ctx.error(
                "[space] tip",
                f"{tip!r} cannot stand on a {floor!r} surface in the engine (it stands on "
                f"{', '.join(TIP_KINDS[tip].floors)})",
            )
    span = {**{k: (v, v) for k, v in spec.fixed.items()}, **spec.ranges}
    for key, knob, above in (
        ("min_radius_um", "radius_um", True),
        ("max_aspect_ratio", "aspect_ratio", False),
    ):
        bound = spec.constraints.get(key)
        lo, hi = span[knob]
        if bound is not None and (bound > hi if above else bound < lo):
            raise ctx.error(
                f"[constraints] {key}",
                f"{bound:g} leaves no design: [space] {knob} spans [{lo:g}, {hi:g}]",
            )
    base = base_params(spec)
    corners = [[(k, v) for v in spec.ranges[k]] for k in spec.ranges]
    sigma0 = spec.material["sigma0_MPa"]
    widest = (-math.inf, "")  # the widest gap between pillars at a corner [µm], where
    fits = 0  # corners whose faces fit the pitch (overlap is monotone: the least is a corner)
    for tip, backing, rim in itertools.product(
        spec.choices["tip"], spec.choices["backing"], spec.choices["mushroom_rim"]
    ):
        for corner in itertools.islice(itertools.product(*corners), 256):
            values = {**spec.fixed, **dict(corner), "tip": tip, "backing": backing}
            values["mushroom_rim"] = rim
            shown = ", ".join(f"{k} = {v:g}" for k, v in corner) or "the fixed values"
            overlap = face_overlap(values, base)
            if overlap is not None and overlap > 0:  # a broken constraint, not refused
                continue
            fits += 1
            try:
                p = base.replace(**overrides_of(values, sigma0))
            except (ValueError, TypeError) as err:
                raise ctx.error(
                    "[space]",
                    f"the design at {shown} (tip {tip!r}) is not a valid parameter set: {err}",
                ) from None
            _check_scan(ctx, spec, p, corner)
            widest = max(widest, (gap_of(p), f"{shown}, tip {tip!r}"))
    if not fits:
        knobs = ("radius_um", "flange_ratio", "fill_fraction", "spacing_um")
        shown = ", ".join(f"{k} in [{span[k][0]:g}, {span[k][1]:g}]" for k in knobs if k in span)
        raise ctx.error(
            "[space]",
            f"{shown} leaves no design whose flanges fit the pitch: flange_ratio·radius_um "
            "must be at most half the pitch (pitch = radius_um·√(π/fill_fraction), or "
            "spacing_um), else neighbouring flanges overlap",
        )
    bound = spec.constraints.get("min_gap_um")
    if bound is not None and widest[0] < bound:  # the gap is monotone in each knob
        raise ctx.error(
            "[constraints] min_gap_um",
            f"{bound:g} leaves no design: the widest gap of [space] is {widest[0]:.4g} µm "
            f"(at {widest[1]})",
        )


def _check_scan(ctx: Ctx, spec: DesignSpec, p: SetaArray, corner) -> None:
    """A measured scan long enough for the longest row the space holds (the engine's floor
    reaches 50 µm + 3L beyond the outermost tips)."""
    if spec.surface["kind"] != "measured":
        return
    from gecko_agents.design.space import measured_profile

    try:
        prof = measured_profile(spec.surface["file"])
    except (ValueError, OSError) as err:
        raise ctx.error("[surface] file", f"cannot be read as a profile: {err}") from None
    n = max(spec.test["pillars"], spec.test["engine_pillars"])
    row = (n - 1) * p.array.pitch + 2 * (50.0 + 3 * p.seta.L)
    length = float(prof.x[-1] - prof.x[0])
    if row > length:
        shown = ", ".join(f"{k} = {v:g}" for k, v in corner) or "the fixed values"
        raise ctx.error(
            "[test] pillars",
            f"{n} pillars at {shown} need {row:.4g} µm of floor; the scan is {length:.4g} µm "
            "long: fewer pillars, a smaller spacing or a longer scan",
        )


def _variant(ctx: Ctx, data: dict, quick_t: dict, path: Path, raw: bytes, quick: bool):
    seed = _number(ctx, "seed", data.get("seed", 0), 0, SEED_MAX, integer=True)
    trials = _number(ctx, "trials", data.get("trials", 100), 1, 100_000, integer=True)
    confirm = _number(ctx, "confirm", data.get("confirm", 3), 0, 100, integer=True)
    description = ctx.type_("description", data.get("description", ""), str)
    if "objectives" not in data:
        raise ctx.error("objectives", f"missing; name one or more of {', '.join(OBJECTIVES)}")
    fixed, ranges, choices = _space(ctx, sub_table(ctx, data, "space"))
    if not ranges and all(len(v) == 1 for v in choices.values()):
        raise ctx.error("[space]", "fixes every knob: give at least one range or list to search")
    spec = DesignSpec(
        path=path,
        text=raw,
        sha256=hashlib.sha256(raw).hexdigest(),
        quick=quick,
        description=description,
        seed=seed,
        trials=trials,
        confirm=confirm,
        material=_material(ctx, sub_table(ctx, data, "material")),
        surface=_surface(ctx, sub_table(ctx, data, "surface")),
        test=_test(ctx, sub_table(ctx, data, "test"), quick_t.get("test", {})),
        fixed=fixed,
        ranges=ranges,
        choices=choices,
        objectives=_objectives(ctx, data["objectives"]),
        constraints=_constraints(ctx, sub_table(ctx, data, "constraints")),
        resolved={k: v for k, v in data.items() if k != "quick"},
    )
    if spec.test["probe"] == "sphere" and spec.surface["kind"] != "flat":
        raise ctx.error(
            "[test] probe",
            "'sphere': the probe is the surface; give [surface] "
            f"kind = 'flat', not {spec.surface['kind']!r}",
        )
    if spec.test["probe"] == "sphere" and spec.test["pillars"] != spec.test["engine_pillars"]:
        t = spec.test
        raise ctx.error(
            "[test] engine_pillars",
            f"{t['engine_pillars']} must equal pillars = {t['pillars']} under a spherical "
            "probe: the pull-off per backing area of a row under a probe depends on the "
            "row's length, so the screen and the engine must hold the same row",
        )
    _cross_checks(ctx, spec)
    return spec


def load_design(path, *, quick: bool = False) -> DesignSpec:
    """Read and check a design file; with ``quick`` take its ``[quick]`` variant (``trials``,
    ``confirm`` and ``[quick.test]`` merged over the file's). Both variants are checked,
    whichever is asked for.

    Raises
    ------
    RunFileError naming the file, the key, the value and the allowed range.
    """
    path, raw, data = read_toml(path)
    ctx = Ctx(path)
    ctx.keys("top level", data, {*_TOP, *_TABLES, "quick"})
    quick_t = sub_table(ctx, data, "quick")
    ctx.keys("[quick]", quick_t, _QUICK)
    body = {k: v for k, v in data.items() if k != "quick"}
    full = _variant(ctx, body, {}, path, raw, False)
    ctx.variant = " (in the --quick variant)"
    merged = {**body, **{k: v for k, v in quick_t.items() if k != "test"}}
    merged["test"] = {
        **sub_table(ctx, data, "test"),
        **sub_table(ctx, quick_t, "test", "[quick.test]"),
    }
    fast = _variant(ctx, merged, quick_t, path, raw, True)
    return fast if quick else full
