"""Run the ```python blocks of Markdown pages (the README, CONTRIBUTING.md, docs/**/*.md).

The blocks of one page run in order in one namespace (a page reads as one session), in a fresh
temporary working directory, with matplotlib's Agg backend. Marks on the line just above a
block:

* ``<!-- not-run -->`` — not run (a sketch of a file to write, not code to run here);
* ``<!-- extra: NAME -->`` — needs the optional extra NAME; with ``skip_missing_extras`` it is
  skipped when that extra's module is not installed (the wheel check installs the bare wheel).

Used by tests/test_doc_blocks.py (every extra installed) and, as a script, by .ci/wheel_check
on the installed wheel: ``python doc_blocks.py [--skip-missing-extras] PAGE.md ...``. Needs
only the package's declared dependencies.
"""

from __future__ import annotations

import importlib.util
import os
import re
import sys
import tempfile
import warnings
from dataclasses import dataclass
from pathlib import Path

FENCE = re.compile(
    r"^(?:<!-- (?P<mark>not-run|extra: [\w-]+) -->\n)?```python\n(?P<code>.*?)^```$", re.M | re.S
)
EXTRA_MODULES = {
    "topography": "SurfaceTopography",
    "pandas": "pandas",
    "fast": "numba",
    "dask": "distributed",
    "video": "imageio_ffmpeg",
    "design": "optuna",
    "contactmechanics": "ContactMechanics",
    "docs": "sphinx",
}
"""Optional extra → the module it installs (pyproject.toml's optional dependencies)."""


@dataclass(frozen=True)
class Block:
    line: int  # line of the block's first code line in its page
    code: str
    extra: str | None  # the optional extra it needs, if marked


def python_blocks(text: str) -> list[Block]:
    """The runnable ```python blocks of a Markdown text, in order."""
    blocks = []
    for m in FENCE.finditer(text):
        mark = m["mark"] or ""
        if mark == "not-run":
            continue
        extra = mark.removeprefix("extra: ") if mark.startswith("extra: ") else None
        blocks.append(Block(text.count("\n", 0, m.start("code")) + 1, m["code"], extra))
    return blocks


def extra_installed(extra: str) -> bool:
    return importlib.util.find_spec(EXTRA_MODULES[extra]) is not None


def run_page(page: Path, skip_missing_extras: bool = False) -> list[Block]:
    """Run a page's blocks in a temporary directory; return the blocks skipped for a missing
    extra. A failing block raises AssertionError naming the page and the block's line."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    namespace: dict = {"__name__": "__main__"}
    skipped = []
    cwd = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the pages' runs are short: validity items expected
        os.chdir(tmp)
        try:
            for block in python_blocks(page.read_text("utf-8")):
                if block.extra and skip_missing_extras and not extra_installed(block.extra):
                    skipped.append(block)
                    continue
                try:
                    exec(compile(block.code, f"{page.name}:{block.line}", "exec"), namespace)
                except Exception as err:  # name the page and the block's line
                    raise AssertionError(f"{page}, block at line {block.line}: {err!r}") from err
        finally:
            os.chdir(cwd)
            plt.close("all")
    return skipped


def main(argv=None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    skip = "--skip-missing-extras" in args
    pages = [Path(a).resolve() for a in args if a != "--skip-missing-extras"]
    ran = 0
    for page in pages:
        blocks = python_blocks(page.read_text("utf-8"))
        if not blocks:
            continue
        skipped = run_page(page, skip_missing_extras=skip)
        ran += len(blocks) - len(skipped)
        note = "".join(f"; line {b.line} skipped (extra {b.extra!r})" for b in skipped)
        print(f"{page.name}: {len(blocks) - len(skipped)} blocks ran{note}")
    print(f"doc blocks: {ran} ran")
    return 0


if __name__ == "__main__":
    sys.exit(main())
