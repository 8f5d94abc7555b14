"""Validation against published experiments: ``literature_comparison.md`` (and ``.json``,
``.png``), one row per published measurement, beside the paper report.

Each row (:data:`gecko_agents.studies.validation_rows.ROWS`) quotes the text we read, gives
their value as printed and the parameters our number uses, cited or assumed (with the reason);
the functions below compute *ours* from the presets of :mod:`gecko_agents.params.literature`
(or a study's own base parameters) with the package's closed forms and agent runs, and every
assumed number is moved to both ends of its plausible range to show how much ours depends on
it (closed forms always; agent runs in the full run only, to keep ``--quick`` under a minute).
Nothing is tuned to a row: a disagreement is a result, with its likely cause.

Verdicts (:func:`verdict`): *agrees within the stated scatter* (ours inside their mean ± their
stated s.e.m.), *trend agrees* (ours on the same side of 1, or with the same sign, as theirs,
where they state a direction or no scatter), *disagrees*, *not comparable* (their value lies
inside the range our number spans over the parameters we had to assume: the comparison needs
what they used). Rows whose source could not be read, or that need a tip the package does not
have yet, are *not scored* and say why.

Units: µm, µN, µs, MPa (= µN/µm²); stiffness µN/µm = N/m. ``python scenarios/validation.py
[--quick] --out DIR`` writes ``DIR/literature_comparison.{md,json,png,csv}`` and
``DIR/metadata.json`` (default ``renders/``); ``gecko-agents reproduce --beyond`` writes them
beside ``paper_comparison.md``.
"""

from __future__ import annotations

import functools
import math
import time

import numpy as np

from gecko_agents import protocol, render
from gecko_agents.analysis.limit_curve import critical_angle
from gecko_agents.analysis.pull import pull_off, release_point
from gecko_agents.model import Model
from gecko_agents.output_paths import atomic_write_bytes
from gecko_agents.params import literature as lit
from gecko_agents.physics import beam
from gecko_agents.provenance import versions
from gecko_agents.studies import frictional_adhesion as fa
from gecko_agents.studies import misalignment as mis
from gecko_agents.studies import pad_peel, pull_speed
from gecko_agents.studies.common import RENDERS, command_line, parse_args, write_json, write_table
from gecko_agents.studies.validation_rows import ROWS

NAME = "literature_comparison"
VERDICTS = ("agrees within the stated scatter", "trend agrees", "disagrees", "not comparable")
NOT_SCORED = "not scored"
TREND_RESOLUTION = 0.01
"""A ratio within 1 % of 1 is no effect (a trend neither way): repeated pull-offs of the same
pad at another plate speed differ by ~0.6 % (backing_stiffness study, 0.340 vs 0.342 N·Fc)."""

# --- ours: closed forms on a tokay seta (AUTUMN2006_SETA) ----------------------------------------
_SETA_KEYS = {"E": "contact.E1", "r": "seta.r", "L": "seta.L", "theta": "seta.theta_deg"}


def tokay_seta(**assumed):
    """:data:`~gecko_agents.params.literature.AUTUMN2006_SETA` with assumed values overridden
    by row-parameter name (E [MPa], r [µm], L [µm], theta [deg])."""
    over = {_SETA_KEYS[k]: v for k, v in assumed.items() if k in _SETA_KEYS}
    return lit.AUTUMN2006_SETA.replace(**over)


def directional_stiffness(params, direction) -> float:
    """Stiffness of a seta [µN/µm = N/m] along the unit vector of ``direction`` (x along the
    backing towards the lean, y up), the tip free to move across it: 1/(dᵀ K⁻¹ d) with K the
    rod's 2×2 stiffness (:func:`gecko_agents.physics.beam.stiffness_matrix`, eq 16–21);
    d = (0, 1) is eq 20's K_y."""
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    K = beam.stiffness_matrix(params.axial_stiffness, params.bending_stiffness, params.seta.theta)
    return float(1.0 / (d @ np.linalg.solve(K, d)))


def seta_stiffness(quick: bool = True, **assumed) -> dict:
    """K_y of eq 20 [N/m] for the tokay seta (Autumn et al. 2006a's vertical loading)."""
    k = tokay_seta(**assumed).Ky
    return {"value": k, "text": f"{k:.3g} N/m (eq 20, K_y of a straight rod)"}


def seta_anisotropy(quick: bool = True, **assumed) -> dict:
    """Stiffness loaded against / along the natural drag path: the backing moved at 45° from
    the vertical, down and towards +x (against) or −x (along, the gripping drag)."""
    p = tokay_seta(**assumed)
    along = directional_stiffness(p, (-1.0, -1.0))
    against = directional_stiffness(p, (1.0, -1.0))
    return {"value": against / along, "trend": against / along - 1.0,
            "text": f"×{against / along:.3g} ({against:.3g} over {along:.3g} N/m)"}  # fmt: skip


def array_modulus(quick: bool = True, D: float = lit.TOKAY_SETAL_DENSITY, **assumed) -> dict:
    """E_eff = K_y·D·L sin θ [kPa]: a bed of springs of density D [1/µm²] and height L sin θ
    (σ = K_y·D·δ, ε = δ/(L sin θ))."""
    p = tokay_seta(**assumed)
    e = p.Ky * D * p.seta.L * math.sin(p.seta.theta) * 1e3  # MPa → kPa
    return {"value": e, "text": f"{e:.3g} kPa"}


# --- ours: agent runs -----------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def gripping_pull(params, beta: float, count: int = 1) -> tuple[float, float, float]:
    """The frictional-adhesion study's load–drag–pull (preload ``count`` × fa.PRELOAD, the
    gripping drag −fa.DRAG, pull at ``beta`` [deg] at the quasi-static plate speed): (adhesion,
    shear) at the release point and the pull-off [µN] (:mod:`gecko_agents.analysis.pull`).
    Cached: the runs are deterministic, and two rows share the spatula's 90° pull."""
    prot = protocol.drag_pull(fa.PRELOAD * count, -fa.DRAG, beta, speed=fa.SPEED)
    h = Model(params, seed=1, record_every=1).run(prot, progress=False)
    rel = release_point(h, -fa.DRAG)
    return rel.adhesion, rel.shear, pull_off(h, -fa.DRAG).adhesion


def frictional_adhesion(quick: bool = True, mu: float | None = None) -> dict:
    """α* [deg] of the spatula seta's gripping releases over pull angles, and the slope of
    adhesion against shear (> 0: adhesion rises with shear)."""
    p = lit.FRICTIONAL_SPATULA if mu is None else lit.FRICTIONAL_SPATULA.replace(
        **{"friction.mu": mu})  # fmt: skip
    betas = (45.0, 90.0) if quick else (15.0, 30.0, 45.0, 60.0, 75.0, 90.0)
    rel = [gripping_pull(p, b) for b in betas]
    shear = np.array([r[1] for r in rel])
    adhesion = np.array([r[0] for r in rel])
    alpha = critical_angle(shear, adhesion)
    slope = float(np.polyfit(shear, adhesion, 1)[0]) if len(set(shear)) > 1 else math.nan
    pts = ", ".join(f"{s:.2f}/{a:.2f}" for s, a in zip(shear, adhesion, strict=True))
    return {"value": alpha, "trend": slope,
            "text": f"α* = {alpha:.0f}°; adhesion/shear at release over pulls at "
            f"{', '.join(f'{b:g}' for b in betas)}°: {pts} µN (slope {slope:.2f})"}  # fmt: skip


def kendall_peel(quick: bool = True) -> dict:
    """Peel force per width at 30° and 90° on the pad_peel study's pad, and each over
    Kendall's w_eff/(1 − cos ψ) with the run's own w_eff (:func:`pad_peel.steady_peel`)."""
    n, speed, frac = (200, 0.5, 0.4) if quick else (240, 0.2, 1.0)
    rows = [pad_peel.run_point(n, psi, speed, frac)[0] for psi in (30.0, 90.0)]
    f30, f90 = (r["F_per_width_uN_per_um"] for r in rows)
    ratios = [r["ratio_to_kendall"] for r in rows]
    return {"value": ratios[1], "values": ratios, "trend": f30 / f90 - 1.0,
            "text": f"F/b = {f30:.3g} µN/µm at {rows[0]['psi_measured_deg']:.0f}°, {f90:.3g} at "
            f"{rows[1]['psi_measured_deg']:.0f}° (×{f30 / f90:.2f}); over Kendall with the "
            f"run's w_eff: {ratios[0]:.2f} and {ratios[1]:.2f} ({n} setae)"}  # fmt: skip


def pad_pull_off(params, n: int, angle: float) -> float:
    """Pull-off / (N·Fc) of ``n`` setae on the elastic strip of ``params`` tilted by ``angle``
    [deg]: the misalignment study's preload (0.2 N·Fc) and straight pull."""
    p = params.replace(**{"array.count": n, "backing.misalignment_deg": angle})
    m = Model(p, seed=1)
    h = m.run(protocol.preload_pull(mis.PRELOAD * n * m.Fc, speed=mis.SPEED), progress=False)
    return float(max(h["strip_setae_force_y_uN"]) / (n * m.Fc))


def booth_misalignment(quick: bool = True, k_stiff: float | None = None) -> dict:
    """Pull-off on the 3.1× compliant mount over the stiff one at 0.4° (quick: 0.8° on half
    the pad, the same rise)."""
    n, angle = (200, 0.8) if quick else (400, 0.4)
    stiff, compliant = lit.BOOTH2018_STIFF_MOUNT, lit.BOOTH2018_COMPLIANT_MOUNT
    if k_stiff is not None:
        stiff = stiff.replace(**{"backing.handle_stiffness": k_stiff})
        compliant = stiff.replace(**{"backing.handle_stiffness": k_stiff /
                                     lit.BOOTH2018_COMPLIANCE_RATIO})  # fmt: skip
    s, c = pad_pull_off(stiff, n, angle), pad_pull_off(compliant, n, angle)
    text = f"×{c / s:.2f} ({c:.3f} over {s:.3f} N·Fc, {n} setae at {angle:g}°)"
    return {"value": c / s, "trend": c / s - 1.0, "text": text}


def kim_sitti_backing(quick: bool = True) -> dict:
    """Pull-off on the 160 µm strip over the 1120 µm one, aligned, pulled straight up."""
    n = 40 if quick else 200
    thin = pad_pull_off(lit.KIM_SITTI2007_THIN, n, 0.0)
    thick = pad_pull_off(lit.KIM_SITTI2007_THICK, n, 0.0)
    text = f"×{thin / thick:.3f} ({thin:.3f} over {thick:.3f} N·Fc, {n} setae)"
    return {"value": thin / thick, "trend": thin / thick - 1.0, "text": text}


def gillies_smooth(quick: bool = True, b: float | None = None) -> dict:
    """90° pull-off after the gripping drag: spatula over sphere, one seta, flat floor."""
    spatula = lit.FRICTIONAL_SPATULA
    if b is not None:
        spatula = spatula.replace(**{"spatula.b": b})
    s = gripping_pull(spatula, 90.0)[2]
    j = gripping_pull(lit.FRICTIONAL_SPHERE, 90.0)[2]
    return {"value": s / j, "trend": s / j - 1.0, "text": f"×{s / j:.2f} ({s:.2f} over {j:.2f} µN)"}


def gillies_rough(quick: bool = True) -> dict:
    """As :func:`gillies_smooth` on a patch of setae, each on its own pad at a Gaussian height
    of RMS 1 µm (eq 28); pull-off per seta."""
    count = 4 if quick else 16
    rough = {"array.count": count, "floor.sigma": 1.0, "floor.correlation_length": 0.0}
    held = [
        gripping_pull(p.replace(**rough), 90.0, count)[2] / count
        for p in (lit.FRICTIONAL_SPATULA, lit.FRICTIONAL_SPHERE)
    ]
    s, j = held
    return {
        "value": s / j,
        "trend": s / j - 1.0,
        "text": f"×{s / j:.2f} ({s:.2f} over {j:.2f} µN per seta, {count} setae)",
    }


def gravish_rate(quick: bool = True, v_star: float | None = None) -> dict:
    """Pull-off at 0.1 over 0.01 µm/µs of one seta with crack kinetics (pull-speed study's
    press)."""
    p = lit.GRAVISH2010_SETA
    if v_star is not None:
        p = p.replace(**{"contact.crack_speed": v_star})
    held = []
    for v in (0.01, 0.1):
        prot = [protocol.PressTo(pull_speed.DEPTH, pull_speed.PRESS_SPEED), protocol.PullOff(v)]
        held.append(Model(p, n_sim=1, seed=1).run(prot, progress=False).peak_pull_off)
    slow, fast = held
    return {
        "value": fast / slow,
        "trend": fast / slow - 1.0,
        "text": f"×{fast / slow:.3f} ({fast:.2f} over {slow:.2f} µN)",
    }


def flat_punch_ours(quick: bool = True) -> dict | None:
    """The flat punch's pull-off against its radius (Kendall 1971): needs the ``flat_punch``
    tip of the designs issue; ``None`` until then (the row stays not scored). Filled in, it
    returns ``{"value": …, "text": …}`` like the others; the row is then scored once its
    ``theirs_value`` (and ``scatter``) are read from the source."""
    return None


def buckled_preload(quick: bool = True) -> dict:
    """Pull-off of a vertical flat-punch pillar (an elastica, L/2r = 5, the pillar-design
    study's) pressed 20 % of its length (past its Euler load P_E) over that pressed 1 %
    (below it); ``trend`` = the loss, 1 − ratio (their direction: a buckled pillar holds
    less)."""
    from gecko_agents.studies import pillar_designs as pd

    p = pd.params_for("flat_punch", 5.0, "flat").replace(**{"array.count": 1})
    P_E = pd.euler_load("flat_punch", p.seta.L)
    held, peak = [], []
    for eps in (0.01, 0.2):
        prot = protocol.press_pull(eps * p.seta.L, speed=pd.SPEED)
        h = Model(p, n_sim=1, seed=pd.SEED).run(prot, progress=False)
        held.append(h.peak_pull_off)
        peak.append(float(h["force_normal_uN"].max()))
    below, above = held
    return {
        "value": above / below,
        "trend": 1.0 - above / below,
        "text": f"×{above / below:.3f} ({above:.2f} µN after a {peak[1]:.2f} µN preload over "
        f"{below:.2f} µN after {peak[0]:.2f} µN; P_E = {P_E:.3g} µN)",
    }


OURS = {f.__name__: f for f in (seta_stiffness, seta_anisotropy, array_modulus,
                                frictional_adhesion, kendall_peel, booth_misalignment,
                                kim_sitti_backing, gillies_smooth, gillies_rough, gravish_rate,
                                flat_punch_ours, buckled_preload)}  # fmt: skip
CLOSED_FORM = {"seta_stiffness", "seta_anisotropy", "array_modulus"}
"""Rows whose ours is a closed form: their sensitivity is computed in ``--quick`` too."""


def sensitivity(row: dict, quick: bool) -> list[dict]:
    """Ours at both ends of each numeric parameter range of ``row`` (agent rows: full run
    only; an empty list otherwise)."""
    if row["ours"] is None or (quick and row["ours"] not in CLOSED_FORM):
        return []
    fn, out = OURS[row["ours"]], []
    for prm in row["params"]:
        if prm.get("range") is None:
            continue
        lo, hi = (fn(quick, **{prm["name"]: x})["value"] for x in prm["range"])
        out.append({"name": prm["name"], "status": prm["status"], "range": prm["range"],
                    "unit": prm["unit"], "ours_at_ends": [lo, hi]})  # fmt: skip
    return out


def verdict(row: dict, ours: dict | None, sens: list[dict]) -> tuple[str, str]:
    """(verdict, the computed part of its reason) for one row and its ours
    (:data:`VERDICTS`, or :data:`NOT_SCORED`)."""
    if row["compare"] is None or ours is None or not math.isfinite(ours["value"]):
        return NOT_SCORED, row.get("unscored", "ours could not be computed")
    theirs, scatter, value = row["theirs_value"], row["scatter"], ours["value"]
    if theirs is None and row["compare"] == "value":
        return NOT_SCORED, "their value was not read: " + row.get("unscored", "")
    if theirs is not None and scatter is not None and abs(value - theirs) <= scatter:
        return VERDICTS[0], f"ours is within their ±{scatter:g}"
    if row["compare"] == "trend":
        # A row whose source reports a large effect in words sets the size that counts.
        resolution = row.get("trend_resolution") or TREND_RESOLUTION
        ok = ours["trend"] > resolution
        size = "" if theirs is None else f" (ours is {value / theirs:.3g}× theirs)"
        if ok:
            return VERDICTS[1], "ours goes the same way as theirs" + size
        way = "no effect" if abs(ours["trend"]) <= resolution else "the other way"
        return VERDICTS[2], f"ours shows {way}" + size
    ends = [v for s in sens if s["status"] == "assumed" for v in s["ours_at_ends"]]
    if ends and min(ends + [value]) <= theirs <= max(ends + [value]):
        return VERDICTS[3], (f"their value lies inside the {min(ends):.3g}–{max(ends):.3g} our "
                             "number spans over the assumed parameters")  # fmt: skip
    return VERDICTS[2], f"ours is {value / theirs:.3g}× theirs, outside their scatter"


def evaluate(row: dict, quick: bool) -> dict:
    """One row of the report: the row's data with ours, its sensitivity and the verdict."""
    t0 = time.perf_counter()
    ours = OURS[row["ours"]](quick) if row["ours"] is not None else None
    sens = sensitivity(row, quick) if ours is not None else []
    v, why = verdict(row, ours, sens)
    return {**row, "ours_value": None if ours is None else ours["value"],
            "ours_values": None if ours is None else ours.get("values", [ours["value"]]),
            "ours_text": "—" if ours is None else ours["text"], "sensitivity": sens,
            "verdict": v, "reason": f"{why}. {row['cause']}".strip(),
            "wall_time_s": time.perf_counter() - t0}  # fmt: skip


def params_cell(row: dict) -> str:
    """The parameters column: each cited or assumed, with the reason."""
    return "; ".join(f"{p['name']} = {p['value']}{(' ' + p['unit']) if p['unit'] else ''} "
                     f"({p['status']}: {p['why']})" for p in row["params"]) or "—"  # fmt: skip


def ours_cell(row: dict) -> str:
    """Ours, and its value at both ends of each parameter range."""
    parts = [row["ours_text"]]
    for s in row["sensitivity"]:
        lo, hi = s["ours_at_ends"]
        parts.append(f"{s['name']} {s['range'][0]:g}–{s['range'][1]:g}: {lo:.3g}–{hi:.3g}")
    if row["ours"] is not None and row["ours"] not in CLOSED_FORM and not row["sensitivity"]:
        if any(p.get("range") for p in row["params"]):
            parts.append("sensitivity: full run only")
    return "; ".join(parts)


def markdown(rows: list[dict], quick: bool, total: float) -> str:
    """literature_comparison.md: the table, the verdict counts and the quotes."""
    lines = [
        "# Literature comparison",
        "",
        "Written by `python scenarios/validation.py" + (" --quick" if quick else "") + "` "
        "(or `gecko-agents reproduce --beyond`); every number under *ours* was computed in "
        "that run from the presets of `gecko_agents/params/literature.py`. Their values are "
        "quoted from the text we read (below); assumed parameters are marked, with ours at "
        "both ends of their range. Nothing is tuned to a row.",
        "",
    ]
    if quick:
        lines += ["**Quick run: small pads and few pulls; agent rows without sensitivity.**", ""]
    lines += ["| source | what was measured | their value (as printed) | parameters used "
              "(cited / assumed, why) | ours | verdict | reason |",
              "|---|---|---|---|---|---|---|"]  # fmt: skip
    for r in rows:
        cells = (r["source"], r["measured"], r["theirs"], params_cell(r), ours_cell(r),
                 r["verdict"], r["reason"])  # fmt: skip
        lines.append("| " + " | ".join(str(c).replace("|", "\\|").replace("\n", " ")
                                       for c in cells) + " |")  # fmt: skip
    counts = {v: sum(r["verdict"] == v for r in rows) for v in VERDICTS + (NOT_SCORED,)}
    lines += ["", "Verdicts: " + ", ".join(f"{v}: {n}" for v, n in counts.items() if n), "",
              f"![ours against theirs]({NAME}.png)", "", "## What we read", ""]  # fmt: skip
    for r in rows:
        quote = r["quote"].replace("\n", " ") or "(nothing: not found)"
        lines.append(f"* **{r['id']}** — {r['read_at']}: “{quote}”")
    lines += ["", f"Wall time {total:.0f} s. Versions: "
              + ", ".join(f"{k} {v}" for k, v in versions().items()), ""]  # fmt: skip
    return "\n".join(lines)


def draw(rows: list[dict], out) -> None:
    """Ours against theirs, one panel per kind of quantity (log axes), the sensitivity range
    as a vertical bar, their stated scatter as a horizontal one, y = x dotted."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    sel = [r for r in rows if r["ours_value"] is not None and r["theirs_value"] is not None]
    kinds = list(dict.fromkeys(r["kind"] for r in sel))
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(4.6 * max(len(kinds), 1), 4.4), layout="constrained")
        axes = np.atleast_1d(fig.subplots(1, max(len(kinds), 1)))
        for ax, kind in zip(axes, kinds, strict=False):
            pts = [r for r in sel if r["kind"] == kind]
            for i, r in enumerate(pts):
                c = f"C{i % 10}"
                for y in r["ours_values"]:
                    ax.plot(r["theirs_value"], y, "o", color=c)
                ends = [v for s in r["sensitivity"] for v in s["ours_at_ends"]]
                if ends:
                    ax.vlines(r["theirs_value"], min(ends), max(ends), color=c, lw=1)
                if r["scatter"]:
                    ax.hlines(r["ours_value"], r["theirs_value"] - r["scatter"],
                              r["theirs_value"] + r["scatter"], color=c, lw=1)  # fmt: skip
                ax.plot([], [], "o", color=c, label=f"{r['id']}: {r['verdict']}")
            vals = [v for r in pts for v in r["ours_values"] + [r["theirs_value"]]]
            vals += [v for r in pts for s in r["sensitivity"] for v in s["ours_at_ends"]]
            vals = [v for v in vals if v > 0]
            lo, hi = min(vals) / 2, max(vals) * 2
            ax.plot([lo, hi], [lo, hi], ":", color="0.5")
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(f"theirs: {kind}")
            ax.set_ylabel(f"ours: {kind}")
            ax.legend(fontsize=6)
        render.save_figure(fig, out / f"{NAME}.png")


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv)
    out = args.out if args.out is not None else RENDERS
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    rows = [evaluate(r, args.quick) for r in ROWS]
    total = time.perf_counter() - t0
    atomic_write_bytes(out / f"{NAME}.md", markdown(rows, args.quick, total).encode())
    write_json(out / f"{NAME}.json", {"rows": rows, "quick": args.quick, "wall_time_s": total})
    draw(rows, out)
    table = [
        {k: r[k] for k in ("id", "kind", "theirs_value", "ours_value", "verdict")} for r in rows
    ]
    write_table(out / f"{NAME}.csv", table)
    counts = {v: sum(r["verdict"] == v for r in rows) for v in VERDICTS + (NOT_SCORED,)}
    write_json(out / "metadata.json", {"scenario": "validation", "quick": args.quick,
                                       "verdicts": counts, "runtime_s": total})  # fmt: skip
    scored = [r for r in rows if r["verdict"] != NOT_SCORED]
    print(f"{NAME}: {len(scored)} of {len(rows)} rows scored in {total:.0f} s → {out}")
    return {"rows": rows, "runtime_s": total}


if __name__ == "__main__":
    main()
