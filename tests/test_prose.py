"""Prose that lasts: the package's code carries no dates and no before/after stories; measured
figures live in tests (pinned) and in the documentation pages, history in CHANGELOG.md."""

import re
from pathlib import Path

import pytest

import gecko_agents

PKG = Path(gecko_agents.__file__).resolve().parent
MODULES = sorted(PKG.rglob("*.py"))
STORIES = [
    (re.compile(r"\b(19|20)\d\d-[01]\d-[0-3]\d\b"), "a date"),
    (re.compile(r"\b(before|after|since) (the|this|that) [\w\- ]{0,30}change\b", re.I),
     "a before/after story"),
    (re.compile(r"\b(previously|used to)\b", re.I), "a before/after story"),
    (re.compile(r"\bit now\b", re.I), "a before/after story"),
    (re.compile(r"README \"\w+\""), "a README section (the README is an entrance; cite the docs)"),
]  # fmt: skip


def _hits(text: str) -> list[tuple[int, str]]:
    return [(n, what) for n, line in enumerate(text.splitlines(), 1)
            for rx, what in STORIES if rx.search(line)]  # fmt: skip


def test_the_checks_find_what_they_look_for():
    text = (
        "measured on 2026-11-26\nsince the ringing change\nit now iterates\n"
        'README "Speed"\nthe chain no longer holds\n'
    )
    assert [n for n, _ in _hits(text)] == [1, 2, 3, 4]


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PKG)))
def test_no_dates_or_change_stories_in_the_code(path):
    hits = _hits(path.read_text(encoding="utf-8"))
    assert not hits, f"{path}: " + "; ".join(f"line {n}: {what}" for n, what in hits)
