"""A sweep on disk: point keys, one JSON file per finished point, and the sweep.csv table.

Layout of a sweep's ``out_dir`` (:mod:`gecko_agents.sweep`)::

    points/<key>.json   one file per finished point, written atomically
    sweep.csv           one row per point in expand_grid order, rebuilt from the point files

A point's key hashes everything that decides its result — the point function's name, its
keyword arguments, the full parameter set, the seed and the code — so a stored point is reused
only by the same computation; each point file carries the SHA-256 of its own record, so one
edited after it was written is recomputed, not reused.
"""

from __future__ import annotations

import csv
import hashlib
import io
import json
from pathlib import Path

from gecko_agents.output_paths import atomic_write_bytes
from gecko_agents.params import SetaArray
from gecko_agents.provenance import code_fingerprint, source_fingerprint
from gecko_agents.sweep.grid import SweepPoint, canonical_json

__all__ = ["point_code", "point_key", "record_digest", "read_record", "write_record", "write_table"]


def point_code(fn) -> str:
    """What identifies the code computing a point: the package's fingerprint plus, for a point
    function defined outside the package (a scenario's), its file's."""
    return code_fingerprint() + (source_fingerprint(fn) or "")


def point_key(
    fn_name: str, fn_kwargs: dict, params: SetaArray, seed: int, code: str | None = None
) -> str:
    """16 hex digits of the sha256 of the canonical JSON of (fn_name, fn_kwargs, params, seed,
    code). ``code`` identifies the code that computes the point (default: the package's
    :func:`~gecko_agents.provenance.code_fingerprint`), so that a point computed by other code
    is never reused."""
    if code is None:
        code = code_fingerprint()
    text = canonical_json(
        {
            "point_fn": fn_name,
            "fn_kwargs": fn_kwargs,
            "params": params.to_dict(),
            "seed": seed,
            "code": code,
        }
    )
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def record_digest(record: dict) -> str:
    """16 hex digits of the SHA-256 of a point record as JSON (keys sorted), its own
    ``"sha256"`` left out: what :func:`write_record` stores and :func:`read_record` checks."""
    rest = {k: v for k, v in record.items() if k != "sha256"}
    text = json.dumps(rest, sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def read_record(path: Path, key: str) -> dict | None:
    """The stored record of point ``key`` at ``path``; None if missing, unreadable, another
    point's, or edited after it was written (its ``"sha256"`` missing or not its digest)."""
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(record, dict) or record.get("key") != key:
        return None
    return record if record.get("sha256") == record_digest(record) else None


def write_record(point_dir: Path, record: dict) -> None:
    """Store a finished point as ``point_dir/<key>.json`` (atomically), with its digest."""
    record = {**record, "sha256": record_digest(record)}
    data = json.dumps(record, indent=2, allow_nan=True).encode()
    atomic_write_bytes(point_dir / f"{record['key']}.json", data)


def write_table(
    path: Path, points: list[SweepPoint], keys: list[str], names: list[str], point_dir: Path
) -> list[dict]:
    """Gather the point files of this sweep into ``sweep.csv``; return its rows as dicts.

    Columns: ``key``, ``seed``, the grid ``names``, every result field met, ``status`` ("ok",
    "error", or "missing" for a point without a file) and ``error``.
    """
    records = [read_record(point_dir / f"{k}.json", k) for k in keys]
    fields: list[str] = []
    for record in records:
        for name in (record or {}).get("result") or {}:
            if name not in fields:
                fields.append(name)
    columns = ["key", "seed", *names, *fields, "status", "error"]
    rows = []
    for point, key, record in zip(points, keys, records, strict=True):
        record = record or {"status": "missing", "result": {}, "error": None}
        result = record.get("result") or {}
        row = {"key": key, "seed": point.seed, **point.overrides}
        row |= {f: result.get(f) for f in fields}
        row |= {"status": record["status"], "error": record.get("error")}
        rows.append(row)
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow([_cell(row[c]) for c in columns])
    atomic_write_bytes(path, buf.getvalue().encode())
    return rows


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)  # every digit: the table round-trips the stored floats
    return str(value)
