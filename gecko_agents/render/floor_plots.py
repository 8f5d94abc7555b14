"""The floor panel: a profile and its PSD on log axes (headless, matplotlib Agg).

Draws from a :class:`gecko_agents.floor.Profile` only (never from pymunk), in the look of
:mod:`gecko_agents.render` (its ``apply_style`` and ``save_figure``).
"""

from __future__ import annotations

import numpy as np
from matplotlib.axes import Axes
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from gecko_agents import floor
from gecko_agents.render import PNG_DPI, apply_style, save_figure

__all__ = ["draw_profile", "draw_psd", "plot_floor"]


def draw_profile(ax: Axes, profile: floor.Profile, label: str | None = None) -> Axes:
    """Heights [µm] against position [µm] on ``ax``."""
    ax.plot(profile.x, profile.y, linewidth=0.7, label=label)
    ax.set_xlabel("x [µm]")
    ax.set_ylabel("height [µm]")
    return apply_style(ax)


def draw_psd(
    ax: Axes, profile: floor.Profile, stats: dict | None = None, label: str | None = None
) -> Axes:
    """1-D PSD C¹ᴰ [µm³] against q [rad/µm] on log–log axes (:func:`floor.psd`, Hann window,
    SurfaceTopography convention), the log-binned average, and the fitted power law of
    :func:`floor.statistics` (``stats``; computed if not given) over its fit range."""
    stats = floor.statistics(profile) if stats is None else stats
    if profile.pad_heights is not None:
        ax.text(
            0.5,
            0.5,
            "pad floor: independent heights,\nno spectrum",
            ha="center",
            va="center",
            transform=ax.transAxes,
        )
        return apply_style(ax)
    q, c = floor.psd(profile)
    ok = (q > 0) & (c > 0)
    ax.loglog(q[ok], c[ok], color="#bbbbbb", linewidth=0.5, label="periodogram")
    qb, cb = np.asarray(stats["psd_q_per_um"]), np.asarray(stats["psd_C_um3"])
    ax.loglog(
        qb[cb > 0], cb[cb > 0], "o-", markersize=3, linewidth=1.0, label=label or "log-binned"
    )
    if stats.get("psd_slope") is not None:
        lo, hi = stats["fit_q_min_per_um"], stats["fit_q_max_per_um"]
        m = (qb >= lo) & (qb <= hi) & (cb > 0)
        if m.sum() >= 2:
            qq = np.array([lo, hi])
            ref = np.exp(np.mean(np.log(cb[m]) - stats["psd_slope"] * np.log(qb[m])))
            ax.loglog(
                qq,
                ref * qq ** stats["psd_slope"],
                "k--",
                linewidth=1.0,
                label=f"fit $q^{{{stats['psd_slope']:.2f}}}$ (H ≈ {stats['hurst']:.2f})",
            )
    ax.set_xlabel("wavevector q [rad/µm]")
    ax.set_ylabel("PSD C¹ᴰ [µm³]")
    ax.legend(frameon=False, fontsize="small")
    return apply_style(ax)


def plot_floor(
    profile: floor.Profile, path=None, title: str | None = None, stats: dict | None = None
) -> Figure:
    """The profile and, where it has one, its PSD (a pad floor of independent heights or a
    flat floor has none: one panel). Saved to ``path`` (atomic) if given."""
    spectrum = profile.pad_heights is None and float(np.ptp(profile.y)) > 0
    fig = Figure(figsize=(9.0 if spectrum else 6.0, 3.4), dpi=PNG_DPI, layout="constrained")
    FigureCanvasAgg(fig)
    ax_h, ax_c = fig.subplots(1, 2, width_ratios=[1.6, 1.0]) if spectrum else (fig.subplots(), None)
    stats = floor.statistics(profile) if stats is None else stats
    draw_profile(ax_h, profile)
    rms = stats["rms_height_um"]
    slope = stats.get("rms_slope")
    ax_h.set_title(
        f"RMS height {rms:.3g} µm" + ("" if slope is None else f", RMS slope {slope:.3g}"),
        fontsize="medium",
    )
    if ax_c is not None:
        draw_psd(ax_c, profile, stats)
    if title:
        fig.suptitle(title)
    if path is not None:
        save_figure(fig, path)
    return fig
