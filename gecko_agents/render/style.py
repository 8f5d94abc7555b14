"""The shared look of every figure: rc settings, colours, sizes, and atomic saving.

Figures are plain :class:`matplotlib.figure.Figure` objects on an Agg canvas: no pyplot, no GUI
backend, no global state. Units on every axis: µm, µN, µs.
"""

from __future__ import annotations

import os
import secrets
from pathlib import Path

import matplotlib as mpl
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from gecko_agents.output_paths import make_dir, replace_into

__all__ = [
    "STYLE_RC",
    "STATE_COLOURS",
    "APPROACH_COLOUR",
    "RETRACT_COLOUR",
    "FIGSIZE",
    "DPI",
    "PNG_DPI",
    "apply_style",
    "new_figure",
    "atomic_target",
    "save_figure",
    "annotate_points",
    "format_number",
]

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


def apply_style(ax: Axes) -> Axes:
    """Give ``ax`` the shared look: light grid behind the data, no top/right spines."""
    ax.grid(True, color="#dddddd", linewidth=0.6)
    ax.set_axisbelow(True)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    ax.tick_params(direction="out", length=3)
    return ax


def new_figure(figsize, dpi=PNG_DPI, layout="constrained") -> Figure:
    """A pyplot-free figure on an Agg canvas (headless, nothing global)."""
    fig = Figure(figsize=figsize, dpi=dpi, layout=layout)
    FigureCanvasAgg(fig)
    return fig


def atomic_target(path: Path, suffix: str) -> Path:
    """A fresh temporary name next to ``path`` ending in ``suffix`` (so writers infer it).

    Only the name is made: the writer creates the file, with the usual permissions (mkstemp
    would leave the final file readable by its owner only).
    """
    make_dir(path.parent)
    return path.with_name(f".{path.stem}.{os.getpid()}-{secrets.token_hex(4)}.tmp{suffix}")


def save_figure(fig: Figure, path, dpi: int = PNG_DPI) -> Path:
    """Save ``fig`` to ``path`` atomically (temporary file in the same directory, then rename).

    The format follows the suffix of ``path`` (``.png``, ``.pdf``, ``.svg``…); ``dpi`` in
    pixel/inch. Returns the final path.
    """
    path = Path(path)
    fmt = path.suffix.lstrip(".").lower() or "png"
    tmp = atomic_target(path, f".{fmt}")
    try:
        # No date in the metadata: the same figure gives the same bytes.
        metadata = {"Software": None} if fmt == "png" else None
        fig.savefig(tmp, format=fmt, dpi=dpi, metadata=metadata)
        replace_into(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


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


def format_number(value: float, spec: str) -> str:
    """``format(value, spec)`` with a typographic minus, as on matplotlib's tick labels."""
    return format(value, spec).replace("-", "\u2212")
