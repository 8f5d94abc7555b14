"""Fit model parameters to measured data: bounded least squares with honest uncertainties.

``fit(data, free, base=PAPER_ARRAY, forward="quasistatic", seed=0)`` adjusts the parameters
named in ``free`` (dotted names as in :meth:`SetaArray.replace`, e.g. ``contact.w``,
``floor.sigma``, plus ``seta.stiffness_scale``, a factor on the seta's Ka and Kp) within their
bounds so the model reproduces the data, and reports what the data determine and what not.

Data (a CSV path or a table: a mapping of column name → values, a pandas DataFrame or a list
of row dicts) use the package's column names with units, one of

* ``preload_uN, pull_off_uN[, pull_off_err_uN][, sigma_um]`` — pull-off force against preload
  (force control, :func:`quasistatic.preload_pull`), optionally at a floor roughness σ per row;
* ``displacement_um, force_uN[, force_err_uN]`` — the normal force (positive compressive) on the
  retract leg of a press-and-pull (:func:`quasistatic.press_pull`, pressed to the deepest
  displacement given or 0.5 µm), against the plate height above the touch-down of the floor's
  mean plane (positive up);
* ``pull_off_uN, release_um[, pull_off_err_uN][, release_err_um]`` — a snap-off: the peak
  tension of a press-and-pull to 0.5 µm and the plate travel above touch-down at which the last
  tip let go.

Other units are converted (N, mN, µN/uN, nN; m, mm, µm/um, nm); other non-numeric columns
(``source``, ``note``) are carried along. Without an uncertainty column every point has unit
weight and the parameter covariance is scaled by the reduced χ² (the scatter estimates the
noise); with one, residuals are divided by it and the covariance is (JᵀJ)⁻¹ (Jacobian J of the
weighted residuals at the optimum, ``scipy.optimize.least_squares``).

Identifiability: a parameter is flagged (``identifiable[name] = False``, with the reason in
``result.notes``) when the data hardly move the model along it (Jacobian column below 1e-6 of
the largest), its standard error exceeds a quarter of its bound interval, its correlation
with another free parameter exceeds 0.95 in magnitude, or the fit ended on one of its bounds
(the data want a value beyond it; the curvature there says nothing about an interval). No
standard error is given (NaN, printed without ±) for a parameter on its bound, nor for any
when the data are as many as the free parameters and state no uncertainties (zero residual
degrees of freedom: the scatter that would scale the covariance cannot be estimated). Fewer
data than free parameters are refused.

Pull-offs may be given as magnitudes (> 0) or in the package's sign convention (tension < 0),
one convention per data set (``Data.pull_off_sign`` records which).

Forward model (quasi-static): heights on a fixed grid of Gaussian quantiles with a moving
contact front, one shared approach for all preloads of a σ and batched retracts, the peak
refined by bisection (:func:`quasistatic.preload_pulls`), so the model is a smooth function of
the parameters. Measured on the paper's 10⁷ array (64 blocks, w = 0.021 J/m², σ = 1.2 µm, six
preloads 0.1–8.6 N, w or σ stepped by 0.25 % over ±1 %): the pull-off scatters about a
quadratic by ≤ 3.4e-5 of itself with the ``linear`` seta and ≤ 1.7e-3 (mostly < 2e-4) with the
``rod`` seta, against d ln F/d ln w ≈ 0.8–1.2; a plain grid of the same blocks jumped by up to
3e-2. The Jacobian step (``diff_step`` = 0.02 of each bound interval, log or linear) moves the
pull-off by 1–10 %, ≥ 10× that noise.

Cost: one forward evaluation is one quasi-static run of the array; with the ``rod`` seta each
seta's Newton solve iterates on its own in a loop compiled by numba
(:func:`gecko_agents.quasistatic.rod_equilibrium.rod_newton`), so a seta at its fold does not
keep the others iterating. Measured fit times are in the documentation (explanation,
"Performance").

Units: µm, µN (see :mod:`gecko_agents.params`).

The pieces live in :mod:`~gecko_agents.calibrate.data` (reading data),
:mod:`~gecko_agents.calibrate.free` (free parameters and their unit box),
:mod:`~gecko_agents.calibrate.forward` (the quasi-static forward model) and
:mod:`~gecko_agents.calibrate.result` (:class:`FitResult`); this module fits, and holds the
agent forward model and the command line.
"""

from __future__ import annotations

import argparse
import re
import sys
import time
from dataclasses import replace
from typing import NamedTuple

import numpy as np
from scipy.optimize import least_squares

from gecko_agents.calibrate.data import Data, load_data
from gecko_agents.calibrate.forward import Forward, predict_quasistatic
from gecko_agents.calibrate.free import (
    PSEUDO_PARAMETERS,
    UnitBox,
    apply_free,
    base_value,
    check_free,
    starts,
)
from gecko_agents.calibrate.result import FitResult
from gecko_agents.params import (
    PAPER_ARRAY,
    PAPER_FIG5_READING,
    PAPER_TABLE1,
    SetaArray,
    check_seed,
)
from gecko_agents.provenance import versions

__all__ = ["fit", "load_data", "FitResult", "Forward", "PSEUDO_PARAMETERS", "main"]


# ------------------------------------------------------------------------------- forward
def predict(
    data: Data,
    params: SetaArray,
    *,
    stiffness_scale: float = 1.0,
    seed: int = 0,
    forward: Forward | None = None,
) -> np.ndarray:
    """Model values for each observation of ``data`` (as :meth:`Data.observed`) [µN, µm].

    The array's floor heights are the fixed quantile grid of
    :func:`quasistatic.quantile_heights` (``seed`` only seeds the agent model's floor); a
    row's ``sigma_um`` overrides ``params.floor.sigma``. Pull-off-vs-preload rows of one σ share
    one approach (:func:`quasistatic.preload_pulls`).
    """
    forward = forward or Forward()
    if forward.kind == "agent":
        return _predict_agent(data, params, stiffness_scale, seed, forward)
    return predict_quasistatic(data, params, stiffness_scale, forward)


def _predict_agent(data, params, scale, seed, forward):
    """Pull-offs of the agent model (pymunk) on an ``n_sim`` patch, scaled to the array."""
    from gecko_agents import protocol
    from gecko_agents.model import Model

    if scale != 1.0:
        raise ValueError("seta.stiffness_scale is available with forward='quasistatic' only")
    if data.kind != "preload":
        raise ValueError("forward='agent' covers pull-off-vs-preload data")
    n = min(forward.n_sim, params.array.count)
    k = params.array.count / n
    out = np.empty(data.n)
    for i in range(data.n):
        p = params
        if "sigma" in data.columns:
            p = p.replace(**{"floor.sigma": float(data.columns["sigma"][i])})
        h = Model(p, n_sim=n, seed=seed).run(
            protocol.preload_pull(float(data.columns["preload"][i]) / k), progress=False
        )
        out[i] = h.peak_pull_off * k
    return out


# ------------------------------------------------------------------------------- fit
def fit(
    data,
    free: dict,
    *,
    base: SetaArray = PAPER_ARRAY,
    forward="quasistatic",
    seed: int = 0,
    n_starts: int = 3,
    n_blocks: int | None = None,
    retract_steps: int | None = None,
    diff_step: float = 0.02,
    max_nfev: int = 15,
) -> FitResult:
    """Fit the parameters named in ``free`` to ``data``.

    Parameters
    ----------
    data : CSV path or table (see the module docstring).
    free : dotted parameter name → (low, high) bounds in the parameter's unit (µm, µN/µm, MPa,
        …). The base value must lie inside. A parameter with 0 < low and high ≥ 10·low is
        fitted in log space (its steps are relative), any other on a linear scale.
    base : parameters of everything not free (its ``mechanics`` is the forward model's).
    forward : ``"quasistatic"``, ``"agent"`` or a :class:`Forward`.
    seed : seed of the agent model's floor (the quasi-static model uses the fixed quantile grid
        of :func:`quasistatic.quantile_heights` and no random draw).
    n_starts : bounded least-squares starts (at the low and high corners of the bounds, the
        centre, …); the best is kept, all are recorded.
    n_blocks, retract_steps : override the :class:`Forward` accuracy settings.
    diff_step : forward-difference step of the Jacobian, as a fraction of each parameter's
        (log or linear) bound interval, taken towards the inside of the bounds.
    max_nfev : residual evaluations per start (scipy's ``max_nfev``; each Jacobian costs one
        more model evaluation per free parameter).

    How diff_step was chosen: the quasi-static pull-off of the paper's 10⁷ array (64 quantile
    blocks, refined peak) scattered about a smooth curve by 2e-4 to 2e-3 of itself when
    w was stepped by 0.25 % (measured over ±1 % of w = 0.02 J/m², six preloads 0.1–8.6 N),
    and d ln F/d ln w ≈ 0.3–3. A step of 0.02 of a log interval of w from 0.002 to 0.2 (4.6 %
    of w) moves the pull-off by 1.5–15 %, 10–100 × that noise, so the Jacobian errs by a
    few per cent at most; smaller steps would measure the noise.

    Returns
    -------
    :class:`FitResult`.
    """
    t0 = time.perf_counter()
    check_seed(seed, "seed")
    fw = _checked_settings(base, forward, n_starts, n_blocks, retract_steps, diff_step)
    d = load_data(data)
    names, lo, hi = check_free(base, free)
    pb = _Problem(d, base, names, UnitBox(lo, hi), seed, fw, diff_step)
    if pb.y.size < len(names):
        raise ValueError(
            f"data = {d.source!r}: {pb.y.size} data value(s) cannot determine {len(names)} "
            f"free parameters ({', '.join(names)}); give at least {len(names)} or free fewer"
        )
    u0s = starts(len(names), n_starts)
    runs = [pb.run(u0, max_nfev) for u0 in u0s]
    best = min(runs, key=lambda r: r.cost)
    values = pb.box.to_param(best.x)
    unc = _uncertainty(pb.jac(best.x), pb.box, values, best.cost, pb.y.size, d.err_given)
    ident, notes = _identifiability(names, unc, pb.box, values, best.x)
    fitted, scale = apply_free(base, names, values)
    model_best = pb.model(best.x)
    return FitResult(
        names,
        dict(zip(names, values.tolist(), strict=True)),
        dict(zip(names, unc.se.tolist(), strict=True)),
        unc.corr,
        float(best.cost),
        ident,
        notes,
        {n: (float(lo[i]), float(hi[i])) for i, n in enumerate(names)},
        pb.y,
        pb.err,
        model_best,
        d,
        _record(pb, (best, runs, u0s), values, unc, (ident, notes), (fitted, scale), t0),
    )


def _checked_settings(base, forward, n_starts, n_blocks, retract_steps, diff_step) -> Forward:
    """The forward model's settings, after checking the fit's arguments."""
    if not isinstance(base, SetaArray):
        raise ValueError(f"base must be a SetaArray, got {type(base).__name__}")
    fw = forward if isinstance(forward, Forward) else Forward(kind=forward)
    for name, value in (("n_blocks", n_blocks), ("retract_steps", retract_steps)):
        if value is not None and (
            not isinstance(value, int) or isinstance(value, bool) or value < 1
        ):
            raise ValueError(f"{name} = {value!r} must be an integer ≥ 1 (or None: the default)")
    if n_blocks is not None or retract_steps is not None:
        fw = replace(
            fw, n_blocks=n_blocks or fw.n_blocks, retract_steps=retract_steps or fw.retract_steps
        )
    if not isinstance(n_starts, int) or n_starts < 1:
        raise ValueError(f"n_starts = {n_starts!r} must be an integer ≥ 1")
    if not 0 < diff_step < 0.5:
        raise ValueError(f"diff_step = {diff_step!r} must be in (0, 0.5)")
    return fw


class _Problem:
    """The least-squares problem in the unit box of the free parameters.

    ``resid(u)`` = (model − observed)/uncertainty at unit-box point u; ``jac(u)`` its forward
    differences with step ``diff_step`` towards the inside of the box; model values are
    cached by point, so ``cache`` counts the model evaluations.
    """

    def __init__(self, d: Data, base, names, box: UnitBox, seed, fw: Forward, diff_step):
        self.d, self.base, self.names, self.box = d, base, names, box
        self.seed, self.fw, self.diff_step = seed, fw, diff_step
        self.y, self.err = d.observed()
        self.cache: dict = {}

    def model(self, u):
        key = tuple(np.round(u, 12))
        if key not in self.cache:
            p, scale = apply_free(self.base, self.names, self.box.to_param(u))
            self.cache[key] = predict(
                self.d, p, stiffness_scale=scale, seed=self.seed, forward=self.fw
            )
        return self.cache[key]

    def run(self, u0, max_nfev):
        """One bounded least-squares search from unit-box point ``u0`` (scipy's trf)."""
        return least_squares(
            self.resid,
            u0,
            jac=self.jac,
            bounds=(0.0, 1.0),
            x_scale=1.0,
            max_nfev=max_nfev,
            xtol=1e-4,
            ftol=1e-6,
            method="trf",
        )

    def resid(self, u):
        return (self.model(u) - self.y) / self.err

    def jac(self, u):
        r0 = self.resid(u)
        J = np.empty((self.y.size, len(self.names)))
        for j in range(len(self.names)):
            step = self.diff_step if u[j] + self.diff_step <= 1.0 else -self.diff_step
            v = np.array(u, dtype=float)
            v[j] += step
            J[:, j] = (self.resid(v) - r0) / step
        return J


class _Uncertainty(NamedTuple):
    """Standard errors and correlations at the optimum (in the parameters' own units), which
    directions are flat, χ², degrees of freedom and the covariance scale."""

    se: np.ndarray
    corr: np.ndarray
    flat: np.ndarray
    chi2: float
    dof: int
    s2: float


def _uncertainty(J_unit, box: UnitBox, values, cost, n_obs, err_given) -> _Uncertainty:
    """Covariance (JᵀJ)⁻¹, scaled by the reduced χ² when no uncertainties were stated, from
    the Jacobian ``J_unit`` in the unit box at the optimum ``values``."""
    dpdu = box.dparam_du(values)
    J = J_unit / dpdu[None, :]
    dof = n_obs - values.size  # ≥ 0: fit refuses fewer data than parameters
    chi2 = float(2 * cost)
    # Without stated uncertainties the scatter scales the covariance; with dof = 0 there is
    # no scatter to measure it by, so no standard error can be given (NaN).
    s2 = 1.0 if err_given else (chi2 / dof if dof > 0 else np.nan)
    JtJ = J.T @ J
    colnorm = np.sqrt(np.diag(JtJ) * dpdu**2)
    with np.errstate(divide="ignore", invalid="ignore"):
        cov = np.linalg.pinv(JtJ, rcond=1e-12)  # the correlation does not depend on s2
        sd = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        corr = cov / np.outer(sd, sd)
        se = sd * np.sqrt(s2)
    flat = colnorm < 1e-6 * max(colnorm.max(), 1e-300)
    se = np.where(flat, np.inf, se)
    corr = np.where(np.isfinite(corr), corr, np.nan)
    np.fill_diagonal(corr, 1.0)
    return _Uncertainty(se, corr, flat, chi2, dof, s2)


BOUND_TOL = 1e-6
"""A fitted value within this fraction of its (log or linear) bound interval of a bound is
on the bound."""


def _identifiability(names, unc: _Uncertainty, box: UnitBox, values, u) -> tuple[dict, dict]:
    """name → whether the data determine it, and name → why not (see the module docstring);
    ``u`` is the optimum in the unit box. Sets ``unc.se`` to NaN where no interval holds."""
    span = box.hi - box.lo
    se, corr = unc.se, unc.corr
    ident, notes = {}, {}
    for i, n in enumerate(names):
        why = []
        if u[i] <= BOUND_TOL or u[i] >= 1.0 - BOUND_TOL:
            side, bound = ("low", box.lo[i]) if u[i] <= 0.5 else ("high", box.hi[i])
            why.append(
                f"the fit ended on its {side} bound {bound:.6g}: the data want a value beyond "
                "it, so no standard error holds (widen the bounds or fix the parameter)"
            )
            se[i] = np.nan
        elif unc.dof == 0 and np.isnan(unc.s2):
            why.append(
                "zero residual degrees of freedom and no stated uncertainties: the data fit "
                "exactly and their scatter, hence the standard error, cannot be estimated"
            )
            se[i] = np.nan
        if unc.flat[i]:
            why.append("the data do not depend on it (flat direction of the fit)")
        elif np.isfinite(se[i]) and (se[i] > 0.25 * span[i] or (box.logs[i] and se[i] > values[i])):
            why.append(
                f"its standard error {se[i]:.3g} exceeds a quarter of its bound "
                f"interval {span[i]:.3g} or its value"
            )
        others = [
            names[j]
            for j in range(len(names))
            if j != i and np.isfinite(corr[i, j]) and abs(corr[i, j]) > 0.95
        ]
        if others:
            why.append(f"correlation above 0.95 with {', '.join(others)}")
        ident[n] = not why
        if why:
            notes[n] = "; ".join(why)
    return ident, notes


def _record(pb: _Problem, search, values, unc: _Uncertainty, verdict, fitted, t0) -> dict:
    """What ``fit.json`` holds: data, free parameters, correlations, fit quality, every start,
    the forward model's settings, parameters before and after, evaluations, time, versions.

    ``search`` = (best run, all runs, their starts); ``verdict`` = (identifiable, notes);
    ``fitted`` = (fitted parameters, seta stiffness scale).
    """
    (best, runs, u0s), (ident, notes), (fitted, scale) = search, verdict, fitted
    d, names, box, fw = pb.d, pb.names, pb.box, pb.fw
    return {
        "data": {
            "source": d.source,
            "sha256": d.digest,
            "kind": d.kind,
            "n": d.n,
            "uncertainties_stated": d.err_given,
        },
        "free": {
            n: {
                "low": float(box.lo[i]),
                "high": float(box.hi[i]),
                "start": base_value(pb.base, n),
                "value": float(values[i]),
                "stderr": float(unc.se[i]) if np.isfinite(unc.se[i]) else None,
                "identifiable": ident[n],
                "note": notes.get(n, ""),
            }
            for i, n in enumerate(names)
        },
        "correlation": [
            [None if not np.isfinite(v) else float(v) for v in row] for row in unc.corr
        ],
        "cost": float(best.cost),
        "chi2": unc.chi2,
        "dof": unc.dof,
        "covariance_scale": unc.s2 if np.isfinite(unc.s2) else None,
        "pull_off_sign": d.pull_off_sign,
        "observed": pb.y.tolist(),
        "uncertainty": pb.err.tolist(),
        "model": pb.model(best.x).tolist(),
        "starts": [
            {
                "start": box.to_param(u0).tolist(),
                "value": box.to_param(r.x).tolist(),
                "cost": float(r.cost),
                "nfev": int(r.nfev),
                "njev": int(r.njev),
                "status": int(r.status),
            }
            for u0, r in zip(u0s, runs, strict=True)
        ],
        "forward": {
            "kind": fw.kind,
            "n_blocks": fw.n_blocks,
            "retract_steps": fw.retract_steps,
            "n_sim": fw.n_sim,
            "dz_um": fw.dz,
            "retract_dz_um": fw.retract_dz,
            "seed": pb.seed,
            "diff_step": pb.diff_step,
            "log_scaled": {n: bool(box.logs[i]) for i, n in enumerate(names)},
            "mechanics": pb.base.mechanics,
            "seta_stiffness_scale": scale,
        },
        "base_params": pb.base.to_dict(),
        "fitted_params": fitted.to_dict(),
        "model_evaluations": len(pb.cache),
        "wall_time_s": time.perf_counter() - t0,
        "versions": versions(),
    }


# ------------------------------------------------------------------------------- CLI
_BASES = {
    "paper_array": PAPER_ARRAY,
    "paper_table1": PAPER_TABLE1,
    "paper_fig5_reading": PAPER_FIG5_READING,
}


def _parse_free(text: str) -> tuple[str, tuple[float, float]]:
    m = re.fullmatch(r"\s*([\w.]+)\s*=\s*([^:]+):(.+)", text)
    if not m:
        raise argparse.ArgumentTypeError(
            f"--free {text!r}: expected NAME=LOW:HIGH, e.g. contact.w=0.01:0.2"
        )
    try:
        return m.group(1), (float(m.group(2)), float(m.group(3)))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--free {text!r}: LOW and HIGH must be numbers") from None


def _parse_set(text: str) -> tuple[str, object]:
    name, eq, value = text.partition("=")
    if not eq:
        raise argparse.ArgumentTypeError(f"--set {text!r}: expected NAME=VALUE")
    try:
        return name.strip(), float(value) if name.strip() != "mechanics" else value.strip()
    except ValueError:
        return name.strip(), value.strip()


def main(argv=None, prog: str = "gecko-agents calibrate") -> int:
    """``gecko-agents calibrate DATA.csv --free contact.w=0.01:0.2 ...`` (also
    ``python -m gecko_agents.calibrate``).

    Exit status 0 on success, 2 on a usage or input error (message on stderr, prefixed with
    ``prog`` as the other commands' are).
    """
    ap = argparse.ArgumentParser(
        prog=prog,
        description="Fit free parameters to a measured data set.",
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog="example:\n  gecko-agents calibrate data.csv --free contact.w=0.01:0.2 "
        "--free floor.sigma=0.1:2 --out fit/",
    )
    ap.add_argument("data", help="CSV with unit-suffixed columns, e.g. preload_uN,pull_off_uN")
    ap.add_argument(
        "--free",
        type=_parse_free,
        action="append",
        required=True,
        metavar="NAME=LOW:HIGH",
        help="a free parameter and its bounds (repeat)",
    )
    ap.add_argument("--base", choices=sorted(_BASES), default="paper_array")
    ap.add_argument(
        "--set",
        type=_parse_set,
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="override a base parameter (repeat)",
    )
    ap.add_argument("--forward", choices=("quasistatic", "agent"), default="quasistatic")
    ap.add_argument(
        "--seed", type=int, default=0, help="seed of the agent model's floor, in [0, 2**63)"
    )
    ap.add_argument(
        "--starts", type=int, default=3, help="least-squares starts (≥ 1); the best is kept"
    )
    ap.add_argument(
        "--blocks",
        type=int,
        default=None,
        help="quasi-static floor-height blocks (≥ 1; default the forward model's)",
    )
    ap.add_argument("--out", default=None, help="directory for fit.json and the plots")
    args = ap.parse_args(argv)
    for flag, pairs in (("--free", args.free), ("--set", args.set)):
        names = [n for n, _ in pairs]
        twice = sorted({n for n in names if names.count(n) > 1})
        if twice:
            ap.error(f"{flag} names {', '.join(twice)} more than once: give each parameter once")
    try:
        base = _BASES[args.base].replace(**dict(args.set))
        res = fit(
            args.data,
            dict(args.free),
            base=base,
            forward=args.forward,
            seed=args.seed,
            n_starts=args.starts,
            n_blocks=args.blocks,
        )
    except ValueError as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return 2
    for n in res.names:
        flag = "" if res.identifiable[n] else f"   NOT DETERMINED: {res.notes[n]}"
        se = res.stderr[n]
        spread = f" ± {se:.3g}" if np.isfinite(se) else " (no standard error)"
        print(f"{n} = {res.values[n]:.6g}{spread}{flag}")
    if res.data.pull_off_sign < 0:
        print("pull-offs read in the package's sign convention (tension < 0), fitted as magnitudes")
    print(f"cost = {res.cost:.6g}")
    if args.out:
        print(f"written to {res.save(args.out)}")
    return 0
