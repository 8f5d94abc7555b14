"""What a design search writes for a designer: the trials' table, the Pareto front and the
objectives against each parameter (figures), parameter importances, the best designs with their
confirmed values, and a short report that places them beside published designs.

The published designs are a comparison, never a target: nothing of the search is tuned to them.
Units: µm, kPa (pull-off per area of backing).
"""

from __future__ import annotations

import csv
import io
import math
import warnings
from pathlib import Path

from gecko_agents.design.confirm import DISAGREE
from gecko_agents.design.search import feasible
from gecko_agents.design.space import KNOBS, OBJECTIVES, TIP_KINDS, in_use

__all__ = [
    "PUBLISHED",
    "trial_rows",
    "write_csv",
    "draw_front",
    "draw_parameters",
    "importances",
    "report_text",
]

PUBLISHED = [
    {
        "design": "PDMS flat-punch pillars, radii 2.5–25 µm, heights 2.5–80 µm",
        "finding": "pull-off per area rises as the radius falls and as the aspect ratio grows",
        "source": "Greiner, del Campo & Arzt 2007, Langmuir 23:3495",
    },
    {
        "design": "PDMS pillars with 3D tip shapes (flat, spherical, spatular, mushroom)",
        "finding": "the contact shape of the tip sets the adhesion of the structured surface",
        "source": "del Campo et al. 2007, Adv Mater, doi:10.1002/adma.200602476",
    },
    {
        "design": "polymer fibres in one and two levels with flat mushroom tips, on a 12 mm "
        "glass hemisphere",
        "finding": "two levels hold more and dissipate more than one level or a flat control",
        "source": "Murphy, Kim & Sitti 2009, ACS Appl Mater Interfaces (abstract)",
    },
]
"""Published pillar designs the report places the search's best beside (their finding in
words; see each source for the numbers and conditions)."""


def trial_rows(spec, trials: list, confirmed: dict) -> list[dict]:
    """One row per finished trial: its number, design, screened objectives, constraints kept,
    and the engine's values where it was confirmed."""
    rows = []
    for t in trials:
        a = t.user_attrs
        row = {"trial": t.number, **a.get("design", {})}
        row |= {f"screen_{k}": v for k, v in a.get("record", {}).get("screen", {}).items()}
        row |= {k: v for k, v in a.get("record", {}).get("metrics", {}).items()}
        row["feasible"] = feasible(t)
        c = confirmed.get(t.number)
        row["engine_pull_off_per_area"] = c["mean"] if c else math.nan
        row["engine_spread"] = c["spread"] if c else math.nan
        if c and "error" in c:  # the column only where a confirmation failed
            row["engine_error"] = c["error"]
        row["code_version"] = a.get("record", {}).get("code_version", "")
        rows.append(row)
    return rows


def write_csv(path: Path, rows: list[dict]) -> None:
    from gecko_agents.output_paths import atomic_write_bytes

    keys = list(dict.fromkeys(k for r in rows for k in r))
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=keys, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    atomic_write_bytes(path, buf.getvalue().encode())


def _label(name: str) -> str:
    direction, unit, _ = OBJECTIVES[name]
    return f"{name} [{unit}] ({direction})"


def draw_front(spec, trials: list, best: list, confirmed: dict, out: Path) -> None:
    """The first two objectives of every trial (feasible filled, infeasible hollow) with the
    Pareto front marked; for one objective, the objective against the trial number with the
    best designs marked. Crosses: the engine's pull-off per area of the confirmed designs."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    from gecko_agents import render

    two = len(spec.objectives) > 1

    def pts(ts):
        if two:
            return [t.values[0] for t in ts], [t.values[1] for t in ts]
        return [t.number for t in ts], [t.values[0] for t in ts]

    ok = [t for t in trials if feasible(t)]
    bad = [t for t in trials if t not in ok]
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(6.0, 4.5), layout="constrained")
        ax = fig.subplots()
        ax.plot(*pts(bad), "o", mfc="none", color="0.6", label="breaks a constraint")
        ax.plot(*pts(ok), "o", color="C0", label="feasible")
        ax.plot(*pts(best), "s", color="C3", label="Pareto front" if two else "best")
        conf = [t for t in best if t.number in confirmed]
        if conf and spec.objectives[0] == "pull_off_per_area":
            x, y = pts(conf)
            engine = [confirmed[t.number]["mean"] for t in conf]
            ax.plot(
                engine if two else x,
                y if two else engine,
                "x",
                ms=10,
                color="k",
                label="engine (confirmed)",
            )
        ax.set_xlabel(_label(spec.objectives[0]) if two else "trial")
        ax.set_ylabel(_label(spec.objectives[1] if two else spec.objectives[0]))
        ax.legend(fontsize="small")
        render.save_figure(fig, out / "pareto_front.png")


def draw_parameters(spec, trials: list, out: Path) -> None:
    """Each objective against each searched parameter, one panel per pair."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    from gecko_agents import render

    names = [k for k in KNOBS if k in spec.ranges]
    cats = [c for c, v in spec.choices.items() if len(v) > 1]
    if not names:
        return
    with mpl.rc_context(render.STYLE_RC):
        nr, nc = len(spec.objectives), len(names)
        fig = Figure(figsize=(3.2 * nc + 0.6, 2.8 * nr + 0.4), layout="constrained")
        axes = fig.subplots(nr, nc, squeeze=False)
        groups = sorted({tuple(t.params.get(c) for c in cats) for t in trials})
        for i, obj in enumerate(spec.objectives):
            for j, key in enumerate(names):
                ax = axes[i][j]
                for g, group in enumerate(groups):
                    sel = [t for t in trials if tuple(t.params.get(c) for c in cats) == group]
                    for ok, face in ((True, f"C{g}"), (False, "none")):
                        part = [t for t in sel if feasible(t) is ok and key in t.params]
                        ax.plot(
                            [t.params[key] for t in part],
                            [t.values[i] for t in part],
                            "o",
                            ms=3.5,
                            color=f"C{g}",
                            mfc=face,
                            label=("/".join(map(str, group)) or "feasible") if ok else None,
                        )
                if KNOBS[key].log:
                    ax.set_xscale("log")
                    for axis in (ax.xaxis.set_major_formatter, ax.xaxis.set_minor_formatter):
                        axis(mpl.ticker.FormatStrFormatter("%g"))
                ax.set_xlabel(f"{key} [{KNOBS[key].unit}]")
                if j == 0:
                    ax.set_ylabel(_label(obj))
        axes[0][0].legend(fontsize="small", title="filled: feasible", title_fontsize="small")
        render.save_figure(fig, out / "objectives_vs_parameters.png")


def importances(study, spec) -> dict:
    """Each searched parameter's importance to each objective: how much it matters for
    reaching the best 10 % of the trials (Optuna's PED-ANOVA evaluator, Parzen estimators of
    those trials against the rest; Watanabe et al. 2023, IJCAI), normalised to sum to 1;
    empty where too few trials vary."""
    from gecko_agents.design.search import require_optuna

    optuna = require_optuna()
    out = {}
    for i, name in enumerate(spec.objectives):
        sign = -1.0 if spec.directions[i] == "maximize" else 1.0  # the evaluator seeks low values
        try:
            with warnings.catch_warnings():  # its note that it ranks low values: the sign does
                warnings.filterwarnings("ignore", message="PedAnovaImportanceEvaluator")
                imp = optuna.importance.get_param_importances(
                    study,
                    target=lambda t, i=i, s=sign: s * t.values[i],
                    evaluator=optuna.importance.PedAnovaImportanceEvaluator(),
                )
        except (ValueError, RuntimeError, ZeroDivisionError):
            imp = {}
        out[name] = {k: float(v) for k, v in imp.items()}
    return out


def _fmt(v) -> str:
    if v is None:  # a knob the design does not have (a rigid backing's thickness)
        return "—"
    return f"{v:.4g}" if isinstance(v, float) else str(v)


def best_table(spec, rows: list[dict]) -> list[str]:
    """Markdown table of the confirmed designs: knobs, screened and confirmed values."""
    knobs = [*[c for c, v in spec.choices.items() if len(v) > 1], *spec.ranges]
    head = [
        "design",
        *knobs,
        *[f"screen {o}" for o in spec.objectives],
        "engine pull-off [kPa]",
        "engine spread",
        "screen/engine",
    ]
    release = "release_force" in spec.objectives
    head += ["engine release [kPa]"] if release else []
    several = len(spec.objectives) > 1
    head += ["Pareto front"] if several else []
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        e = r["engine"]
        engine = ["failed (below)", "—", "—"] if "error" in e else [e["mean"], e["spread"]]
        cells = [
            r["label"],
            *[_fmt(in_use(r["design"]).get(k)) for k in knobs],
            *[_fmt(r["screen"][o]) for o in spec.objectives],
            *[_fmt(v) for v in engine],
            *([] if "error" in e else [_fmt(r["ratio"])]),
        ]
        if release:
            cells.append(
                "screen only (level backing)" if e["release"] is None else _fmt(e["release"])
            )
        if several:
            cells.append("yes" if r.get("front") else "—")
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def _failed_lines(failed: list[dict]) -> list[str]:
    """The report's section on confirmations the engine could not finish, each with its
    reason; nothing when every one ran."""
    if not failed:
        return []
    lines = ["## Confirmations that failed", ""]
    lines += [f"- {r['label']} (trial {r['trial']}): {r['engine']['error']}" for r in failed]
    return [*lines, ""]


def report_text(spec, rows: list[dict], imp: dict, n_trials: int, screen_flags: dict) -> str:
    """The report: the best designs, where the fidelities disagree, the models' validity
    items, the parameter importances, and the published designs beside them."""
    failed = [r for r in rows if "error" in r["engine"]]
    disagree = [r for r in rows if r not in failed and not abs(r["ratio"] - 1.0) <= DISAGREE]
    lines = [
        f"# Design search: {spec.path.name}{' (quick)' if spec.quick else ''}",
        "",
        spec.description,
        "",
        f"{n_trials} screening trials (seed {spec.seed}; objectives "
        f"{', '.join(f'{o} ({OBJECTIVES[o][0]})' for o in spec.objectives)}); "
        f"{len(rows)} designs confirmed with the time-stepped engine "
        f"({spec.test['engine_pillars']} pillars, {spec.test['engine_seeds']} floor seeds).",
        "",
        "## Best designs",
        "",
        *best_table(spec, rows),
        "",
        "Run files that reproduce each engine run: `runs/<design>.toml` "
        "(`gecko-agents run runs/design_1.toml`).",
        "",
        *_failed_lines(failed),
        "## Where the screen and the engine disagree",
        "",
    ]
    lines += [
        f"- {r['label']}: screen {_fmt(r['screen']['pull_off_per_area'])} kPa, engine "
        f"{_fmt(r['engine']['mean'])} kPa (ratio {_fmt(r['ratio'])})"
        for r in disagree
    ] or [f"- none beyond ±{DISAGREE:.0%}"]
    n, m = spec.test["pillars"], spec.test["engine_pillars"]
    if "layer" in spec.choices["backing"] and n != m:
        lines.append(
            f"- on a backing layer the load sharing depends on the row's length: the screen's "
            f"row has {n} pillars, the engine's {m} (set test.engine_pillars = test.pillars "
            "to compare like with like)"
        )
    lines += ["", "## Models", ""]
    for tip in spec.choices["tip"]:
        kind = TIP_KINDS[tip]
        screen = (
            "the quasi-static solver on linear pillars (the paper's eq 22–27)"
            if kind.release_force is None
            else "linear fibrils over the floor, released at the law's closed-form force"
        )
        lines.append(
            f"- {tip}: screen — {screen} ({kind.source}); engine — "
            "gecko_agents.model.Model, elastica pillars, the same floors"
        )
    if "layer" in spec.choices["backing"]:
        lines.append(
            "- backing layer: screen — the field model's fibrils, coupled through the layer's "
            "compliance (gecko_agents.physics.layer_field; Bettscheider et al. 2021, J Mech "
            "Phys Solids 104365), event to event; engine — rod pillars on "
            "gecko_agents.backing.layer, the explicit step"
        )
    lines += ["", "## Validity items not met", ""]
    lines += [
        f"- screen, {name}: {n} of {n_trials + n} trials failed ({meaning})"
        if name == "failed_trials"  # not among the n_trials finished ones
        else f"- screen, {name}: not met in {n} of {n_trials} trials ({meaning})"
        for name, (n, meaning) in screen_flags.items()
    ] or ["- screen: none"]
    for r in rows:
        for name, item in r["engine"]["validity_flags"].items():
            lines.append(
                f"- engine, {r['label']}, {name}: {_fmt(item['value'])} "
                f"(rule {item['rule']}; {item['meaning']})"
            )
    lines += ["", "## Parameter importances (PED-ANOVA)", ""]
    for obj, d in imp.items():
        lines.append(f"- {obj}: " + (", ".join(f"{k} {v:.2f}" for k, v in d.items()) or "—"))
    lines += ["", "## Beside published designs (a comparison, not a target)", ""]
    lines += [f"- {p['design']}: {p['finding']} ({p['source']})" for p in PUBLISHED]
    return "\n".join(lines) + "\n"
