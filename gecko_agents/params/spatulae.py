"""Parameters of the branched seta (``tip = "spatulae"``): :class:`Spatulae`, and
:func:`check_spatulae`, the check that ties the group to the tip.

Units: µm, MPa (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gecko_agents.params.checks import LENGTH_RANGE, check

__all__ = ["SPATULAE_MAX", "Spatulae", "check_spatulae"]

SPATULAE_MAX = 100_000
"""Most spatulae one seta may carry: a tokay seta has 100–1000 (see :class:`Spatulae`)."""


@dataclass(frozen=True)
class Spatulae:
    """The branched end of a seta (``tip = "spatulae"``,
    :class:`gecko_agents.contact.spatulae.SpatulaeTip`): the shaft (``seta``) splits into
    ``count`` branches, each ending in one spatula film of the ``spatula`` group (width b,
    thickness h, modulus E_f, pad length ℓ0) that peels by the package's film law. A tokay
    seta "branches into hundreds of 200-nm spatulae" (Hansen & Autumn 2005, PNAS 102:385,
    abstract, https://pmc.ncbi.nlm.nih.gov/articles/PMC544316).

    The branches share the load equally and are rigid in the time-stepped law: what a branch's
    axial stiffness is next to the shaft's is :meth:`branch_stiffness` (the study reports the
    ratio: N·k_b over the shaft's stiffness).

    Attributes
    ----------
    count : number N of spatulae (and branches) on the seta [-], an integer in
        [1, 100 000]; default 1 (one film: the ``"spatula"`` tip).
    branch_length : length of one branch from the shaft's end to its spatula [µm]; default
        20.0 µm (an assumption: the branches are "hundreds" of fibres at the seta's end; no
        text we read gives their length).
    branch_radius : radius of one branch [µm]; default 0.1 µm (an assumption: as wide as its
        200 nm spatula).
    """

    count: int = 1
    branch_length: float = 20.0
    branch_radius: float = 0.1

    def __post_init__(self):
        check(self, "count", 1, SPATULAE_MAX, lo_open=False, hi_open=False, integer=True)
        check(self, "branch_length", *LENGTH_RANGE)
        check(self, "branch_radius", *LENGTH_RANGE)

    def branch_stiffness(self, E: float) -> float:
        """Axial stiffness of one branch, a bar E·π r_b²/L_b [µN/µm], for the branch's
        modulus E [MPa] (the seta's keratin, ``contact.E1``)."""
        return E * math.pi * self.branch_radius**2 / self.branch_length


def check_spatulae(p) -> None:
    """Refuse a :class:`Spatulae` group away from its default on a parameter set whose tip
    is not ``"spatulae"`` (it would be silently ignored), naming the field and value."""
    if p.tip == "spatulae" or p.spatulae == Spatulae():
        return
    for name in ("count", "branch_length", "branch_radius"):
        value = getattr(p.spatulae, name)
        if value != getattr(Spatulae(), name):
            raise ValueError(
                f"Spatulae.{name} = {value!r} acts on tip = 'spatulae' only; with "
                f"tip = {p.tip!r} leave the spatulae group at its defaults"
            )
