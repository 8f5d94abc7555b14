"""The floor polyline, :class:`Profile`, and the argument checks every floor generator shares.

The bottom of the floor modules: :mod:`gecko_agents.floor.spectral` (self-affine synthesis,
PSD and statistics) and :mod:`gecko_agents.floor` (eq 28 floors, measured profiles, the floor
under an array) build on it; import :class:`Profile` from :mod:`gecko_agents.floor`.
Heights and positions in µm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Profile", "check_rng", "check_positive"]


@dataclass(frozen=True)
class Profile:
    """A floor polyline.

    Attributes
    ----------
    x : vertex abscissae [µm], shape (M,), increasing.
    y : vertex heights [µm], shape (M,).
    pad_heights : for a pad floor (correlation length 0), the height under each seta [µm],
        shape (N,); ``None`` for a continuous profile.
    spacing : uniform vertex spacing [µm] of a profile sampled on x[0] + spacing·k (generated
        and measured profiles); ``None`` if not uniform (pad floors).
    source : where the heights came from (file name, or a short description).
    """

    x: np.ndarray
    y: np.ndarray
    pad_heights: np.ndarray | None = None
    spacing: float | None = None
    source: str = ""

    def height_at(self, x) -> np.ndarray:
        """Floor height at abscissa(e) x [µm] (linear between vertices) [µm]."""
        return np.interp(x, self.x, self.y)


def check_rng(rng) -> np.random.Generator:
    """``rng`` itself if it is a numpy Generator (the only source of randomness), else TypeError."""
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator, got {type(rng).__name__}")
    return rng


def check_positive(name: str, value, lo: float = 0.0) -> float:
    """``value`` as a float if it is a finite real number > ``lo``, else ValueError naming it."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float | np.floating | np.integer)
        or not np.isfinite(value)
        or value <= lo
    ):
        raise ValueError(f"{name} = {value!r} must be a finite number > {lo}")
    return float(value)
