"""Parameters of the flat-faced tips, and the checks that tie them to the rest of a parameter
set: :func:`check_tip_options`.

Units: µm, MPa (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math

__all__ = ["FLAT_FACE_TIPS", "check_tip_options"]

FLAT_FACE_TIPS = ("flat_punch",)
"""Tips whose face is flat and bonded: the ones an interface strength ``contact.sigma0`` acts on."""


def check_tip_options(p) -> None:
    """Refuse, naming the field, value and allowed range, options of a
    :class:`gecko_agents.params.SetaArray` that its tip does not model."""
    sigma0 = p.contact.sigma0
    if math.isfinite(sigma0) and p.tip not in FLAT_FACE_TIPS:
        raise ValueError(
            f"Contact.sigma0 = {sigma0!r} acts on a flat face (tip in {FLAT_FACE_TIPS}); "
            f"with tip = {p.tip!r} it must be inf"
        )
