"""Warnings as a user of the command line reads them: short lines, one per item per run family.

The library warns through the standard :mod:`warnings` machinery (a
:class:`~gecko_agents.diagnostics.ValidityWarning` per violated validity item of every run,
:mod:`gecko_agents.diagnostics`), so a library user filters them as usual. Only the command line
and the main job (``gecko-agents run``/``sweep``/``reproduce``, ``python
scenarios/reproduce_paper.py``) read them through :class:`WarningLog`, which replaces Python's
``file.py:533: ValidityWarning: …`` decoration, for the duration of a ``with`` block, by

* at ``verbosity`` 1 (the default): one line per item per run family, written when the family
  ends: the values met, the limit, the number of runs, and what to do;
* at 0 (``--quiet``): nothing but the closing summary line;
* at 2 (``--verbose``): every warning as it comes, in full (still one line, no source line).

:func:`summary_line` gives the closing line of a run or of the main job, e.g.
``validity: 3 items outside range in 24 runs (a_over_R in 24, …) — see the report's table``.
"""

from __future__ import annotations

import re
import sys
import warnings
from dataclasses import dataclass, field

from gecko_agents.diagnostics import LIMITS, ValidityWarning

__all__ = [
    "ADVICE",
    "WarningLog",
    "summary_line",
    "validity_counts",
    "add_verbosity_arguments",
    "verbosity",
]

ADVICE = {
    "a_over_R": "the tip's forces are JKR's formula, not a sphere's (JKR needs a ≪ R)",
    "tabor": "below μ ≈ 5 Maugis–Dugdale or DMT apply, not JKR",
    "linear_deflection": 'the small-deflection beam left its range: use mechanics = "rod"',
    "quasi_static": "slow the plate: the seta's damper costs a held tip that force",
    "time_step": "pass a smaller dt",
    "touched": "press deeper or slow the plate",
    "crack_deborah": "slow the plate or raise contact.crack_speed",
}
"""Validity item → what a user can do about it, for the one-line report."""

_VALIDITY = re.compile(r"^validity: (\w+) = (\S+) violates value (\S+) (\S+):")


@dataclass
class _Family:
    """What one run family (a study, a run file) warned: item → values; other messages."""

    values: dict = field(default_factory=dict)
    other: dict = field(default_factory=dict)


class WarningLog:
    """Within ``with WarningLog(verbosity, stream):``, warnings are collected and reported as
    short lines (module docstring); :meth:`family` names the run family they belong to.

    Parameters
    ----------
    verbosity : int
        0 quiet, 1 one line per item per family, 2 every warning as it comes.
    stream : file-like
        Where the lines go (default ``sys.stderr``).
    """

    def __init__(self, verbosity: int = 1, stream=None):
        self.verbosity = verbosity
        self.stream = stream
        self.families: dict[str, _Family] = {}
        self._current = ""
        self._catch = None

    def __enter__(self):
        self._catch = warnings.catch_warnings()
        self._catch.__enter__()
        warnings.simplefilter("always", ValidityWarning)  # one per run, for the counts
        warnings.showwarning = self._show
        return self

    def __exit__(self, *exc):
        self._catch.__exit__(*exc)
        self.end_family()
        return False

    def _out(self, text: str) -> None:
        print(text, file=self.stream or sys.stderr, flush=True)

    def family(self, name: str) -> None:
        """Report the family before (if any) and collect the next warnings under ``name``."""
        self.end_family()
        self._current = name

    def _show(self, message, category, filename, lineno, file=None, line=None):
        text = str(message).strip()
        fam = self.families.setdefault(self._current, _Family())
        match = _VALIDITY.match(text)
        if match and issubclass(category, ValidityWarning):
            fam.values.setdefault(match[1], []).append(match[2])
        else:
            first = text.splitlines()[0] if text else category.__name__
            fam.other[first] = fam.other.get(first, 0) + 1
        if self.verbosity >= 2:
            self._out(f"{self._prefix(self._current)}{category.__name__}: {' '.join(text.split())}")

    @staticmethod
    def _prefix(name: str) -> str:
        return f"{name}: " if name else ""

    def lines(self, name: str) -> list[str]:
        """The short lines of family ``name`` (item: values, limit, runs, what to do)."""
        fam = self.families.get(name)
        if fam is None:
            return []
        out = []
        for item, vals in fam.values.items():
            nums = sorted({float(v) for v in vals if v != "?"})
            shown = "?" if not nums else f"{nums[0]:.3g}"
            if len(nums) > 1:
                shown += f"–{nums[-1]:.3g}"
            rel, limit = LIMITS.get(item, ("?", float("nan")))
            runs = f"{len(vals)} run{'s' * (len(vals) != 1)}"
            advice = ADVICE.get(item, "see the run's metadata.json 'validity'")
            out.append(
                f"{self._prefix(name)}{item} = {shown} (limit {rel} {limit:g}) in {runs}: {advice}"
            )
        for text, count in fam.other.items():
            times = f" (×{count})" if count > 1 else ""
            out.append(f"{self._prefix(name)}warning: {text}{times}")
        return out

    def end_family(self) -> None:
        """Write the lines of the current family (verbosity 1) and close it."""
        if self.verbosity == 1:
            for text in self.lines(self._current):
                self._out(text)
        self._current = ""

    def report(self, name: str, records: dict) -> None:
        """Add a family collected elsewhere (a worker process's :meth:`records`) and write
        its lines (verbosity 1)."""
        fam = self.families.setdefault(name, _Family())
        for item, vals in records.get("values", {}).items():
            fam.values.setdefault(item, []).extend(vals)
        for text, count in records.get("other", {}).items():
            fam.other[text] = fam.other.get(text, 0) + count
        if self.verbosity == 1:
            for text in self.lines(name):
                self._out(text)

    def records(self) -> dict:
        """Everything collected, merged over families, as plain data (for another process)."""
        merged = _Family()
        for fam in self.families.values():
            for item, vals in fam.values.items():
                merged.values.setdefault(item, []).extend(vals)
            for text, count in fam.other.items():
                merged.other[text] = merged.other.get(text, 0) + count
        return {"values": merged.values, "other": merged.other}


def validity_counts(validities) -> tuple[int, dict]:
    """(number of runs, item → runs outside its range) over ``meta["validity"]`` dicts."""
    runs, outside = 0, {}
    for v in validities:
        runs += 1
        for name in v.get("violations", []):
            outside[name] = outside.get(name, 0) + 1
    return runs, outside


def summary_line(validities, where: str) -> str:
    """The one closing line: how many items were outside their range in how many runs.

    Parameters
    ----------
    validities : iterable of dict
        The ``meta["validity"]`` of every run (:func:`gecko_agents.diagnostics.diagnose`).
    where : str
        Where the full table is, e.g. ``"the report's table"``.
    """
    runs, outside = validity_counts(validities)
    plural = "s" * (runs != 1)
    if not outside:
        return f"validity: every item within range in {runs} run{plural}"
    each = ", ".join(f"{name} in {k}" for name, k in outside.items())
    n = len(outside)
    return (
        f"validity: {n} item{'s' * (n != 1)} outside range in {runs} run{plural} ({each}) — "
        f"see {where}"
    )


def add_verbosity_arguments(parser) -> None:
    """``--quiet`` and ``--verbose`` (mutually exclusive) on an argparse parser; read them back
    with ``verbosity(args)``."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument(
        "--quiet",
        action="store_true",
        help="print no warning lines, only the closing validity summary",
    )
    group.add_argument(
        "--verbose",
        action="store_true",
        help="print every warning in full as it comes (default: one line per item per study)",
    )


def verbosity(args) -> int:
    """0, 1 or 2 from the ``--quiet``/``--verbose`` of :func:`add_verbosity_arguments`."""
    return 0 if getattr(args, "quiet", False) else 2 if getattr(args, "verbose", False) else 1
