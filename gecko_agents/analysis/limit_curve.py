"""The frictional-adhesion limit curve: adhesion against shear at release, and its critical angle.

Autumn, Dittmore, Santos, Spenko & Cutkosky (2006, J Exp Biol 209:3569) found that a gecko
seta, array or toe holds an adhesion F⊥ only with a shear F∥ in the gripping sense, up to the
limit line F⊥ ≤ F∥·tan α* through the origin ("frictional adhesion"); α*, the critical angle,
was ≈ 25–30°. Each pull gives one point of the curve: the forces at its release point
(:func:`gecko_agents.analysis.pull.release_point`).

Units: µN, degrees. Sign convention: adhesion > 0 when the floor is pulled (tension; the
history's ``force_normal_uN`` is negative there); shear > 0 in the gripping sense (the force
on the tips along +x, the direction the setae lean: the tip dragged back along the shaft).
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["critical_angle", "force_angle", "limit_adhesion"]


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


def limit_adhesion(shear, alpha_deg: float):
    """The largest adhesion [µN] the limit line allows at a shear [µN]: F∥·tan α*, 0 for a
    shear ≤ 0 (no adhesion without gripping shear; Autumn et al. 2006).

    Parameters
    ----------
    shear : shear force(s) [µN], > 0 gripping.
    alpha_deg : the critical angle α* [degrees] (:func:`critical_angle`).
    """
    return np.maximum(np.asarray(shear, dtype=float), 0.0) * math.tan(math.radians(alpha_deg))


def force_angle(adhesion: float, shear: float) -> float:
    """Angle [degrees] of one release force (shear, adhesion) from the gripping shear axis, in
    (−180°, 180°]: atan2(adhesion, shear).

    A gripping release in tension lies at 0°–90° (its own α*, were it alone on the limit line);
    > 90°: the force points over the tip. For a film under tension it is the film's peel
    angle φ (Kendall 1975, J Phys D 8:1449).
    """
    return math.degrees(math.atan2(adhesion, shear))
