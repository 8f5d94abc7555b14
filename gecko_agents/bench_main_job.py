"""The main job's benchmark: the README's first command against itself without its fast paths.

``python -m gecko_agents.bench --main-job`` (``--quick`` for the short form of the job,
``--docs PATH`` to also write the result as a Markdown page) runs the main job,
``python scenarios/reproduce_paper.py`` (``gecko_agents.studies.reproduce_paper.main``,
two scenarios at a time), twice in one run, each in a process of its own writing to a
temporary folder:

* **default**: as a user runs it;
* **baseline**: the same job with two fast paths switched off in every one of its processes
  (:func:`without_fast_paths`): the agent model's multirate stepping
  (:class:`~gecko_agents.numerics.Numerics` ``multirate = False``: the whole patch takes
  the located steps) and the quasi-static Fig 11 sweeps' curves
  (``gecko_agents.studies.preload.CURVES = False``: one press-and-pull per preload point
  instead of one shared approach per floor).

For each it measures the wall time and the CPU seconds of the job and every process it started
(``resource.getrusage(RUSAGE_CHILDREN)`` around it), and the wall time of each scenario (the
report's ``timings_s``). A machine shared with other work inflates both runs alike; the ratios
baseline / default are the result, CPU steadier than wall. The last line is
``main job baseline/default: wall ×A, CPU ×B``.
"""

from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from gecko_agents.provenance import versions

__all__ = ["main_job", "without_fast_paths", "write_page"]

RUNS = ("baseline", "default")
"""The two forms of the job, in the order they run."""


def without_fast_paths() -> None:
    """Switch the main job's fast paths off in this process (the benchmark's baseline): every
    :class:`~gecko_agents.numerics.Numerics` made from here on defaults to
    ``multirate = False``, and the Fig 11 sweeps take one press-and-pull per point."""
    from gecko_agents.numerics import NUMERICS_FIELDS, Numerics
    from gecko_agents.studies import preload

    defaults = list(Numerics.__init__.__defaults__)
    defaults[NUMERICS_FIELDS.index("multirate")] = False
    Numerics.__init__.__defaults__ = tuple(defaults)
    preload.CURVES = False


def _job(argv: list[str]) -> None:
    """One form of the main job (``argv`` = [form, output folder, "quick" or "full"]), the
    entry of the subprocess :func:`_timed_job` starts."""
    from gecko_agents.studies import reproduce_paper

    form, out, size = argv
    args = ["--out", out, "--no-progress"] + (["--quick"] if size == "quick" else [])
    reproduce_paper.main(args, setup=without_fast_paths if form == "baseline" else None)


def _timed_job(form: str, out: Path, quick: bool, log) -> dict:
    """Run one form of the job in a subprocess; its wall time [s], CPU seconds of it and its
    processes [s] and per-scenario wall times [s]."""
    code = "import sys; from gecko_agents.bench_main_job import _job; _job(sys.argv[1:])"
    cmd = [sys.executable, "-c", code, form, str(out), "quick" if quick else "full"]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=log, stderr=subprocess.STDOUT)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    report = json.loads((out / "paper_comparison.json").read_text())
    return {"wall_s": wall, "cpu_s": cpu, "scenarios_s": report["timings_s"]}


def main_job(quick: bool = False, docs=None) -> dict:
    """The benchmark (module docstring): {form: its times} and the ratios baseline/default
    under ``"wall_ratio"`` and ``"cpu_ratio"``; ``docs``: a path to write the page to."""
    out = {}
    with tempfile.TemporaryDirectory(prefix="main_job_") as tmp:
        for form in RUNS:
            with open(Path(tmp) / f"{form}.log", "w") as log:
                out[form] = _timed_job(form, Path(tmp) / form, quick, log)
            r = out[form]
            print(f"main job, {form}: {r['wall_s']:.1f} s wall, {r['cpu_s']:.1f} s CPU", flush=True)
    out["wall_ratio"] = out["baseline"]["wall_s"] / out["default"]["wall_s"]
    out["cpu_ratio"] = out["baseline"]["cpu_s"] / out["default"]["cpu_s"]
    out["quick"] = quick
    if docs:
        write_page(out, docs)
    print(f"main job baseline/default: wall ×{out['wall_ratio']:.2f}, CPU ×{out['cpu_ratio']:.2f}")
    return out


def _numba_version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("numba")
    except PackageNotFoundError:
        return "absent"


def write_page(out: dict, path) -> None:
    """Write :func:`main_job`'s result ``out`` as a Markdown page at ``path``."""
    b, d = out["baseline"], out["default"]
    lines = [
        "# The main job, as measured",
        "",
        "Written by `python -m gecko_agents.bench --main-job"
        + (" --quick" if out["quick"] else "")
        + " --docs PATH`: both rows come from",
        f"that one run ({os.cpu_count()} cores, gecko_agents "
        f"{versions().get('gecko_agents', '?')}, numba {_numba_version()}). *default* is the",
        "README's first command, `python scenarios/reproduce_paper.py`; *baseline* is the same",
        "job with the agent model's multirate stepping and the Fig 11 sweeps' curves switched",
        "off (`gecko_agents.bench_main_job`). CPU counts the job and every process it started;",
        "on a machine shared with other jobs it is the steadier figure.",
        "",
        "| run | wall [s] | CPU [s] |",
        "|---|---|---|",
        f"| baseline | {b['wall_s']:.1f} | {b['cpu_s']:.1f} |",
        f"| default | {d['wall_s']:.1f} | {d['cpu_s']:.1f} |",
        f"| baseline / default | ×{out['wall_ratio']:.2f} | ×{out['cpu_ratio']:.2f} |",
        "",
        "Wall time per scenario [s] (two run side by side):",
        "",
        "| scenario | baseline | default |",
        "|---|---|---|",
    ]
    for name, t in d["scenarios_s"].items():
        lines.append(f"| {name} | {b['scenarios_s'].get(name, float('nan')):.1f} | {t:.1f} |")
    lines.append("")
    Path(path).write_text("\n".join(lines), encoding="utf-8")
