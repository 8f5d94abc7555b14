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
    every = {k: pair[0] for k, pair in runs.items()}
    # Each row is run twice, recorded every step and at the default records: the same steps.
    assert all(a["steps"] == b["steps"] for a, b in runs.values())
    # The implicit runs take fewer steps the longer their step, the explicit the most.
    steps = [every[f"implicit {f:g}×"]["steps"] for f in factors]
    assert steps == sorted(steps, reverse=True) and every["explicit"]["steps"] > steps[0]
    assert ref["steps"] > every["explicit"]["steps"]
    # The ratio is the explicit seta-steps over the fewest of a run within 0.5 %.
    ok = [r["seta_steps"] for k, r in every.items() if k != "explicit" and r["error"] <= 0.005]
    if every["explicit"]["error"] <= 0.005 and ok:
        assert math.isclose(case["ratio"], every["explicit"]["seta_steps"] / min(ok))
    # The last line is the default's ratio read at the default records.
    records = runs["implicit (default)"][1]
    if records["error"] <= 0.005:
        ratio = every["explicit"]["seta_steps"] / records["seta_steps"]
        assert math.isclose(case["default_ratio_records"], ratio)
        assert lines[-1].endswith(f"{ratio:.1f}")


def test_error_is_relative_to_the_reference():
    ref = {"pull_off": 2.0, "release": 10.0}
    assert bench._wp_error({"pull_off": 2.0, "release": 10.0}, ref) == 0.0
    assert math.isclose(bench._wp_error({"pull_off": 2.02, "release": 10.05}, ref), 0.01)
    # No adhesion (Hertz): the release alone counts.
    assert bench._wp_error({"pull_off": 0.0, "release": 10.1}, ref | {"pull_off": 0.0}) > 0
