"""Floors in Fourier space: self-affine synthesis from a PSD, and the PSD of any profile.

* :func:`self_affine_psd` — the self-affine 1-D PSD with a short and a long wavelength cutoff;
* :func:`self_affine` — a random self-affine (fractal) profile with Hurst exponent H between
  those cutoffs, by spectral synthesis (Persson et al. 2005);
* :func:`psd`, :func:`hurst_estimate` and :func:`statistics` — what a profile's spectrum and
  heights say (RMS height and slope, PSD, Hurst estimate), for a run's metadata.

Generation and measurement share one PSD convention (below), so a synthesised floor's PSD is
its request. All names are also importable from :mod:`gecko_agents.floor`. Lengths in µm,
wavevectors in rad/µm, PSDs in µm³.

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

import numpy as np

from gecko_agents.floor.profile import Profile, check_positive, check_rng

__all__ = ["self_affine_psd", "self_affine", "psd", "hurst_estimate", "statistics"]


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
    check_rng(rng)
    short_cutoff, long_cutoff, target, dx = _checked_request(
        x_start, x_end, hurst, rms_height, rms_slope, short_cutoff, long_cutoff, rolloff, spacing
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
    c0 = target**2 / _mean_square_per_c0(shape, weight, q, L, dx, slope=rms_height is None)
    h = _synthesise(rng, L * c0 * shape, weight, n_box, L)
    x = x_start + dx * np.arange(n)
    return Profile(
        x=x,
        y=h[:n],
        spacing=dx,
        source=f"self-affine H={hurst:g}, λs={short_cutoff:g} µm, λL={long_cutoff:g} µm",
    )


def _checked_request(
    x_start, x_end, hurst, rms_height, rms_slope, short_cutoff, long_cutoff, rolloff, spacing
) -> tuple[float, float, float, float]:
    """Validate :func:`self_affine`'s request (errors name the argument, its value and range);
    returns (λs [µm], λL [µm], the requested RMS height [µm] or slope [-], Δx [µm])."""
    if isinstance(hurst, bool) or not isinstance(hurst, int | float) or not 0 < hurst < 1:
        raise ValueError(f"hurst = {hurst!r} must be in (0, 1)")
    short_cutoff = check_positive("short_cutoff", short_cutoff)
    long_cutoff = check_positive("long_cutoff", long_cutoff)
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
    dx = short_cutoff / 4.0 if spacing is None else check_positive("spacing", spacing)
    if short_cutoff < 2 * dx * (1 - 1e-12):
        raise ValueError(
            f"short_cutoff = {short_cutoff!r} µm must be ≥ 2·spacing = "
            f"{2 * dx!r} µm (the Nyquist wavelength)"
        )
    return short_cutoff, long_cutoff, target, dx


def _mean_square_per_c0(shape, weight, q, L: float, dx: float, slope: bool) -> float:
    """Expected mean square over the box of the heights [µm²] (or, with ``slope``, of the
    polyline's slopes [-]) per unit C0: (1/L)·Σ_k C(q_k) [·(2 sin(q_k Δx/2)/Δx)²], k ≠ 0."""
    if not slope:
        return np.sum(weight * shape) / L
    return np.sum(weight * shape * (2 * np.sin(q * dx / 2) / dx) ** 2) / L


def _synthesise(rng: np.random.Generator, var, weight, n_box: int, L: float) -> np.ndarray:
    """Heights of the periodic box [µm] from Gaussian complex amplitudes with E|h̃_k|² = var
    [µm²·µm]: h̃_k = √(var/2)·(a + ib) for ±k pairs, √var·a at q = 0 and Nyquist (real)."""
    a = rng.standard_normal(weight.size)
    b = rng.standard_normal(weight.size)
    b[0] = b[-1] = 0.0
    scale = np.where(weight == 2.0, np.sqrt(var / 2), np.sqrt(var))
    coeff = scale * (a + 1j * b)
    return np.fft.irfft(coeff, n=n_box) * (n_box / L)


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
      profile (a profile of at most 64 points has no such range: no fit, ``hurst`` and
      the fit bounds are None). The estimate means something only where the PSD is a power
      law: for a self-affine floor pass (2λs, λL/2), inside its cutoffs.
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
    if fit_wavelengths is not None and not 0 < lam_min < lam_max:
        raise ValueError(
            f"fit_wavelengths = {fit_wavelengths!r} µm must be (λ_min, λ_max) "
            "with 0 < λ_min < λ_max"
        )
    if lam_min < lam_max:
        q_lo, q_hi = 2 * np.pi / lam_max, 2 * np.pi / lam_min
        H, slope = hurst_estimate(q, c, q_lo, q_hi)
    else:  # at most 64 points (a probe's coarse polyline): no wavelengths to fit
        q_lo = q_hi = H = slope = float("nan")
    qb, cb = _log_bins(q, c)
    out.update(
        spacing_um=float(dx),
        hurst=None if np.isnan(H) else float(H),
        psd_slope=None if np.isnan(slope) else float(slope),
        fit_q_min_per_um=None if np.isnan(q_lo) else float(q_lo),
        fit_q_max_per_um=None if np.isnan(q_hi) else float(q_hi),
        psd_q_per_um=[float(v) for v in qb],
        psd_C_um3=[float(v) for v in cb],
    )
    return out
