"""The validity items of several runs as one markdown table (``renders/paper_comparison.md``)."""

from __future__ import annotations

from gecko_agents.diagnostics.limits import LIMITS

__all__ = ["validity_table"]


def _validity_of(obj) -> dict | None:
    meta = getattr(obj, "meta", obj)
    if not isinstance(meta, dict):
        return None
    if "items" in meta:
        return meta
    return meta.get("validity")


def validity_table(runs, labels=None) -> str:
    """Markdown table of the validity items of several runs.

    ``runs``: histories, metadata dicts (with ``"validity"``) or validity dicts, or a dict
    label → one of those. Each cell is the value, with ✗ when it violates its limit and "—"
    where the item does not apply.
    """
    if isinstance(runs, dict) and _validity_of(runs) is None:
        labels, runs = list(runs), list(runs.values())
    runs = list(runs)
    labels = list(labels) if labels is not None else [f"run {i + 1}" for i in range(len(runs))]
    names = list(LIMITS)
    head = "| run | " + " | ".join(f"{n} ({LIMITS[n][0]} {LIMITS[n][1]:g})" for n in names)
    lines = [head + " |", "|" + " --- |" * (len(names) + 1)]
    for label, run in zip(labels, runs, strict=True):
        v = _validity_of(run) or {"items": {}}
        cells = []
        for n in names:
            it = v["items"].get(n)
            if it is None or it["ok"] is None:
                cells.append("—")
            elif it["value"] is None:
                cells.append("ok" if it["ok"] else "✗")
            else:
                cells.append(f"{it['value']:.3g}" + ("" if it["ok"] else " ✗"))
        lines.append(f"| {label} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"
