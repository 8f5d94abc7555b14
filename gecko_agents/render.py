"""Figures and animations drawn from a recorded :class:`~gecko_agents.history.History` only.

Units on every axis: µm, µN, µs. The floor's mean plane is y = 0, y points up. Force curves
are drawn against the pressing displacement d = (touch-down height) − (plate height) [µm],
positive when the plate is pressed towards the floor past the height at which a resting tip
touches the mean plane, negative when pulled away beyond it; forces are positive in
compression, negative in tension (docs/physics.md, "Sign conventions").

* :func:`animate` — side view of the array (plate, setae, tips coloured by contact state, floor,
  all to scale) next to the force–displacement curve, written as a GIF (Pillow) or MP4 (ffmpeg
  from ``imageio-ffmpeg``, the ``video`` extra);
* :func:`render_frame` — one frame of that animation, with the axes, for tests and stills;
* :func:`plot_history` — force vs plate displacement, approach and retract, pull-off, snap-offs;
* :func:`plot_force_curves`, :func:`annotate_points`, :func:`apply_style`, :data:`STYLE_RC` —
  the shared look of the scenario figures.

Command line: ``python -m gecko_agents.render RUN_DIR [--gif|--mp4] [--window N] [--frames N]
[--fps N]`` writes ``RUN_DIR/detachment.gif`` (or ``.mp4``) and ``RUN_DIR/force_history.png``.

Figures are plain :class:`matplotlib.figure.Figure` objects on an Agg canvas: no pyplot, no GUI
backend, no global state, and nothing here imports pymunk.
"""

from __future__ import annotations

import argparse
import os
import secrets
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import matplotlib as mpl
import numpy as np
from matplotlib.animation import FFMpegWriter, PillowWriter
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import EllipseCollection, LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle
from PIL import Image

from .beam import rest_tip_offset
from .history import STATE_SLIP, STATE_STICK, History, load

__all__ = [
    "STYLE_RC",
    "STATE_COLOURS",
    "FIGSIZE",
    "DPI",
    "PNG_DPI",
    "Frame",
    "animate",
    "render_frame",
    "frame_records",
    "window_range",
    "plot_history",
    "plot_force_curves",
    "annotate_points",
    "apply_style",
    "save_figure",
    "touchdown_height",
    "pressing_displacement",
    "PRESSING_LABEL",
    "main",
]

# Look ------------------------------------------------------------------------------------------
STYLE_RC = {
    "font.size": 10,
    "axes.titlesize": 11,
    "axes.labelsize": 10,
    "xtick.labelsize": 9,
    "ytick.labelsize": 9,
    "legend.fontsize": 9,
    "legend.framealpha": 0.9,
    "lines.linewidth": 1.6,
    "axes.prop_cycle": mpl.cycler(
        color=[
            "#1f77b4",
            "#d62728",
            "#2ca02c",
            "#ff7f0e",
            "#9467bd",
            "#8c564b",
            "#17becf",
            "#7f7f7f",
        ]
    ),
}
"""rc settings every figure here is drawn under (``matplotlib.rc_context(STYLE_RC)``)."""

STATE_COLOURS = {
    "free": "#9e9e9e",
    "compressed": "#1f77b4",
    "tension": "#d62728",
    "sliding": "#ff7f0e",
}
"""Tip colours: free (grey), attached & compressed (blue), attached in tension (red), sliding."""

APPROACH_COLOUR, RETRACT_COLOUR = "#1f77b4", "#d62728"
FIGSIZE = (10.0, 4.2)
"""Animation frame size [inch]; the frame is FIGSIZE × dpi pixels."""
DPI = 100
"""Default animation resolution [pixel/inch]."""
PNG_DPI = 120
"""Resolution of saved PNG figures [pixel/inch]."""
MAX_FRAMES = 300
_CURVE_POINTS = 16  # points per drawn seta: enough for a smooth cubic


def apply_style(ax: Axes) -> Axes:
    """Give ``ax`` the shared look: light grid behind the data, no top/right spines."""
    ax.grid(True, color="#dddddd", linewidth=0.6)
    ax.set_axisbelow(True)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    ax.tick_params(direction="out", length=3)
    return ax


def _new_figure(figsize, dpi=PNG_DPI, layout="constrained") -> Figure:
    """A pyplot-free figure on an Agg canvas (headless, nothing global)."""
    fig = Figure(figsize=figsize, dpi=dpi, layout=layout)
    FigureCanvasAgg(fig)
    return fig


def _atomic_target(path: Path, suffix: str) -> Path:
    """A fresh temporary name next to ``path`` ending in ``suffix`` (so writers infer it).

    Only the name is made: the writer creates the file, with the usual permissions (mkstemp
    would leave the final file readable by its owner only).
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    return path.with_name(f".{path.stem}.{os.getpid()}-{secrets.token_hex(4)}.tmp{suffix}")


def save_figure(fig: Figure, path, dpi: int = PNG_DPI) -> Path:
    """Save ``fig`` to ``path`` atomically (temporary file in the same directory, then rename).

    The format follows the suffix of ``path`` (``.png``, ``.pdf``, ``.svg``…); ``dpi`` in
    pixel/inch. Returns the final path.
    """
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    tmp = _atomic_target(path, f".{fmt}")
    try:
        # No date in the metadata: the same figure gives the same bytes.
        metadata = {"Software": None} if fmt == "png" else None
        fig.savefig(tmp, format=fmt, dpi=dpi, metadata=metadata)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


# Static plots -----------------------------------------------------------------------------------
def annotate_points(ax: Axes, points) -> None:
    """Mark and label points on ``ax``.

    Parameters
    ----------
    ax : the axes, in its own data units (e.g. µm on x, µN on y).
    points : iterable of ``(x, y, label)`` in the axes' data units; the label is written next
        to a black dot, offset so it does not cover the curve.
    """
    for i, (x, y, label) in enumerate(points):
        ax.plot([x], [y], "o", color="black", markersize=4, zorder=5)
        ax.annotate(
            label,
            (x, y),
            xytext=(8, 10 if i % 2 == 0 else -14),
            textcoords="offset points",
            fontsize=9,
            arrowprops={"arrowstyle": "-", "color": "#555555", "lw": 0.6},
        )


PRESSING_LABEL = "pressing displacement d [µm] (> 0 pressed)"
"""x-axis label of every force–displacement plot (docs/physics.md, "Sign conventions")."""


def touchdown_height(params) -> float:
    """Plate height [µm] at which a resting tip touches the floor's mean plane y = 0.

    R + L sin θ: the plate carries the seta roots, the resting tip centre sits at
    :func:`gecko_agents.beam.rest_tip_offset` from its root, and the tip (radius R) touches
    y = 0 when its centre is at y = R.
    """
    dy = rest_tip_offset(params.seta.L, params.seta.theta)[1]
    return float(params.contact.R - dy)


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
        fig = _new_figure((6.4, 4.4))
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


def _num(value: float, spec: str) -> str:
    """``format(value, spec)`` with a typographic minus, as on matplotlib's tick labels."""
    return format(value, spec).replace("-", "\u2212")


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


def _draw_force_curve(ax: Axes, history: History, annotate: bool) -> None:
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
    if not annotate:
        return
    k = int(np.argmin(f))
    if f[k] < 0:
        ax.plot(
            [x[k]],
            [f[k]],
            "v",
            color="black",
            markersize=7,
            zorder=5,
            label=f"pull-off {_num(f[k], '.3g')} µN",
        )
        ax.annotate(
            f"pull-off {_num(f[k], '.3g')} µN\nat {_num(x[k], '+.3g')} µm",
            (x[k], f[k]),
            xytext=(12, 14),
            textcoords="offset points",
            fontsize=9,
            va="bottom",
            bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.8},
        )
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
            fig = _new_figure((6.4, 4.4))
            ax = fig.add_subplot()
        else:
            fig = ax.figure
        apply_style(ax)
        _draw_force_curve(ax, history, annotate=True)
        ax.set_title(
            f"N = {history.params.array.count} setae, {history.params.mechanics} "
            f"mechanics, {len(history)} records"
        )
        ax.legend(loc="best")
    if path is not None:
        save_figure(fig, path)
    return fig


# Animation --------------------------------------------------------------------------------------
def window_range(n_setae: int, window: int) -> range:
    """Indices of the ``window`` setae drawn around the centre of an ``n_setae`` array.

    All of them when ``n_setae <= window``; e.g. ``window_range(1000, 40)`` is 480…519.
    """
    if window < 1:
        raise ValueError(f"window = {window!r} must be ≥ 1")
    if n_setae <= window:
        return range(n_setae)
    first = n_setae // 2 - window // 2
    return range(first, first + window)


def frame_records(n_records: int, frames: int | None = None) -> np.ndarray:
    """Record indices shown by an animation of ``frames`` frames (default ≤ 300).

    Evenly spaced, first and last record included, never repeating a record.
    """
    if n_records < 1:
        raise ValueError("the history has no records to draw")
    frames = min(n_records, MAX_FRAMES) if frames is None else frames
    if frames < 1:
        raise ValueError(f"frames = {frames!r} must be ≥ 1")
    frames = min(frames, n_records)
    return np.unique(np.round(np.linspace(0, n_records - 1, frames)).astype(int))


def _tip_colours(state: np.ndarray, force: np.ndarray) -> list[str]:
    """Colour per seta from its contact state and normal force [µN]."""
    out = []
    for s, f in zip(state, force, strict=True):
        if s == STATE_SLIP:
            out.append(STATE_COLOURS["sliding"])
        elif s == STATE_STICK:
            out.append(STATE_COLOURS["tension" if f < 0 else "compressed"])
        else:
            out.append(STATE_COLOURS["free"])
    return out


@dataclass
class Frame:
    """One drawn frame of :func:`animate`.

    Attributes
    ----------
    figure : the figure (Agg canvas), ``FIGSIZE`` × dpi pixels.
    side_ax : side view, data units µm, aspect 1.
    force_ax : force [µN] vs pressing displacement d [µm].
    record : index of the drawn record.
    shown : indices of the setae drawn.
    window_text : e.g. ``"setae 480–519 of 1000 shown"``; empty when all setae are drawn.
    """

    figure: Figure
    side_ax: Axes
    force_ax: Axes
    record: int
    shown: range
    window_text: str

    def rgb(self) -> np.ndarray:
        """The frame as an (height, width, 3) uint8 array, row 0 at the top."""
        self.figure.canvas.draw()
        return np.asarray(self.figure.canvas.buffer_rgba())[..., :3].copy()

    def pixel(self, x_um: float, y_um: float) -> tuple[int, int]:
        """(row, column) in :meth:`rgb` (and in the animation frame) of side-view point [µm]."""
        px, py = self.side_ax.transData.transform((x_um, y_um))
        height = self.figure.bbox.height
        return int(round(height - py)), int(round(px))


class _Scene:
    """The animation figure, built once; :meth:`draw` moves the artists to record k."""

    def __init__(self, history: History, window: int, dpi: float):
        if not history.setae:
            raise ValueError(
                "this run was recorded without per-seta data, so there is nothing "
                "to animate; re-run it with record_setae=True"
            )
        for key in ("root_dx_um", "root_dy_um"):
            if key not in history.geometry:
                raise ValueError(f"history.geometry lacks {key!r}; cannot place the setae")
        self.h = history
        p = history.params
        self.R, self.L, self.theta = p.contact.R, p.seta.L, p.seta.theta
        self.linear = p.mechanics == "linear"
        n_setae = np.asarray(history.setae["tip_x_um"]).shape[1]
        self.shown = window_range(n_setae, window)
        sel = slice(self.shown.start, self.shown.stop)
        self.window_text = (
            f"setae {self.shown.start}–{self.shown.stop - 1} of {n_setae} shown"
            if len(self.shown) < n_setae
            else ""
        )
        g = history.geometry
        self.root_dx = np.asarray(g["root_dx_um"], dtype=float)[sel]
        self.root_dy = np.asarray(g["root_dy_um"], dtype=float)[sel]
        s = history.setae
        self.tip_x = np.asarray(s["tip_x_um"], dtype=float)[:, sel]
        self.tip_y = np.asarray(s["tip_y_um"], dtype=float)[:, sel]
        self.force = np.asarray(s["force_normal_uN"], dtype=float)[:, sel]
        self.state = np.asarray(s["state"])[:, sel]
        self.plate_x = np.asarray(history["plate_x_um"], dtype=float)
        self.plate_y = np.asarray(history["plate_y_um"], dtype=float)
        self.disp = pressing_displacement(history, self.plate_y)
        self.time = np.asarray(history["time_us"], dtype=float)
        self.plate_h = 0.15 * self.L  # drawn plate thickness [µm], a visual choice
        self.pitch = (
            float(np.median(np.diff(np.sort(self.root_dx))))
            if len(self.root_dx) > 1
            else 2.0 * self.R
        )
        with mpl.rc_context(STYLE_RC):
            self._build(dpi)

    def _limits(self):
        """Fixed side-view limits covering every record, so the picture does not jump."""
        root_x = self.plate_x[:, None] + self.root_dx[None, :]
        xs = [
            root_x.min() - self.pitch / 2,
            root_x.max() + self.pitch / 2,
            self.tip_x.min() - self.R,
            self.tip_x.max() + self.R,
        ]
        xlo, xhi = min(xs), max(xs)
        floor_y = self._floor(xlo, xhi)[1]
        ylo = min(self.tip_y.min() - self.R, floor_y.min())
        yhi = max(self.plate_y.max() + self.root_dy.max() + self.plate_h, self.tip_y.max() + self.R)
        mx, my = 0.04 * (xhi - xlo), 0.06 * (yhi - ylo)
        return (xlo - mx, xhi + mx), (ylo - my - 0.1 * self.R, yhi + my)

    def _floor(self, xlo, xhi):
        """Floor polyline [µm] clipped to [xlo, xhi] (flat y = 0 if the run stored none)."""
        g = self.h.geometry
        if "floor_x_um" not in g or len(g["floor_x_um"]) < 2:
            return np.array([xlo, xhi]), np.zeros(2)
        fx = np.asarray(g["floor_x_um"], dtype=float)
        fy = np.asarray(g["floor_y_um"], dtype=float)
        order = np.argsort(fx)
        fx, fy = fx[order], fy[order]
        inside = (fx > xlo) & (fx < xhi)
        x = np.concatenate([[xlo], fx[inside], [xhi]])
        return x, np.interp(x, fx, fy)

    def _build(self, dpi):
        fig = Figure(figsize=FIGSIZE, dpi=dpi)
        FigureCanvasAgg(fig)
        self.fig = fig
        side = fig.add_axes((0.06, 0.17, 0.54, 0.68))
        force = fig.add_axes((0.68, 0.17, 0.30, 0.68))
        (xlo, xhi), (ylo, yhi) = self._limits()
        side.set_xlim(xlo, xhi)
        side.set_ylim(ylo, yhi)
        side.set_aspect("equal")  # to scale: 1 µm is as long across as up
        side.set(xlabel="x [µm]", ylabel="y [µm]")
        fx, fy = self._floor(xlo, xhi)
        side.fill_between(fx, fy, ylo, color="#e8dcc0", zorder=1, lw=0)
        side.plot(fx, fy, color="#8b6f47", lw=1.2, zorder=2)
        self.plate = Rectangle((0.0, 0.0), 1.0, self.plate_h, color="#444444", zorder=3)
        side.add_patch(self.plate)
        side.apply_aspect()
        # Rod linewidth to scale (diameter 2r), but never thinner than a hairline.
        px_per_um = side.transData.transform((1.0, 0.0))[0] - side.transData.transform((0, 0))[0]
        lw = max(0.6, 2.0 * self.h.params.seta.r * px_per_um * 72.0 / dpi)
        self.rods = LineCollection([], colors="#5a5a5a", linewidths=lw, capstyle="butt", zorder=4)
        side.add_collection(self.rods)
        n = len(self.shown)
        self.tips = EllipseCollection(
            np.full(n, 2 * self.R),
            np.full(n, 2 * self.R),
            np.zeros(n),
            units="xy",
            offsets=np.zeros((n, 2)),
            offset_transform=side.transData,
            edgecolors="#333333",
            linewidths=0.5,
            zorder=5,
        )
        side.add_collection(self.tips)
        handles = [
            Line2D([], [], ls="", marker="o", markersize=8, color=c, mec="#333333", label=name)
            for name, c in (
                ("free", STATE_COLOURS["free"]),
                ("attached, compressed", STATE_COLOURS["compressed"]),
                ("attached, tension", STATE_COLOURS["tension"]),
                ("sliding", STATE_COLOURS["sliding"]),
            )
        ]
        fig.legend(
            handles=handles,
            loc="lower left",
            bbox_to_anchor=(0.06, 0.0),
            ncol=4,
            frameon=False,
            fontsize=9,
        )
        apply_style(force)
        _draw_force_curve(force, self.h, annotate=False)
        force.legend(loc="lower left", fontsize=8)
        (self.marker,) = force.plot([], [], "o", color="black", markersize=6, zorder=6)
        self.caption = fig.text(0.06, 0.93, "", fontsize=11, ha="left", va="baseline")
        fig.text(
            0.06, 0.88, self.window_text, fontsize=9, color="#555555", ha="left", va="baseline"
        )
        self.side, self.force_ax = side, force
        # What changes from frame to frame, in drawing (zorder) order; the rest is drawn once.
        self.moving = [self.plate, self.rods, self.tips, self.marker, self.caption]
        self.background = None

    def rgb_fast(self, k: int) -> np.ndarray:
        """Record ``k`` as an RGB array, redrawing only the moving artists.

        Axes, ticks, legends and curves are rendered once and pasted back each frame (blitting),
        which is about three times faster than a full draw.
        """
        canvas = self.fig.canvas
        if self.background is None:
            for a in self.moving:
                a.set_visible(False)
            canvas.draw()
            self.background = canvas.copy_from_bbox(self.fig.bbox)
            for a in self.moving:
                a.set_visible(True)
        self.draw(k)
        canvas.restore_region(self.background)
        for a in self.moving:
            self.fig.draw_artist(a)
        return np.asarray(canvas.buffer_rgba())[..., :3].copy()

    def _segments(self, k: int) -> np.ndarray:
        """Seta centre lines [µm], shape (n_shown, points, 2), root to tip centre."""
        root = np.stack([self.plate_x[k] + self.root_dx, self.plate_y[k] + self.root_dy], -1)
        tip = np.stack([self.tip_x[k], self.tip_y[k]], -1)
        if not self.linear:  # rod mechanics: a rigid straight rod
            return np.stack([root, tip], axis=1)
        # Cantilever with a tip load: leaves the root along the rest direction e_a, transverse
        # deflection w(ξ) = w_tip (3ξ² − ξ³)/2, axial stretch spread evenly along the rod.
        e_a = np.array(rest_tip_offset(1.0, self.theta))
        e_t = np.array([-e_a[1], e_a[0]])
        d = tip - root
        a, t = d @ e_a, d @ e_t
        xi = np.linspace(0.0, 1.0, _CURVE_POINTS)
        shape = (3 * xi**2 - xi**3) / 2
        return (
            root[:, None, :]
            + (a[:, None] * xi)[..., None] * e_a
            + (t[:, None] * shape)[..., None] * e_t
        )

    def draw(self, k: int) -> None:
        """Move every artist to record ``k``."""
        root_x = self.plate_x[k] + self.root_dx
        self.plate.set_xy((root_x.min() - self.pitch / 2, self.plate_y[k] + self.root_dy.max()))
        self.plate.set_width(root_x.max() - root_x.min() + self.pitch)
        self.rods.set_segments(list(self._segments(k)))
        self.tips.set_offsets(np.stack([self.tip_x[k], self.tip_y[k]], -1))
        self.tips.set_facecolor(_tip_colours(self.state[k], self.force[k]))
        self.marker.set_data([self.disp[k]], [self.h["force_normal_uN"][k]])
        self.caption.set_text(
            f"t = {_num(self.time[k], '.2f')} µs    pressing displacement d = "
            f"{_num(self.disp[k], '+.3f')} µm    "
            f"(record {k + 1} of {len(self.time)})"
        )


def render_frame(history: History, k: int, *, window: int = 40, dpi: float = DPI) -> Frame:
    """Draw record ``k`` of ``history`` exactly as :func:`animate` does.

    Parameters
    ----------
    history : a run recorded with per-seta data (``record_setae=True``).
    k : record index (negative counts from the end).
    window : number of setae drawn around the centre of the array.
    dpi : resolution [pixel/inch]; the frame is :data:`FIGSIZE` × dpi pixels.

    Returns a :class:`Frame` (figure, axes, and a data→pixel mapping for the side view).
    """
    k = range(len(history))[k]
    scene = _Scene(history, window, dpi)
    scene.draw(k)
    return Frame(scene.fig, scene.side, scene.force_ax, k, scene.shown, scene.window_text)


class _GifWriter(PillowWriter):
    """PillowWriter fed with ready RGB arrays, palettising each frame as it comes.

    A GIF frame holds at most 256 colours anyway; converting at once keeps 1 byte/pixel in
    memory instead of 3, and the fast octree quantiser is ~8× quicker than Pillow's default
    median cut for a mean error of ~1/255 on these flat-coloured drawings.
    """

    def grab_rgb(self, rgb: np.ndarray) -> None:
        frame = Image.fromarray(rgb).quantize(256, method=Image.Quantize.FASTOCTREE)
        self._frames.append(frame)


def _mp4_writer(fps: float) -> tuple[FFMpegWriter, str]:
    """An FFMpegWriter and the ffmpeg binary from ``imageio-ffmpeg``."""
    try:
        import imageio_ffmpeg
    except ImportError as err:
        raise RuntimeError(
            "MP4 output needs the ffmpeg binary from imageio-ffmpeg: "
            "pip install -e '.[video]' (or write a .gif)"
        ) from err
    # With codec "h264" matplotlib rounds the frame to even pixels and asks for yuv420p, so
    # the file plays everywhere.
    writer = FFMpegWriter(fps=fps, codec="h264")
    return writer, imageio_ffmpeg.get_ffmpeg_exe()


def animate(
    history: History,
    path,
    *,
    window: int = 40,
    frames: int | None = None,
    fps: float = 20,
    fmt: str | None = None,
    dpi: float = DPI,
) -> Path:
    """Animate a run: the array seen from the side next to its force–displacement curve.

    Parameters
    ----------
    history : a run recorded with per-seta data (``record_setae=True``); positions in µm,
        forces in µN, time in µs.
    path : output file; written atomically (temporary file in the same directory, renamed).
    window : number of setae drawn around the centre of the array (the frame says which).
    frames : number of frames, evenly spread over the records; default min(records, 300).
    fps : frames per second of the movie [1/s].
    fmt : ``"gif"`` (Pillow) or ``"mp4"`` (ffmpeg from ``imageio-ffmpeg``); default from the
        suffix of ``path``.
    dpi : resolution [pixel/inch]; frames are :data:`FIGSIZE` × dpi pixels.

    Tips are circles of radius R coloured by :data:`STATE_COLOURS`; the side view is to scale.
    Returns the path written. Raises ValueError for a run without per-seta data or an unknown
    format, RuntimeError for MP4 without ``imageio-ffmpeg``.
    """
    path = Path(path)
    fmt = (fmt or path.suffix.lstrip(".")).lower()
    if fmt not in ("gif", "mp4"):
        raise ValueError(f"unknown animation format {fmt!r} for {str(path)!r}: use .gif or .mp4")
    if fps <= 0:
        raise ValueError(f"fps = {fps!r} must be > 0")
    records = frame_records(len(history), frames)
    rc = dict(STYLE_RC)
    if fmt == "mp4":
        writer, exe = _mp4_writer(fps)
        rc["animation.ffmpeg_path"] = exe
    else:
        writer = _GifWriter(fps=fps)
    scene = _Scene(history, window, dpi)
    tmp = _atomic_target(path, f".{fmt}")
    try:
        with mpl.rc_context(rc):
            writer.setup(scene.fig, str(tmp), dpi=dpi)
            for k in records:
                if fmt == "gif":
                    writer.grab_rgb(scene.rgb_fast(int(k)))
                else:  # ffmpeg takes whole redrawn frames through a pipe
                    scene.draw(int(k))
                    writer.grab_frame()
            writer.finish()
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


# Command line -----------------------------------------------------------------------------------
def main(argv=None) -> int:
    """``python -m gecko_agents.render RUN_DIR [--gif|--mp4] [--window N] [--frames N]
    [--fps N]``: render a saved run into RUN_DIR/detachment.gif (or .mp4) and
    RUN_DIR/force_history.png. Returns the exit code (2 on a missing or corrupt run)."""
    parser = argparse.ArgumentParser(
        prog="python -m gecko_agents.render", description="Render a saved gecko_agents run."
    )
    add_arguments(parser)
    return run(parser.parse_args(argv))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The render command's arguments (``python -m gecko_agents.render`` and
    ``gecko-agents render``)."""
    parser.add_argument("run_dir", type=Path, help="directory written by History.save")
    kind = parser.add_mutually_exclusive_group()
    kind.add_argument(
        "--gif", dest="fmt", action="store_const", const="gif", help="animated GIF (default)"
    )
    kind.add_argument(
        "--mp4",
        dest="fmt",
        action="store_const",
        const="mp4",
        help="MP4 video (needs pip install -e '.[video]')",
    )
    parser.add_argument("--window", type=int, default=40, help="setae drawn (default 40)")
    parser.add_argument("--frames", type=int, default=None, help="frames (default ≤ 300)")
    parser.add_argument("--fps", type=float, default=20, help="frames per second (default 20)")


def run(args: argparse.Namespace) -> int:
    """Render the run directory ``args.run_dir`` (arguments of :func:`add_arguments`);
    returns the exit code (2 on a missing or corrupt run)."""
    try:
        start = time.perf_counter()
        history = load(args.run_dir)
        png = args.run_dir / "force_history.png"
        plot_history(history, png)
        print(f"wrote {png}")
        movie = animate(
            history,
            args.run_dir / f"detachment.{args.fmt or 'gif'}",
            window=args.window,
            frames=args.frames,
            fps=args.fps,
        )
        print(f"wrote {movie}")
        print(f"rendered in {time.perf_counter() - start:.1f} s")
    except (FileNotFoundError, ValueError, RuntimeError) as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
