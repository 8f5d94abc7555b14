"""Validation against published measurements: ``literature_comparison.md`` (and ``.json``,
``.png``, ``.csv``), one row per published measurement, beside the paper report.

The rows are data (:data:`gecko_agents.data.LITERATURE_ROWS`, read by
:mod:`gecko_agents.studies.validation_rows`): each quotes the text we read, gives their value
as printed, the parameters our number uses, cited or assumed (with the reason), and how a
magnitude agrees. Ours is computed by the function the row names
(:mod:`gecko_agents.studies.validation_ours`), and every ranged parameter is moved to both ends
of its range to show how much ours depends on it (closed forms always, at every corner of the
ranges together; agent runs one parameter at a time, in the full run only, to keep ``--quick``
short). Nothing is tuned to a row: a disagreement is a result, with its likely cause.

Rows come in three kinds, counted apart: experiments, other models (simulations and published
laws) and self-consistency checks (the package against its own closed form or run). The
headline (:func:`headline`) counts *magnitude rows* (:func:`is_magnitude`): a printed number
of an experiment or another model against ours at the source's own geometry; direction checks
and values read from words are *trend* rows (:func:`is_trend`), counted apart. Rows sharing an
independent measurement (a table, a figure, an abstract sentence) count once beside the rows,
and one model number never scores two rows (the loader refuses it). Verdicts
(:func:`verdict`), magnitudes first:

* *agrees (within their scatter)*: ours inside their value ± the scatter the row states;
* *agrees (within the stated tolerance)*: ours within ± the tolerance (±25 % where the source
  states no scatter) of theirs, or for a bounded quantity (Φ ≤ 1) of its distance to the
  nearer bound (:func:`half_width`);
* *agrees (within the stated factor)*: a self-consistency check within theirs/f to theirs·f;
* *trend agrees (sign and stated factor)*: a direction first (ours on their side of 1, or of 0
  for a slope), then its size: the effect ln(ours) within 1/f to f times ln(theirs), or, where
  they state a direction in words only, at least the size their words state (``min_effect``);
* *disagrees (sign)*: ours goes the other way; *disagrees (magnitude)*: the right way, or no
  effect, but outside the scatter, tolerance or factor;
* *not comparable*: outside, but their value lies inside the band ours spans over the
  parameters whose value for their specimen we could not read (assumed, or a published range).

Rows that are not scored say why: *pending* (the physics they need is not in the package yet),
*out of scope* (a mechanism the package does not model), *not scored* (the number could not
be read), *calibration point* (an unreported parameter is calibrated on it) or *derived* (the
model ties its number to another row's). The report states its run; a ``--quick`` verdict of a
row whose run is smaller there (:data:`~gecko_agents.studies.validation_ours.QUICK_SIZED`) is
marked †.

Units: µm, µN, µs, MPa (= µN/µm²); stiffness µN/µm = N/m. ``python scenarios/validation.py
[--quick] --out DIR`` writes ``DIR/literature_comparison.{md,json,png,csv}`` and
``DIR/metadata.json`` (default ``renders/``); ``gecko-agents reproduce --beyond`` writes them
beside ``paper_comparison.md``.
"""

from __future__ import annotations

import itertools
import math
import time

import numpy as np

from gecko_agents import render
from gecko_agents.output_paths import atomic_write_bytes
from gecko_agents.provenance import versions
from gecko_agents.studies.common import RENDERS, command_line, parse_args, write_json, write_table
from gecko_agents.studies.validation_ours import CLOSED_FORM, OURS, QUICK_SIZED
from gecko_agents.studies.validation_rows import KINDS, MAGNITUDE_KINDS, ROWS

NAME = "literature_comparison"
AGREES_SCATTER = "agrees (within their scatter)"
AGREES_TOLERANCE = "agrees (within the stated tolerance)"
AGREES_BAND = "agrees (within the stated factor)"
TREND_AGREES = "trend agrees (sign and stated factor)"
DISAGREES_MAGNITUDE = "disagrees (magnitude)"
DISAGREES_SIGN = "disagrees (sign)"
NOT_COMPARABLE = "not comparable"
VERDICTS = (
    AGREES_SCATTER,
    AGREES_TOLERANCE,
    AGREES_BAND,
    TREND_AGREES,
    DISAGREES_MAGNITUDE,
    DISAGREES_SIGN,
    NOT_COMPARABLE,
)
"""The verdicts of a scored row."""
AGREES = (AGREES_SCATTER, AGREES_TOLERANCE, AGREES_BAND)
"""The verdicts of a magnitude that agrees."""
UNSCORED = {
    "pending": "pending",
    "out of scope": "out of scope",
    "not read": "not scored",
    "calibration": "calibration point (not scored)",
    "derived": "derived (not scored again)",
}
"""The verdict of a row that is not scored, by its status."""
TREND_RESOLUTION = 0.01
"""An effect within 1 % is no effect (a trend neither way): repeated pull-offs of the same pad
at another plate speed differ by ~0.6 % (backing_stiffness study, 0.340 vs 0.342 N·Fc)."""


def effect(row: dict, value: float) -> float:
    """Ours' effect in their direction (> 0 where it goes their way): value − 1 for a ratio
    they report above 1 (``expect = ">1"``), 1 − value below it (``"<1"``), the value itself
    for a slope (``">0"``)."""
    expect = row["expect"]
    if expect == ">1":
        return value - 1.0
    if expect == "<1":
        return 1.0 - value
    if expect == ">0":
        return value
    raise ValueError(f"row {row['id']!r}: expect = {expect!r} must be '>1', '<1' or '>0'")


def half_width(row: dict) -> float | None:
    """The half-width of a tolerance row's band, in the quantity's unit: the tolerance times
    their value, or for a bounded quantity (0 ≤ theirs ≤ 1, as Φ = σ_s/σ₀) times its distance
    to the nearer bound, min(theirs, 1 − theirs): the band on Φ or on 1 − Φ, whichever is
    the smaller number (a band on 0.97 itself would accept every Φ above 0.73)."""
    if row["tolerance"] is None:
        return None
    theirs = row["theirs_value"]
    scale = min(theirs, 1.0 - theirs) if row["bounded"] else abs(theirs)
    return row["tolerance"] * scale


def _magnitude(row: dict, value: float) -> tuple[str, str] | None:
    """The agreeing verdict where ours' magnitude lies within the row's scatter, tolerance or
    (trend rows and self-consistency checks) factor band."""
    theirs, scatter, band = row["theirs_value"], row["scatter"], row["band"]
    if scatter is not None and abs(value - theirs) <= scatter:
        return AGREES_SCATTER, f"ours is within their ±{scatter:g} ({row['scatter_why']})"
    hw = half_width(row)
    if hw is not None and abs(value - theirs) <= hw:
        on = "on the distance to the nearer bound" if row["bounded"] else "of theirs"
        return AGREES_TOLERANCE, (
            f"ours {value:.4g} is within ±{hw:.3g} of theirs {theirs:g} "
            f"(±{100 * row['tolerance']:g} % {on}: {row['tolerance_why']})"
        )
    if band is None:
        return None
    if row["compare"] == "value" and theirs / band <= value <= theirs * band:
        return AGREES_BAND, f"ours is {value / theirs:.3g}× theirs, within ×{band:g}"
    if row["compare"] == "trend" and value > 0 and theirs > 0:
        size = math.log(value) / math.log(theirs)
        if 1.0 / band <= size <= band:
            return TREND_AGREES, f"the same way, ours' effect {size:.2g}× theirs, within ×{band:g}"
    return None


def _outside(row: dict, value: float, sens: list[dict]) -> tuple[str, str]:
    """The verdict of a value outside the row's scatter and band."""
    theirs = row["theirs_value"]
    ends = [v for s in sens if s["status"] != "cited" for v in s["ours_at_ends"]]
    if row["compare"] == "value" and ends and min(ends + [value]) <= theirs <= max(ends + [value]):
        return NOT_COMPARABLE, (
            f"ours is {value / theirs:.3g}× theirs, but their value lies "
            f"inside the {min(ends):.3g}–{max(ends):.3g} ours spans over "
            "the parameters we could not read for their specimen"
        )
    if row["scatter"] is not None:
        how = f"±{row['scatter']:g}"
    elif row["tolerance"] is not None:
        how = f"±{half_width(row):.3g} (±{100 * row['tolerance']:g} %)"
    else:
        how = f"×{row['band']:g}"
    if row["compare"] == "trend" and row["scatter"] is None:
        size = math.log(value) / math.log(theirs)
        return DISAGREES_MAGNITUDE, (
            f"the same way, but ours' effect is {size:.3g}× theirs (ln ratio), outside {how}"
        )
    return DISAGREES_MAGNITUDE, f"ours is {value / theirs:.4g}× theirs, outside {how}"


def verdict(row: dict, ours: dict | None, sens: list[dict]) -> tuple[str, str]:
    """(verdict, the computed part of its reason) for one row and its ours
    (:data:`VERDICTS`, or the row's :data:`UNSCORED` label)."""
    if row["status"] != "scored":
        return UNSCORED[row["status"]], row["unscored"]
    if ours is None or not math.isfinite(ours["value"]):
        return UNSCORED["not read"], "ours could not be computed"
    value = ours["value"]
    if row["compare"] == "trend":
        v = _trend(row, value)
        if v is not None and v[0] != TREND_AGREES and _words_met_at_an_end(row, sens):
            return NOT_COMPARABLE, (
                f"{v[1]}, but their stated size is met at an end of the range ours spans over "
                "the parameters we could not read for their specimen"
            )
        if v is not None:
            return v
    return _magnitude(row, value) or _outside(row, value, sens)


def _trend(row: dict, value: float) -> tuple[str, str] | None:
    """The verdict of a trend row's direction, and of its size where stated in words (None:
    a size stated as a number, judged by :func:`_magnitude`)."""
    e = effect(row, value)
    if e < -TREND_RESOLUTION:
        return DISAGREES_SIGN, f"ours goes the other way (effect {e:+.3g})"
    if e <= TREND_RESOLUTION:
        return DISAGREES_MAGNITUDE, f"ours shows no effect ({e:+.3g}, within ±1 %)"
    if row["theirs_value"] is not None:
        return None
    if e >= row["min_effect"]:
        return TREND_AGREES, (
            f"the same way, effect {e:.3g} ≥ {row['min_effect']:g} ({row['band_why']})"
        )
    return DISAGREES_MAGNITUDE, (
        f"the same way but effect {e:.3g} < {row['min_effect']:g} ({row['band_why']})"
    )


def _words_met_at_an_end(row: dict, sens: list[dict]) -> bool:
    """Whether a direction stated in words (``min_effect``) is met at an end of a parameter
    whose value for their specimen we could not read."""
    if row["min_effect"] is None:
        return False
    ends = [v for s in sens if s["status"] != "cited" for v in s["ours_at_ends"]]
    return any(math.isfinite(v) and effect(row, v) >= row["min_effect"] for v in ends)


def _ranged(row: dict) -> list[dict]:
    return [p for p in row["params"] if p.get("range") is not None]


def sensitivity(row: dict, quick: bool) -> list[dict]:
    """Ours at both ends of each ranged parameter of ``row``, the others at their values, and
    for a closed form at every corner of the ranges together (``name`` "all together"); agent
    rows in the full run only (an empty list otherwise)."""
    if row["ours"] is None or (quick and row["ours"] not in CLOSED_FORM):
        return []
    fn, out = OURS[row["ours"]], []
    for prm in _ranged(row):
        lo, hi = (fn(quick, **{prm["name"]: x})["value"] for x in prm["range"])
        out.append(
            {
                "name": prm["name"],
                "status": prm["status"],
                "range": prm["range"],
                "unit": prm["unit"],
                "ours_at_ends": [lo, hi],
            }
        )
    ranged = [p for p in _ranged(row) if p["status"] != "cited"]
    if row["ours"] in CLOSED_FORM and len(ranged) > 1:
        corners = [
            fn(quick, **{p["name"]: x for p, x in zip(ranged, xs, strict=True)})["value"]
            for xs in itertools.product(*(p["range"] for p in ranged))
        ]
        out.append(
            {
                "name": "all together",
                "status": "assumed",
                "range": None,
                "unit": "",
                "ours_at_ends": [min(corners), max(corners)],
            }
        )
    return out


def quick_may_differ(row: dict) -> bool:
    """Whether the row's ``--quick`` verdict may differ from the full run's: its run is smaller
    there (:data:`~gecko_agents.studies.validation_ours.QUICK_SIZED`), or it is an agent run
    with a parameter range, whose ends (which can make it *not comparable*) only the full run
    computes."""
    if row["ours"] is None:
        return False
    ranged = any(p["status"] != "cited" for p in _ranged(row))
    return row["ours"] in QUICK_SIZED or (ranged and row["ours"] not in CLOSED_FORM)


def evaluate(row: dict, quick: bool) -> dict:
    """One row of the report: the row's data with ours (where it names a function, scored or
    not), its sensitivity and the verdict."""
    t0 = time.perf_counter()
    # A pending row may name ours too: shown beside it, not scored.
    ours = OURS[row["ours"]](quick) if row["ours"] else None
    sens = sensitivity(row, quick) if ours is not None else []
    v, why = verdict(row, ours, sens)
    return {
        **row,
        "quick_may_differ": quick and quick_may_differ(row),
        "ours_value": None if ours is None else ours["value"],
        "ours_values": None if ours is None else ours.get("values", [ours["value"]]),
        "ours_text": "—" if ours is None else ours["text"],
        "sensitivity": sens,
        "verdict": v,
        "reason": f"{why}. {row['cause']}".strip(),
        "wall_time_s": time.perf_counter() - t0,
    }


def is_magnitude(row: dict) -> bool:
    """A magnitude row: an experiment's or another model's printed value compared with ours
    (not a value read from words, such as 'preload-independent')."""
    return row["compare"] == "value" and row["kind"] in MAGNITUDE_KINDS and not row["in_words"]


def is_trend(row: dict) -> bool:
    """A trend row, counted apart: a direction, or a value read from words."""
    return row["compare"] == "trend" or (row["compare"] == "value" and row["in_words"])


def headline(rows: list[dict]) -> dict:
    """The report's headline: magnitude rows (:func:`is_magnitude`) scored, agreeing, and the
    same counted by independent measurement (a paper's figure, table or abstract sentence,
    the rows' ``measurement``: it agrees where all its scored rows do) and by paper; trend
    rows are counted apart. Rows *not comparable* or not scored are left out of both."""
    mag = [r for r in rows if is_magnitude(r) and r["verdict"] in VERDICTS]
    mag = [r for r in mag if r["verdict"] != NOT_COMPARABLE]
    groups: dict[str, list[dict]] = {}
    for r in mag:
        groups.setdefault(r["measurement"], []).append(r)
    trend = [r for r in rows if is_trend(r) and r["verdict"] in VERDICTS]
    trend = [r for r in trend if r["verdict"] != NOT_COMPARABLE]
    return {
        "magnitude_rows": len(mag),
        "magnitude_agree": sum(r["verdict"] in AGREES for r in mag),
        "measurements": len(groups),
        "measurements_agree": sum(all(r["verdict"] in AGREES for r in g) for g in groups.values()),
        "papers": len({r["source"] for r in mag}),
        "not_comparable": sum(is_magnitude(r) and r["verdict"] == NOT_COMPARABLE for r in rows),
        "trend_rows": len(trend),
        "trend_agree": sum(r["verdict"] in (TREND_AGREES,) + AGREES for r in trend),
        "quick_may_differ": sum(r["quick_may_differ"] for r in mag + trend),
    }


def headline_text(h: dict) -> str:
    """:func:`headline` as one sentence."""
    return (
        f"Magnitude: {h['magnitude_agree']} of {h['magnitude_rows']} rows agree within their "
        f"band ({h['measurements_agree']} of {h['measurements']} independent measurements, "
        f"{h['papers']} papers; {h['not_comparable']} more not comparable). Trend, counted "
        f"apart: {h['trend_agree']} of {h['trend_rows']} agree."
    )


def counts(rows: list[dict]) -> dict:
    """Verdict counts per kind of row: {kind: {verdict: n}} (verdicts with no row left out),
    and ``scored``: the rows with a verdict of :data:`VERDICTS` but *not comparable*, per kind."""
    out = {}
    labels = VERDICTS + tuple(dict.fromkeys(UNSCORED.values()))
    for kind in KINDS:
        sel = [r for r in rows if r["kind"] == kind]
        out[kind] = {v: n for v in labels if (n := sum(r["verdict"] == v for r in sel))}
    out["scored"] = {
        kind: sum(
            r["verdict"] in VERDICTS and r["verdict"] != NOT_COMPARABLE
            for r in rows
            if r["kind"] == kind
        )
        for kind in KINDS
    }
    return out


def params_cell(row: dict) -> str:
    """The parameters column: each cited or assumed, with the reason."""
    return (
        "; ".join(
            f"{p['name']} = {p['value']}{(' ' + p['unit']) if p['unit'] else ''} "
            f"({p['status']}: {p['why']})"
            for p in row["params"]
        )
        or "—"
    )


def ours_cell(row: dict) -> str:
    """Ours, and its value at both ends of each parameter range."""
    parts = [row["ours_text"]]
    for s in row["sensitivity"]:
        lo, hi = s["ours_at_ends"]
        span = "" if s["range"] is None else f" {s['range'][0]:g}–{s['range'][1]:g}"
        parts.append(f"{s['name']}{span}: {lo:.3g}–{hi:.3g}")
    if row["ours"] is not None and row["ours"] not in CLOSED_FORM and not row["sensitivity"]:
        if any(p.get("range") for p in row["params"]):
            parts.append("sensitivity: full run only")
    return "; ".join(parts)


KIND_TITLES = {
    "experiment": "Experiments",
    "model": "Other models (simulations, published laws)",
    "self-consistency": "Self-consistency checks",
}


def _table(rows: list[dict]) -> list[str]:
    lines = [
        "| source | what was measured | their value (as printed) | parameters used "
        "(cited / assumed, why) | ours | verdict | reason |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        cells = (
            r["source"],
            r["measured"],
            r["theirs"],
            params_cell(r),
            ours_cell(r),
            r["verdict"] + (" †" if r.get("quick_may_differ") else ""),
            r["reason"],
        )
        lines.append(
            "| " + " | ".join(str(c).replace("|", "\\|").replace("\n", " ") for c in cells) + " |"
        )
    return lines


def _band_text(row: dict) -> str:
    if row["scatter"] is not None:
        return f"±{row['scatter']:g} ({row['scatter_why']})"
    if row["tolerance"] is not None:
        on = " of the distance to the nearer bound" if row["bounded"] else ""
        return f"±{half_width(row):.3g} (±{100 * row['tolerance']:g} %{on})"
    return "—"


def _magnitude_table(rows: list[dict]) -> list[str]:
    """The magnitude rows at a glance: their number, ours, the band and the verdict."""
    lines = [
        "| row | measurement | quantity | theirs | ours | band | verdict |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        if not is_magnitude(r) or r["ours_value"] is None:
            continue
        cells = (
            r["id"],
            r["measurement"],
            r["quantity"],
            f"{r['theirs_value']:g}",
            f"{r['ours_value']:.4g}",
            _band_text(r),
            r["verdict"] + (" †" if r["quick_may_differ"] else ""),
        )
        lines.append("| " + " | ".join(str(c).replace("|", "\\|") for c in cells) + " |")
    return lines + [""]


def summary(rows: list[dict], quick: bool) -> list[str]:
    """The headline, the verdict counts (one line per kind) and the scored total."""
    c, h = counts(rows), headline(rows)
    lines = ["## Headline", "", headline_text(h), ""]
    if quick and h["quick_may_differ"]:
        lines += [
            f"Quick run: {h['quick_may_differ']} of these rows ran smaller than in the full run, "
            "or without the ends of their parameter ranges (marked † in the tables); their "
            "verdict may differ there.",
            "",
        ]
    lines += _magnitude_table(rows) + ["## Verdicts", ""]
    for kind in KINDS:
        parts = ", ".join(f"{v}: {n}" for v, n in c[kind].items()) or "none"
        lines.append(f"* {KIND_TITLES[kind]}: {parts}")
    scored = c["scored"]
    lines += [
        "",
        f"Scored (a verdict other than *not comparable*): {sum(scored.values())} rows, "
        + ", ".join(f"{n} {k}" for k, n in scored.items())
        + ".",
        "",
    ]
    return lines


def markdown(rows: list[dict], quick: bool, total: float) -> str:
    """literature_comparison.md: one table per kind of row, the verdict counts and the quotes."""
    lines = [
        "# Literature comparison",
        "",
        "Written by `python scenarios/validation.py" + (" --quick" if quick else "") + "` "
        "(or `gecko-agents reproduce --beyond`); every number under *ours* was computed in "
        "that run. The rows, their quotes and their parameters are read from "
        "`gecko_agents/data/literature/validation.toml`; how a row is scored is in "
        "`docs/validation.md`. Assumed parameters are marked, with ours at both ends of their "
        "range. Nothing is tuned to a row.",
        "",
    ]
    if quick:
        lines += [
            "**Run: quick** (small pads and few pulls; agent rows without sensitivity; a "
            "verdict marked † may differ in the full run).",
            "",
        ]
    else:
        lines += ["**Run: full.**", ""]
    lines += summary(rows, quick)
    for kind in KINDS:
        sel = [r for r in rows if r["kind"] == kind]
        if sel:
            lines += [f"## {KIND_TITLES[kind]}", ""] + _table(sel) + [""]
    lines += [f"![ours against theirs]({NAME}.png)", "", "## What we read", ""]
    for r in rows:
        quote = r["quote"].replace("\n", " ") or "(nothing quoted: see the row)"
        lines.append(f"* **{r['id']}** — {r['read_at']}: “{quote}”")
    lines += [
        "",
        f"Wall time {total:.0f} s. Versions: "
        + ", ".join(f"{k} {v}" for k, v in versions().items()),
        "",
    ]
    return "\n".join(lines)


def _panel(row: dict) -> str:
    """The figure's panel of a row: every dimensionless ratio on one, other quantities each on
    their own."""
    return "ratio [-]" if row["quantity"].endswith("[-]") else row["quantity"]


def draw(rows: list[dict], out) -> None:
    """Ours against theirs, one panel per quantity (:func:`_panel`, log axes), the sensitivity
    range as a vertical bar, their stated scatter as a horizontal one, y = x dotted."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    sel = [r for r in rows if r["ours_value"] is not None and r["theirs_value"] is not None]
    kinds = list(dict.fromkeys(_panel(r) for r in sel))
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(4.6 * max(len(kinds), 1), 4.4), layout="constrained")
        axes = np.atleast_1d(fig.subplots(1, max(len(kinds), 1)))
        for ax, kind in zip(axes, kinds, strict=False):
            pts = [r for r in sel if _panel(r) == kind]
            for i, r in enumerate(pts):
                c = f"C{i % 10}"
                for y in r["ours_values"]:
                    ax.plot(r["theirs_value"], y, "o", color=c)
                ends = [v for s in r["sensitivity"] for v in s["ours_at_ends"]]
                if ends:
                    ax.vlines(r["theirs_value"], min(ends), max(ends), color=c, lw=1)
                if r["scatter"]:
                    ax.hlines(
                        r["ours_value"],
                        r["theirs_value"] - r["scatter"],
                        r["theirs_value"] + r["scatter"],
                        color=c,
                        lw=1,
                    )
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
        {
            k: r[k]
            for k in ("id", "kind", "status", "quantity", "theirs_value", "ours_value", "verdict")
        }
        for r in rows
    ]
    write_table(out / f"{NAME}.csv", table)
    c = counts(rows)
    h = headline(rows)
    write_json(
        out / "metadata.json",
        {
            "scenario": "validation",
            "quick": args.quick,
            "headline": h,
            "verdicts": c,
            "runtime_s": total,
        },
    )
    run = "quick run" if args.quick else "full run"
    print(f"{NAME} ({run}): {headline_text(h)} {len(rows)} rows in {total:.0f} s → {out}")
    return {"rows": rows, "runtime_s": total}


if __name__ == "__main__":
    main()
