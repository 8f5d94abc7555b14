"""Recorded force histories, kept apart from stepping, with atomic save/load.

A :class:`History` is what a run leaves behind: a table of scalar series (one row per recorded
step), optional per-seta arrays, the floor, and the metadata needed to reproduce and draw it.
Nothing here imports pymunk or matplotlib.

Sign conventions (units µm, µN, µs, pJ):

* ``force_normal_uN`` — total normal contact force of the floor on the tips, positive when it
  pushes the tips up (compression), negative in adhesion (tension);
* ``plate_force_y_uN`` — force the setae exert on the plate, positive up (so it equals the
  contact force in the quasi-static limit);
* per-seta ``state``: 0 free, 1 attached and sticking, 2 attached and sliding.

Run directory integrity. ``history.csv`` is plain CSV (a header of column names, one row per
record: ``pandas.read_csv(path)`` reads it). ``metadata.json``, written last, holds the run's
identifier (:meth:`History.run_id`, a hash of the parameters, seed, protocol, code version and
series) as ``"run_id"`` and the SHA-256 of each data file as ``"files"``; ``setae.npz`` carries
the identifier too; every other field of ``metadata.json`` (``dt_us``, ``n_sim``,
``record_every``, ``scale_to_array``, …) has the SHA-256 of its value in ``"fields_sha256"``.
:func:`load_history` refuses files that disagree, a table not the one the identifier was made
from or not ``n_records`` long, a file whose SHA-256 is not the recorded one (naming it), and a
metadata field edited, added or removed after the save (naming it;
``gecko_agents._run_directory`` reads and checks the files). Directories saved before the
checksums (a ``# run_id: <id>`` first line in ``history.csv``, no ``"files"``) still load,
checked by that line; those saved before the field digests, without the field check.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from gecko_agents._deprecation import renamed
from gecko_agents._run_directory import (
    ID_FIELDS,
    check_checksums,
    field_digest,
    read_arrays,
    read_metadata,
    read_series,
    saved_run_id,
)
from gecko_agents.output_paths import atomic_write_bytes, make_dir
from gecko_agents.params import SetaArray
from gecko_agents.provenance import versions

__all__ = [
    "History",
    "SCALAR_COLUMNS",
    "PER_SETA_FIELDS",
    "FILM_FIELDS",
    "STATE_FREE",
    "STATE_STICK",
    "STATE_SLIP",
    "load_history",
    "versions",
    "atomic_write_bytes",
    "invariant_violations",
    "energy_balance_error",
    "ENERGY_RTOL",
    "ENERGY_SCALE_COLUMNS",
    "RUN_FILES",
]

RUN_FILES = (
    "history.csv",
    "setae.npz",
    "metadata.json",
    "force_history.png",
    "detachment.gif",
    "detachment.mp4",
)
"""Files a run directory may hold (the history and what is drawn from it). Saving a different
run into a directory removes these files of the previous run, so no stale figure or animation
sits beside the new history."""

STATE_FREE, STATE_STICK, STATE_SLIP = 0, 1, 2

SCALAR_COLUMNS = (
    "time_us",
    "plate_x_um",
    "plate_y_um",
    "force_normal_uN",
    "force_tangential_uN",
    "plate_force_x_uN",
    "plate_force_y_uN",
    "n_attached",
    "n_sliding",
    "energy_elastic_pJ",
    "energy_kinetic_pJ",
    "energy_dissipated_pJ",
    "work_plate_pJ",
)
"""Columns of ``history.csv``; every name carries its unit."""

PER_SETA_FIELDS = (
    "tip_x_um",
    "tip_y_um",
    "force_normal_uN",
    "force_tangential_uN",
    "overlap_um",
    "state",
)
"""Per-seta arrays of shape (n_records, N) in ``setae.npz`` (optional)."""

FILM_FIELDS = (
    "film_front_x_um",
    "film_attached_um",
)
"""Per-seta arrays recorded beside :data:`PER_SETA_FIELDS` for film tips
(:class:`gecko_agents.contact.SpatulaTip`): the peel front's x [µm] and the floor length ℓ the
pad still covers [µm], NaN while the tip is free. Runs of other tips, and runs saved before
these fields existed, have none."""


@dataclass
class History:
    """A recorded run.

    Attributes
    ----------
    params : the :class:`~gecko_agents.params.SetaArray` simulated.
    seed : seed of the run's ``numpy.random.Generator``.
    scalars : dict column → array (n_records,), columns :data:`SCALAR_COLUMNS` and the
        backing's (:attr:`columns`).
    setae : dict field → array (n_records, N), fields from :data:`PER_SETA_FIELDS` (may be
        empty when per-seta recording is off).
    geometry : dict of static arrays for drawing: ``root_dx_um`` (N,) root abscissae relative
        to the plate, ``root_dy_um`` (N,) root heights relative to the plate, ``floor_x_um``,
        ``floor_y_um`` (floor polyline).
    detachments : dict of arrays, one entry per detachment event: ``seta``, ``time_us``,
        ``plate_y_um``, ``overlap_um`` (the overlap at which the tip let go), ``force_uN`` (the
        seta's normal force at its release: the law's at δ_detach where the tip passed it,
        :meth:`gecko_agents.contact.base.ContactLaw.release_force`, else its last force), and
        ``mode`` (where its detachment started, ``"edge"`` or ``"centre"``) for a law that has
        more than one (the mushroom tip).
    meta : everything else worth keeping (dt, protocol, quasi-static measure, versions…),
        with the live model's facts that :func:`gecko_agents.diagnostics.diagnose` reads
        (:data:`gecko_agents.diagnostics.MODEL_FACTS`), so a loaded run is diagnosed as it ran.
    backing : dict field → array (n_records, …) the backing recorded per record (an elastic
        strip's nodes, :meth:`gecko_agents.backing.elastic.ElasticBacking.record`; none for
        the rigid plate).
    """

    params: SetaArray
    seed: int
    scalars: dict[str, np.ndarray]
    setae: dict[str, np.ndarray] = field(default_factory=dict)
    geometry: dict[str, np.ndarray] = field(default_factory=dict)
    detachments: dict[str, np.ndarray] = field(default_factory=dict)
    meta: dict = field(default_factory=dict)
    backing: dict[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self):
        missing = [c for c in SCALAR_COLUMNS if c not in self.scalars]
        if missing:
            raise ValueError(f"History.scalars lacks columns {missing}")
        n = {len(np.asarray(v)) for v in self.scalars.values()}
        if len(n) != 1:
            raise ValueError(f"History.scalars columns differ in length: {sorted(n)}")

    @property
    def columns(self) -> tuple[str, ...]:
        """Columns of ``history.csv``: :data:`SCALAR_COLUMNS`, then the backing's, if any."""
        return SCALAR_COLUMNS + tuple(c for c in self.scalars if c not in SCALAR_COLUMNS)

    def __len__(self) -> int:
        return len(self.scalars["time_us"])

    def __getitem__(self, column: str) -> np.ndarray:
        return self.scalars[column]

    @property
    def peak_pull_off(self) -> float:
        """Largest adhesive (tensile) contact force magnitude over the run [µN], ≥ 0: over
        every step where the run kept its stepped force range
        (``meta["stepped_force_normal_range_uN"]``, which no record cadence can step over),
        else over the records."""
        stepped = self.meta.get("stepped_force_normal_range_uN")
        lowest = np.min(self.scalars["force_normal_uN"], initial=np.inf)
        if stepped:
            lowest = min(lowest, stepped[0])
        return float(max(0.0, -lowest)) if np.isfinite(lowest) else 0.0

    @classmethod
    def from_quasistatic(cls, result, params: SetaArray, seed: int = 0) -> History:
        """The same vocabulary for a quasi-static result (:mod:`gecko_agents.quasistatic`):
        one row per plate position, the agent model's columns and units, so every plot and
        comparison takes either.

        A quasi-static history has no time and no energy bookkeeping: ``time_us`` and the
        ``energy_*``/``work_plate_pJ`` columns are NaN, ``meta["solver"]`` is
        ``"quasistatic"`` (and :func:`invariant_violations` skips those columns). The plate
        force equals the contact force (static equilibrium); ``n_attached`` counts setae of the
        whole array (blocks weighted). Per-seta arrays and releases are kept when recorded.
        """
        n = len(result.plate_y)
        nan = np.full(n, np.nan)
        per = getattr(result, "per_seta", {}) or {}
        state = per.get("state")
        sliding = (
            np.sum((np.asarray(state) == STATE_SLIP) * result.weights, axis=1)
            if state is not None
            else nan
        )
        scalars = {
            "time_us": nan,
            "plate_x_um": np.zeros(n),
            "plate_y_um": result.plate_y,
            "force_normal_uN": result.force_normal,
            "force_tangential_uN": result.force_tangential,
            "plate_force_x_uN": -np.asarray(result.force_tangential, dtype=float),
            "plate_force_y_uN": result.force_normal,
            "n_attached": result.n_attached,
            "n_sliding": sliding,
            "energy_elastic_pJ": nan,
            "energy_kinetic_pJ": nan,
            "energy_dissipated_pJ": nan,
            "work_plate_pJ": nan,
        }
        setae: dict[str, np.ndarray] = {}
        if per:
            fields = {"force_normal_uN": "force", "overlap_um": "overlap", "state": "state"}
            setae = {k: np.asarray(per[v]) for k, v in fields.items() if per.get(v) is not None}
        releases = list(getattr(result, "releases", []) or [])
        det = {
            "record": np.array([r[0] for r in releases], dtype=int),
            "seta": np.array([r[1] for r in releases], dtype=int),
            "plate_y_um": np.array([result.plate_y[r[0]] for r in releases], dtype=float),
            "overlap_um": np.array([r[2] for r in releases], dtype=float),
        }
        geometry = {
            "floor_heights_um": np.asarray(result.heights),
            "weights": np.asarray(result.weights),
        }
        meta = {
            "solver": "quasistatic",
            "n_sim": int(len(result.heights)),
            "scale_to_array": 1.0,
            "versions": versions(),
        }
        return cls(params, int(seed), scalars, setae, geometry, det, meta)

    def to_dataframe(self):
        """The scalar series as a :class:`pandas.DataFrame`, one row per record, columns
        :attr:`columns` (units in the names); the run's metadata in ``df.attrs``.

        Needs pandas (``pip install 'gecko_agents[pandas]'``).
        """
        try:
            import pandas as pd
        except ImportError as err:
            raise ImportError(
                "History.to_dataframe needs pandas: pip install 'gecko_agents[pandas]'"
            ) from err
        df = pd.DataFrame({c: np.asarray(self.scalars[c]) for c in self.columns})
        df.attrs = json.loads(json.dumps(self.metadata(), default=_json_default))
        return df

    def run_id(self, params_dict: dict | None = None) -> str:
        """16 hex digits identifying this run: sha256 of the parameters, seed, protocol, code
        version (``meta["versions"]["gecko_agents"]``) and the recorded scalar series (the
        same parameters and seed give the same series, so the series only tell apart a model
        run twice or a history edited after the run). ``params_dict``: the parameters as a
        file recorded them, instead of ``params.to_dict()`` (a run saved before a parameter
        field existed recorded fewer fields)."""
        meta = self.meta
        code = (meta.get("versions") or versions()).get("gecko_agents")
        digest = hashlib.sha256()
        for c in self.columns:
            digest.update(np.ascontiguousarray(self.scalars[c], dtype=np.float64).tobytes())
        ident = {
            "params": self.params.to_dict() if params_dict is None else params_dict,
            "seed": int(self.seed),
            "protocol": meta.get("protocol"),
            "code_version": code,
            "n_records": len(self),
            "series_sha256": digest.hexdigest(),
        }
        text = json.dumps(ident, sort_keys=True, default=_json_default)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    @classmethod
    def load(cls, directory) -> History:
        """Read a run directory written by :meth:`save` (the same as :func:`load_history`)."""
        return load_history(directory)

    def metadata(self) -> dict:
        """Everything needed to reproduce the run: parameters, seed, meta, versions, run_id."""
        meta = {
            "params": self.params.to_dict(),
            "seed": int(self.seed),
            "n_records": len(self),
            "columns": list(self.columns),
        }
        meta.update(self.meta)
        meta.setdefault("versions", versions())
        meta["run_id"] = self.run_id()
        return meta

    def save(self, directory) -> Path:
        """Write ``history.csv``, ``metadata.json`` and ``setae.npz`` into ``directory``.

        Each file is written to a temporary name and renamed, so a killed run never leaves a
        half-written file under the final name; ``metadata.json`` carries :meth:`run_id` and
        the SHA-256 of the other two files and is written last, so a save interrupted half-way
        does not load.
        If ``directory`` holds a different saved run, its files (:data:`RUN_FILES`, e.g. a
        ``detachment.gif`` drawn from it) are removed first; other files are left alone. A
        folder that holds files of those names but no saved run is refused (FileExistsError
        naming them): they are not a run's to replace.
        """
        d = Path(directory)
        if d.exists() and not d.is_dir():
            raise NotADirectoryError(f"{str(d)!r} exists and is not a directory")
        run_id = self.run_id()
        saved = saved_run_id(d)
        taken = [n for n in RUN_FILES if (d / n).exists() or (d / n).is_symlink()]
        if saved is None and taken:
            raise FileExistsError(
                f"{str(d)!r} holds {', '.join(taken)} but no saved run (no metadata.json with "
                "a run_id): saving would replace files that are not a run's; choose another "
                "directory"
            )
        make_dir(d)
        if saved != run_id:
            for name in RUN_FILES:  # metadata.json before the data it describes is replaced
                (d / name).unlink(missing_ok=True)
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(self.columns)
        cols = [np.asarray(self.scalars[c]) for c in self.columns]
        for row in zip(*cols, strict=True):
            writer.writerow([repr(float(v)) for v in row])
        files = {"history.csv": buf.getvalue().encode()}
        atomic_write_bytes(d / "history.csv", files["history.csv"])
        arrays = {f"setae__{k}": np.asarray(v) for k, v in self.setae.items()}
        arrays |= {f"geometry__{k}": np.asarray(v) for k, v in self.geometry.items()}
        arrays |= {f"detachments__{k}": np.asarray(v) for k, v in self.detachments.items()}
        arrays |= {f"backing__{k}": np.asarray(v) for k, v in self.backing.items()}
        arrays["run_id"] = np.array(run_id)
        npz = io.BytesIO()
        np.savez_compressed(npz, **arrays)  # type: ignore[arg-type]
        files["setae.npz"] = npz.getvalue()
        atomic_write_bytes(d / "setae.npz", files["setae.npz"])
        meta = self.metadata()
        meta["files"] = {name: hashlib.sha256(data).hexdigest() for name, data in files.items()}
        # Each field the run id does not cover, as it will read back (a tuple as a list).
        stored = json.loads(json.dumps(meta, default=_json_default))
        meta["fields_sha256"] = {
            k: field_digest(v) for k, v in stored.items() if k not in ID_FIELDS
        }
        text = json.dumps(meta, indent=2, default=_json_default)
        atomic_write_bytes(d / "metadata.json", text.encode())
        return d


def _json_default(obj):
    if isinstance(obj, np.integer):
        return int(obj)
    if isinstance(obj, np.floating):
        return float(obj)
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(f"cannot store {type(obj).__name__} in metadata.json")


def load_history(directory) -> History:
    """Read a run saved by :meth:`History.save`, checking that its files belong together.

    Raises
    ------
    FileNotFoundError naming the missing file or directory (or the file given instead of its
    run directory), or ValueError naming the file that is corrupt, truncated (and the line
    cut short), or from another run (its run_id differs from metadata.json's), and what to do.
    """
    d = Path(directory)
    if d.exists() and not d.is_dir():
        inside = (d.parent / "metadata.json").is_file()
        raise FileNotFoundError(
            f"{str(d)!r} is a file, not a run directory"
            + (
                f"; load the run directory it is in: load_history({str(d.parent)!r})"
                if inside
                else ""
            )
        )
    if not d.is_dir():
        raise FileNotFoundError(f"run directory {str(d)!r} does not exist")
    for name in ("history.csv", "metadata.json"):
        if not (d / name).is_file():
            raise FileNotFoundError(f"{name} is missing from run directory {str(d)!r}")
    meta_path, csv_path, npz_path = d / "metadata.json", d / "history.csv", d / "setae.npz"
    meta, raw_params, params, seed, n_records = read_metadata(meta_path)
    saved_id = meta.get("run_id")
    csv_id, columns, table = read_series(csv_path, SCALAR_COLUMNS)
    if n_records is not None and len(table) != n_records:
        what = "a header and no data rows" if len(table) == 0 else f"{len(table)} data rows"
        raise ValueError(
            f"{csv_path} has {what}, but {meta_path.name} says n_records = {n_records}: the "
            "file was truncated or the save was interrupted; re-run to regenerate it"
        )
    checksums = meta.pop("files", None)  # None: saved before them, with a run_id comment line
    if checksums is None and csv_id != saved_id:
        raise ValueError(
            f"{csv_path} belongs to run {csv_id}, but {meta_path.name} to run {saved_id}: "
            "the directory mixes files of two runs (an interrupted save?); re-run to "
            "regenerate it"
        )
    groups: dict = {"setae": {}, "geometry": {}, "detachments": {}, "backing": {}}
    if npz_path.is_file():
        npz_id = read_arrays(npz_path, groups)
        if npz_id != saved_id:
            raise ValueError(
                f"{npz_path} belongs to run {npz_id}, but {meta_path.name} to run "
                f"{saved_id}: the directory mixes files of two runs; re-run to regenerate it"
            )
    if checksums is not None:
        check_checksums(d, checksums, saved_id)
    meta.pop("columns", None)
    saved_id = meta.pop("run_id", None)
    try:
        h = History(
            params=params,
            seed=seed,
            scalars={c: table[:, i] for i, c in enumerate(columns)},
            meta=meta,
            **groups,
        )
    except ValueError as err:
        raise ValueError(f"{d}: {err}") from err
    # The parameters as the file recorded them: a run saved before a field was added to the
    # parameters (now at its default) is intact, and an edit still changes them.
    if saved_id is not None and saved_id not in (h.run_id(), h.run_id(raw_params)):
        raise ValueError(
            f"{csv_path} does not hold the series run {saved_id} recorded (or "
            f"{meta_path.name}'s parameters, seed or protocol were edited): re-run to "
            "regenerate it"
        )
    return h


load = renamed("gecko_agents.history.load", "gecko_agents.history.load_history", load_history)


ENERGY_RTOL = 0.02
"""Default tolerance of the energy balance, relative to the run's energy scale (the largest of
the peak plate work, stored elastic energy and dissipated energy; :func:`energy_balance_error`).

Semi-implicit Euler conserves a linear spring's energy in the form the recorder books, so the
balance error comes from the few steps where the contact stiffness jumps: a tip snapping in
(δ = 0: the JKR branch starts at −(8/9)Fc) or off (dP/dδ → ∞ at δc). Those steps book the
contact's energy change exactly but integrate its force to first order, so the error is a
fraction ~ω_max·dt of the energy the events exchange and halves with dt (a 16-seta rod press:
5.0 %, 0.64 %, 0.54 % of the plate work at dt, dt/2, dt/4, while jump-ins released ten times
the plate work). It is therefore measured against the largest energy the run moves around,
not the plate work alone. On the test suite's 64 agent runs (linear and rod, 1–200 setae,
sliding and not, every kernel) the largest error is 0.59 %; 2 % leaves margin for those events
while a missing or double-counted term fails it (a sliding tip's Coulomb work booked as
½k_t(ξ² − ξ_new²) was off by 4.5 %).
"""


ENERGY_SCALE_COLUMNS = ("work_plate_pJ", "energy_elastic_pJ", "energy_dissipated_pJ")
"""The columns whose largest magnitude is a run's energy scale [pJ]
(:func:`energy_balance_error`)."""


def energy_balance_error(h: History) -> float:
    """max |W − (E_el + E_kin + D)| / scale over the recorded steps [-].

    W is the work the plate has done (``work_plate_pJ``), E_el the elastic energy stored in the
    setae and their contacts, E_kin the kinetic energy and D the energy dissipated (damping,
    Coulomb slip, snap-off); all in pJ, W and D cumulative from the start of the run; the
    balance is taken on the changes since the first record. The scale is
    the largest of max|W|, max|E_el| and max|D|: the energy the run exchanges. Returns 0 for a
    run in which nothing happened.
    """
    W = np.asarray(h["work_plate_pJ"], dtype=float)
    booked = h["energy_elastic_pJ"] + h["energy_kinetic_pJ"] + h["energy_dissipated_pJ"]
    if not len(W):
        return 0.0
    # Changes since the first record: a run may start from a loaded state (a model set up
    # pressed, as the pad peel's), whose stored energy no plate work paid for.
    err = float(np.max(np.abs((W - W[0]) - (booked - booked[0]))))
    scale = max(float(np.max(np.abs(h[c]), initial=0.0)) for c in ENERGY_SCALE_COLUMNS)
    if scale == 0.0:
        return 0.0 if err == 0.0 else np.inf
    return err / scale


def _law_bounds(h: History) -> tuple[float, float, float]:
    """(largest tension one tip holds [µN], overlap below which no tip stays attached [µm],
    energy tolerance factor [-]) of a history's tip law: the bounds the recorder wrote
    (:func:`gecko_agents.contact.bounds`); a history without them (older runs, quasi-static
    results) has the JKR sphere's."""
    c = h.params.contact
    rate = math.isfinite(getattr(c, "crack_speed", math.inf))
    bounds = h.meta.get("tip_bounds") or {
        "max_tension_uN": math.inf if rate else c.pull_off_force,
        "detach_overlap_um": 20.0 * c.snap_off_overlap if rate else c.snap_off_overlap,
        "rate_dependent": rate,
    }
    # Older histories lack the law's factor: 2 for crack kinetics, as it has now.
    factor = bounds.get("energy_tolerance_factor", 2.0 if bounds["rate_dependent"] else 1.0)
    return float(bounds["max_tension_uN"]), float(bounds["detach_overlap_um"]), factor


def invariant_violations(
    h: History, rtol: float = 1e-9, energy_rtol: float | None = None
) -> list[str]:
    """Force-history invariants that every recorded step must satisfy; [] when all hold.

    Parameters
    ----------
    rtol : relative slack of the force bounds [-].
    energy_rtol : tolerance of the energy balance relative to the run's energy scale [-];
        default :data:`ENERGY_RTOL` times the tip law's ``energy_tolerance_factor`` (2 for
        crack kinetics and the spatula, whose books carry a first-order error that halves with
        dt; the reasons are stated with the laws); ``False`` skips it (for histories without
        energy bookkeeping).

    * every recorded value is finite;
    * energy balance: plate work = elastic + kinetic + dissipated energy on every recorded
      step, within ``energy_rtol`` of the run's energy scale (:func:`energy_balance_error`);
    * no contact force while no tip is attached;
    * elastic tip laws: total tension ≤ n_attached·Fc, and (per-seta records) each tip's
      tension ≤ Fc (a rate-dependent contact may hold more: its crack lags);
    * (per-seta records) a free tip carries no force; an attached tip has δ ≥ the law's
      detachment overlap (δc for the JKR sphere);
    * once every tip has let go at the end of a run, the force is zero.
    """
    out = []
    Fc, detach, factor = _law_bounds(h)
    if energy_rtol is None:
        energy_rtol = ENERGY_RTOL * factor
    quasi_static = h.meta.get("solver") == "quasistatic"
    untimed = (
        "time_us",
        "n_sliding",
        "energy_elastic_pJ",
        "energy_kinetic_pJ",
        "energy_dissipated_pJ",
        "work_plate_pJ",
    )
    if quasi_static or h.meta.get("energy_complete") is False:
        energy_rtol = False  # no (complete) energy bookkeeping: quasi-static, elastic backing
    for name in SCALAR_COLUMNS:  # a backing's own columns may hold NaN (no front)
        col = h.scalars[name]
        if quasi_static and name in untimed:
            continue
        if not np.all(np.isfinite(col)):
            out.append(f"{name} has non-finite values")
    n_att = h["n_attached"]
    fn, ft = h["force_normal_uN"], h["force_tangential_uN"]
    if np.any(fn[n_att == 0] != 0) or np.any(ft[n_att == 0] != 0):
        out.append("contact force while no tip is attached")
    if math.isfinite(Fc) and np.any(-fn > n_att * Fc * (1 + rtol)):  # inf: no bound
        out.append("total tension exceeds n_attached·Fc")
    if h.setae:
        P, state = h.setae["force_normal_uN"], h.setae["state"]
        if np.any(P < -Fc * (1 + rtol)):
            out.append("a tip pulls harder than Fc")
        if np.any(P[state == STATE_FREE] != 0):
            out.append("a free tip carries a contact force")
        d = h.setae["overlap_um"][state != STATE_FREE]
        if np.any(d < detach - rtol * abs(detach)):
            out.append("an attached tip is past the snap-off overlap δc")
    if energy_rtol is not False and len(h):
        err = energy_balance_error(h)
        if not err <= energy_rtol:
            out.append(
                f"energy balance off by {err:.3g} of the run's energy scale "
                f"(tolerance {energy_rtol:g})"
            )
    if len(h) and n_att[-1] == 0 and fn[-1] != 0:
        out.append("force is not zero after full detachment")
    return out
