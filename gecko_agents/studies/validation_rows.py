"""The published measurements of the literature comparison (:mod:`gecko_agents.studies.
validation`), read from the data file :data:`gecko_agents.data.LITERATURE_ROWS` (TOML): one
table per row with the source cited in full, the text we read (``quote``, word for word, with
the address it came from in ``read_at``), their value as printed, how a magnitude agrees
(their scatter or a relative tolerance, on the nearer bound for a bounded quantity; a factor
band for a trend or a self-consistency check; for a direction stated in words the smallest
effect the words state), the independent measurement it comes from, and the parameters our
number uses, each cited or assumed with the reason and, where a number, its plausible range.

Nothing here is computed; the file's header comment describes each field. :func:`load_rows`
resolves each row's source and shared parameters and fills the optional fields with ``None``,
so that the study reads every row the same way.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from gecko_agents.data import LITERATURE_ROWS

KINDS = ("experiment", "model", "self-consistency")
"""What a row compares with: a measurement, another model (a simulation or a published law),
or the package's own closed form or run."""
STATUSES = ("scored", "pending", "out of scope", "not read", "calibration", "derived")
"""``scored``, or why not: the physics it needs is not in the package yet (``pending``), the
mechanism is one the package does not model, the number could not be read, the point an
unreported parameter is calibrated on (``calibration``: declared, never scored), or a number
the model ties to another row's (``derived``: one model number scores one observation)."""
MAGNITUDE_KINDS = ("experiment", "model")
"""The kinds whose ``compare = "value"`` rows are magnitude rows: the report's headline."""
REQUIRED = ("id", "source", "kind", "read_at", "quote", "measured", "theirs", "quantity", "cause")
OPTIONAL = (
    "theirs_value",
    "scatter",
    "scatter_why",
    "band",
    "band_why",
    "min_effect",
    "compare",
    "expect",
    "ours",
    "unscored",
    "tolerance",
    "tolerance_why",
    "bounded",
    "measurement",
    "in_words",
)
"""Row fields that may be absent from the file (``None`` in the rows :func:`load_rows` gives)."""
PARAM_FIELDS = ("name", "value", "unit", "status", "why")
PARAM_STATUSES = ("cited", "cited range", "assumed")


def _param(where: str, p: dict) -> dict:
    lacking = [k for k in PARAM_FIELDS if k not in p]
    if lacking:
        raise ValueError(f"{where}, parameter {p.get('name')!r} lacks {lacking}")
    if p["status"] not in PARAM_STATUSES:
        raise ValueError(
            f"{where}, parameter {p['name']!r}: status {p['status']!r} is not one "
            f"of {PARAM_STATUSES}"
        )
    return {**{k: p[k] for k in PARAM_FIELDS}, "range": p.get("range")}


def _check(where: str, row: dict) -> None:
    """Refuse a row whose fields contradict each other (named in the message)."""
    if row["kind"] not in KINDS:
        raise ValueError(f"{where}: kind {row['kind']!r} is not one of {KINDS}")
    if row["status"] not in STATUSES:
        raise ValueError(f"{where}: status {row['status']!r} is not one of {STATUSES}")
    if row["status"] != "scored":
        if not row["unscored"]:
            raise ValueError(f"{where}: a row with status {row['status']!r} says why (unscored)")
        return  # it may name ours: shown, not scored
    if row["compare"] not in ("value", "trend") or not row["ours"]:
        raise ValueError(f"{where}: a scored row needs compare ('value' or 'trend') and ours")
    ways = [k for k in ("scatter", "tolerance", "band", "min_effect") if row[k] is not None]
    if not ways:
        raise ValueError(
            f"{where}: a scored row states how a magnitude agrees (scatter, tolerance, band or "
            "min_effect)"
        )
    if row["min_effect"] is not None and row["theirs_value"] is not None:
        raise ValueError(f"{where}: min_effect is for a direction in words (no theirs_value)")
    if row["theirs_value"] is None and row["min_effect"] is None:
        raise ValueError(f"{where}: without theirs_value the row needs min_effect")
    if (row["band"] is not None or row["min_effect"] is not None) and not row["band_why"]:
        raise ValueError(f"{where}: band or min_effect needs its reason (band_why)")
    if row["band"] is not None and row["band"] <= 1.0:
        raise ValueError(f"{where}: band = {row['band']!r} must be a factor > 1")
    _check_magnitude(where, row)


def _check_magnitude(where: str, row: dict) -> None:
    """A magnitude row (a value compared, of an experiment or another model) agrees within
    their scatter or a relative tolerance, never a factor band; a tolerance says why; a
    bounded quantity lies in [0, 1]."""
    if row["tolerance"] is not None:
        if not 0.0 < row["tolerance"] < 1.0:
            raise ValueError(f"{where}: tolerance = {row['tolerance']!r} must be in (0, 1)")
        if not row["tolerance_why"]:
            raise ValueError(f"{where}: tolerance needs its reason (tolerance_why)")
        if row["compare"] != "value":
            raise ValueError(f"{where}: a tolerance is for compare = 'value' rows")
    if row["bounded"] and not 0.0 <= row["theirs_value"] <= 1.0:
        raise ValueError(f"{where}: bounded, but theirs_value = {row['theirs_value']!r}")
    if row["compare"] == "value" and row["kind"] in MAGNITUDE_KINDS and not row["in_words"]:
        if row["scatter"] is None and row["tolerance"] is None:
            raise ValueError(
                f"{where}: a magnitude row agrees within their scatter or a tolerance "
                "(±25 % where none is stated), not a factor band"
            )


def load_rows(path: Path = LITERATURE_ROWS) -> list[dict]:
    """The rows of the literature data file at ``path``: each a dict with every field of
    :data:`REQUIRED` and :data:`OPTIONAL`, ``status`` (default ``"scored"``), ``source`` the
    citation in full, and ``params``: the shared parameters it ``uses``, then its own (each
    with a ``range``, ``None`` where the file gives none). A row missing a field, with a
    repeated id, an unknown source or shared parameter, or fields that contradict each other
    is refused with its id and the field."""
    with open(path, "rb") as f:
        data = tomllib.load(f)
    sources, shared = data.get("sources", {}), data.get("params", {})
    seen, out = set(), []
    for i, raw in enumerate(data["rows"]):
        where = f"{path.name}: row {raw.get('id', i)!r}"
        missing = [k for k in REQUIRED if k not in raw]
        if missing:
            raise ValueError(f"{where} lacks the field(s) {missing}")
        if raw["id"] in seen:
            raise ValueError(f"{where} appears twice")
        seen.add(raw["id"])
        if raw["source"] not in sources:
            raise ValueError(f"{where}: source {raw['source']!r} is not in [sources]")
        unknown = [k for k in raw.get("uses", []) if k not in shared]
        if unknown:
            raise ValueError(f"{where}: uses {unknown}, not in [params]")
        row = {k: raw.get(k) for k in REQUIRED + OPTIONAL}
        row["source"] = sources[raw["source"]]
        row["status"] = raw.get("status", "scored")
        row["params"] = [_param(where, shared[k]) for k in raw.get("uses", [])]
        row["params"] += [_param(where, p) for p in raw.get("params", [])]
        row["measurement"] = row["measurement"] or raw["id"]
        row["bounded"] = bool(row["bounded"])
        row["in_words"] = bool(row["in_words"])
        _check(where, row)
        out.append(row)
    _one_number_one_observation(path, out)
    return out


def _one_number_one_observation(path: Path, rows: list[dict]) -> None:
    """Refuse two scored rows that name the same ``ours``: one model number never scores two
    observations."""
    seen: dict[str, str] = {}
    for r in rows:
        if r["status"] != "scored":
            continue
        if r["ours"] in seen:
            raise ValueError(
                f"{path.name}: rows {seen[r['ours']]!r} and {r['id']!r} both score ours = "
                f"{r['ours']!r}: one model number scores one observation"
            )
        seen[r["ours"]] = r["id"]


ROWS: list[dict] = load_rows()
