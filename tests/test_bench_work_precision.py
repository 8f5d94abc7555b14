"""The work-precision benchmark: its rows are what they claim and its last line is the steps
ratio at ≤ 0.5 % error."""

import math
import re

import pytest

from gecko_agents import bench

pytestmark = pytest.mark.slow  # it runs the benchmark's cases


def test_work_precision_rows_and_last_line(capsys):
    factors = (5.0, 10.0)
    out = bench.work_precision(cases=["rod sphere"], speed=0.02, factors=factors)
    lines = capsys.readouterr().out.strip().splitlines()
    assert re.fullmatch(r"steps explicit/default at ≤ 0\.5 % error: \d+\.\d", lines[-1])
    case = out["rod sphere"]
    runs, ref = case["runs"], case["ref"]
    # The implicit runs take fewer steps the longer their step, the explicit the most.
    steps = [runs[f"implicit {f:g}×"]["steps"] for f in factors]
    assert steps == sorted(steps, reverse=True) and runs["explicit"]["steps"] > steps[0]
    assert ref["steps"] > runs["explicit"]["steps"]
    # The ratio is the explicit steps over the fewest steps of a run within 0.5 %.
    ok = [r["steps"] for k, r in runs.items() if k != "explicit" and r["error"] <= 0.005]
    if runs["explicit"]["error"] <= 0.005 and ok:
        assert math.isclose(case["ratio"], runs["explicit"]["steps"] / min(ok))


def test_error_is_relative_to_the_reference():
    ref = {"pull_off": 2.0, "release": 10.0}
    assert bench._wp_error({"pull_off": 2.0, "release": 10.0}, ref) == 0.0
    assert math.isclose(bench._wp_error({"pull_off": 2.02, "release": 10.05}, ref), 0.01)
    # No adhesion (Hertz): the release alone counts.
    assert bench._wp_error({"pull_off": 0.0, "release": 10.1}, ref | {"pull_off": 0.0}) > 0
