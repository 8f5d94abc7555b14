"""The documentation gallery's examples run (the site itself is built in CI by sphinx-build with
warnings as errors; this keeps the examples working where Sphinx is not installed)."""

import runpy
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")
GALLERY = Path(__file__).resolve().parents[1] / "docs" / "gallery"
EXAMPLES = sorted(GALLERY.glob("plot_*.py"))


def test_the_gallery_has_two_to_four_examples():
    assert 2 <= len(EXAMPLES) <= 4


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.stem)
def test_gallery_example_runs_and_draws_a_figure(path):
    import matplotlib.pyplot as plt

    plt.close("all")
    runpy.run_path(str(path), run_name="__main__")
    assert plt.get_fignums(), f"{path.name} drew no figure"
    plt.close("all")
