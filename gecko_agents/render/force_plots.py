"""Force–displacement plots of a recorded :class:`~gecko_agents.history.History`.

Force curves are drawn against the pressing displacement d = (touch-down height) − (plate
height) [µm], positive when the plate is pressed towards the floor past the height at which a
resting tip touches the mean plane, negative when pulled away beyond it; forces are positive in
compression, negative in tension (docs/physics.md, "Sign conventions").
"""

from __future__ import annotations

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from gecko_agents.history import History
from gecko_agents.physics import beam
from gecko_agents.render.style import (
    APPROACH_COLOUR,
    RETRACT_COLOUR,
    STYLE_RC,
    annotate_points,
    apply_style,
    format_number,
    new_figure,
    save_figure,
)

__all__ = [
    "PRESSING_LABEL",
    "touchdown_height",
    "pressing_displacement",
    "plot_force_curves",
    "draw_force_curve",
    "plot_history",
]

PRESSING_LABEL = "pressing displacement d [µm] (> 0 pressed)"
"""x-axis label of every force–displacement plot (docs/physics.md, "Sign conventions")."""


def touchdown_height(params) -> float:
    """Plate height [µm] at which a resting tip of ``params`` touches the floor's mean plane
    y = 0: R + L sin θ (:func:`gecko_agents.physics.beam.touchdown_height`)."""
    return float(beam.touchdown_height(params.seta.L, params.seta.theta, params.contact.R))


def pressing_displacement(history: History, plate_y=None) -> np.ndarray:
    """Pressing displacement d = :func:`touchdown_height` − plate height [µm].

    Positive when the plate is pressed towards the floor past mean-plane touch-down, negative
    when it is pulled away beyond it. ``plate_y`` [µm] defaults to ``history["plate_y_um"]``.
    """
    y = history["plate_y_um"] if plate_y is None else plate_y
    return touchdown_height(history.params) - np.asarray(y, dtype=float)


def plot_force_curves(
    curves,
    path=None,
    xlabel: str = PRESSING_LABEL,
    ylabel: str = "contact force [µN]",
    title: str = "",
    points=None,
) -> Figure:
    """A multi-curve panel for the paper-figure scenarios.

    Parameters
    ----------
    curves : list of dicts ``{"x": array, "y": array, "label": str, "style": dict}``; ``style``
        (optional) is passed to ``Axes.plot`` (e.g. ``{"ls": "--", "color": "k"}``). x and y in
        the units named by ``xlabel`` / ``ylabel``.
    path : where to save a PNG at :data:`PNG_DPI` (atomically); ``None`` saves nothing.
    xlabel, ylabel : axis labels **with units**, e.g. ``"overlap δ [µm]"``.
    title : panel title.
    points : optional ``(x, y, label)`` list handed to :func:`annotate_points`.

    Returns the :class:`~matplotlib.figure.Figure`.
    """
    with mpl.rc_context(STYLE_RC):
        fig = new_figure((6.4, 4.4))
        ax = apply_style(fig.add_subplot())
        for c in curves:
            ax.plot(
                np.asarray(c["x"]), np.asarray(c["y"]), label=c.get("label"), **c.get("style", {})
            )
        if points:
            annotate_points(ax, points)
        ax.set(xlabel=xlabel, ylabel=ylabel, title=title)
        if any(c.get("label") for c in curves):
            ax.legend()
    if path is not None:
        save_figure(fig, path)
    return fig


def _direction_runs(y: np.ndarray) -> list[tuple[int, int, bool]]:
    """Split records into runs of plate motion: ``(first, last, approaching)``, inclusive.

    Approach means plate_y decreasing; a step where the plate holds still keeps the previous
    direction (a run that starts still counts as approach).
    """
    if len(y) < 2:
        return [(0, len(y) - 1, True)]
    sign = np.sign(np.diff(y))
    last_moving = np.maximum.accumulate(np.where(sign != 0, np.arange(len(sign)), 0))
    down = sign[last_moving] <= 0
    cuts = np.flatnonzero(np.diff(down)) + 1
    starts = np.concatenate([[0], cuts])
    stops = np.concatenate([cuts, [len(down)]])
    return [(int(s), int(e), bool(down[s])) for s, e in zip(starts, stops, strict=True)]


def _snap_offs(history: History) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Detachment events as (pressing displacement d [µm], total force [µN], seta index).

    The force is the total contact force of the last record at or before the event, so the
    mark sits on the plotted curve (``detachments['force_uN']`` is the one seta's force).
    """
    det = history.detachments
    if not det or len(np.atleast_1d(det.get("plate_y_um", []))) == 0:
        return np.empty(0), np.empty(0), np.empty(0, int)
    if "record" in det:  # quasi-static: the record (plate position) of each release
        k = np.asarray(det["record"], dtype=int)
    else:
        t = np.asarray(history["time_us"])
        t_det = np.asarray(det["time_us"])
        k = np.clip(np.searchsorted(t, t_det, side="right") - 1, 0, len(t) - 1)
    seta = np.asarray(det.get("seta", np.full(len(k), -1)), dtype=int)
    d = pressing_displacement(history, np.asarray(det["plate_y_um"], dtype=float))
    return d, history["force_normal_uN"][k], seta


def draw_force_curve(ax: Axes, history: History, annotate: bool) -> None:
    """Force vs pressing displacement d, approach and retract coloured apart."""
    y = np.asarray(history["plate_y_um"], dtype=float)
    x = pressing_displacement(history, y)
    f = np.asarray(history["force_normal_uN"], dtype=float)
    labelled = set()
    for first, last, down in _direction_runs(y):
        name = "approach" if down else "retract"
        ax.plot(
            x[first : last + 1],
            f[first : last + 1],
            color=APPROACH_COLOUR if down else RETRACT_COLOUR,
            label=None if name in labelled else name,
        )
        labelled.add(name)
    ax.axhline(0.0, color="#888888", linewidth=0.6, zorder=1)
    ax.set(xlabel=PRESSING_LABEL, ylabel="contact force [µN]")
    if annotate:
        _mark_pull_off(ax, x, f)
        _mark_snap_offs(ax, history)


def _mark_pull_off(ax: Axes, x: np.ndarray, f: np.ndarray) -> None:
    """Mark and label the most tensile force (pull-off) [µN] at its displacement d [µm]."""
    k = int(np.argmin(f))
    if f[k] < 0:
        ax.plot(
            [x[k]],
            [f[k]],
            "v",
            color="black",
            markersize=7,
            zorder=5,
            label=f"pull-off {format_number(f[k], '.3g')} µN",
        )
        ax.annotate(
            f"pull-off {format_number(f[k], '.3g')} µN\nat {format_number(x[k], '+.3g')} µm",
            (x[k], f[k]),
            xytext=(12, 14),
            textcoords="offset points",
            fontsize=9,
            va="bottom",
            bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.8},
        )


def _mark_snap_offs(ax: Axes, history: History) -> None:
    """Mark the detachment events on the curve (labelled by seta when there are few)."""
    sx, sf, seta = _snap_offs(history)
    if len(sx):
        ax.plot(
            sx,
            sf,
            "x",
            color="#2ca02c",
            markersize=7,
            mew=1.8,
            zorder=6,
            label=f"snap-off ({len(sx)})",
        )
        if len(sx) <= 5:  # more labels than that would bury the curve
            for xi, fi, s in zip(sx, sf, seta, strict=True):
                ax.annotate(
                    f"seta {s}" if s >= 0 else "snap-off",
                    (xi, fi),
                    xytext=(6, 6),
                    textcoords="offset points",
                    fontsize=8,
                    color="#2ca02c",
                )


def _count_title(history: History) -> str:
    """How many setae were simulated (the forces drawn are theirs) and, if different, the
    array size the run stands for (``meta["scale_to_array"]``), e.g. "3 setae simulated,
    scaled to 10 000 000"."""
    count = int(history.params.array.count)
    n_sim = int(history.meta.get("n_sim", count))
    text = f"{n_sim} seta{'e' * (n_sim != 1)} simulated"
    if n_sim != count:
        text += ", scaled to " + f"{count:,}".replace(",", " ")
    return text


def plot_history(history: History, path=None, ax: Axes | None = None) -> Figure:
    """Total contact force vs pressing displacement, approach and retract in different colours.

    Parameters
    ----------
    history : the recorded run; uses ``plate_y_um`` [µm], ``force_normal_uN`` [µN],
        ``time_us`` [µs] and ``history.detachments``.
    path : optional PNG path, saved atomically at :data:`PNG_DPI`.
    ax : draw into these axes instead of a new figure.

    The x axis is the pressing displacement d = :func:`touchdown_height` − ``plate_y_um`` [µm]
    (> 0 pressed past touch-down, < 0 pulled away beyond it); the most negative force
    (pull-off) and the detachment events (snap-offs, placed on the curve at the last record
    before each event) are marked. Returns the Figure.
    """
    with mpl.rc_context(STYLE_RC):
        if ax is None:
            fig = new_figure((6.4, 4.4))
            ax = fig.add_subplot()
        else:
            fig = ax.figure
        apply_style(ax)
        draw_force_curve(ax, history, annotate=True)
        ax.set_title(
            f"{_count_title(history)}, {history.params.mechanics} mechanics, "
            f"{len(history)} records",
            fontsize="medium",
        )
        ax.legend(loc="best")
    if path is not None:
        save_figure(fig, path)
    return fig
