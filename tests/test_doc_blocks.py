"""Every ```python block of README.md, CONTRIBUTING.md and docs/**/*.md runs.

The blocks of one page run in order in one namespace (a page reads as one session), in a
temporary working directory, with matplotlib's Agg backend. A block the page marks with the
line ``<!-- not-run -->`` just above it is skipped (a sketch of a file to write, not code to
run here); other languages (bash, toml, text) are not run. The wheel check runs the command
lines the pages show (`.ci/wheel_check`: every example file).
"""

import os
import re
import warnings
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")
ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted(
    [ROOT / "README.md", ROOT / "CONTRIBUTING.md"]
    + [p for p in (ROOT / "docs").rglob("*.md") if not {"_build", "_generated"} & set(p.parts)]
)
FENCE = re.compile(r"^(?P<mark><!-- not-run -->\n)?```python\n(?P<code>.*?)^```$", re.M | re.S)
SKIP = "<!-- not-run -->"


def python_blocks(text: str) -> list[tuple[int, str]]:
    """(line number, code) of each runnable ```python block of a Markdown text."""
    return [
        (text.count("\n", 0, m.start("code")) + 1, m["code"])
        for m in FENCE.finditer(text)
        if not m["mark"]
    ]


def test_blocks_are_found_and_the_skip_mark_skips():
    text = "a\n```python\nx = 1\n```\n<!-- not-run -->\n```python\ny = 2\n```\n```bash\nls\n```\n"
    assert python_blocks(text) == [(3, "x = 1\n")]


PAGES_WITH_CODE = [p for p in PAGES if p.exists() and python_blocks(p.read_text("utf-8"))]


def test_the_readme_and_the_tutorials_have_runnable_code():
    names = {p.relative_to(ROOT).as_posix() for p in PAGES_WITH_CODE}
    assert "README.md" in names
    assert {n for n in names if n.startswith("docs/tutorials/")}


@pytest.mark.parametrize(
    "page", PAGES_WITH_CODE, ids=lambda p: p.relative_to(ROOT).as_posix().replace("/", ".")
)
def test_page_code_runs(page, tmp_path):
    import matplotlib.pyplot as plt

    namespace: dict = {"__name__": "__main__"}
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the pages' runs are short: validity items expected
            for line, code in python_blocks(page.read_text("utf-8")):
                try:
                    exec(compile(code, f"{page.name}:{line}", "exec"), namespace)
                except Exception as err:  # name the page and the block's line
                    raise AssertionError(f"{page.name}, block at line {line}: {err!r}") from err
    finally:
        os.chdir(cwd)
        plt.close("all")
