"""Rough floors with Gaussian heights (paper eq 28), generated from an explicit RNG.

Heights are in µm, measured upward from the floor's mean plane. Two kinds:

* correlation length 0 — the paper's model: an independent height h_i ~ N(0, σ²) under every
  seta (a flat pad of one pitch width per seta);
* correlation length ℓ > 0 — a continuous 1-D profile whose heights are Gaussian with RMS σ and
  autocorrelation C(r) = σ²·exp(−r²/ℓ²) (white noise filtered with a Gaussian kernel of standard
  deviation ℓ/2: the self-convolution of that kernel has exactly this autocorrelation).

Two more floors are not from eq 28:

* :func:`self_affine` — a random self-affine (fractal) profile with Hurst exponent H between a
  short and a long wavelength cutoff, by spectral synthesis (Persson et al. 2005);
* :func:`from_profile` — a measured profile (arrays; files through
  :mod:`gecko_agents.floor.readers`), detrended, converted to µm and resampled to a uniform spacing.

:func:`for_array` is the one place the models turn ``params.Floor`` (or a measured profile)
into the floor under an array; :func:`statistics` summarises any profile (RMS height and slope,
PSD, Hurst estimate) for a run's metadata.

Either way the result is a polyline (``x``, ``y``) that the pymunk model turns into segments.

The PSD convention (SurfaceTopography's C¹ᴰ, q in rad/µm) is stated in
:mod:`gecko_agents.floor.spectral`, which holds :func:`self_affine`, :func:`psd` and
:func:`statistics`; :class:`Profile` lives in :mod:`gecko_agents.floor.profile`. All are
importable from here.
"""

from __future__ import annotations

import numpy as np

from gecko_agents.floor.probe import probe_profile
from gecko_agents.floor.profile import Profile, check_positive, check_rng
from gecko_agents.floor.spectral import (
    hurst_estimate,
    psd,
    self_affine,
    self_affine_psd,
    statistics,
)

__all__ = [
    "Profile",
    "seta_heights",
    "correlated_profile",
    "pad_profile",
    "make_profile",
    "self_affine",
    "self_affine_psd",
    "from_profile",
    "psd",
    "hurst_estimate",
    "statistics",
    "for_array",
    "probe_profile",
    "LENGTH_UNITS",
    "length_factor",
]


def seta_heights(n: int, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """Independent floor heights under n setae, h ~ N(0, σ²) (eq 28) [µm].

    Parameters
    ----------
    n : number of setae. sigma : RMS height [µm], ≥ 0. rng : the run's Generator.
    """
    if sigma < 0 or not np.isfinite(sigma):
        raise ValueError(f"sigma = {sigma!r} must be finite and ≥ 0 [µm]")
    return sigma * check_rng(rng).standard_normal(int(n))


def correlated_profile(
    sigma: float,
    correlation_length: float,
    x_start: float,
    x_end: float,
    rng: np.random.Generator,
    spacing: float | None = None,
) -> Profile:
    """Continuous Gaussian profile on [x_start, x_end] with RMS σ and correlation length ℓ.

    Parameters
    ----------
    sigma : RMS height [µm], ≥ 0.
    correlation_length : ℓ [µm], > 0; C(r) = σ² exp(−r²/ℓ²).
    x_start, x_end : extent [µm].
    rng : the run's Generator.
    spacing : vertex spacing [µm]; default ℓ/8 (the profile is then smooth between vertices).
    """
    if not correlation_length > 0:
        raise ValueError(f"correlation_length = {correlation_length!r} must be > 0 [µm] here")
    if not x_end > x_start:
        raise ValueError(f"x_end = {x_end!r} must exceed x_start = {x_start!r}")
    dx = correlation_length / 8.0 if spacing is None else float(spacing)
    n = int(np.ceil((x_end - x_start) / dx)) + 1
    x = x_start + dx * np.arange(n)
    s = 0.5 * correlation_length / dx  # kernel std in vertex units
    half = int(np.ceil(4.0 * s))
    k = np.exp(-0.5 * (np.arange(-half, half + 1) / s) ** 2)
    k /= np.sqrt(np.sum(k * k))  # unit variance after filtering
    noise = check_rng(rng).standard_normal(n + 2 * half)
    y = sigma * np.convolve(noise, k, mode="valid")
    return Profile(x=x, y=y)


def pad_profile(heights: np.ndarray, pitch: float, x_centres: np.ndarray, margin: float) -> Profile:
    """Pad floor: a flat pad of width ``pitch`` at height h_i centred under x_centres[i].

    The outermost pads are extended by ``margin`` [µm] so tips never run off the floor.
    Vertical steps join neighbouring pads.
    """
    h = np.asarray(heights, dtype=float)
    xc = np.asarray(x_centres, dtype=float)
    left = xc - 0.5 * pitch
    right = xc + 0.5 * pitch
    left[0] -= margin
    right[-1] += margin
    x = np.column_stack([left, right]).ravel()
    y = np.repeat(h, 2)
    return Profile(x=x, y=y, pad_heights=h)


def make_profile(
    sigma: float,
    correlation_length: float,
    n_setae: int,
    pitch: float,
    x_centres: np.ndarray,
    margin: float,
    rng: np.random.Generator,
) -> Profile:
    """The floor for an array: pads if ``correlation_length == 0``, else a continuous profile.

    Parameters
    ----------
    sigma : RMS height [µm]. correlation_length : [µm]. n_setae : N. pitch : [µm].
    x_centres : abscissae under which each seta touches down [µm], shape (N,).
    margin : extra floor beyond the outermost tips on each side [µm].
    rng : the run's Generator (the only source of randomness).
    """
    if correlation_length == 0:
        return pad_profile(seta_heights(n_setae, sigma, rng), pitch, x_centres, margin)
    x_centres = np.asarray(x_centres, dtype=float)
    return correlated_profile(
        sigma, correlation_length, x_centres.min() - margin, x_centres.max() + margin, rng
    )


# --- Measured profiles -----------------------------------------------------------------------

LENGTH_UNITS = {
    "m": 1e6,
    "meter": 1e6,
    "meters": 1e6,
    "metre": 1e6,
    "metres": 1e6,
    "mm": 1e3,
    "millimeter": 1e3,
    "millimeters": 1e3,
    "millimetre": 1e3,
    "millimetres": 1e3,
    "um": 1.0,
    "µm": 1.0,
    "μm": 1.0,
    "micrometer": 1.0,
    "micrometers": 1.0,
    "micrometre": 1.0,
    "micrometres": 1.0,
    "micron": 1.0,
    "microns": 1.0,
    "nm": 1e-3,
    "nanometer": 1e-3,
    "nanometers": 1e-3,
    "nanometre": 1e-3,
    "nanometres": 1e-3,
    "pm": 1e-6,
    "picometer": 1e-6,
    "picometers": 1e-6,
    "picometre": 1e-6,
    "picometres": 1e-6,
    "å": 1e-4,
    "angstrom": 1e-4,
    "angstroms": 1e-4,
}
"""Length units a profile may come in → micrometres per unit (keys lower case; 'µ' is the
micro sign U+00B5, 'μ' the Greek mu U+03BC)."""


def length_factor(unit: str, what: str = "unit") -> float:
    """Micrometres per ``unit`` (one of :data:`LENGTH_UNITS`, case-insensitive) [µm/unit]."""
    key = str(unit).strip().lower()
    if key not in LENGTH_UNITS:
        raise ValueError(
            f"{what} = {unit!r} is not a known length unit; use one of {sorted(set(LENGTH_UNITS))}"
        )
    return LENGTH_UNITS[key]


DETRENDS = ("linear", "mean", "none")


MAX_HEIGHT_RANGE = 1e4
"""Largest peak-to-valley height [µm] of a measured floor after detrending: 10 mm, three
orders above the setae's length; a profile beyond it is almost always read in the wrong unit."""


def _check_height_span(h: np.ndarray, where: str, unit: str) -> None:
    """Refuse detrended heights h [µm] spanning more than :data:`MAX_HEIGHT_RANGE`."""
    span = float(h.max() - h.min())
    if span > MAX_HEIGHT_RANGE:
        raise ValueError(
            f"the detrended heights span {span:.3g} µm{where}, outside the allowed range "
            f"[0, {MAX_HEIGHT_RANGE:g}] µm for a floor under setae tens of µm long: check "
            f"height_unit (read as {unit!r})"
        )


def from_profile(
    x,
    h,
    *,
    unit: str = "um",
    height_unit: str | None = None,
    spacing: float | None = None,
    detrend: str = "linear",
    x_range: tuple[float, float] | None = None,
    source: str = "",
) -> Profile:
    """A floor from a measured line profile: units → µm, detrended, resampled uniformly.

    Steps: convert x with ``unit`` and h with ``height_unit`` (default ``unit``) to µm; keep
    ``x_range`` (in µm, after conversion) if given; remove the mean or the least-squares line
    (a tilted sample or stage); resample linearly (``numpy.interp``) onto x0 + Δx·k, the
    profile read as piecewise linear between its points (as SurfaceTopography reads
    non-uniform line scans). The floor's x then runs from 0 at the first point.

    Parameters
    ----------
    x : positions along the scan [``unit``], strictly increasing, ≥ 2 points.
    h : heights [``height_unit``], same length, finite.
    unit : length unit of x (and of h unless ``height_unit``); one of :data:`LENGTH_UNITS`.
    height_unit : length unit of h, default ``unit``.
    spacing : resampling spacing Δx [µm], > 0; default the mean spacing of the data.
    detrend : ``"linear"`` (default), ``"mean"`` or ``"none"``.
    x_range : (start, end) part of the scan to keep [µm]; default all of it.
    source : a name for error messages and metadata (e.g. the file).
    """
    where = f" ({source})" if source else ""
    fx = length_factor(unit, "unit")
    fh = fx if height_unit is None else length_factor(height_unit, "height_unit")
    x = np.asarray(x, dtype=float).ravel() * fx
    h = np.asarray(h, dtype=float).ravel() * fh
    if x.shape != h.shape:
        raise ValueError(f"x has {x.size} points but h has {h.size}{where}")
    if x.size < 2:
        raise ValueError(f"a profile needs at least 2 points, got {x.size}{where}")
    for name, arr in (("x", x), ("h", h)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise ValueError(
                f"{name} has {bad.size} NaN or infinite values (first at index "
                f"{bad[0]}){where}: fill or cut the gaps before use"
            )
    steps = np.diff(x)
    if np.any(steps <= 0):
        i = int(np.flatnonzero(steps <= 0)[0])
        raise ValueError(
            f"x must be strictly increasing: x[{i}] = {x[i]!r} µm, x[{i + 1}] = "
            f"{x[i + 1]!r} µm{where}"
        )
    if x_range is not None:
        lo, hi = (float(v) for v in x_range)
        if not (x[0] <= lo < hi <= x[-1]):
            raise ValueError(
                f"x_range = {x_range!r} µm must lie within the scan [{x[0]!r}, {x[-1]!r}] µm{where}"
            )
        keep = (x >= lo) & (x <= hi)
        if keep.sum() < 2:
            raise ValueError(f"x_range = {x_range!r} µm holds fewer than 2 points{where}")
        x, h = x[keep], h[keep]
    if detrend not in DETRENDS:
        raise ValueError(f"detrend = {detrend!r} must be one of {DETRENDS}")
    if detrend == "linear":
        h = h - np.polyval(np.polyfit(x - x[0], h, 1), x - x[0])
    elif detrend == "mean":
        h = h - h.mean()
    _check_height_span(h, where, height_unit or unit)
    length = x[-1] - x[0]
    dx = length / (x.size - 1) if spacing is None else check_positive("spacing", spacing)
    n = int(np.floor(length / dx + 1e-9)) + 1
    if n < 2:
        raise ValueError(f"spacing = {dx!r} µm exceeds the scan length {length!r} µm{where}")
    xs = dx * np.arange(n)
    return Profile(x=xs, y=np.interp(x[0] + xs, x, h), spacing=dx, source=source)


# --- The floor under an array ----------------------------------------------------------------


def place(profile: Profile, x_start: float, x_end: float) -> Profile:
    """The part of a uniformly sampled ``profile`` that covers [x_start, x_end] [µm], moved so
    that its first point sits at x_start: vertices x_start + Δx·k, k = 0 … ⌈(x_end −
    x_start)/Δx⌉ (the grid :func:`correlated_profile` uses), heights y[k] of the profile.
    A profile too short for the extent is refused."""
    if profile.spacing is None:
        raise ValueError(
            "a measured floor must be uniformly sampled: build it with "
            "floor.from_profile or gecko_agents.floor.readers"
        )
    dx = float(profile.spacing)
    n = int(np.ceil((x_end - x_start) / dx)) + 1
    have = np.asarray(profile.y).size
    if have < n:
        where = f" ({profile.source})" if profile.source else ""
        raise ValueError(
            f"the profile{where} is {(have - 1) * dx:.6g} µm long but the array "
            f"with its margins needs {x_end - x_start:.6g} µm: use a longer "
            "scan or fewer setae"
        )
    return Profile(
        x=x_start + dx * np.arange(n),
        y=np.asarray(profile.y, float)[:n],
        spacing=dx,
        source=profile.source,
    )


def for_array(
    floor_params,
    x_centres: np.ndarray,
    pitch: float,
    margin: float,
    rng: np.random.Generator,
    measured: Profile | None = None,
) -> Profile:
    """The floor under an array: the one place the models turn floor parameters into a profile.

    ``measured`` (a profile object, e.g. from :func:`from_profile` or
    :mod:`gecko_agents.floor.readers`) wins: its start is put under the left edge of the floor,
    x_centres.min() − margin (``place``), and it must reach x_centres.max() + margin.
    Otherwise ``floor_params.kind`` chooses: ``"gaussian"`` → :func:`make_profile` (eq 28; the
    floor every earlier run used, drawn identically), ``"self_affine"`` → :func:`self_affine`
    with RMS height ``sigma`` (or ``rms_slope``), ``hurst``, ``short_cutoff``,
    ``long_cutoff``, ``"probe"`` → :func:`~gecko_agents.floor.probe.probe_profile`, a
    spherical probe of radius ``probe_radius`` with its apex under the middle of the array.

    Parameters
    ----------
    floor_params : :class:`gecko_agents.params.Floor`.
    x_centres : abscissae under which each seta touches down [µm], shape (N,).
    pitch : root spacing [µm]. margin : extra floor beyond the outermost tips [µm].
    rng : the run's Generator (the only source of randomness; a measured floor draws none).
    measured : a given profile (e.g. a measured surface) used instead of generating one.
    """
    x_centres = np.asarray(x_centres, dtype=float)
    x_start, x_end = x_centres.min() - margin, x_centres.max() + margin
    if measured is not None:
        if not isinstance(measured, Profile):
            raise TypeError(f"measured must be a floor.Profile, got {type(measured).__name__}")
        return place(measured, x_start, x_end)
    kind = getattr(floor_params, "kind", "gaussian")
    if kind == "self_affine":
        fp = floor_params
        size = {"rms_slope": fp.rms_slope} if fp.rms_slope is not None else {"rms_height": fp.sigma}
        return self_affine(
            x_start,
            x_end,
            rng,
            hurst=fp.hurst,
            short_cutoff=fp.short_cutoff,
            long_cutoff=fp.long_cutoff,
            **size,
        )
    if kind == "probe":
        centre = 0.5 * (x_centres.min() + x_centres.max())
        return probe_profile(floor_params.probe_radius, x_start, x_end, centre, margin)
    if kind != "gaussian":
        raise ValueError(f"Floor.kind = {kind!r} must be 'gaussian', 'self_affine' or 'probe'")
    return make_profile(
        floor_params.sigma,
        floor_params.correlation_length,
        x_centres.size,
        pitch,
        x_centres,
        margin,
        rng,
    )
