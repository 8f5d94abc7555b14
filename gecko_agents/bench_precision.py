"""Work-precision benchmark: the steps a run takes against the error of what a user reads
from it, for the explicit and the implicit step.

Run ``python -m gecko_agents.bench --work-precision`` (``--quick``: the rod sphere alone;
``--docs PATH``: also write the table as a Markdown page). For every case of
:data:`WP_CASES` it runs a reference (the explicit step at 1/:data:`WP_REFERENCE_DIVISOR` of
its default dt, recorded every step), the explicit step at its default, the implicit step at
its default and at :data:`WP_FACTORS` explicit steps (single setae), and, for arrays, the
implicit default with the whole array taking the located steps (``multirate=False``). Each
row is measured twice: recorded every step (the pull-off from the records after the pull's
start, :func:`pull_off_and_release`) and at the default record cadence (the pull-off the run
reports, :attr:`gecko_agents.history.History.peak_pull_off`); both read the release from the
detachments. The error of a row is the larger relative error of its pull-off and release
against the reference (:func:`wp_error`).

Work is counted in seta-steps: a whole-array step counts N, a multirate step's near setae their
k short steps and the one long step whose share is taken out
(:mod:`gecko_agents.model.multirate`). The last line is ``steps explicit/default at ≤ 0.5 %
error: X.X``, the smallest ratio over the cases run implicitly by default, read at the default
record cadence.
"""

from __future__ import annotations

import math
import os
import time
import warnings

import numpy as np

from gecko_agents import protocol
from gecko_agents.model import Model, Numerics
from gecko_agents.protocol import DEFAULT_SPEED
from gecko_agents.provenance import versions

__all__ = [
    "WP_CASES",
    "WP_FACTORS",
    "WP_REFERENCE_DIVISOR",
    "pull_off_and_release",
    "work_precision",
    "wp_case",
    "wp_error",
    "wp_measure",
    "write_page",
]

WP_CASES = {
    # name: (parameter overrides on PAPER_TABLE1, protocol factory, setae)
    "linear sphere": (
        {"seta.theta_deg": 60.0, "seta.r": 3.0},
        lambda v: protocol.press_pull(0.1, v),
        1,
    ),
    "rod sphere": ({"mechanics": "rod"}, lambda v: protocol.press_pull(0.1, v), 1),
    "Hertz": (
        {"seta.theta_deg": 60.0, "tip": "hertz"},
        lambda v: protocol.preload_pull(0.1, v),
        1,
    ),
    "crack kinetics": (
        {"mechanics": "rod", "contact.crack_speed": 1.0},
        lambda v: protocol.press_pull(0.1, v),
        1,
    ),
    "spatula drag-pull": (
        {"mechanics": "rod", "tip": "spatula"},
        lambda v: protocol.drag_pull(1.0, 0.5, 90.0, v),
        1,
    ),
    "Savkoor-Briggs": (
        {"mechanics": "rod", "contact.shear_coupling": "savkoor_briggs"},
        lambda v: protocol.drag_pull(1.0, 0.5, 90.0, v),
        1,
    ),
    "elastic backing": (
        {"mechanics": "rod", "backing.kind": "elastic", "array.count": 4},
        lambda v: protocol.press_pull(0.1, v),
        4,
    ),
    "rough patch": (
        {"mechanics": "rod", "floor.sigma": 0.5, "array.count": 10},
        lambda v: protocol.press_pull(1.0, v),
        10,
    ),
    "rough array": (
        {"mechanics": "rod", "floor.sigma": 0.5, "array.count": 1000},
        lambda v: protocol.press_pull(1.0, v),
        1000,
    ),
}
"""The work-precision benchmark's cases: a single seta of the paper's Table 1 on a flat floor
(the linear seta at 60° and twice as thick, r = 3 µm, whose pull, Fc/Ky = 17 µm, is 60 times
shorter than the paper's; the Hertz tip on the 60° linear seta pressed to 0.1 µN: a rod seta
pressed 0.3 µm holds a hundredth of that and slides), 4 setae on the elastic strip, and 10
and 1000 rod setae on a σ = 0.5 µm pad floor (the paper's eq 28) pressed 1 µm and pulled."""

WP_REFERENCE_DIVISOR = 2.0
"""The reference is the explicit step at half its default dt and the same plate speed (dt/4
at a quarter of the speed would cost 16 times the explicit run; the explicit row's error
against it shows how far the explicit step itself is from converged)."""

WP_FACTORS = (5.0, 10.0, 20.0, 50.0)
"""Implicit steps tried on single setae, in units of the explicit default step (besides the
implicit default)."""


def wp_measure(
    case: str,
    integrator: str,
    dt_factor: float | None,
    speed: float,
    record_every: int | None = 1,
    multirate: bool | None = None,
) -> dict:
    """One run of a work-precision case: steps, seta-steps, wall time [s], pull-off force [µN]
    and release displacement [µm] (plate travel from the start of the pull to the last tip's
    release). ``dt_factor``: the step in explicit default steps (None: the integrator's
    default). ``record_every`` = 1: the pull-off from the records after the pull's start
    (:func:`pull_off_and_release`); None (the default cadence): the pull-off the run reports
    (``History.peak_pull_off``)."""
    from gecko_agents.params import PAPER_TABLE1

    over, proto, n = WP_CASES[case]
    p = PAPER_TABLE1.replace(**over)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        dt = None
        if dt_factor is not None:
            dt = dt_factor * Model(p, n_sim=n, numerics=Numerics(integrator="explicit")).dt
        num = Numerics(dt=dt, integrator=integrator, record_every=record_every)
        m = Model(p, n_sim=n, numerics=num.replace(multirate=multirate))
        t = time.perf_counter()
        h = m.run(proto(speed), progress=False)
        wall = time.perf_counter() - t
        po, release = pull_off_and_release(h)
    steps = int(h.meta["n_steps"])
    return {
        "steps": steps,
        "seta_steps": steps * n + int(h.meta.get("multirate_seta_substeps", 0)),
        "wall_s": wall,
        "pull_off": po if record_every == 1 else h.peak_pull_off,
        "peak": h.peak_pull_off,
        "release": release,
        "dt": m.dt,
    }


def pull_off_and_release(h) -> tuple[float, float]:
    """Pull-off force [µN] (largest adhesion, ≥ 0) and release displacement [µm] (plate
    travel to the last tip's release) of a history, both from the start of the pull: the
    deepest plate position or, after a drag, the drag's end
    (:func:`gecko_agents.analysis.pull.pull_start`). Not from the press's largest force
    (``pull_start`` of a press-pull): that is the touch-down's overshoot where the step rings
    (explicit) and the turning point where it does not (implicit)."""
    from gecko_agents.analysis.pull import pull_start

    k0 = max(pull_start(h), int(np.argmin(h["plate_y_um"])))
    po = max(0.0, float(np.max(-h["force_normal_uN"][k0:])))
    det = h.detachments
    if not len(det["plate_y_um"]):
        return po, math.nan
    dx = det["plate_x_um"][-1] - h["plate_x_um"][k0]
    return po, float(np.hypot(dx, det["plate_y_um"][-1] - h["plate_y_um"][k0]))


def wp_error(run: dict, ref: dict) -> float:
    """Largest relative error of pull-off and release against the reference [-] (the pull-off
    of a law without adhesion, 0, counts by its release alone)."""
    err = abs(run["release"] - ref["release"]) / abs(ref["release"])
    if ref["pull_off"] > 0:
        err = max(err, abs(run["pull_off"] - ref["pull_off"]) / ref["pull_off"])
    return err if math.isfinite(err) else math.inf


_wp_error = wp_error  # the name the benchmark's tests know


def _rows(case: str, factors, speed: float) -> dict:
    """The runs of a case's table, each as (every step, default records)."""
    n = WP_CASES[case][2]
    # multirate None: where it applies (the default); False: the whole array takes the steps
    plan = {"explicit": ("explicit", None, None), "implicit (default)": ("implicit", None, None)}
    if n > 1 and _multirate_applies(case):
        plan["implicit, whole array located"] = ("implicit", None, False)
    if n == 1:
        plan |= {f"implicit {f:g}×": ("implicit", f, None) for f in factors}
    runs = {}
    for label, (integrator, factor, multirate) in plan.items():
        try:
            runs[label] = tuple(
                wp_measure(case, integrator, factor, speed, every, multirate) for every in (1, None)
            )
        except Exception as err:  # an unstable or refused run is a row, not a crash
            runs[label] = ({"failed": repr(err)},) * 2
    return runs


def wp_case(case: str, factors, ref_div: float, speed: float) -> dict:
    """A case's table (module docstring); prints the rows and returns {label: (run every
    step, run at the default records), each with ``error``}, the reference, and the
    seta-steps ratios explicit/implicit at ≤ 0.5 % error: ``ratio`` (the best implicit row,
    every step), ``default_ratio`` (the implicit default, every step) and
    ``default_ratio_records`` (the implicit default, at the default records)."""
    ref = wp_measure(case, "explicit", 1.0 / ref_div, speed)
    ref_records = ref | {"pull_off": ref["peak"]}  # as a run reports it (every step here)
    runs = _rows(case, factors, speed)
    print(
        f"\n{case}: reference explicit dt/{ref_div:g}, {ref['steps']} steps, pull-off "
        f"{ref['pull_off']:.6g} µN, release after {ref['release']:.6g} µm"
    )
    print(
        f"  {'integrator':<32} {'dt [µs]':>8} {'steps':>8} {'seta-steps':>11} {'wall [s]':>9} "
        f"{'error [%]':>10} {'at records [%]':>15}"
    )
    for label, (every, records) in runs.items():
        if "failed" in every:
            print(f"  {label:<32} failed: {every['failed'][:60]}")
            every["error"] = records["error"] = math.inf
            continue
        every["error"] = wp_error(every, ref)
        records["error"] = wp_error(records, ref_records)
        print(
            f"  {label:<32} {every['dt']:8.3g} {every['steps']:8d} {every['seta_steps']:11d} "
            f"{every['wall_s']:9.3g} {100 * every['error']:10.3g} {100 * records['error']:15.3g}"
        )
    exp = runs["explicit"][0]
    ok = [r["seta_steps"] for k, (r, _) in runs.items() if k != "explicit" and r["error"] <= 0.005]
    ratio = exp["seta_steps"] / min(ok) if ok and exp["error"] <= 0.005 else math.nan
    every, records = runs["implicit (default)"]
    d_ratio = exp["seta_steps"] / every["seta_steps"] if every["error"] <= 0.005 else math.nan
    r_ratio = exp["seta_steps"] / records["seta_steps"] if records["error"] <= 0.005 else math.nan
    print(
        f"  seta-steps explicit/implicit at ≤ 0.5 % error: best {ratio:.3g}, default "
        f"{d_ratio:.3g} (every step), {r_ratio:.3g} (default records)",
        flush=True,
    )
    return {
        "runs": runs,
        "ref": ref,
        "ratio": ratio,
        "default_ratio": d_ratio,
        "default_ratio_records": r_ratio,
    }


def _multirate_applies(case: str) -> bool:
    """Whether the default model of ``case`` may take multirate steps."""
    from gecko_agents.model.multirate import multirate_applies
    from gecko_agents.params import PAPER_TABLE1

    over, _, n = WP_CASES[case]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return multirate_applies(Model(PAPER_TABLE1.replace(**over), n_sim=n))


def _runs_implicit(case: str) -> bool:
    """Whether the model's default integrator runs ``case`` of ``WP_CASES`` implicitly
    (:func:`gecko_agents.model.implicit.check_integrator`)."""
    from gecko_agents.model.implicit import check_integrator
    from gecko_agents.params import PAPER_TABLE1

    default = Numerics().integrator
    params = PAPER_TABLE1.replace(**WP_CASES[case][0])
    return check_integrator(default, "batch", params) == "implicit"


def work_precision(
    quick: bool = False, cases=None, speed: float = DEFAULT_SPEED, factors=None, docs=None
) -> dict:
    """The work-precision benchmark (module docstring): every case of ``WP_CASES`` (or
    ``cases``; ``quick``: the rod sphere alone, fewer implicit steps), the plate at ``speed``
    [µm/µs], the implicit step also at ``factors`` explicit steps (default ``WP_FACTORS``);
    ``docs``: a path to write the table to as a Markdown page (:func:`write_page`)."""
    cases = cases or (["rod sphere"] if quick else list(WP_CASES))
    factors = factors or ((10.0, 50.0) if quick else WP_FACTORS)
    out = {}
    for case in cases:
        out[case] = wp_case(case, factors, WP_REFERENCE_DIVISOR, speed)
    default = [c for c in cases if _runs_implicit(c)] or cases
    worst = float(np.min([np.nan_to_num(out[c]["default_ratio_records"]) for c in default]))
    best = float(np.min([np.nan_to_num(out[c]["ratio"]) for c in cases]))
    if docs:
        write_page(out, speed, docs, worst)
    print(f"\nseta-steps explicit/implicit (its best step) at ≤ 0.5 % error: {best:.1f}")
    print(f"steps explicit/default at ≤ 0.5 % error: {worst:.1f}")
    return out


def write_page(out: dict, speed: float, path, worst: float) -> None:
    """Write the benchmark's table ``out`` (:func:`work_precision`) and its last line's ratio
    ``worst`` as a Markdown page at ``path``."""
    lines = [
        "# Work and precision, as measured",
        "",
        "Written by `python -m gecko_agents.bench --work-precision --docs PATH`: every number",
        f"comes from that one run (plate speed {speed:g} µm/µs, {os.cpu_count()} cores,",
        f"gecko_agents {versions().get('gecko_agents', '?')}). Each case is run against the",
        f"explicit step at dt/{WP_REFERENCE_DIVISOR:g}, recorded every step. *Error, every step*",
        "reads the pull-off from the records after the pull's start; *error, default records*",
        "reads the pull-off the run reports (`History.peak_pull_off`) at the default record",
        "cadence; both read the release from the detachments and give the larger relative",
        "error of the two. Work is counted in seta-steps (`gecko_agents.bench_precision`).",
        "",
        "| case | run | seta-steps | wall [s] | error, every step | error, default records "
        "| fewer seta-steps |",
        "|---|---|---|---|---|---|---|",
    ]
    for case, res in out.items():
        exp = res["runs"]["explicit"][0]["seta_steps"]
        for label, (every, records) in res["runs"].items():
            if "failed" in every:
                lines.append(f"| {case} | {label} | failed | | | | |")
                continue
            lines.append(
                f"| {case} | {label} | {every['seta_steps']:,} | {every['wall_s']:.3g} | "
                f"{100 * every['error']:.3g} % | {100 * records['error']:.3g} % | "
                f"{exp / every['seta_steps']:.1f}× |"
            )
    lines += [
        "",
        f"Fewest seta-steps saved by the implicit default at ≤ 0.5 % error, read at the default "
        f"record cadence, over the cases: {worst:.1f}×.",
        "",
    ]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
