"""Every ```python block of README.md, CONTRIBUTING.md and docs/**/*.md runs (tests/doc_blocks.py
says how pages are run and marked). A block marked for an extra runs where the extra is
installed and skips the page's test, naming the extra, where it is not; .ci/wheel_check runs
the same pages on the bare installed wheel."""

import tomllib
from pathlib import Path

import extras
import pytest
from doc_blocks import EXTRA_MODULES, Block, python_blocks, run_page

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted(
    [ROOT / "README.md", ROOT / "CONTRIBUTING.md"]
    + [p for p in (ROOT / "docs").rglob("*.md") if not {"_build", "_generated"} & set(p.parts)]
)
PAGES_WITH_CODE = [p for p in PAGES if p.exists() and python_blocks(p.read_text("utf-8"))]


def test_blocks_are_found_and_the_marks_read():
    text = (
        "a\n```python\nx = 1\n```\n<!-- not-run -->\n```python\ny = 2\n```\n"
        "<!-- extra: topography -->\n```python\nz = 3\n```\n```bash\nls\n```\n"
    )
    assert python_blocks(text) == [Block(3, "x = 1\n", None), Block(11, "z = 3\n", "topography")]


def test_every_extra_that_installs_a_module_is_known_by_its_module():
    """The pages' marks and the tests' skips (tests/extras.py) know every optional extra of
    pyproject.toml but the developer tool sets."""
    with open(ROOT / "pyproject.toml", "rb") as f:
        declared = tomllib.load(f)["project"]["optional-dependencies"]
    assert set(EXTRA_MODULES) == set(declared) - {"dev", "mutation"}


def test_a_failing_block_names_its_page_and_line(tmp_path):
    page = tmp_path / "page.md"
    page.write_text("text\n\n```python\nx = 1\n```\n\n```python\n1 / 0\n```\n")
    with pytest.raises(AssertionError, match=r"page\.md, block at line 8: ZeroDivisionError"):
        run_page(page)


def test_the_readme_and_the_tutorials_have_runnable_code():
    names = {p.relative_to(ROOT).as_posix() for p in PAGES_WITH_CODE}
    assert "README.md" in names
    assert {n for n in names if n.startswith("docs/tutorials/")}


@pytest.mark.parametrize(
    "page", PAGES_WITH_CODE, ids=lambda p: p.relative_to(ROOT).as_posix().replace("/", ".")
)
def test_page_code_runs(page):
    """Every block runs; a block marked for an extra that is not installed is skipped, and the
    page's test says which extra to install."""
    skipped = run_page(page, skip_missing_extras=True)
    if skipped:
        pytest.skip("; ".join(sorted({extras.reason(block.extra) for block in skipped})))


def test_the_readme_test_command_is_the_one_ci_runs():
    """.ci/run's install-lint-test line is the README's test command, character for character."""
    ci = (ROOT / ".ci" / "run").read_text("utf-8").splitlines()
    command = next(line for line in ci if line.startswith("pip install -e '.["))
    command = command.removesuffix(" || exit 1")  # CI's own stop (set -e skips && lists)
    readme_first_screen = (ROOT / "README.md").read_text("utf-8").splitlines()[:30]
    assert any(line.startswith(command + "   # tests") for line in readme_first_screen)
