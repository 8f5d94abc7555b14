"""A rigid spherical probe as the floor: the standard pull-off test of fibrillar adhesives.

In the test a sphere of radius R_p is pressed into the array and retracted. The model keeps its
frame: the array moves and the floor holds still, so the probe is the floor, its apex under the
middle of the array. The simulated row of setae lies in the plane through the probe's centre,
so each seta meets the probe's circle of radius R_p there. Heights in µm from the apex (0 at the
apex, negative away from it).
"""

from __future__ import annotations

import numpy as np

from gecko_agents.floor.profile import Profile, check_positive

__all__ = ["probe_profile", "probe_heights", "SAG_TOLERANCE_UM"]

SAG_TOLERANCE_UM = 1e-4
"""Gap between the polyline and the circle it stands for at the apex [µm]: a chord of length s
sags s²/(8R_p) below its arc there (s²/(8R_p·cos³α) where the probe slopes at α), so the
vertex spacing is √(8·R_p·tolerance) (0.28 µm for a 100 µm probe), far below any contact
overlap of interest (≈ 0.01–1 µm)."""


def probe_heights(x, probe_radius: float, centre: float = 0.0, beyond=None) -> np.ndarray:
    """Heights of the probe's circle below its apex, √(R_p² − (x − x_c)²) − R_p [µm]; beyond
    its equator (|x − x_c| > R_p) there is no probe: the height is ``beyond`` (default −R_p).

    Parameters
    ----------
    x : abscissae [µm]. probe_radius : R_p [µm]. centre : abscissa of the apex x_c [µm].
    beyond : height where there is no probe [µm]; a floor for the time-stepped model puts
        it out of every tip's reach (:func:`probe_profile`).
    """
    r = np.asarray(x, dtype=float) - centre
    inside = np.clip(probe_radius**2 - r * r, 0.0, None)
    h = np.sqrt(inside) - probe_radius
    if beyond is not None:
        h = np.where(np.abs(r) > probe_radius, beyond, h)
    return h


def probe_profile(
    probe_radius: float, x_start: float, x_end: float, centre: float, out_of_reach: float = 0.0
) -> Profile:
    """The probe's circle as a floor polyline from ``x_start`` to ``x_end`` [µm], vertex spacing
    √(8·R_p·:data:`SAG_TOLERANCE_UM`) (capped at R_p/50 so a small probe keeps its shape).
    Beyond the equator, where a tip finds no probe, the floor drops ``out_of_reach`` [µm]
    below the equator: a tip there touches nothing (a probe narrower than the array holds
    only the setae it meets).

    Parameters
    ----------
    probe_radius : R_p [µm], > 0. x_start, x_end : extent of the floor [µm]. centre : apex
        abscissa [µm]. out_of_reach : depth below the equator beyond it [µm], more than any
        tip reaches.
    """
    R = check_positive("Floor.probe_radius", probe_radius)
    spacing = min(np.sqrt(8.0 * R * SAG_TOLERANCE_UM), R / 50.0)
    n = max(int(np.ceil((x_end - x_start) / spacing)) + 1, 2)
    x = np.linspace(x_start, x_end, n)
    return Profile(
        x=x,
        y=probe_heights(x, R, centre, beyond=-R - out_of_reach),
        spacing=float(x[1] - x[0]),
        source=f"spherical probe, R_p = {R:g} µm",
    )
