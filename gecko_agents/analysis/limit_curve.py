"""The frictional-adhesion limit curve: adhesion against shear at release, and its critical angle.

Units: µN. Sign convention: adhesion > 0 when the floor is pulled (tension); shear > 0 in the
gripping sense (the tip dragged back along the seta's shaft).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["critical_angle"]


def critical_angle(shear, adhesion) -> float:
    """Critical angle α* [degrees] of the frictional-adhesion model, F⊥ ≤ F∥·tan α* (Autumn,
    Dittmore, Santos, Spenko & Cutkosky 2006, J Exp Biol 209:3569): the angle from the shear
    axis of the limit line through the origin fitted (least squares, through the origin) to the
    release forces held in tension with gripping shear (adhesion > 0 and shear > 0);
    tan α* = Σ(shear·adhesion)/Σ(shear²). NaN if no release qualifies.

    Parameters
    ----------
    shear, adhesion : release forces [µN], one per pull (same length).
    """
    s = np.asarray(shear, dtype=float)
    a = np.asarray(adhesion, dtype=float)
    held = (a > 0.0) & (s > 0.0)
    if not held.any():
        return math.nan
    slope = float(np.sum(s[held] * a[held]) / np.sum(s[held] * s[held]))
    return math.degrees(math.atan(slope))
