"""One frame of the detachment animation: the array seen from the side, to scale, next to its
force–displacement curve, drawn from a recorded :class:`~gecko_agents.history.History` only.

Units: µm on the side view (the floor's mean plane is y = 0, y up), µN on the force axis. The
figure is built once (:class:`Scene`); :meth:`Scene.draw` moves its artists to record k.
"""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib as mpl
import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.collections import EllipseCollection, LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.patches import Rectangle

from gecko_agents.history import STATE_SLIP, STATE_STICK, History
from gecko_agents.physics.beam import rest_tip_offset
from gecko_agents.render.backing import BackingTrack
from gecko_agents.render.force_plots import draw_force_curve, pressing_displacement
from gecko_agents.render.style import (
    DPI,
    FIGSIZE,
    STATE_COLOURS,
    STYLE_RC,
    apply_style,
    format_number,
)

__all__ = ["MAX_FRAMES", "Frame", "Scene", "render_frame", "frame_records", "window_range"]

MAX_FRAMES = 300
FRONT_COLOUR = "#9467bd"
"""Colour of the detachment-front marker of an elastic backing."""
FILM_COLOUR = "#1b9e77"
"""Colour of a film tip's free film and attached pad."""
_CURVE_POINTS = 16  # points per drawn seta: enough for a smooth cubic


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
    strip : the elastic backing's line through its nodes [µm] (None: a rigid plate is drawn,
        or the backing's nodes were not recorded).
    front : the marker of the backing's detachment front (None without an elastic backing).
    films, pads : film tips' free films (peel front to the tip body's bottom) and attached pads
        (front to front + ℓ) [µm]; None unless the run recorded
        :data:`~gecko_agents.history.FILM_FIELDS`.
    """

    figure: Figure
    side_ax: Axes
    force_ax: Axes
    record: int
    shown: range
    window_text: str
    strip: Line2D | None = None
    front: Line2D | None = None
    films: LineCollection | None = None
    pads: LineCollection | None = None

    def rgb(self) -> np.ndarray:
        """The frame as an (height, width, 3) uint8 array, row 0 at the top."""
        self.figure.canvas.draw()
        return np.asarray(self.figure.canvas.buffer_rgba())[..., :3].copy()

    def pixel(self, x_um: float, y_um: float) -> tuple[int, int]:
        """(row, column) in :meth:`rgb` (and in the animation frame) of side-view point [µm]."""
        px, py = self.side_ax.transData.transform((x_um, y_um))
        height = self.figure.bbox.height
        return int(round(height - py)), int(round(px))


class Scene:
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
        # Film tips: peel front x and attached length ℓ [µm] (NaN while free), when recorded.
        self.film = (
            (
                np.asarray(s["film_front_x_um"], dtype=float)[:, sel],
                np.asarray(s["film_attached_um"], dtype=float)[:, sel],
            )
            if "film_front_x_um" in s
            else None
        )
        self.plate_x = np.asarray(history["plate_x_um"], dtype=float)
        self.plate_y = np.asarray(history["plate_y_um"], dtype=float)
        self.disp = pressing_displacement(history, self.plate_y)
        self.time = np.asarray(history["time_us"], dtype=float)
        self.plate_h = 0.15 * self.L  # drawn plate thickness [µm], a visual choice
        self.backing = BackingTrack.of(history)
        self.strip = self.front = None
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
        strip = self.backing.extent() if self.backing else None
        if strip:
            xs += [strip[0] - self.pitch / 2, strip[1] + self.pitch / 2]
        xlo, xhi = min(xs), max(xs)
        floor_y = self._floor(xlo, xhi)[1]
        ylo = min(self.tip_y.min() - self.R, floor_y.min())
        yhi = max(self.plate_y.max() + self.root_dy.max() + self.plate_h, self.tip_y.max() + self.R)
        if strip:
            yhi = max(yhi, strip[3] + self.plate_h)
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
        self.floor_line = fx, fy  # drawn once; films and pads lie on it
        side.fill_between(fx, fy, ylo, color="#e8dcc0", zorder=1, lw=0)
        side.plot(fx, fy, color="#8b6f47", lw=1.2, zorder=2)
        self.plate = Rectangle((0.0, 0.0), 1.0, self.plate_h, color="#444444", zorder=3)
        side.apply_aspect()
        # Rod linewidth to scale (diameter 2r), but never thinner than a hairline.
        px_per_um = side.transData.transform((1.0, 0.0))[0] - side.transData.transform((0, 0))[0]
        pt_per_um = px_per_um * 72.0 / dpi
        lw = max(0.6, 2.0 * self.h.params.seta.r * pt_per_um)
        body = self._backing_artists(side, pt_per_um)
        self.rods = LineCollection([], colors="#5a5a5a", linewidths=lw, capstyle="butt", zorder=4)
        side.add_collection(self.rods)
        self.films = self.pads = None
        if self.film is not None:  # the free film (thin) and the attached pad (thick)
            self.films = LineCollection([], colors=FILM_COLOUR, linewidths=1.2, zorder=4.5)
            self.pads = LineCollection(
                [], colors=FILM_COLOUR, linewidths=3.0, zorder=4.5, capstyle="butt"
            )
            side.add_collection(self.films)
            side.add_collection(self.pads)
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
        state_legend(self.fig, film=self.film is not None, front=self.front is not None)
        apply_style(force)
        draw_force_curve(force, self.h, annotate=False)
        force.legend(loc="lower left", fontsize=8)
        (self.marker,) = force.plot([], [], "o", color="black", markersize=6, zorder=6)
        self.caption = fig.text(0.06, 0.93, "", fontsize=11, ha="left", va="baseline")
        fig.text(
            0.06, 0.88, self.window_text, fontsize=9, color="#555555", ha="left", va="baseline"
        )
        self.side, self.force_ax = side, force
        # What changes from frame to frame, in drawing (zorder) order; the rest is drawn once.
        self.moving = [
            body,
            self.rods,
            self.films,
            self.pads,
            self.tips,
            self.front,
            self.marker,
            self.caption,
        ]
        self.moving = [a for a in self.moving if a is not None]
        self.background = None

    def _backing_artists(self, side, pt_per_um: float):
        """The rigid plate or the elastic strip (and the detachment front's marker) in the
        side view; returns the backing's moving artist."""
        if self.backing and self.backing.has_nodes:  # the strip instead of the rigid plate
            # As thick as the drawn plate (a visual choice: the strip's own t_b would hide the
            # setae, whose roots sit on its centre line).
            width = max(1.5, self.plate_h * pt_per_um)
            (self.strip,) = side.plot([], [], color="#444444", lw=width, zorder=3, gid="backing")
            self.strip.set_solid_capstyle("butt")
            body = self.strip
        else:
            side.add_patch(self.plate)
            body = self.plate
        if self.backing:
            (self.front,) = side.plot(
                [],
                [],
                ls="",
                marker="v",
                markersize=9,
                color=FRONT_COLOUR,
                mec="#222222",
                zorder=6,
                gid="detachment front",
            )
        return body

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
        root = np.stack(self._roots(k), -1)
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

    def _roots(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Seta roots [µm] at record ``k``: on the plate, or on the elastic strip (at their
        abscissa along it) when its nodes were recorded."""
        if self.strip is not None:
            return self.backing.on_strip(k, self.root_dx)
        return self.plate_x[k] + self.root_dx, self.plate_y[k] + self.root_dy

    def _draw_backing(self, k: int) -> None:
        """The strip through its nodes, and the detachment front on it (or on the plate's
        lower edge when the nodes were not recorded); no marker while nothing is attached."""
        b = self.backing
        if self.strip is not None:
            self.strip.set_data(*b.nodes(k))
        a = b.front_abscissa(k)
        if not np.isfinite(a):
            self.front.set_data([], [])
        elif self.strip is not None:
            x, y = b.on_strip(k, a)
            self.front.set_data([x], [y])
        else:
            self.front.set_data([self.plate_x[k] + a], [self.plate_y[k] + self.root_dy.max()])

    def _draw_films(self, k: int) -> None:
        """Each attached film tip's free film, a chord from its peel front on the floor to the
        bottom of its tip body (:class:`~gecko_agents.contact.SpatulaTip`'s geometry), and its
        pad, the floor it covers from the front towards +x."""
        front, ell = self.film[0][k], self.film[1][k]
        on = np.isfinite(front)
        x0, length = front[on], ell[on]
        floor_x, floor_y = self.floor_line
        y0 = np.interp(x0, floor_x, floor_y)
        x1 = x0 + length
        y1 = np.interp(x1, floor_x, floor_y)
        tip_x, tip_y = self.tip_x[k][on], self.tip_y[k][on] - self.R
        tip_y = np.maximum(tip_y, y0)  # a pressed tip body: the film turns under it
        self.films.set_segments(
            [[(a, b), (c, d)] for a, b, c, d in zip(x0, y0, tip_x, tip_y, strict=True)]
        )
        self.pads.set_segments(
            [[(a, b), (c, d)] for a, b, c, d in zip(x0, y0, x1, y1, strict=True)]
        )

    def draw(self, k: int) -> None:
        """Move every artist to record ``k``."""
        root_x = self.plate_x[k] + self.root_dx
        self.plate.set_xy((root_x.min() - self.pitch / 2, self.plate_y[k] + self.root_dy.max()))
        self.plate.set_width(root_x.max() - root_x.min() + self.pitch)
        if self.backing is not None:
            self._draw_backing(k)
        self.rods.set_segments(list(self._segments(k)))
        if self.film is not None:
            self._draw_films(k)
        self.tips.set_offsets(np.stack([self.tip_x[k], self.tip_y[k]], -1))
        self.tips.set_facecolor(_tip_colours(self.state[k], self.force[k]))
        self.marker.set_data([self.disp[k]], [self.h["force_normal_uN"][k]])
        self.caption.set_text(
            f"t = {format_number(self.time[k], '.2f')} µs    pressing displacement d = "
            f"{format_number(self.disp[k], '+.3f')} µm    "
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
    scene = Scene(history, window, dpi)
    scene.draw(k)
    return Frame(
        scene.fig,
        scene.side,
        scene.force_ax,
        k,
        scene.shown,
        scene.window_text,
        scene.strip,
        scene.front,
        scene.films,
        scene.pads,
    )


def state_legend(fig, film: bool, front: bool) -> None:
    """The tip states below a scene's side view on ``fig``, with the film and pad (``film``)
    and the detachment front of an elastic backing (``front``)."""
    handles = [
        Line2D([], [], ls="", marker="o", markersize=8, color=c, mec="#333333", label=name)
        for name, c in (
            ("free", STATE_COLOURS["free"]),
            ("attached, compressed", STATE_COLOURS["compressed"]),
            ("attached, tension", STATE_COLOURS["tension"]),
            ("sliding", STATE_COLOURS["sliding"]),
        )
    ]
    if film:
        handles.append(Line2D([], [], color=FILM_COLOUR, lw=2.0, label="film, pad"))
    if front:
        handles.append(
            Line2D([], [], ls="", marker="v", markersize=8, color=FRONT_COLOUR, mec="#222222",
                   label="detachment front")
        )  # fmt: skip
    fig.legend(
        handles=handles,
        loc="lower left",
        bbox_to_anchor=(0.06, 0.0),
        ncol=len(handles),
        frameon=False,
        fontsize=9,
    )
