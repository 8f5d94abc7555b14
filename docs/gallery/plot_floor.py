"""
A self-affine floor and its spectrum
====================================

A rough floor drawn by :func:`gecko_agents.floor.self_affine` (Hurst exponent 0.8, RMS height
0.5 µm, roll-off between 2 and 50 µm), and its one-dimensional power spectrum with the fitted
power law, as :mod:`gecko_agents.render.floor_plots` draws them.
"""

import matplotlib.pyplot as plt
import numpy as np

from gecko_agents import floor
from gecko_agents.render.floor_plots import draw_profile, draw_psd

profile = floor.self_affine(
    0.0, 999.5, np.random.default_rng(1), hurst=0.8, rms_height=0.5, short_cutoff=2.0,
    long_cutoff=50.0,
)  # fmt: skip
fig, (ax_h, ax_c) = plt.subplots(1, 2, figsize=(9, 3.4), width_ratios=[1.6, 1.0])
draw_profile(ax_h, profile)
draw_psd(ax_c, profile)
stats = floor.statistics(profile)
ax_h.set_title(f"RMS height {stats['rms_height_um']:.3g} µm, Hurst {stats['hurst']:.2f}")
fig.tight_layout()
