"""The published measurements of the literature comparison (:mod:`gecko_agents.studies.
validation`), read from the data file :data:`gecko_agents.data.LITERATURE_ROWS` (TOML): one
table per row with the source cited in full, the text we read (``quote``, word for word, with
the address it came from in ``read_at``), their value as printed, and the parameters our number
uses, each cited or assumed with the reason and, where a number, its plausible range.

Nothing here is computed; the file's header comment describes each field. :func:`load_rows`
fills the optional fields with ``None`` so that the study reads every row the same way.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from gecko_agents.data import LITERATURE_ROWS

OPTIONAL = ("theirs_value", "scatter", "compare", "expect", "ours", "unscored",
            "trend_resolution")  # fmt: skip
"""Row fields that may be absent from the file (``None`` in the rows :func:`load_rows` gives)."""
REQUIRED = ("id", "source", "read_at", "quote", "measured", "theirs", "kind", "cause")
PARAM_FIELDS = ("name", "value", "unit", "status", "why")


def load_rows(path: Path = LITERATURE_ROWS) -> list[dict]:
    """The rows of the literature data file at ``path``, each a dict with every field of
    :data:`REQUIRED` and :data:`OPTIONAL` and a ``params`` list (each parameter with a
    ``range``, ``None`` where the file gives none). A row missing a required field, or with a
    duplicate id, is refused with its id and the field."""
    with open(path, "rb") as f:
        rows = tomllib.load(f)["rows"]
    seen = set()
    out = []
    for i, raw in enumerate(rows):
        name = raw.get("id", f"row {i}")
        missing = [k for k in REQUIRED if k not in raw]
        if missing:
            raise ValueError(f"{path.name}: row {name!r} lacks the field(s) {missing}")
        if name in seen:
            raise ValueError(f"{path.name}: row id {name!r} appears twice")
        seen.add(name)
        row = {k: raw.get(k) for k in REQUIRED + OPTIONAL}
        row["params"] = []
        for p in raw.get("params", []):
            lacking = [k for k in PARAM_FIELDS if k not in p]
            if lacking:
                raise ValueError(f"{path.name}: row {name!r}, parameter {p.get('name')!r} "
                                 f"lacks {lacking}")  # fmt: skip
            row["params"].append({**{k: p[k] for k in PARAM_FIELDS}, "range": p.get("range")})
        out.append(row)
    return out


ROWS: list[dict] = load_rows()
