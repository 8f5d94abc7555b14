"""A parameter set as a table: dotted name, value, unit, meaning and paper equation.

Units, meanings and equation numbers are read from the docstrings of
:mod:`gecko_agents.params` (the ``name : text [unit] … (eq N)`` entries of each dataclass's
Attributes section, and the docstrings of the derived properties), so the table and the code
cannot drift apart. Used by ``gecko-agents params``.
"""

from __future__ import annotations

import dataclasses
import inspect
import re

__all__ = ["parameter_table"]

_EXTRA_DOCS = {
    "mechanics": (
        "-",
        "seta model: 'linear' (2×2 beam stiffness), 'rod' (rotary bending spring + axial "
        "spring) or 'elastica' (a bar chain that bends and buckles, for pillars)",
        "eq 20–21",
    ),
}


def _tip_doc() -> tuple[str, str, str]:
    """(unit, meaning, equation) of ``tip``: every law of the contact registry by name, with
    the first clause of its docstring, so a new law is listed as soon as it is registered."""
    from gecko_agents.contact.registry import TIP_LAWS

    laws = []
    for name, law in TIP_LAWS.items():
        first = " ".join((inspect.getdoc(law) or "").split("\n\n", 1)[0].split())
        clause = re.split(r" \(|: |; |\. ", first, maxsplit=1)[0].rstrip(".").replace("``", "")
        laws.append(f"'{name}' ({clause[:1].lower() + clause[1:]})")
    return "-", "the tip's contact law (gecko_agents.contact): " + ", ".join(laws), "eq 1–15"


_EQ = re.compile(r"\beq ([0-9][0-9–\-, ]*[0-9])")


def _field_docs(cls) -> dict[str, str]:
    """``name : text`` entries of a dataclass docstring's Attributes section."""
    doc = inspect.getdoc(cls) or ""
    if "Attributes" not in doc:
        return {}
    out: dict[str, str] = {}
    current: list[str] = []
    for line in doc.split("Attributes", 1)[1].splitlines()[2:]:
        m = re.match(r"^([A-Za-z_][\w]*(?:, [A-Za-z_]\w*)*) : (.*)$", line)
        if m:
            current = [n.strip() for n in m.group(1).split(",")]
            for n in current:
                out[n] = m.group(2)
        elif line.startswith(" ") and current:
            for n in current:
                out[n] += " " + line.strip()
        elif not line.strip():
            current = []
    return out


def _split_doc(text: str, group_eq: str = "") -> tuple[str, str, str]:
    """(unit, meaning, equation) from a docstring entry ``… [unit] …``."""
    m = re.search(r"\[([^\]]+)\]", text)
    unit = m.group(1) if m else "-"
    meaning = (text[: m.start()] + text[m.end() :]) if m else text
    meaning = re.sub(r":\w+:`~?([^`]+)`", r"\1", meaning.replace("``", ""))
    meaning = re.sub(r"\s+", " ", meaning).strip().rstrip(".")
    meaning = re.sub(r"^(\w+) : ", r"\1: ", re.sub(r"\s*\(eq [^)]*\)$", "", meaning))
    meaning = re.sub(r"\s+([,.;)])", r"\1", meaning).strip().rstrip(".").strip()
    eq = _EQ.search(text)
    return unit, meaning, (f"eq {eq.group(1)}" if eq else group_eq)


def parameter_table(params) -> list[tuple[str, str, str, str, str]]:
    """Rows (dotted name, value, unit, meaning, paper equation) of a :class:`SetaArray`, then
    its derived quantities (names in parentheses). Units and meanings come from the docstrings
    of :mod:`gecko_agents.params`."""
    rows = []
    for f in dataclasses.fields(params):
        sub = getattr(params, f.name)
        if not dataclasses.is_dataclass(sub):
            unit, meaning, eq = (
                _tip_doc() if f.name == "tip" else _EXTRA_DOCS.get(f.name, ("-", "", ""))
            )
            rows.append((f.name, repr(sub), unit, meaning, eq))
            continue
        first = (inspect.getdoc(type(sub)) or "").split("\n", 1)[0]
        group_eq = _EQ.search(first)
        docs = _field_docs(type(sub))
        for g in dataclasses.fields(sub):
            unit, meaning, eq = _split_doc(
                docs.get(g.name, ""), f"eq {group_eq.group(1)}" if group_eq else ""
            )
            rows.append((f"{f.name}.{g.name}", _fmt(getattr(sub, g.name)), unit, meaning, eq))
    derived = [
        (
            params.contact,
            "contact",
            ("work_of_adhesion", "E_star", "pull_off_force", "snap_off_overlap"),
        ),
        (params, "", ("axial_stiffness", "bending_stiffness", "Ky", "Kx")),
    ]
    for obj, prefix, names in derived:
        for name in names:
            doc = inspect.getdoc(getattr(type(obj), name)) or ""
            unit, meaning, eq = _split_doc(doc)
            label = f"({prefix + '.' if prefix else ''}{name})"
            rows.append((label, _fmt(getattr(obj, name)), unit, meaning, eq))
    return rows


def _fmt(value) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value)
