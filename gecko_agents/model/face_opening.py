"""Buckling-induced detachment: a bonded flat face whose pillar bends it opens from its edge.

A flat face (:class:`gecko_agents.contact.FlatPunch`, :class:`gecko_agents.contact.MushroomTip`)
held by the elastica's clamp (:meth:`gecko_agents.physics.elastica.Elastica.face_moment`)
carries a moment M as well as its normal force P. By the tilted-punch criterion
(:func:`gecko_agents.physics.punch.edge_stress_intensity`: K_I = −(P − 3|M|/a)/(2a√(πa)) at
the edge the moment lifts, Griffith's K_I²/(2E*) = w there), the edge opens where
3|M|/a − P ≥ F_e, F_e the face's edge-mode pull-off (Kendall's for a punch or a flawed rim;
``inf`` for a mushroom rim that is not singular). On Sneddon's stiffness P = 2E*aδ that is
δ < −(F_e − 3|M|/a)/(2E*a): the face's detachment overlap moves with the moment, whether the
face is pulled or pressed (a buckled pillar's face can open under compression).

Once open, the face is taken to stay open (Kendall's instability) while the pillar's end,
pressed on the floor along the face's remaining part, still carries compression: the tip stays
in contact, pushed by Sneddon's P = 2E*aδ ≥ 0 and held by friction, but holds no tension and no
longer holds the face's direction (the elastica's clamp lets go, its energy booked as
dissipated). It lets go without a force jump where δ falls below 0, and a later approach bonds a
fresh face (hysteresis: the face does not re-bond while its tip stays on the floor). Round-edged
pillars pressed past buckling lose their adhesion this way, while pillars whose faces end in
thin flaps keep it until high preloads (Paretkar et al. 2013, J R Soc Interface 10:20130171,
abstract read); buckled pillars detach partly and show hysteresis (Stark, Begley & McMeeking
2013, J Appl Mech 80:041022, abstract read). The partial contact of the opened face (its
compressed part's stiffness and its tilt) is not modelled beyond that.
"""

from __future__ import annotations

import numpy as np

__all__ = ["FaceOpening"]


class FaceOpening:
    """Per-tip detachment overlaps from the face moments, and the opened faces (in contact,
    without adhesion) until their tip leaves the floor.

    Parameters
    ----------
    law : the flat-faced contact law (``edge_force`` [µN], ``pull_off_force`` [µN], ``a`` [µm],
        ``E_star`` [MPa], ``detach_overlap`` and ``attach_overlap`` [µm]). n : number of setae.
    """

    def __init__(self, law, n: int):
        self.law = law
        self.detach_at = np.full(n, float(law.detach_overlap))  # δ_detach of each tip [µm]
        self.opened = np.zeros(n, bool)  # faces open, still pressed on the floor
        self.count = 0  # faces opened by their moment over the run
        same = law.edge_force == law.pull_off_force
        self._base = law.detach_overlap if same else -law.edge_force / (2.0 * law.E_star * law.a)

    def update(self, moments) -> None:
        """The detachment overlaps of bonded faces carrying ``moments`` [µN·µm]:
        max(δ_detach, −(F_e − 3|M|/a)/(2E*a)) (the module docstring)."""
        law = self.law
        shift = 3.0 * np.abs(moments) / (2.0 * law.E_star * law.a * law.a)
        np.maximum(law.detach_overlap, self._base + shift, out=self.detach_at)

    def screen(self, idx, delta, attached):
        """The tips among ``idx`` that let go at overlaps ``delta``: an open face below δ = 0,
        a bonded one below its detachment overlap unless its moment opened it while it is
        still pressed (then it is marked open and stays)."""
        law = self.law
        opened = self.opened[idx] & attached
        below = attached & (delta < self.detach_at[idx])
        opens = below & ~opened & (delta >= law.attach_overlap)
        opened |= opens
        gone = np.where(opened, attached & (delta < law.attach_overlap), below)
        self.opened[idx] = opened & ~gone
        self.count += int(np.count_nonzero(opens))
        return gone
