"""The pad-size study (gecko_agents.studies.pad_scale): its ratios in the limit where the
layer's thickness cannot matter, and their pairing by width."""

import pytest

from gecko_agents.studies import pad_scale


@pytest.mark.parametrize("fn", [pad_scale.kim_sitti_pad, pad_scale.booth_pad_aligned])
def test_a_pad_much_narrower_than_both_layers_does_not_tell_them_apart(fn):
    """A pad of 8 × 8 fibres (32 µm) on layers of 100 µm and more: both are a half-space to it
    (the kernel's correction is of order (width/t)), so the aligned pull-offs agree to 1 %."""
    got = fn(True, width_mm=0.032)
    assert got["value"] == pytest.approx(1.0, abs=1e-2)
    assert "8×8" in got["text"]


def test_ratios_pair_the_cases_at_each_width():
    """A ratio is taken only where both of its cases ran, numerator over denominator."""
    rows = [
        {"case": "Kim & Sitti, 160 µm", "n": 10, "width_mm": 0.04, "pull_off_uN": 6.0},
        {"case": "Kim & Sitti, 1120 µm", "n": 10, "width_mm": 0.04, "pull_off_uN": 3.0},
        {"case": "Kim & Sitti, 160 µm", "n": 20, "width_mm": 0.08, "pull_off_uN": 9.0},
    ]
    (only,) = pad_scale.ratio_rows(rows)
    assert (only["n"], only["ours"], only["measured"]) == (10, 2.0, 9.0)
