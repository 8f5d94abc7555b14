"""Reading a run directory's files and checking that they belong together, for
:func:`gecko_agents.history.load_history` (which states the integrity rules): ``metadata.json``'s
fields against their digests, each data file against its SHA-256, ``history.csv``'s table and
``setae.npz``'s arrays."""

from __future__ import annotations

import hashlib
import io
import json
import re
import zipfile
import zlib
from pathlib import Path

import numpy as np

from gecko_agents.params import SetaArray, check_seed

ID_FIELDS = ("params", "seed", "n_records", "columns", "run_id", "files", "fields_sha256")
"""Fields of metadata.json that the run id, the checksums or the table's own checks cover;
every other field carries its digest in ``"fields_sha256"``."""


FIELDS_REQUIRED_FROM = (0, 2)
"""The package version from which every saved run carries ``fields_sha256``."""


def _version(meta: dict) -> tuple[int, int]:
    """(major, minor) of the gecko_agents version a run recorded; (0, 0) if unreadable."""
    text = str((meta.get("versions") or {}).get("gecko_agents", ""))
    m = re.match(r"(\d+)\.(\d+)", text)
    return (int(m.group(1)), int(m.group(2))) if m else (0, 0)


def field_digest(value) -> str:
    """16 hex digits of the SHA-256 of a metadata field's value as JSON (keys sorted)."""
    text = json.dumps(value, sort_keys=True, allow_nan=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def check_fields(meta_path: Path, meta: dict) -> None:
    """Refuse a metadata.json field (dt_us, n_sim, record_every, scale_to_array, …) edited,
    added or removed after the save, naming it; pops ``"fields_sha256"`` (absent from runs
    saved before it: nothing to check)."""
    digests = meta.pop("fields_sha256", None)
    if digests is None:
        if _version(meta) < FIELDS_REQUIRED_FROM:
            return  # saved before the digests existed
        raise ValueError(
            f"{meta_path}: the field 'fields_sha256' was removed from it after the run was "
            "saved (every run of this version carries it); re-run to regenerate the directory"
        )
    if not isinstance(digests, dict):
        raise ValueError(f"{meta_path}: fields_sha256 = {digests!r} is not an object")
    names = [k for k in meta if k not in ID_FIELDS]
    for key in sorted(set(names) | set(digests)):
        if key not in meta or key not in digests:
            done = "removed from" if key not in meta else "added to"
            raise ValueError(
                f"{meta_path}: the field {key!r} was {done} it after the run was saved; "
                "re-run to regenerate the directory"
            )
        if field_digest(meta[key]) != digests[key]:
            raise ValueError(
                f"{meta_path}: {key} = {str(meta[key])[:80]} is not the value the run saved "
                "(the file was edited after the save); re-run to regenerate the directory"
            )


def saved_run_id(d: Path) -> str | None:
    """The run_id in ``d/metadata.json``, or None (no file, unreadable, or none recorded)."""
    try:
        meta = json.loads((d / "metadata.json").read_text())
        return meta.get("run_id") if isinstance(meta, dict) else None
    except (OSError, ValueError):
        return None


def check_checksums(d: Path, checksums: dict, run_id) -> None:
    """Refuse a file of ``d`` whose SHA-256 is not the one ``metadata.json`` recorded."""
    for name, expected in checksums.items():
        path = d / name
        if not path.is_file():
            raise FileNotFoundError(f"{name} is missing from run directory {str(d)!r}")
        if hashlib.sha256(path.read_bytes()).hexdigest() != expected:
            raise ValueError(
                f"{path} is not the file run {run_id} saved: its SHA-256 is not the one "
                "metadata.json recorded (edited, truncated or of another run); re-run it"
            )


def read_metadata(meta_path: Path) -> tuple[dict, dict, SetaArray, int, int | None]:
    """metadata.json as (the rest of its dict, its params as recorded, params, seed,
    n_records or None)."""
    try:
        meta = json.loads(meta_path.read_text(encoding="utf-8"))
        if not isinstance(meta, dict):
            raise TypeError(f"it holds a {type(meta).__name__}, not an object")
    except (ValueError, TypeError) as err:
        # UnicodeDecodeError and JSONDecodeError are ValueErrors: a binary or garbled file.
        raise ValueError(f"{meta_path} is not a gecko_agents metadata file: {err}") from err
    check_fields(meta_path, meta)
    try:
        raw_params = meta.pop("params")
        params = SetaArray.from_dict(raw_params)
        seed = check_seed(meta.pop("seed"), "seed")
        n_records = meta.pop("n_records", None)
        if n_records is not None:
            n_records = check_seed(n_records, "n_records")
    except (ValueError, KeyError, TypeError, AttributeError) as err:
        raise ValueError(f"{meta_path} is not a gecko_agents metadata file: {err}") from err
    return meta, raw_params, params, seed, n_records


def read_series(
    csv_path: Path, first_columns: tuple[str, ...]
) -> tuple[str | None, tuple[str, ...], np.ndarray]:
    """history.csv as (the run_id of its ``#`` header line, which files saved before the
    checksums carry, else None; its columns; the table, one row per record); refuses a table
    that does not start with ``first_columns``."""
    try:
        lines = csv_path.read_text(encoding="utf-8").split("\n")
    except ValueError as err:  # UnicodeDecodeError: a binary file
        raise ValueError(f"{csv_path} is not a history table: {err}") from err
    csv_id = None
    n_comments = 0
    while lines and lines[0].startswith("#"):
        key, _, value = lines.pop(0)[1:].partition(":")
        n_comments += 1
        if key.strip() == "run_id":
            csv_id = value.strip()
    header = lines[0].split(",") if lines else []
    columns = tuple(header)
    if columns[: len(first_columns)] != first_columns or len(set(columns)) < len(columns):
        raise ValueError(f"{csv_path} has columns {header}, expected {list(first_columns)} first")
    return csv_id, columns, _table(csv_path, lines[1:], len(columns), n_comments + 2)


def _table(csv_path: Path, rows: list[str], n_columns: int, first_line: int) -> np.ndarray:
    """The data rows of history.csv as an array (one row per record); refuses, naming the
    line, a last row without its line break (every row a save writes ends with one: the file
    was cut short), a row of another length or a value that is not a number."""
    if rows and rows[-1]:
        raise ValueError(
            f"{csv_path} line {first_line + len(rows) - 1} ends without its line break "
            f"({len(rows[-1].split(','))} of its {n_columns} values): the file was cut short "
            "(truncated, or its save interrupted); re-run to regenerate it"
        )
    rows = rows[:-1]
    for i, row in enumerate(rows):
        if len(row.split(",")) != n_columns:
            raise ValueError(
                f"{csv_path} line {first_line + i} has {len(row.split(','))} of its "
                f"{n_columns} values: the table was edited or damaged; re-run to regenerate it"
            )
    try:
        body = "\n".join(rows)
        if not body.strip():
            return np.zeros((0, n_columns))
        return np.loadtxt(io.StringIO(body), delimiter=",", ndmin=2)
    except ValueError as err:
        for i, row in enumerate(rows):  # the error path only: name the line
            for value in row.split(","):
                try:
                    float(value)
                except ValueError:
                    raise ValueError(
                        f"{csv_path} line {first_line + i} holds {value[:40]!r}, not a number: "
                        "the table was edited or damaged; re-run to regenerate it"
                    ) from err
        raise ValueError(f"{csv_path} cannot be read as numbers: {err}") from err


def read_arrays(npz_path: Path, groups: dict) -> str | None:
    """Fill ``groups`` (setae, geometry, detachments) from setae.npz; returns its run_id."""
    npz_id = None
    try:
        with np.load(npz_path) as z:
            for key in z.files:
                if key == "run_id":
                    npz_id = str(z[key])
                    continue
                group, _, name = key.partition("__")
                groups[group][name] = z[key]
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile, zlib.error) as err:
        raise ValueError(
            f"{npz_path} is corrupt or truncated ({type(err).__name__}: {err}); "
            "re-run to regenerate it"
        ) from err
    return npz_id
