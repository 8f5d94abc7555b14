"""The figure a designer looks at first (``showcase.png`` of a design search): what holds best
and how robustly, and where the process bounds the search.

Left (two or more objectives): the first two objectives of every trial, one colour per tip
and one marker per backing, hollow where a constraint is broken, the Pareto front as a line;
each confirmed design an arrow from its screened value to the engine's (a cross). Right: the
first objective against the stalk radius (or the first searched knob), the smallest radius the
process makes (``min_radius_um``), the confirmed designs' engine values as crosses and, for
flat punches under a gap bound, the most any punch array can hold (:func:`gap_bound`).
Units: kPa (pull-off per area of backing), µm.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from gecko_agents.design.search import feasible
from gecko_agents.design.space import KNOBS, KPA, OBJECTIVES
from gecko_agents.physics import flaw_tolerance

__all__ = ["draw_showcase", "gap_bound", "SHOWCASE"]

SHOWCASE = "showcase.png"
"""The figure's file name in a design search's output folder."""

_MARKERS = {"rigid": "o", "elastic": "s", "layer": "^"}


def gap_bound(radius, gap: float, w: float, E_star: float, sigma0: float = math.inf):
    """Pull-off per area of backing [kPa] of flat punches of radius a = ``radius`` [µm] in the
    densest square array a gap g = ``gap`` [µm] allows (pitch 2a + g), all sharing the load
    equally on a flat floor: F(a)/(2a + g)², F the punch's pull-off
    (:func:`gecko_agents.physics.flaw_tolerance.punch_pull_off`: Kendall 1971, J Phys D 4:1186,
    capped by σ₀ = ``sigma0`` [MPa]; w [µN/µm], E* [MPa]). No array of such punches holds more
    (a rough floor, a tilt or a compliant backing share the load unequally). Without σ₀,
    F ∝ a^{3/2} and the bound peaks at a = 1.5·g."""
    a = np.asarray(radius, float)
    return flaw_tolerance.punch_pull_off(a, w, E_star, sigma0) / (2 * a + gap) ** 2 / KPA


def _draw_gap_bound(ax, spec, trials: list, key: str) -> None:
    g = spec.constraints.get("min_gap_um")
    punch = [t for t in trials if t.user_attrs.get("design", {}).get("tip") == "flat_punch"]
    if key != "radius_um" or g is None or not punch:
        return
    from gecko_agents.design.screen import design_params

    p = design_params(spec, punch[0].user_attrs["design"])
    c = p.contact
    r = np.geomspace(*spec.ranges[key], 200)
    ax.plot(
        r,
        gap_bound(r, g, c.work_of_adhesion, c.E_star, c.sigma0),
        "-",
        color="0.3",
        lw=1.2,
        label=f"flat punches at the {g:g} µm gap (flat floor, equal sharing)",
    )


def _label(name: str) -> str:
    direction, unit, _ = OBJECTIVES[name]
    better = "higher" if direction == "maximize" else "lower"
    return f"{name.replace('_', ' ')} [{unit}] ({better} is better)"


def _groups(spec, trials: list) -> dict:
    """(tip, backing) → the trials of that kind, in a fixed order."""
    out: dict = {}
    for t in trials:
        d = {**spec.fixed, **t.user_attrs.get("design", {})}
        out.setdefault((d.get("tip"), d.get("backing", "rigid")), []).append(t)
    return dict(sorted(out.items(), key=lambda kv: (str(kv[0][0]), str(kv[0][1]))))


def _scatter(ax, spec, groups: dict, x, y) -> None:
    tips = sorted({tip for tip, _ in groups}, key=str)
    for (tip, backing), ts in groups.items():
        color = f"C{tips.index(tip)}"
        for ok in (True, False):
            part = [t for t in ts if feasible(t) is ok]
            if part:
                ax.plot(
                    [x(t) for t in part],
                    [y(t) for t in part],
                    _MARKERS.get(backing, "o"),
                    ms=4.5,
                    color=color if ok else "0.65",
                    mfc=color if ok else "none",
                    alpha=0.85,
                    label=f"{tip}, {backing} backing" if ok else None,
                )
    if any(not feasible(t) for ts in groups.values() for t in ts):
        ax.plot([], [], "o", ms=4.5, color="0.65", mfc="none", label="a constraint broken")


def _front_panel(ax, spec, groups, front: list, rows: list) -> None:
    _scatter(ax, spec, groups, lambda t: t.values[0], lambda t: t.values[1])
    pts = sorted((t.values[0], t.values[1]) for t in front)
    if pts:
        ax.plot(
            *zip(*pts, strict=True), "-", color="k", lw=1.6, zorder=5, label="Pareto front (screen)"
        )
    for r in rows:
        sx, sy = r["screen"][spec.objectives[0]], r["screen"][spec.objectives[1]]
        ex = r["engine"]["mean"]
        ey = r["engine"]["spread"] if spec.objectives[1] == "spread" else sy
        ax.annotate("", (ex, ey), (sx, sy), arrowprops={"arrowstyle": "->", "color": "C3"})
        ax.plot(ex, ey, "x", ms=9, mew=2, color="C3")
    ax.plot([], [], "x", ms=9, mew=2, color="C3", label="engine (confirmed)")
    ax.set_xlabel(_label(spec.objectives[0]))
    ax.set_ylabel(_label(spec.objectives[1]))
    ax.set_title("what holds best, and how robustly")
    ax.legend(fontsize="x-small", loc="best")


def _knob_panel(ax, spec, groups, rows: list, key: str) -> None:
    import matplotlib as mpl

    drawn = {g: [t for t in ts if key in t.params] for g, ts in groups.items()}
    _scatter(ax, spec, drawn, lambda t: t.params[key], lambda t: t.values[0])
    lo = spec.constraints.get("min_radius_um") if key == "radius_um" else None
    if lo is not None:
        ax.axvline(lo, color="0.4", lw=1.0, ls="--", label=f"smallest radius made, {lo:g} µm")
    _draw_gap_bound(ax, spec, [t for ts in groups.values() for t in ts], key)
    for r in rows:
        if key in r["design"]:
            ax.plot(r["design"][key], r["engine"]["mean"], "x", ms=9, mew=2, color="C3")
    ax.legend(fontsize="x-small", loc="best")
    if KNOBS[key].log:
        ax.set_xscale("log")
        for axis in (ax.xaxis.set_major_formatter, ax.xaxis.set_minor_formatter):
            axis(mpl.ticker.FormatStrFormatter("%g"))
    ax.set_xlabel(f"{key.replace('_um', '')} [{KNOBS[key].unit}]")
    ax.set_ylabel(_label(spec.objectives[0]))
    ax.set_title(f"{spec.objectives[0].replace('_', ' ')} against {key.replace('_um', '')}")


def draw_showcase(spec, trials: list, front: list, rows: list, out: Path) -> Path | None:
    """Draw :data:`SHOWCASE` into ``out`` from a study's finished trials, its Pareto front and
    the confirmed rows of :func:`gecko_agents.design.study.run_design` (each with ``label``,
    ``design``, ``screen`` and ``engine``). None (nothing drawn) when no knob is searched."""
    import matplotlib as mpl
    from matplotlib.figure import Figure

    from gecko_agents import render

    knobs = [k for k in KNOBS if k in spec.ranges]
    if not knobs or not trials:
        return None
    key = "radius_um" if "radius_um" in knobs else knobs[0]
    two = len(spec.objectives) > 1
    groups = _groups(spec, trials)
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(11.0 if two else 5.8, 4.6), layout="constrained")
        axes = fig.subplots(1, 2 if two else 1, squeeze=False)[0]
        if two:
            _front_panel(axes[0], spec, groups, front, rows)
        _knob_panel(axes[-1], spec, groups, rows, key)
        fig.suptitle(
            f"{spec.description or spec.path.stem}: {len(trials)} designs screened, "
            f"{len(rows)} confirmed",
            fontsize="medium",
        )
        return render.save_figure(fig, Path(out) / SHOWCASE)
