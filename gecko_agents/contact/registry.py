"""Tip laws by name: :data:`TIP_LAWS`, :func:`contact_law` (the law of a parameter set) and
:func:`bounds` (what history invariants may assume of it)."""

from __future__ import annotations

import math

from gecko_agents.contact.base import ContactLaw
from gecko_agents.contact.flat_punch import FlatPunch
from gecko_agents.contact.hertz import HertzSphere
from gecko_agents.contact.jkr_sphere import JKRSphere
from gecko_agents.contact.mushroom import MushroomTip
from gecko_agents.contact.rate_jkr import RateJKRSphere
from gecko_agents.contact.sheared_jkr import ShearedJKRSphere
from gecko_agents.contact.spatula import SpatulaTip
from gecko_agents.contact.spatulae import SpatulaeTip

__all__ = ["TIP_LAWS", "bounds", "contact_law"]


TIP_LAWS: dict[str, type[ContactLaw]] = {
    "sphere": JKRSphere,
    "hertz": HertzSphere,
    "spatula": SpatulaTip,
    "flat_punch": FlatPunch,
    "mushroom": MushroomTip,
    "spatulae": SpatulaeTip,
}
"""Tip laws by the name ``params.tip`` selects."""


def bounds(law: ContactLaw) -> dict:
    """What :func:`gecko_agents.history.invariant_violations` may assume of a law's histories:
    the largest tension one tip holds [µN] (inf for a rate-dependent contact, whose crack lags),
    the overlap below which no tip stays attached [µm], whether the law is rate dependent and
    its energy balance's tolerance in units of ``history.ENERGY_RTOL``."""
    tension = math.inf if law.rate_dependent else law.pull_off_force
    if not math.isnan(law.max_tension):  # the law's own bound (a film holds many w·b)
        tension = law.max_tension
    return {
        "max_tension_uN": tension,
        "detach_overlap_um": law.detach_overlap,
        "rate_dependent": bool(law.rate_dependent),
        "energy_tolerance_factor": float(law.energy_tolerance_factor),
    }


def contact_law(params) -> ContactLaw:
    """The contact law of a :class:`gecko_agents.params.SetaArray`: ``params.tip``, with crack
    kinetics (:class:`RateJKRSphere`) for a sphere of finite ``contact.crack_speed`` and the
    Savkoor–Briggs coupling (:class:`ShearedJKRSphere`) for ``contact.shear_coupling``; the
    spatula, the branched seta's spatulae and the mushroom take their own parameter groups as
    well."""
    if params.tip == "sphere" and math.isfinite(getattr(params.contact, "crack_speed", math.inf)):
        return RateJKRSphere(params.contact)
    if params.tip == "sphere" and getattr(params.contact, "shear_coupling", "none") != "none":
        return ShearedJKRSphere(params.contact, params.friction)
    if params.tip == "spatula":
        return SpatulaTip(params.contact, params.spatula, params.friction)
    if params.tip == "spatulae":
        return SpatulaeTip(params.contact, params.spatula, params.spatulae, params.friction)
    if params.tip == "mushroom":
        return MushroomTip(params.contact, params.mushroom)
    return TIP_LAWS[params.tip](params.contact)
