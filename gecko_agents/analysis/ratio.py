"""The gripping/releasing ratio: how much more a seta holds after a drag back along its shaft.

Autumn et al. (2000, Nature 405:681) found a seta's adhesion large only after a preload and a
drag in the gripping direction (−x here, the tip pulled back along the shaft), and small after
a drag in the releasing one (+x, the seta pushed over its tip). The ratio of the two pull-offs
(:func:`gecko_agents.analysis.pull.pull_off`) at the same pull angle measures that anisotropy.

Units: the two pull-offs in µN (≥ 0, tension positive); the ratio is dimensionless.
"""

from __future__ import annotations

import math

__all__ = ["gripping_over_releasing"]


def gripping_over_releasing(gripping: float, releasing: float) -> float:
    """Gripping over releasing pull-off [-]; NaN if the releasing pull held no tension
    (``releasing`` ≤ 0 or NaN), where the ratio is undefined.

    Parameters
    ----------
    gripping, releasing : pull-off forces [µN] after a drag along −x and along +x.
    """
    return gripping / releasing if releasing > 0 else math.nan
