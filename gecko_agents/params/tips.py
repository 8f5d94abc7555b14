"""Parameters of the flat-faced tips: :class:`Mushroom`, and :func:`check_tip_options`, the
checks that tie a tip to the rest of a parameter set.

Units: µm, MPa, degrees (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from gecko_agents.params.checks import LENGTH_RANGE, check

__all__ = ["FLAT_FACE_TIPS", "MUSHROOM_RIMS", "Mushroom", "check_tip_options"]

FLAT_FACE_TIPS = ("flat_punch", "mushroom")
"""Tips whose face is flat and bonded: the ones an interface strength ``contact.sigma0`` acts on."""
MUSHROOM_RIMS = ("flawed", "sharp")


@dataclass(frozen=True)
class Mushroom:
    """The flange of a mushroom tip (``tip = "mushroom"``,
    :class:`gecko_agents.contact.mushroom.MushroomTip`): its radius is ``contact.R``, its
    stalk's ``seta.r`` (a flange as wide as its stalk is the flat punch), the interface's
    strength ``contact.sigma0`` (Aksak, Şahin & Sitti 2014, Beilstein J Nanotechnol 5:630).

    Attributes
    ----------
    rim : how the flange's rim meets the floor. ``"flawed"`` (default): a step or rounding at
        the rim restores an edge crack (Kendall's with a cohesive zone at σ₀: the flat punch's
        law).
        ``"sharp"``: an intact corner of edge angle ``rim_angle_deg`` bonded to the floor,
        singular or not by the wedge's eigenproblem (:mod:`gecko_agents.physics.wedge`);
        needs a finite ``contact.sigma0``.
    rim_angle_deg : edge angle θ of a sharp rim between the floor and the flange's free face
        [degrees], in (0, 135]; default 90 (a square rim). At ν = 0.5 a rim of θ ≤ 45° is not
        singular and detachment starts at the centre.
    defect_radius : radius c of a central interface defect [µm], ≥ 0 and below the flange
        radius; 0 (default) is none (the centre then lets go uniformly at σ₀).
    """

    rim: str = "flawed"
    rim_angle_deg: float = 90.0
    defect_radius: float = 0.0

    def __post_init__(self):
        if self.rim not in MUSHROOM_RIMS:
            raise ValueError(f"Mushroom.rim = {self.rim!r} must be one of {MUSHROOM_RIMS}")
        check(self, "rim_angle_deg", 0.0, 135.0, hi_open=False)
        check(self, "defect_radius", 0.0, LENGTH_RANGE[1], lo_open=False)


def check_tip_options(p) -> None:
    """Refuse, naming the field, value and allowed range, options of a
    :class:`gecko_agents.params.SetaArray` that its tip does not model."""
    sigma0 = p.contact.sigma0
    if math.isfinite(sigma0) and p.tip not in FLAT_FACE_TIPS:
        raise ValueError(
            f"Contact.sigma0 = {sigma0!r} acts on a flat face (tip in {FLAT_FACE_TIPS}); "
            f"with tip = {p.tip!r} it must be inf"
        )
    if p.contact.edge_opening and (p.tip not in FLAT_FACE_TIPS or p.mechanics != "elastica"):
        raise ValueError(
            f"Contact.edge_opening = True needs a flat face on an elastica pillar (tip in "
            f"{FLAT_FACE_TIPS}, mechanics = 'elastica'); got tip = {p.tip!r}, "
            f"mechanics = {p.mechanics!r}"
        )
    if p.tip == "mushroom":
        _check_mushroom(p.contact, p.seta, p.mushroom)
    if p.tip in FLAT_FACE_TIPS:
        _check_faces_fit(p)


def _check_faces_fit(p) -> None:
    """A face wider than its stalk (a mushroom's flange, a punch with R > r) fits the pitch:
    neighbouring faces of radius R on roots ``array.pitch`` apart overlap past R = pitch/2,
    an array no floor can hold (each face would carry σ₀ over area it shares)."""
    R, r, pitch = p.contact.R, p.seta.r, p.array.pitch
    if p.array.count > 1 and R > r and 2.0 * R > pitch:
        raise ValueError(
            f"Contact.R = {R!r} (the {p.tip} face's radius, wider than its stalk Seta.r = "
            f"{r!r}) is outside the allowed range [0, Array.pitch/2 = {pitch / 2.0!r}] of an "
            f"array of {p.array.count} at Array.pitch = {pitch!r}: neighbouring faces would "
            "overlap"
        )


def _check_mushroom(contact, seta, shape: Mushroom) -> None:
    if contact.R < seta.r:
        raise ValueError(
            f"Contact.R = {contact.R!r} (the mushroom's flange radius) is outside the allowed "
            f"range [Seta.r = {seta.r!r} (its stalk radius), inf): a flange is not smaller "
            "than its stalk"
        )
    if shape.defect_radius >= contact.R:
        raise ValueError(
            f"Mushroom.defect_radius = {shape.defect_radius!r} is outside the allowed range "
            f"[0, Contact.R = {contact.R!r}) (a defect inside the flange)"
        )
    if shape.rim == "sharp" and math.isinf(contact.sigma0):
        raise ValueError(
            "Mushroom.rim = 'sharp' needs a finite Contact.sigma0 (an intact bonded corner "
            "lets go at the interface's strength): Contact.sigma0 = inf is outside the "
            "allowed range (0, inf)"
        )
