"""Probes over a pad as the experiments had them: a flat, a flat tilted by the misalignment, or
a sphere of any radius (micrometres to centimetres), on a floor that is smooth, randomly rough
or a measured 2-D map. Heights h ≤ 0 [µm] of the probe's surface over the fibres' tips of a
:class:`~gecko_agents.physics.layer_field.LayerField`, 0 where it touches first, for
:func:`gecko_agents.physics.pad_field.press_pull_pad`.

The probe's shape is :func:`gecko_agents.physics.layer_field.probe_heights` (one home); a
floor's heights z [µm] (up, towards the fibres, mean 0) add to it: h = h_probe + z, shifted
so that max h = 0. A rough floor is a self-affine random surface over the pad, periodic on it
(SurfaceTopography's ``fourier_synthesis``: Fourier-filtered noise, Jacobs, Junge & Pastewka
2017, Surf Topogr Metrol Prop 5:013001); a measured map is read by
:func:`gecko_agents.floor.readers.read_map`, its mean plane removed, and sampled at the
fibres by bilinear interpolation, repeated past its edges (a periodic continuation: the
wavelengths longer than the map are missing).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.ndimage import map_coordinates

from gecko_agents.physics.layer_field import LayerField, probe_heights

__all__ = ["map_floor", "pad_heights", "rough_floor"]


def rough_floor(
    field: LayerField, rms_height: float, hurst: float = 0.8, seed: int = 1
) -> np.ndarray:
    """A self-affine random floor z [µm] (n, n) at the fibres, of RMS height ``rms_height``
    [µm] (> 0, the sample scaled to it exactly) and Hurst exponent ``hurst`` (in (0, 1]),
    wavelengths from the pad's width down to two pitches; one ``numpy.random.Generator`` from
    ``seed``."""
    from SurfaceTopography.Generation import fourier_synthesis

    if not (math.isfinite(rms_height) and rms_height > 0):
        raise ValueError(f"rms_height = {rms_height!r} µm must be in (0, inf)")
    if not 0.0 < hurst <= 1.0:
        raise ValueError(f"hurst = {hurst!r} must be in (0, 1]")
    n, s = field.n, field.pitch
    topo = fourier_synthesis(
        (n, n), (n * s, n * s), hurst, rms_height=rms_height, rng=np.random.default_rng(seed)
    )
    z = np.asarray(topo.heights(), float)
    z = z - z.mean()
    return z * (rms_height / z.std())


def map_floor(field: LayerField, path=None, channel: int | None = None) -> np.ndarray:
    """A measured 2-D map as the floor z [µm] (n, n) at the fibres: read by
    :func:`gecko_agents.floor.readers.read_map` (default: the AFM map shipped in
    ``gecko_agents/data/surfaces``), its least-squares plane removed, sampled bilinearly at
    the fibres' positions from the map's corner, repeated past its edges. A map narrower than
    a pitch (the shipped one is 0.6 µm wide) is seen at each fibre's position modulo its width:
    a few of its points, uncorrelated from fibre to fibre."""
    from gecko_agents.data import WSXM_AFM
    from gecko_agents.floor.readers import read_map

    x, y, z = read_map(WSXM_AFM if path is None else path, channel=channel)
    if not np.all(np.isfinite(z)):
        raise ValueError(f"the map {path!s} has missing points; fill them first")
    X, Y = np.meshgrid(x - x.mean(), y - y.mean(), indexing="ij")
    A = np.column_stack([np.ones(z.size), X.ravel(), Y.ravel()])
    z = z - (A @ np.linalg.lstsq(A, z.ravel(), rcond=None)[0]).reshape(z.shape)
    px, py = field.positions()
    ix, iy = (px - px.min()) / (x[1] - x[0]), (py - py.min()) / (y[1] - y[0])
    return map_coordinates(z, [ix, iy], order=1, mode="grid-wrap")


def pad_heights(
    field: LayerField, probe_radius: float = math.inf, tilt_deg: float = 0.0, floor=None
) -> np.ndarray:
    """Heights h ≤ 0 [µm] (n, n) of the probe over the fibres' tips: the probe of
    :func:`~gecko_agents.physics.layer_field.probe_heights` (radius R_p [µm], inf for a flat;
    a flat tilted by ``tilt_deg``) on the floor ``floor`` (z [µm] (n, n), e.g.
    :func:`rough_floor` or :func:`map_floor`; None: smooth), 0 where it touches first."""
    h = probe_heights(field, probe_radius, tilt_deg)
    if floor is not None:
        z = np.asarray(floor, float)
        if z.shape != h.shape or not np.all(np.isfinite(z)):
            raise ValueError(f"floor must be a finite {h.shape} array, got {z.shape}")
        h = h + z
    return h - h.max()
