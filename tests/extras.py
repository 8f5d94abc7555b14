"""Tests that need an optional extra skip, naming the extra to install, when it is missing.

The fast tier passes with ``pip install -e '.[dev]'`` alone; each test of an extra's feature
says which extra it needs, so a skip in the summary reads as an instruction. The extras and the
modules they install are tests/doc_blocks.py's ``EXTRA_MODULES`` (one list for the pages and the
tests).
"""

from __future__ import annotations

import pytest
from doc_blocks import EXTRA_MODULES, extra_installed


def reason(extra: str) -> str:
    """The skip reason for a missing ``extra``: its name and the command that installs it."""
    return (
        f"needs the {extra!r} extra ({EXTRA_MODULES[extra]}): pip install 'gecko_agents[{extra}]'"
    )


def needs(extra: str) -> pytest.MarkDecorator:
    """Mark a test (or, as ``pytestmark``, a module) to skip when ``extra`` is not installed."""
    return pytest.mark.skipif(not extra_installed(extra), reason=reason(extra))


def require(extra: str, module: str | None = None):
    """Import ``module`` (the extra's own by default) or skip the running test, naming ``extra``."""
    return pytest.importorskip(module or EXTRA_MODULES[extra], reason=reason(extra))
