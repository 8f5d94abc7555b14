"""The mushroom (flanged) tip of a pillar: :class:`MushroomTip`."""

from __future__ import annotations

import math

from gecko_agents.contact.flat_punch import FlatPunch
from gecko_agents.physics import mushroom

__all__ = ["MushroomTip"]


class MushroomTip(FlatPunch):
    """A stalk of radius ``seta.r`` ending in a thin flange of radius a_t = ``contact.R`` whose
    face stays parallel to the floor: the flat punch of the flange (Sneddon's stiffness
    P = 2E*a_tδ while bonded, in series with the stalk's springs: the flange's compliance adds
    to the stalk's), letting go at the smaller of its two modes'
    tensions (:func:`gecko_agents.physics.mushroom.pull_offs`): from the rim (Kendall's edge
    crack with a cohesive zone for a flawed rim, Tang's form with the rim's singularity for a
    sharp one) or from the centre (Griffith's penny crack from a defect of radius
    ``mushroom.defect_radius``, bounded by ``contact.sigma0``). Aksak, Şahin & Sitti 2014,
    Beilstein J Nanotechnol 5:630.

    :attr:`release_mode` names the mode (``"edge"`` or ``"centre"``), recorded with each
    detachment in the history. With a flawed rim, no defect and any σ₀, the tip is the flat
    punch of radius a_t exactly (a flange as wide as its stalk: the pillar's flat end).

    Parameters
    ----------
    contact : :class:`gecko_agents.params.Contact` (R = flange radius [µm], moduli [MPa],
        w [µN/µm], sigma0 [MPa]). shape : :class:`gecko_agents.params.tips.Mushroom`.
    """

    name = "mushroom"
    label = "tip = 'mushroom'"

    def __init__(self, contact, shape):
        super().__init__(contact)
        modes = mushroom.pull_offs(
            self.a,
            shape.defect_radius,
            self.w,
            self.E_star,
            self.sigma0,
            shape.rim,
            shape.rim_angle_deg,
            contact.nu1,
        )
        self.mode_forces = modes
        self.release_mode = min(modes, key=modes.get)
        force = modes[self.release_mode]
        if not math.isfinite(force):  # refused by the parameters; kept as a guard
            raise ValueError(f"{self.label}: no mode lets go ({modes})")
        self.set_pull_off(force)
        self.edge_force = modes["edge"]  # inf where the rim is not singular: no edge opening
