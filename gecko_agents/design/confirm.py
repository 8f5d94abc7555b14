"""Confirmation: the best designs of a screen run again in the time-stepped engine
(:class:`gecko_agents.model.Model`, elastica pillars; rod pillars on a backing layer, which
the engine couples with the explicit step, :mod:`gecko_agents.backing.layer`), and a run file
for each.

Each design is pressed to the test's preload (the pressure on the backing over the engine row's
area, ``engine_pillars``·s²) and pulled straight off at the test's speed, once per engine seed
(the first ``engine_seeds`` floor seeds of the screen, on the same floors). The confirmed
pull-off per area is their mean, its spread their relative standard deviation; every validity
item the engine judged is carried into the report. Backing tilts are confirmed on an elastic
backing only (``Backing.misalignment_deg``); the engine's rigid plate and its backing layer
are level, so there the spread is over floors only and the release force is the screen's
alone.
"""

from __future__ import annotations

import json
import math

import numpy as np

from gecko_agents.design.screen import design_params, engine_floor, floor_seed
from gecko_agents.design.space import KPA

__all__ = ["confirm_design", "run_file_text", "DISAGREE"]

DISAGREE = 0.25
"""Relative difference between the screened and the confirmed pull-off per area above which
the report says the two fidelities disagree."""


def engine_setup(spec, values: dict, i: int, tilt: float = 0.0):
    """(parameters, model keywords, protocol) of engine run ``i`` of a design, its backing
    turned by ``tilt`` [°] (an elastic backing only: the rigid plate is level)."""
    from gecko_agents import protocol

    n = spec.test["engine_pillars"]
    p = design_params(spec, values, n)
    p = p.replace(**{"floor.seed": floor_seed(spec, i), "backing.misalignment_deg": tilt})
    preload = spec.test["preload_kPa"] * KPA * n * p.array.pitch**2
    prot = protocol.preload_pull(preload, speed=spec.test["pull_speed_um_per_us"])
    kw = {"n_sim": n, "seed": floor_seed(spec, i), "floor_profile": engine_floor(spec, p, i)}
    return p, kw, prot


def _engine_run(spec, values, i, tilt, flagged) -> float:
    """Pull-off per backing area [kPa] of one engine run; its unmet validity items into
    ``flagged``."""
    from gecko_agents.analysis.pull import pull_off
    from gecko_agents.model import Model

    p, kw, prot = engine_setup(spec, values, i, tilt)
    h = Model(p, **kw).run(prot, progress=False)
    for name, item in h.meta["validity"]["items"].items():
        if item.get("ok") is False:
            flagged[name] = {
                "value": item.get("value"),
                "rule": item.get("rule"),
                "meaning": item.get("meaning"),
            }
    return pull_off(h).adhesion / (p.array.count * p.array.pitch**2) / KPA


def confirm_design(spec, values: dict) -> dict:
    """The engine's pull-off per area of one design over the engine seeds (and, on an elastic
    backing, the screen's tilts): ``mean`` and ``spread`` (std/mean), each run's value,
    ``release`` (the pull-off with the backing at ``test.release_tilt_deg``; None on a rigid
    plate or a backing layer, which the engine keeps level), its wall time, and the validity
    items any run found not met (name → the item of the last run that broke it). A run the
    engine refuses or cannot finish (a preload it cannot reach, a step that fails) ends the
    design's confirmation: ``error`` then gives the exception and its message, ``mean`` and
    ``spread`` are NaN."""
    import time

    from gecko_agents.design.screen import tilts
    from gecko_agents.design.search import CAUGHT

    values = {**spec.fixed, **values}
    elastic = values.get("backing", "rigid") == "elastic"
    angles = tilts(spec) if elastic else (0.0,)
    runs, flagged, t0 = [], {}, time.perf_counter()
    release = None
    try:
        for i in range(spec.test["engine_seeds"]):
            runs += [_engine_run(spec, values, i, a, flagged) for a in angles]
        if elastic and "release_force" in spec.objectives:
            release = _engine_run(spec, values, 0, spec.test["release_tilt_deg"], flagged)
    except CAUGHT as err:  # a design the engine cannot run: the report's row says why
        return {
            "mean": math.nan,
            "spread": math.nan,
            "runs": [float(r) for r in runs],
            "release": None,
            "validity_flags": flagged,
            "wall_s": time.perf_counter() - t0,
            "error": f"{type(err).__name__}: {err}",
        }
    mean = float(np.mean(runs))
    return {
        "mean": mean,
        "spread": float(np.std(runs) / mean) if mean > 0 else 1.0,
        "runs": [float(r) for r in runs],
        "release": release,
        "validity_flags": flagged,
        "wall_s": time.perf_counter() - t0,
    }


def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value)
    return repr(float(value)) if isinstance(value, float) else repr(value)


def run_file_text(spec, values: dict, label: str) -> str:
    """A run file that reproduces engine run 0 of a design with ``gecko-agents run``."""
    from gecko_agents.params import PAPER_ARRAY

    p, kw, _ = engine_setup(spec, values, 0)
    base, mine = PAPER_ARRAY.to_dict(), p.to_dict()
    over = {}
    for group, fields in mine.items():
        if isinstance(fields, dict):
            over |= {f"{group}.{k}": v for k, v in fields.items() if base[group][k] != v}
        elif base[group] != fields:
            over[group] = fields
    preload = spec.test["preload_kPa"] * KPA * p.array.count * p.array.pitch**2
    lines = [
        f"# {label} of the design search {spec.path.name}: "
        + ", ".join(
            f"{k} = {v:.4g}" if isinstance(v, float) else f"{k} = {v}" for k, v in values.items()
        ),
        f"#   gecko-agents run {label}.toml",
        f"description = {json.dumps(f'{label} of {spec.path.name} (engine run, floor seed 0)')}",
        'preset = "PAPER_ARRAY"',
        "",
        "[params]",
        *[f'"{k}" = {_toml(v)}' for k, v in over.items() if v is not None],
        "",
        "[model]",
        f"n_sim = {kw['n_sim']}",
        f"seed = {kw['seed']}",
    ]
    if kw["floor_profile"] is not None:
        lines += [
            "",
            "[floor]",
            f"file = {json.dumps(_scan_name(spec))}",
            f"offset_um = {_offset(kw['floor_profile'], spec):.9g}",
        ]
    lines += [
        "",
        "[protocol]",
        'preset = "preload_pull"',
        f"preload_uN = {preload!r}",
        f"speed_um_per_us = {spec.test['pull_speed_um_per_us']!r}",
        "",
    ]
    return "\n".join(lines)


def _scan_name(spec) -> str:
    """The run file's name for the scan: a packaged scan by its name, else the file's path."""
    from gecko_agents.design.schema import PACKAGED_SCANS

    name = spec.surface.get("name", "")
    return name if name in PACKAGED_SCANS else spec.surface["file"]


def _offset(cropped, spec) -> float:
    """Where the engine's cropped scan starts on the scan file [µm] (0 for floor seed 0)."""
    from gecko_agents.design.space import measured_profile

    full = measured_profile(spec.surface["file"])
    k = full.x.size - cropped.x.size
    return float(full.x[k] - full.x[0]) if math.isfinite(full.x[0]) else 0.0
