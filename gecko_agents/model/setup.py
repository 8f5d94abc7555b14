"""Choices :class:`gecko_agents.model.Model` makes once, when it is built: its arguments
checked (naming each bad one), how contact is detected, which per-step kernel runs (and on how
many threads) and the floor's statistics for a run's metadata.

Units: µm, µN, µs, ng (:mod:`gecko_agents.params`).
"""

from __future__ import annotations

import math
import os

import numpy as np

from gecko_agents.floor import Profile
from gecko_agents.floor import statistics as _floor_stats
from gecko_agents.model.step_loop import PARALLEL_MIN_SETAE, pad_loop
from gecko_agents.model.step_loop import numba_available as _numba_installed
from gecko_agents.params import SetaArray

__all__ = [
    "KERNELS",
    "MAX_N",
    "MAX_THREADS",
    "checked_arguments",
    "choose_kernel",
    "choose_threads",
    "detection_mode",
    "floor_statistics",
    "idle_cores",
    "numba_available",
]

KERNELS = ("auto", "numpy", "numba", "python")
MAX_N = 200_000  # peak RSS pressed and stepping: ~1.1 GB here, ~0.7 GB at 10⁵ (bench.pressed_model)
_PYTHON_MAX_N = 6  # below this many setae the interpreted loop beats numpy's call overhead
MAX_THREADS = 64
_LOADAVG = "/proc/loadavg"  # Linux: its fourth field is runnable/total scheduling entities


def numba_available() -> bool:
    """Whether the optional numba kernel can be used (``pip install numba``)."""
    return _numba_installed()


def numba_threads() -> int:
    """Threads numba may use (``NUMBA_NUM_THREADS``; 1 without numba)."""
    try:
        import numba
    except ImportError:
        return 1
    return numba.get_num_threads()


def checked_arguments(params, n_sim, contact, record_every, kernel, floor_profile) -> int:
    """Refuse bad Model arguments, naming them; returns the number of setae to simulate."""
    if not isinstance(params, SetaArray):
        raise TypeError(f"params must be a SetaArray, got {type(params).__name__}")
    n = params.array.count if n_sim is None else n_sim
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= MAX_N:
        raise ValueError(
            f"n_sim = {n!r} must be an integer in [1, {MAX_N}] (~1.1 GB of pymunk bodies "
            "at the top); simulate a patch of a large array with n_sim (the quasi-static "
            "solver does 10⁷)"
        )
    if n > params.array.count:
        raise ValueError(
            f"n_sim = {n} is more than array.count = {params.array.count}: the model would "
            "simulate setae the array does not have (scale_to_array = array.count / n_sim "
            "< 1); simulate at most array.count setae, or raise it "
            f"(params.replace(**{{'array.count': {n}}}))"
        )
    if contact not in ("batch", "callback"):
        raise ValueError(f"contact = {contact!r} must be 'batch' or 'callback'")
    if record_every is not None and (not isinstance(record_every, int) or record_every < 1):
        raise ValueError(f"record_every = {record_every!r} must be an integer ≥ 1")
    if kernel not in KERNELS:
        raise ValueError(f"kernel = {kernel!r} must be one of {KERNELS}")
    if floor_profile is not None and not isinstance(floor_profile, Profile):
        raise TypeError(
            f"floor_profile must be a gecko_agents.floor.Profile, got "
            f"{type(floor_profile).__name__}"
        )
    return int(n)


def detection_mode(detection, contact) -> str:
    """The detection asked of the world ("auto": lazy on pad floors, World decides)."""
    if detection not in ("auto", "full", "lazy"):
        raise ValueError(f"detection = {detection!r} must be 'auto', 'full' or 'lazy'")
    if contact == "callback":
        if detection == "lazy":
            raise ValueError("detection='lazy' needs contact='batch'; use 'full'")
        return "full"
    return detection


def choose_threads(threads, n: int, contact: str = "batch") -> int:
    """Threads of a model of ``n`` setae: ``threads`` if given (an integer in [1,
    MAX_THREADS], refused otherwise, naming it), else (None) numba's thread count
    (``NUMBA_NUM_THREADS``; the machine's cores without numba) from
    ``gecko_agents.model.step_loop.PARALLEL_MIN_SETAE`` setae on, where a step is long enough
    to pay
    for them, and 1 below; at most the cores that other processes leave idle when the model is
    built (:func:`idle_cores`: threads that wait for a busy core make a step 2–3× slower).
    The per-contact reference path (``contact = "callback"``) runs on one: its callbacks add
    up the dissipation in the order pymunk calls them."""
    if threads is not None:
        if isinstance(threads, bool) or not isinstance(threads, int | np.integer):
            raise ValueError(f"threads = {threads!r} must be None or an integer ≥ 1")
        if not 1 <= threads <= MAX_THREADS:
            raise ValueError(f"threads = {threads!r} must be in [1, {MAX_THREADS}] (or None)")
        if threads > 1 and contact == "callback":
            raise ValueError(
                f"threads = {threads!r}: contact='callback' (the per-contact reference path) "
                "runs on one thread; use threads=1 or contact='batch'"
            )
        return int(threads)
    if n < PARALLEL_MIN_SETAE or contact == "callback":
        return 1
    cores = numba_threads() if _numba_installed() else (os.cpu_count() or 1)
    return max(1, min(cores, idle_cores(), MAX_THREADS))


def idle_cores() -> int:
    """Cores not running another thread now: the machine's cores minus the runnable threads
    of ``/proc/loadavg`` other than the caller's (Linux), else minus the 1-minute load
    average."""
    cores = os.cpu_count() or 1
    try:
        with open(_LOADAVG) as f:
            busy = int(f.read().split()[3].split("/")[0]) - 1
    except (OSError, IndexError, ValueError):
        busy = os.getloadavg()[0]
    return max(1, round(cores - busy))


def explicit_time_step(dt, omega_max: float, k_max: float, mass: float, rate_dependent: bool):
    """The explicit step [µs]: ``dt`` if inside the stable range (0, 2/ω_max), refused naming
    the stiffest spring k_max [µN/µm] and the tip mass [ng] otherwise; None gives 0.75/ω_max
    (0.375/ω_max for a rate-dependent contact)."""
    bound = 2.0 / omega_max
    if dt is None:
        # A rate-dependent contact switches between its opening and closing branches within
        # a step during a jump-in's ring-down: half the step keeps that first-order error
        # (energy balance 3.8 % → 1.5 % of the run's energy on a stubby seta) in bounds.
        return (0.375 if rate_dependent else 0.75) / omega_max
    if not (isinstance(dt, int | float) and math.isfinite(dt) and 0 < dt < bound):
        raise ValueError(
            f"dt = {dt!r} µs is outside the stable range (0, {bound:.4g}) µs: "
            f"the stiffest spring ({k_max:.3g} µN/µm) on a tip of "
            f"{mass:.3g} ng needs ω·dt < 2"
        )
    return float(dt)


def choose_kernel(kernel: str, fast_pads: bool, n: int, law_type, threads: int = 1):
    """``(kernel, loop, threads)``: the kernel that runs (``"auto"`` resolved: numba if
    installed, else the interpreted loop up to a handful of setae, else numpy), its compiled
    or interpreted pad loop (None for numpy) and the loop's threads (numba's, when
    ``threads`` > 1). ``fast_pads``: a pad floor with the batch contact path, the only case
    the loops cover."""
    if kernel in ("numba", "python") and not fast_pads:
        raise ValueError(
            f"kernel={kernel!r} covers pad floors "
            "(floor.correlation_length = 0) with contact='batch'"
        )
    if kernel == "auto":
        kernel = "numpy"
        if fast_pads:
            kernel = "numba" if numba_available() else "python" if n <= _PYTHON_MAX_N else "numpy"
    if kernel == "numba" and not numba_available():
        raise ValueError("kernel='numba' needs numba (pip install numba); use kernel='numpy'")
    if kernel == "numpy":
        return kernel, None, 1
    # The blocks on numba's threads: the same history either way.
    loop_threads = numba_threads() if kernel == "numba" and threads > 1 else 1
    return kernel, pad_loop(law_type, kernel == "numba", loop_threads > 1), loop_threads


def floor_statistics(profile: Profile, floor_params) -> dict:
    """The floor's RMS height and slope, PSD and Hurst estimate for a run's metadata
    (:func:`gecko_agents.floor.statistics`; a self-affine floor's Hurst exponent is fitted
    between twice its short and half its long cutoff)."""
    fit = None
    if getattr(floor_params, "kind", "gaussian") == "self_affine":
        fit = (2.0 * floor_params.short_cutoff, 0.5 * floor_params.long_cutoff)
    return _floor_stats(profile, fit_wavelengths=fit)
