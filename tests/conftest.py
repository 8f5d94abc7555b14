"""Every history an agent run produces in the test suite passes the force-history invariants
(energy balance included), whatever the test itself asserts."""

import os

# One OpenBLAS thread per test process: on a shared 2-core machine more threads only spin
# waiting for the cores (scipy's expm in the wedge solve, most of all).
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import pytest  # noqa: E402

from gecko_agents import history  # noqa: E402
from gecko_agents.model import Model  # noqa: E402

_run = Model.run


def _checked_run(self, *args, **kwargs):
    h = _run(self, *args, **kwargs)
    if not self.external_force.any():  # probing forces do work the plate does not see
        bad = history.invariant_violations(h)
        assert bad == [], f"invariants violated: {bad}"
    return h


@pytest.fixture(autouse=True)
def _invariants_on_every_history(monkeypatch):
    monkeypatch.setattr(Model, "run", _checked_run)


def pytest_collection_modifyitems(config, items):
    """``MUTATION_TESTS`` (paths or node-id prefixes, space-separated) keeps only those tests:
    tools/mutation.sh scores a costly module by the fast tests written for it, a part of the
    fast tier (what they kill, the whole tier kills)."""
    only = os.environ.get("MUTATION_TESTS", "").split()
    if not only:
        return
    kept = [item for item in items if item.nodeid.startswith(tuple(only))]
    config.hook.pytest_deselected(items=[item for item in items if item not in kept])
    items[:] = kept
