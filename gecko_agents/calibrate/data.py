"""Measured data for :mod:`gecko_agents.calibrate`: read, check units and convert to µm, µN.

Columns use the package's names with a unit suffix (``preload_uN``, ``pull_off_mN``,
``displacement_um``, ...); the set of columns decides the kind of data set (pull-off against
preload, a force curve, or a snap-off). See :mod:`gecko_agents.calibrate` for the kinds.
"""

from __future__ import annotations

import csv
import hashlib
import io
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

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
    pull_off_sign: int = 1
    """+1 when pull-offs were given as magnitudes (> 0), −1 when in the package's sign
    convention (tension negative); ``columns["pull_off"]`` holds magnitudes either way."""

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
    sign = 1
    if "pull_off" in found:
        found["pull_off"], sign = _pull_off_magnitudes(found["pull_off"])
    return Data(kind, found, bool(errs), digest, source, extra, sign)


def _pull_off_magnitudes(pull_off: np.ndarray) -> tuple[np.ndarray, int]:
    """Pull-offs as magnitudes [µN], and the sign convention they were given in.

    Either convention is accepted as long as one is used throughout: all ≥ 0 (magnitudes, +1)
    or all ≤ 0 (the package's convention, tension negative: −1). Mixed signs are refused,
    naming the rows, since a pull-off is a tension and cannot change sign within a data set.
    """
    if np.all(pull_off >= 0):
        return pull_off, 1
    if np.all(pull_off <= 0):
        return -pull_off, -1
    pos, neg = np.flatnonzero(pull_off > 0) + 1, np.flatnonzero(pull_off < 0) + 1
    raise ValueError(
        f"column pull_off mixes signs (positive in rows {pos.tolist()}, negative in rows "
        f"{neg.tolist()}): give every pull-off as a magnitude (> 0) or every one in the "
        "package's sign convention (tension < 0)"
    )
