"""
The JKR tip: force against overlap
==================================

The tip law of the paper's seta (Table 1: R = 4 µm, E* = 1.55 MPa, w = 0.165 J/m²) as the
plain functions of :mod:`gecko_agents.physics.jkr` give it: the force P against the overlap δ
along the contact radius a, with the pull-off force Fc = 3πwR/2 (load control) and the
snap-off overlap δc (displacement control) marked.
"""

import matplotlib.pyplot as plt
import numpy as np

from gecko_agents.params import PAPER_TABLE1
from gecko_agents.physics import jkr

R, w, E = PAPER_TABLE1.contact.jkr_args()
a0 = float(jkr.zero_load_contact_radius(R, w, E))
a = np.linspace(0.05 * a0, 1.6 * a0, 400)
P = jkr.force_from_radius(a, R, w, E)
delta = jkr.overlap_from_radius(a, R, w, E)

fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(delta, P, label="JKR (stable and unstable branches)")
Fc = PAPER_TABLE1.contact.pull_off_force
dc = PAPER_TABLE1.contact.snap_off_overlap
ax.axhline(-Fc, color="grey", linestyle=":", label=f"−Fc = −{Fc:.2f} µN")
ax.axvline(dc, color="grey", linestyle="--", label=f"δc = {dc:.3f} µm")
ax.set(xlabel="overlap δ [µm]", ylabel="normal force P [µN] (> 0 compressive)")
ax.legend(frameon=False)
