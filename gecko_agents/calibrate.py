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
the largest), its standard error exceeds a quarter of its bound interval, or its correlation
with another free parameter exceeds 0.95 in magnitude.

Forward model (quasi-static): heights on a fixed grid of Gaussian quantiles with a moving
contact front, one shared approach for all preloads of a σ and batched retracts, the peak
refined by bisection (:func:`quasistatic.preload_pulls`), so the model is a smooth function of
the parameters. Measured on the paper's 10⁷ array (64 blocks, w = 0.021 J/m², σ = 1.2 µm, six
preloads 0.1–8.6 N, w or σ stepped by 0.25 % over ±1 %): the pull-off scatters about a
quadratic by ≤ 3.4e-5 of itself with the ``linear`` seta and ≤ 1.7e-3 (mostly < 2e-4) with the
``rod`` seta, against d ln F/d ln w ≈ 0.8–1.2; a plain grid of the same blocks jumped by up to
3e-2. The Jacobian step (``diff_step`` = 0.02 of each bound interval, log or linear) moves the
pull-off by 1–10 %, ≥ 10× that noise.

Speed (measured, not a test): a fit of six pull-off-vs-preload points (the paper's Fig 10 and
11a numbers) with two free parameters (w, σ) of the paper's 10⁷ array, ``linear`` seta, two
starts, 63 model evaluations: 50 s of CPU on one core, 139 s wall while the 2-core machine
ran at load 10–17. With the ``rod`` seta (a Newton solve per seta and step instead of a table)
an evaluation costs 4–5× as much: the five-point Fig 10 + 11a fit took 52 evaluations and
534 s wall at load 5–17, so the rod does not meet a two-minute budget on this machine.

Units: µm, µN (see :mod:`gecko_agents.params`).
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import io
import json
import math
import re
import sys
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from . import quasistatic as qs
from .history import atomic_write_bytes, versions
from .params import PAPER_ARRAY, PAPER_FIG5_READING, PAPER_TABLE1, SetaArray

__all__ = ["fit", "load_data", "FitResult", "Forward", "PSEUDO_PARAMETERS", "main"]

PSEUDO_PARAMETERS = ("seta.stiffness_scale",)
"""Free parameters that are not fields of :class:`SetaArray`: ``seta.stiffness_scale``
multiplies the seta's axial and bending stiffness (Ka, Kp of eq 17, 19) and nothing else."""

_UNITS = {
    "uN": ("force", 1.0),
    "µN": ("force", 1.0),
    "N": ("force", 1e6),
    "mN": ("force", 1e3),
    "nN": ("force", 1e-3),
    "um": ("length", 1.0),
    "µm": ("length", 1.0),
    "nm": ("length", 1e-3),
    "mm": ("length", 1e3),
    "m": ("length", 1e6),
}
_QUANTITIES = {  # quantity → dimension
    "pull_off_err": "force",
    "pull_off": "force",
    "preload": "force",
    "force_err": "force",
    "force": "force",
    "displacement": "length",
    "sigma": "length",
    "release_err": "length",
    "release": "length",
}
_KINDS = {
    "preload": (("preload", "pull_off"), ("pull_off_err", "sigma")),
    "curve": (("displacement", "force"), ("force_err",)),
    "snapoff": (("pull_off", "release"), ("pull_off_err", "release_err")),
}
_COL = re.compile(r"^(" + "|".join(sorted(_QUANTITIES, key=len, reverse=True)) + r")_(\S+)$")


# ------------------------------------------------------------------------------- data
@dataclass
class Data:
    """A validated data set in µm and µN.

    kind : ``"preload"``, ``"curve"`` or ``"snapoff"``.
    columns : quantity → float array (n,) in µN / µm.
    err_given : whether measurement uncertainties were stated.
    digest : sha256 of the table as read (the CSV bytes, or the canonical CSV of a table).
    extra : non-numeric columns carried along.
    """

    kind: str
    columns: dict
    err_given: bool
    digest: str
    source: str
    extra: dict = field(default_factory=dict)

    @property
    def n(self) -> int:
        return len(next(iter(self.columns.values())))

    def observed(self) -> tuple[np.ndarray, np.ndarray]:
        """Observed values (n_residuals,) and their uncertainties (ones if none stated)."""
        c = self.columns
        if self.kind == "preload":
            y, e = c["pull_off"], c.get("pull_off_err")
        elif self.kind == "curve":
            y, e = c["force"], c.get("force_err")
        else:
            y = np.concatenate([c["pull_off"], c["release"]])
            e = None
            if self.err_given:
                e = np.concatenate(
                    [
                        c.get("pull_off_err", np.full(self.n, np.nan)),
                        c.get("release_err", np.full(self.n, np.nan)),
                    ]
                )
                if np.any(np.isnan(e)):
                    raise ValueError(
                        "a snap-off table needs both pull_off_err_uN and release_err_um, or neither"
                    )
        return y, (np.ones_like(y) if e is None else e)


def _read_table(data) -> tuple[dict, str, str]:
    """Columns as lists of strings or numbers, the digest and a description of the source."""
    if isinstance(data, str | Path):
        path = Path(data)
        if not path.is_file():
            raise ValueError(f"data = {str(path)!r}: no such file")
        raw = path.read_bytes()
        rows = list(csv.DictReader(io.StringIO(raw.decode("utf-8-sig"))))
        if not rows:
            raise ValueError(f"data file {str(path)!r} has no rows")
        cols = {k.strip(): [r[k] for r in rows] for k in rows[0]}
        return cols, hashlib.sha256(raw).hexdigest(), str(path)
    if hasattr(data, "to_dict") and hasattr(data, "columns"):  # pandas DataFrame
        cols = {str(k): list(v) for k, v in data.to_dict(orient="list").items()}
    elif isinstance(data, dict):
        cols = {str(k): list(np.atleast_1d(v)) for k, v in data.items()}
    elif isinstance(data, list | tuple) and data and isinstance(data[0], dict):
        cols = {k: [r.get(k) for r in data] for k in data[0]}
    else:
        raise ValueError(
            f"data must be a CSV path or a table (dict of columns, DataFrame or "
            f"list of row dicts), got {type(data).__name__}"
        )
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(list(cols))
    for row in zip(*cols.values(), strict=True):
        w.writerow([repr(float(v)) if isinstance(v, int | float) else str(v) for v in row])
    return cols, hashlib.sha256(buf.getvalue().encode()).hexdigest(), "table"


def load_data(data) -> Data:
    """Read and validate a data set; raises ValueError naming the problem."""
    cols, digest, source = _read_table(data)
    found, extra = {}, {}
    for name, values in cols.items():
        m = _COL.match(name)
        if m is None:
            extra[name] = values
            continue
        q, unit = m.group(1), m.group(2)
        if unit not in _UNITS:
            raise ValueError(
                f"column {name!r}: unknown unit {unit!r} (known: {', '.join(sorted(_UNITS))})"
            )
        dim, factor = _UNITS[unit]
        if dim != _QUANTITIES[q]:
            raise ValueError(f"column {name!r}: {q} is a {_QUANTITIES[q]}, {unit!r} is a {dim}")
        if q in found:
            raise ValueError(f"column {name!r}: {q} given twice")
        try:
            arr = np.array([float(v) for v in values], dtype=float)
        except (TypeError, ValueError) as exc:
            raise ValueError(f"column {name!r} holds a non-number: {exc}") from None
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise ValueError(
                f"column {name!r} has NaN or infinite values in rows {(bad + 1).tolist()}"
            )
        found[q] = arr * factor
    kind = None
    for k, (need, _) in _KINDS.items():
        if all(q in found for q in need):
            kind = k
            break
    if kind is None:
        wanted = " or ".join("(" + ", ".join(need) + ")" for need, _ in _KINDS.values())
        raise ValueError(
            f"data columns {sorted(cols)} lack the required columns: need {wanted} "
            "with units, e.g. preload_uN, pull_off_uN"
        )
    need, optional = _KINDS[kind]
    unused = set(found) - set(need) - set(optional)
    if unused:
        raise ValueError(
            f"columns {sorted(unused)} do not belong to a {kind} data set "
            f"({', '.join(need + optional)})"
        )
    errs = [q for q in optional if q.endswith("_err") and q in found]
    for q in errs:
        if np.any(found[q] <= 0):
            raise ValueError(f"column {q}: uncertainties must be > 0")
    if kind == "preload" and np.any(found["preload"] <= 0):
        raise ValueError("column preload: preloads must be > 0 µN")
    if "sigma" in found and np.any(found["sigma"] < 0):
        raise ValueError("column sigma: roughness must be ≥ 0 µm")
    return Data(kind, found, bool(errs), digest, source, extra)


# ------------------------------------------------------------------------------- forward
@dataclass
class Forward:
    """How the model is evaluated.

    kind : ``"quasistatic"`` (default; :mod:`quasistatic` on representative heights) or
        ``"agent"`` (the pymunk model on an ``n_sim`` patch, scaled to the array; slow, for a
        final check of a fitted point).
    n_blocks : representative heights per array, on the fixed Gaussian quantile grid of
        :func:`quasistatic.quantile_heights` (no random draw: the model is a smooth function of
        σ and of every other parameter).
    retract_steps : plate steps of each retract (the travel of :func:`quasistatic.preload_pull`
        divided by this; an array pulls off within about the first half of it).
    n_sim : agent patch size.
    dz : approach step [µm] (the turning point is bisected exactly; the result does not depend
        on it, measured: 0.0072 and 0.02 µm give the same pull-offs to 5 digits).
    retract_dz : largest retract step [µm] (the step is travel/retract_steps or this, the
        smaller); the peak is refined by bisection (``preload_pulls(refine_peak=True)``).

    The defaults are set by the forward model's noise (see :func:`fit`).
    """

    kind: str = "quasistatic"
    n_blocks: int = 64
    retract_steps: int = 400
    n_sim: int = 20
    dz: float = 0.05
    retract_dz: float | None = 0.25

    def __post_init__(self):
        if self.kind not in ("quasistatic", "agent"):
            raise ValueError(f"forward = {self.kind!r} must be 'quasistatic' or 'agent'")
        for name, lo in (("n_blocks", 1), ("retract_steps", 10), ("n_sim", 1)):
            v = getattr(self, name)
            if not isinstance(v, int) or v < lo:
                raise ValueError(f"Forward.{name} = {v!r} must be an integer ≥ {lo}")


def _apply(base: SetaArray, names, values) -> tuple[SetaArray, float]:
    """Parameters with the free values set, and the seta stiffness scale."""
    scale, over = 1.0, {}
    for n, v in zip(names, values, strict=True):
        if n == "seta.stiffness_scale":
            scale = float(v)
        else:
            over[n] = float(v)
    return base.replace(**over), scale


def _heights(p: SetaArray, sigma: float, n_blocks: int):
    """Heights [µm], weights and the ``gaussian`` front argument of the fixed quantile grid."""
    if p.array.count == 1 or sigma == 0 or n_blocks == 1:
        return np.zeros(1), np.array([float(p.array.count)]), None
    h, w, e = qs.quantile_heights(
        p.array.count, sigma, min(n_blocks, p.array.count), return_edges=True
    )
    return h, w, (sigma, e)


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
    c = data.columns
    forward = forward or Forward()
    if forward.kind == "agent":
        return _predict_agent(data, params, stiffness_scale, seed, forward)
    z_touch = params.contact.R + params.seta.L * math.sin(params.seta.theta)
    if data.kind == "preload":
        out = np.empty(data.n)
        sig = c.get("sigma", np.full(data.n, params.floor.sigma))
        for s in np.unique(sig):
            rows = np.flatnonzero(sig == s)
            h, w, g = _heights(params, float(s), forward.n_blocks)
            res = qs.preload_pulls(
                params,
                h,
                c["preload"][rows],
                weights=w,
                stiffness_scale=stiffness_scale,
                retract_steps=forward.retract_steps,
                dz=forward.dz,
                retract_dz=forward.retract_dz,
                gaussian=g,
                refine_peak=True,
            )
            out[rows] = [r.pull_off for r in res]
        return out
    h, w, _ = _heights(params, params.floor.sigma, forward.n_blocks)
    depth = 0.5
    if data.kind == "curve":
        depth = max(0.5, -float(np.min(c["displacement"])))
    r = qs.press_pull(
        params,
        h,
        depth,
        weights=w,
        stiffness_scale=stiffness_scale,
        n_retract=forward.retract_steps * 2,
    )
    if data.kind == "curve":
        t = r.turn_index
        z = r.plate_y[t:] - z_touch
        return np.interp(
            c["displacement"], z, r.force_normal[t:], left=r.force_normal[t], right=0.0
        )
    last = max((i for i, _, _ in r.releases), default=len(r.plate_y) - 1)
    return np.array([r.pull_off, r.plate_y[last] - z_touch])


def _predict_agent(data, params, scale, seed, forward):
    from . import protocol
    from .model import Model

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
@dataclass
class FitResult:
    """Outcome of :func:`fit`.

    values, stderr : fitted value and one standard error per free parameter (dicts by name).
    correlation : (k, k) correlation matrix in the order of ``names``.
    cost : ½ Σ (weighted residual)² at the optimum (scipy's convention).
    identifiable : name → bool (see the module docstring); ``notes`` says why not.
    """

    names: list
    values: dict
    stderr: dict
    correlation: np.ndarray
    cost: float
    identifiable: dict
    notes: dict
    bounds: dict
    observed: np.ndarray
    uncertainty: np.ndarray
    model: np.ndarray
    data: Data
    record: dict

    @property
    def residuals(self) -> np.ndarray:
        """(model − observed) / uncertainty at the optimum."""
        return (self.model - self.observed) / self.uncertainty

    def save(self, out) -> Path:
        """Write ``fit.json``, ``fit.png`` and ``residuals.png`` into directory ``out``."""
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        atomic_write_bytes(out / "fit.json", json.dumps(self.record, indent=2).encode())
        self._plots(out)
        return out

    def _plots(self, out: Path):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        d, c = self.data, self.data.columns
        x = {"preload": c.get("preload"), "curve": c.get("displacement")}.get(d.kind)
        label = {"preload": "preload [µN]", "curve": "plate above touch-down [µm]"}.get(d.kind)
        if x is None:
            x, label = np.arange(self.observed.size), "observation"
        else:
            x = np.tile(x, self.observed.size // x.size)
        fig, ax = plt.subplots(figsize=(5.5, 3.8))
        ax.errorbar(
            x, self.observed, yerr=self.uncertainty if d.err_given else None, fmt="o", label="data"
        )
        ax.plot(x, self.model, "s", mfc="none", label="model at the fit")
        ax.set_xlabel(label)
        ax.set_ylabel(
            {"preload": "pull-off [µN]", "curve": "normal force [µN]"}.get(
                d.kind, "value [µN or µm]"
            )
        )
        ax.set_title(
            ", ".join(f"{n} = {self.values[n]:.3g} ± {self.stderr[n]:.2g}" for n in self.names),
            fontsize=8,
        )
        ax.legend()
        fig.tight_layout()
        fig.savefig(out / "fit.png", dpi=120)
        plt.close(fig)
        fig, ax = plt.subplots(figsize=(5.5, 3.0))
        ax.axhline(0.0, color="grey", lw=0.8)
        ax.plot(x, self.residuals, "o")
        ax.set_xlabel(label)
        ax.set_ylabel("(model − data)/σ" if d.err_given else "model − data")
        fig.tight_layout()
        fig.savefig(out / "residuals.png", dpi=120)
        plt.close(fig)


def _base_value(base: SetaArray, name: str) -> float:
    if name == "seta.stiffness_scale":
        return 1.0
    part, _, attr = name.partition(".")
    if name == "contact.w":
        return base.contact.work_of_adhesion
    return float(getattr(getattr(base, part), attr) if attr else getattr(base, part))


def _check_free(base: SetaArray, free) -> tuple[list, np.ndarray, np.ndarray]:
    if not isinstance(free, dict) or not free:
        raise ValueError("free must map at least one dotted parameter name to (low, high)")
    names, lo, hi = [], [], []
    for name, b in free.items():
        if name not in PSEUDO_PARAMETERS:
            try:
                if "." not in name:
                    raise ValueError(name)
                base.replace(**{name: _base_value(base, name)})
            except (ValueError, AttributeError, TypeError):
                raise ValueError(
                    f"unknown parameter name {name!r} in free (dotted names of "
                    f"SetaArray fields, e.g. 'contact.w', or one of "
                    f"{PSEUDO_PARAMETERS})"
                ) from None
        try:
            low, high = (float(v) for v in b)
        except (TypeError, ValueError):
            raise ValueError(f"free[{name!r}] = {b!r} must be a (low, high) pair") from None
        if not (math.isfinite(low) and math.isfinite(high) and low < high):
            raise ValueError(f"free[{name!r}] = ({low}, {high}): need finite low < high")
        start = _base_value(base, name)
        if not low <= start <= high:
            raise ValueError(
                f"bounds of {name!r} ({low}, {high}) exclude its start value "
                f"{start} in the base parameters; widen them or set the base"
            )
        for v in (low, high):  # both ends must be valid parameter values
            try:
                _apply(base, [name], [v])
            except ValueError as exc:
                raise ValueError(f"bound {v} of {name!r} is not allowed: {exc}") from None
        names.append(name)
        lo.append(low)
        hi.append(high)
    return names, np.array(lo), np.array(hi)


def _starts(k: int, n_starts: int) -> list[np.ndarray]:
    """Starts in the unit box: all-low and all-high corners (2 % inside), the centre, then
    alternating corners."""
    pts = [np.full(k, 0.02), np.full(k, 0.98), np.full(k, 0.5)]
    for i in range(max(0, n_starts - 3)):
        pts.append(
            np.array([0.02 if (i >> j) & 1 == 0 else 0.98 for j in range(k)])
            if k > 1
            else np.array([0.25 + 0.5 * (i % 2)])
        )
    return pts[:n_starts]


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
    if not isinstance(base, SetaArray):
        raise ValueError(f"base must be a SetaArray, got {type(base).__name__}")
    fw = forward if isinstance(forward, Forward) else Forward(kind=forward)
    if n_blocks is not None or retract_steps is not None:
        fw = replace(
            fw, n_blocks=n_blocks or fw.n_blocks, retract_steps=retract_steps or fw.retract_steps
        )
    if not isinstance(n_starts, int) or n_starts < 1:
        raise ValueError(f"n_starts = {n_starts!r} must be an integer ≥ 1")
    if not 0 < diff_step < 0.5:
        raise ValueError(f"diff_step = {diff_step!r} must be in (0, 0.5)")
    d = load_data(data)
    names, lo, hi = _check_free(base, free)
    y, err = d.observed()
    k = len(names)
    logs = (lo > 0) & (hi >= 10 * lo)
    tlo = np.where(logs, np.log(np.where(logs, lo, 1.0)), lo)
    thi = np.where(logs, np.log(np.where(logs, hi, 1.0)), hi)
    tspan = thi - tlo

    def to_param(u):
        t = tlo + tspan * np.asarray(u, dtype=float)
        return np.where(logs, np.exp(t), t)

    cache: dict = {}

    def model(u):
        key = tuple(np.round(u, 12))
        if key not in cache:
            p, scale = _apply(base, names, to_param(u))
            cache[key] = predict(d, p, stiffness_scale=scale, seed=seed, forward=fw)
        return cache[key]

    def resid(u):
        return (model(u) - y) / err

    def jac(u):
        r0 = resid(u)
        J = np.empty((y.size, k))
        for j in range(k):
            step = diff_step if u[j] + diff_step <= 1.0 else -diff_step
            v = np.array(u, dtype=float)
            v[j] += step
            J[:, j] = (resid(v) - r0) / step
        return J

    runs = []
    for u0 in _starts(k, n_starts):
        r = least_squares(
            resid,
            u0,
            jac=jac,
            bounds=(0.0, 1.0),
            x_scale=1.0,
            max_nfev=max_nfev,
            xtol=1e-4,
            ftol=1e-6,
            method="trf",
        )
        runs.append(r)
    best = min(runs, key=lambda r: r.cost)
    values = to_param(best.x)
    # d(parameter)/du at the optimum: the covariance in the parameters' own units.
    dpdu = np.where(logs, values * tspan, tspan)
    J = jac(best.x) / dpdu[None, :]
    span = hi - lo
    dof = max(y.size - k, 1)
    chi2 = float(2 * best.cost)
    s2 = 1.0 if d.err_given else chi2 / dof
    JtJ = J.T @ J
    colnorm = np.sqrt(np.diag(JtJ) * dpdu**2)
    with np.errstate(divide="ignore", invalid="ignore"):
        cov = np.linalg.pinv(JtJ, rcond=1e-12) * s2
        se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        corr = cov / np.outer(se, se)
    flat = colnorm < 1e-6 * max(colnorm.max(), 1e-300)
    se = np.where(flat, np.inf, se)
    corr = np.where(np.isfinite(corr), corr, np.nan)
    np.fill_diagonal(corr, 1.0)
    ident, notes = {}, {}
    for i, n in enumerate(names):
        why = []
        if flat[i]:
            why.append("the data do not depend on it (flat direction of the fit)")
        elif se[i] > 0.25 * span[i] or (logs[i] and se[i] > values[i]):
            why.append(
                f"its standard error {se[i]:.3g} exceeds a quarter of its bound "
                f"interval {span[i]:.3g} or its value"
            )
        others = [
            names[j]
            for j in range(k)
            if j != i and np.isfinite(corr[i, j]) and abs(corr[i, j]) > 0.95
        ]
        if others:
            why.append(f"correlation above 0.95 with {', '.join(others)}")
        ident[n] = not why
        if why:
            notes[n] = "; ".join(why)
    fitted, scale = _apply(base, names, values)
    model_best = model(best.x)
    record = {
        "data": {
            "source": d.source,
            "sha256": d.digest,
            "kind": d.kind,
            "n": d.n,
            "uncertainties_stated": d.err_given,
        },
        "free": {
            n: {
                "low": float(lo[i]),
                "high": float(hi[i]),
                "start": _base_value(base, n),
                "value": float(values[i]),
                "stderr": float(se[i]),
                "identifiable": ident[n],
                "note": notes.get(n, ""),
            }
            for i, n in enumerate(names)
        },
        "correlation": [[None if not np.isfinite(v) else float(v) for v in row] for row in corr],
        "cost": float(best.cost),
        "chi2": chi2,
        "dof": dof,
        "covariance_scale": s2,
        "observed": y.tolist(),
        "uncertainty": err.tolist(),
        "model": model_best.tolist(),
        "starts": [
            {
                "start": to_param(u0).tolist(),
                "value": to_param(r.x).tolist(),
                "cost": float(r.cost),
                "nfev": int(r.nfev),
                "njev": int(r.njev),
                "status": int(r.status),
            }
            for u0, r in zip(_starts(len(names), n_starts), runs, strict=True)
        ],
        "forward": {
            "kind": fw.kind,
            "n_blocks": fw.n_blocks,
            "retract_steps": fw.retract_steps,
            "n_sim": fw.n_sim,
            "dz_um": fw.dz,
            "retract_dz_um": fw.retract_dz,
            "seed": seed,
            "diff_step": diff_step,
            "log_scaled": {n: bool(logs[i]) for i, n in enumerate(names)},
            "mechanics": base.mechanics,
            "seta_stiffness_scale": scale,
        },
        "base_params": base.to_dict(),
        "fitted_params": fitted.to_dict(),
        "model_evaluations": len(cache),
        "wall_time_s": time.perf_counter() - t0,
        "versions": versions(),
    }
    return FitResult(
        names,
        dict(zip(names, values.tolist(), strict=True)),
        dict(zip(names, se.tolist(), strict=True)),
        corr,
        float(best.cost),
        ident,
        notes,
        {n: (float(lo[i]), float(hi[i])) for i, n in enumerate(names)},
        y,
        err,
        model_best,
        d,
        record,
    )


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


def main(argv=None) -> int:
    """``python -m gecko_agents.calibrate DATA.csv --free contact.w=0.01:0.2 ...``

    Exit status 0 on success, 2 on a usage or input error (message on stderr).
    """
    ap = argparse.ArgumentParser(
        prog="python -m gecko_agents.calibrate",
        description="Fit free parameters to a measured data set.",
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
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--starts", type=int, default=3)
    ap.add_argument("--blocks", type=int, default=None)
    ap.add_argument("--out", default=None, help="directory for fit.json and the plots")
    args = ap.parse_args(argv)
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
        print(f"error: {exc}", file=sys.stderr)
        return 2
    for n in res.names:
        flag = "" if res.identifiable[n] else f"   NOT DETERMINED: {res.notes[n]}"
        print(f"{n} = {res.values[n]:.6g} ± {res.stderr[n]:.3g}{flag}")
    print(f"cost = {res.cost:.6g}")
    if args.out:
        print(f"written to {res.save(args.out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
