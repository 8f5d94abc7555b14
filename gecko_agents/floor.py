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
* :func:`from_profile` — a measured profile (arrays; files through :mod:`gecko_agents.profiles`),
  detrended, converted to µm and resampled to a uniform spacing.

:func:`for_array` is the one place the models turn ``params.Floor`` (or a measured profile)
into the floor under an array; :func:`statistics` summarises any profile (RMS height and slope,
PSD, Hurst estimate) for a run's metadata.

Either way the result is a polyline (``x``, ``y``) that the pymunk model turns into segments.

PSD convention
--------------
The one-dimensional power spectral density of a profile h(x) of length L is, as in
SurfaceTopography (``power_spectrum_from_profile``) and Jacobs, Junge & Pastewka (2017, Surf
Topogr Metrol Prop 5:013001, doi:10.1088/2051-672X/aa51f8, their definition of the 1-D PSD)

    C¹ᴰ(q) = |h̃(q)|² / L,   h̃(q) = ∫ h(x) e^(−iqx) dx   [µm³],

so that ⟨h²⟩ = (1/2π) ∫₋∞^∞ C¹ᴰ dq = (1/π) ∫₀^∞ C¹ᴰ dq. Persson's convention (Persson et al.
2005, J Phys Condens Matter 17:R1, doi:10.1088/0953-8984/17/1/R01) puts 1/(2π)ᵈ in front of
the transform of the autocorrelation, so that ⟨h²⟩ = ∫ C dᵈq: his C is this C¹ᴰ/(2π) for a
line scan and the areal C²ᴰ/(2π)² for a map (the (2π)² usually quoted between the two).
Every PSD in gecko_agents is C¹ᴰ in the SurfaceTopography convention, q in rad/µm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

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
    "statistics",
    "for_array",
    "LENGTH_UNITS",
    "length_factor",
]


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


def _check_rng(rng) -> np.random.Generator:
    if not isinstance(rng, np.random.Generator):
        raise TypeError(f"rng must be a numpy.random.Generator, got {type(rng).__name__}")
    return rng


def seta_heights(n: int, sigma: float, rng: np.random.Generator) -> np.ndarray:
    """Independent floor heights under n setae, h ~ N(0, σ²) (eq 28) [µm].

    Parameters
    ----------
    n : number of setae. sigma : RMS height [µm], ≥ 0. rng : the run's Generator.
    """
    if sigma < 0 or not np.isfinite(sigma):
        raise ValueError(f"sigma = {sigma!r} must be finite and ≥ 0 [µm]")
    return sigma * _check_rng(rng).standard_normal(int(n))


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
    noise = _check_rng(rng).standard_normal(n + 2 * half)
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


# --- Self-affine profiles --------------------------------------------------------------------


def self_affine_psd(
    q, hurst: float, c0: float, short_cutoff: float, long_cutoff: float, rolloff: float = 1.0
) -> np.ndarray:
    """The self-affine 1-D PSD with cutoffs, C¹ᴰ(q) [µm³] (module docstring for the convention).

    C(q) = C0·q^−(1+2H) for q_L ≤ q ≤ q_s; rolloff²·C0·q_L^−(1+2H) for 0 < q < q_L (the
    roll-off region of Persson et al. 2005; flat for rolloff = 1); 0 above q_s and at q = 0;
    q_s = 2π/λs, q_L = 2π/λL. The areal PSD of a self-affine surface falls as q^−(2+2H); a
    line scan of it as q^−(1+2H) (Jacobs, Junge & Pastewka 2017).

    Parameters
    ----------
    q : wavevector(s) [rad/µm], ≥ 0.
    hurst : H [-], in (0, 1). c0 : prefactor C0 [µm^(2−2H), so that C is in µm³].
    short_cutoff : λs [µm]. long_cutoff : λL [µm] > λs. rolloff : [-], ≥ 0.
    """
    q = np.abs(np.asarray(q, dtype=float))
    q_s, q_L = 2 * np.pi / short_cutoff, 2 * np.pi / long_cutoff
    with np.errstate(divide="ignore"):
        c = c0 * np.where(q < q_L, rolloff**2 * q_L ** (-1 - 2 * hurst), q ** (-1 - 2 * hurst))
    return np.where((q > q_s) | (q == 0), 0.0, c)


def _check_positive(name: str, value, lo: float = 0.0) -> float:
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float | np.floating | np.integer)
        or not np.isfinite(value)
        or value <= lo
    ):
        raise ValueError(f"{name} = {value!r} must be a finite number > {lo}")
    return float(value)


def self_affine(
    x_start: float,
    x_end: float,
    rng: np.random.Generator,
    *,
    hurst: float,
    rms_height: float | None = None,
    rms_slope: float | None = None,
    short_cutoff: float,
    long_cutoff: float,
    rolloff: float = 1.0,
    spacing: float | None = None,
) -> Profile:
    """Random self-affine profile on [x_start, x_end] by spectral (Fourier) synthesis.

    A periodic box of N = L/Δx points and length L ≥ max(x_end − x_start, 8·λL) gets random
    Fourier coefficients h̃_k = √(L·C(q_k)/2)·(a + ib), a, b ~ N(0, 1) (real with variance
    L·C at the Nyquist wavevector), q_k = 2πk/L, with C = :func:`self_affine_psd`; the heights
    are h_j = (1/L)·Σ_k h̃_k e^(i q_k x_j) (an inverse real FFT). The expectation of the PSD of
    the box is then exactly C(q_k) in the SurfaceTopography convention (module docstring), and
    the profile is the box's first points from x_start. This is the usual random Fourier
    synthesis of self-affine surfaces (as in SurfaceTopography's ``fourier_synthesis``, used
    for the computer-generated surfaces of Jacobs, Junge & Pastewka 2017), written here with
    the run's Generator and Gaussian complex amplitudes.

    C0 is chosen so that the **expected** mean square of the heights (or of the polyline's
    slopes) over the box equals the request: ⟨h²⟩ = (1/L)·Σ_k C(q_k) over all k ≠ 0, and for
    the slope ⟨((h_{j+1} − h_j)/Δx)²⟩ = (1/L)·Σ_k C(q_k)·(2 sin(q_k Δx/2)/Δx)², the slope of
    the polyline the model sees. Any one window is a sample: its RMS scatters about the request,
    the more so the closer λL is to the window length.

    Parameters
    ----------
    x_start, x_end : extent [µm], x_end > x_start.
    rng : the run's Generator (the only source of randomness).
    hurst : Hurst exponent H [-], in (0, 1).
    rms_height : RMS height [µm], ≥ 0; or
    rms_slope : RMS slope [-], ≥ 0 (exactly one of the two).
    short_cutoff : λs [µm], > 0: no roughness at shorter wavelengths; ≥ 2·spacing.
    long_cutoff : λL [µm], > λs: the PSD is flat (``rolloff``) at longer wavelengths.
    rolloff : PSD below q_L relative to C(q_L), as an amplitude ratio [-], ≥ 0 (1: flat).
    spacing : vertex spacing Δx [µm]; default λs/4.
    """
    _check_rng(rng)
    if isinstance(hurst, bool) or not isinstance(hurst, int | float) or not 0 < hurst < 1:
        raise ValueError(f"hurst = {hurst!r} must be in (0, 1)")
    short_cutoff = _check_positive("short_cutoff", short_cutoff)
    long_cutoff = _check_positive("long_cutoff", long_cutoff)
    if not long_cutoff > short_cutoff:
        raise ValueError(
            f"long_cutoff = {long_cutoff!r} µm must exceed short_cutoff = {short_cutoff!r} µm"
        )
    if not (isinstance(rolloff, int | float) and np.isfinite(rolloff) and rolloff >= 0):
        raise ValueError(f"rolloff = {rolloff!r} must be a finite number ≥ 0")
    if (rms_height is None) == (rms_slope is None):
        raise ValueError(
            f"give exactly one of rms_height = {rms_height!r} µm and rms_slope = {rms_slope!r}"
        )
    target_name, target = (
        ("rms_height", rms_height) if rms_height is not None else ("rms_slope", rms_slope)
    )
    if (
        isinstance(target, bool)
        or not isinstance(target, int | float)
        or not np.isfinite(target)
        or target < 0
    ):
        raise ValueError(f"{target_name} = {target!r} must be a finite number ≥ 0")
    if not (np.isfinite(x_start) and np.isfinite(x_end) and x_end > x_start):
        raise ValueError(f"x_end = {x_end!r} must exceed x_start = {x_start!r} [µm]")
    dx = short_cutoff / 4.0 if spacing is None else _check_positive("spacing", spacing)
    if short_cutoff < 2 * dx * (1 - 1e-12):
        raise ValueError(
            f"short_cutoff = {short_cutoff!r} µm must be ≥ 2·spacing = "
            f"{2 * dx!r} µm (the Nyquist wavelength)"
        )
    n = int(np.ceil((x_end - x_start) / dx - 1e-9)) + 1
    n_box = max(n, int(np.ceil(8 * long_cutoff / dx)))
    n_box += n_box % 2  # even: one real Nyquist mode
    L = n_box * dx
    k = np.arange(n_box // 2 + 1)
    q = 2 * np.pi * k / L
    shape = self_affine_psd(q, hurst, 1.0, short_cutoff, long_cutoff, rolloff)
    weight = np.full(k.size, 2.0)  # ±k pairs
    weight[0], weight[-1] = 0.0, 1.0  # q = 0 excluded; Nyquist once
    if rms_height is not None:
        mean_square = np.sum(weight * shape) / L
    else:
        mean_square = np.sum(weight * shape * (2 * np.sin(q * dx / 2) / dx) ** 2) / L
    c0 = target**2 / mean_square
    a = rng.standard_normal(k.size)
    b = rng.standard_normal(k.size)
    b[0] = b[-1] = 0.0
    var = L * c0 * shape  # E|h̃_k|²
    scale = np.where(weight == 2.0, np.sqrt(var / 2), np.sqrt(var))
    coeff = scale * (a + 1j * b)
    h = np.fft.irfft(coeff, n=n_box) * (n_box / L)
    x = x_start + dx * np.arange(n)
    return Profile(
        x=x,
        y=h[:n],
        spacing=dx,
        source=f"self-affine H={hurst:g}, λs={short_cutoff:g} µm, λL={long_cutoff:g} µm",
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
    length = x[-1] - x[0]
    dx = length / (x.size - 1) if spacing is None else _check_positive("spacing", spacing)
    n = int(np.floor(length / dx + 1e-9)) + 1
    if n < 2:
        raise ValueError(f"spacing = {dx!r} µm exceeds the scan length {length!r} µm{where}")
    xs = dx * np.arange(n)
    return Profile(x=xs, y=np.interp(x[0] + xs, x, h), spacing=dx, source=source)


# --- Statistics ------------------------------------------------------------------------------


def _uniform(profile: Profile) -> tuple[np.ndarray, float]:
    """Heights on a uniform grid and its spacing (resampled if the profile is not uniform)."""
    x, y = np.asarray(profile.x, float), np.asarray(profile.y, float)
    if profile.spacing is not None:
        return y, float(profile.spacing)
    dx = float(np.min(np.diff(x)[np.diff(x) > 0]))
    xs = x[0] + dx * np.arange(int(np.floor((x[-1] - x[0]) / dx + 1e-9)) + 1)
    return np.interp(xs, x, y), dx


def psd(profile: Profile, window: str | None = "hann") -> tuple[np.ndarray, np.ndarray]:
    """1-D PSD of a profile on its FFT wavevectors: (q [rad/µm], C¹ᴰ [µm³]).

    C(q_k) = |Δx·Σ_j w_j h_j e^(−i q_k x_j)|²/L with q_k = 2πk/L, L = NΔx, k = 0 … ⌊N/2⌋
    (+q and −q are equal for real heights), the SurfaceTopography convention (module docstring;
    Jacobs, Junge & Pastewka 2017). ``window="hann"`` (default, for non-periodic measured
    scans) multiplies the heights by a Hann window scaled to ⟨w²⟩ = 1, as SurfaceTopography
    does; ``None`` is the plain periodogram (exact for periodic profiles). The heights' mean
    is removed first.
    """
    h, dx = _uniform(profile)
    h = h - h.mean()
    n = h.size
    if window == "hann":
        w = np.hanning(n)
        h = h * w / np.sqrt(np.mean(w * w))
    elif window is not None:
        raise ValueError(f"window = {window!r} must be 'hann' or None")
    L = n * dx
    c = np.abs(dx * np.fft.rfft(h)) ** 2 / L
    q = 2 * np.pi * np.arange(c.size) / L
    return q, c


def _log_bins(q, c, per_decade: int = 10):
    """Average C in logarithmic bins of q (q > 0): the bin-average resampling of
    SurfaceTopography, so a power law is not dominated by its many short-wavelength points."""
    q, c = q[1:], c[1:]
    lo, hi = np.floor(np.log10(q[0]) * per_decade), np.ceil(np.log10(q[-1]) * per_decade)
    edges = 10 ** (np.arange(lo, hi + 2) / per_decade)
    idx = np.digitize(q, edges)
    qb, cb = [], []
    for i in np.unique(idx):
        m = idx == i
        qb.append(np.exp(np.mean(np.log(q[m]))))
        cb.append(np.mean(c[m]))
    return np.array(qb), np.array(cb)


def hurst_estimate(q, c, q_min: float, q_max: float) -> tuple[float, float]:
    """Fit C ∝ q^−(1+2H) to log-binned PSD points with q_min ≤ q ≤ q_max [rad/µm]:
    returns (H [-], slope [-]); NaNs if fewer than 3 bins fall in the range."""
    qb, cb = _log_bins(np.asarray(q), np.asarray(c))
    m = (qb >= q_min) & (qb <= q_max) & (cb > 0)
    if m.sum() < 3:
        return float("nan"), float("nan")
    slope = float(np.polyfit(np.log(qb[m]), np.log(cb[m]), 1)[0])
    return (-slope - 1) / 2, slope


def statistics(profile: Profile, fit_wavelengths: tuple[float, float] | None = None) -> dict:
    """Statistics of a floor profile, JSON-friendly (plain floats and lists).

    * ``rms_height_um`` — √⟨(h − h̄)²⟩ over the profile's points [µm] (Rq);
    * ``rms_slope`` — √⟨((h_{j+1} − h_j)/Δx_j)²⟩ of the polyline [-] (RΔq);
    * ``psd_q_per_um``, ``psd_C_um3`` — Hann-windowed 1-D PSD (:func:`psd`), averaged in
      logarithmic bins (10 per decade), SurfaceTopography convention;
    * ``hurst`` and ``psd_slope`` — a fit C ∝ q^−(1+2H) (:func:`hurst_estimate`) for
      wavelengths λ = 2π/q in ``fit_wavelengths`` = (λ_min, λ_max) [µm]; default (8Δx, L/8):
      clear of the window's leakage and of aliasing, at least eight wavelengths in the
      profile. The estimate means something only where the PSD is a power law: for a
      self-affine floor pass (2λs, λL/2), inside its cutoffs.
    * ``length_um``, ``n_points``, ``spacing_um``, ``source``.

    Pad floors (the paper's independent heights) have no spatial structure: their PSD fields
    are empty and ``hurst`` is None.
    """
    x, y = np.asarray(profile.x, float), np.asarray(profile.y, float)
    out = {"source": profile.source, "n_points": int(x.size), "length_um": float(x[-1] - x[0])}
    if profile.pad_heights is not None:
        h = np.asarray(profile.pad_heights, float)
        out.update(
            kind="pads",
            rms_height_um=float(np.sqrt(np.mean((h - h.mean()) ** 2))),
            rms_slope=None,
            spacing_um=None,
            hurst=None,
            psd_slope=None,
            psd_q_per_um=[],
            psd_C_um3=[],
        )
        return out
    dx_all = np.diff(x)
    ok = dx_all > 0
    out["kind"] = "profile"
    out["rms_height_um"] = float(np.sqrt(np.mean((y - y.mean()) ** 2)))
    out["rms_slope"] = float(np.sqrt(np.mean((np.diff(y)[ok] / dx_all[ok]) ** 2)))
    q, c = psd(profile)
    h_u, dx = _uniform(profile)
    L = h_u.size * dx
    lam_min, lam_max = (8 * dx, L / 8) if fit_wavelengths is None else fit_wavelengths
    if not 0 < lam_min < lam_max:
        raise ValueError(
            f"fit_wavelengths = {fit_wavelengths!r} µm must be (λ_min, λ_max) "
            "with 0 < λ_min < λ_max"
        )
    q_lo, q_hi = 2 * np.pi / lam_max, 2 * np.pi / lam_min
    H, slope = hurst_estimate(q, c, q_lo, q_hi)
    qb, cb = _log_bins(q, c)
    out.update(
        spacing_um=float(dx),
        hurst=None if np.isnan(H) else float(H),
        psd_slope=None if np.isnan(slope) else float(slope),
        fit_q_min_per_um=float(q_lo),
        fit_q_max_per_um=float(q_hi),
        psd_q_per_um=[float(v) for v in qb],
        psd_C_um3=[float(v) for v in cb],
    )
    return out


# --- The floor under an array ----------------------------------------------------------------


def place(profile: Profile, x_start: float, x_end: float) -> Profile:
    """The part of a uniformly sampled ``profile`` that covers [x_start, x_end] [µm], moved so
    that its first point sits at x_start: vertices x_start + Δx·k, k = 0 … ⌈(x_end −
    x_start)/Δx⌉ (the grid :func:`correlated_profile` uses), heights y[k] of the profile.
    A profile too short for the extent is refused."""
    if profile.spacing is None:
        raise ValueError(
            "a measured floor must be uniformly sampled: build it with "
            "floor.from_profile or gecko_agents.profiles"
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
    :mod:`gecko_agents.profiles`) wins: its start is put under the left edge of the floor,
    x_centres.min() − margin (:func:`place`), and it must reach x_centres.max() + margin.
    Otherwise ``floor_params.kind`` chooses: ``"gaussian"`` → :func:`make_profile` (eq 28; the
    floor every earlier run used, drawn identically), ``"self_affine"`` → :func:`self_affine`
    with RMS height ``sigma`` (or ``rms_slope``), ``hurst``, ``short_cutoff``,
    ``long_cutoff``.

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
    if kind != "gaussian":
        raise ValueError(f"Floor.kind = {kind!r} must be 'gaussian' or 'self_affine'")
    return make_profile(
        floor_params.sigma,
        floor_params.correlation_length,
        x_centres.size,
        pitch,
        x_centres,
        margin,
        rng,
    )
