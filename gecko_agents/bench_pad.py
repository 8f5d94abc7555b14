"""Scaling benchmark of the layer field at pad scale: time and memory against the number of
fibres N = n² from 64² to 1024², and the pad tolerances' error beside them.

Run ``python -m gecko_agents.bench_pad`` (``--quick``: 32² and 64²; ``--max-n``: the largest
field; ``--docs PATH``: also write the table as a Markdown page). Each field is the
backing-layer study's pillars (``gecko_agents.studies.probe_test.PILLARS``, pitch 4 µm)
on a layer of :data:`THICKNESSES` (E = 1.413 MPa, ν = 0.3), pressed by a flat probe to
0.2 N·F_r and pulled off by :func:`gecko_agents.physics.pad_field.press_pull_pad` at
:data:`~gecko_agents.physics.pad_field.PAD_TOLERANCES` (two FFT threads). Time is CPU
seconds of the process (both threads; the machine is shared, so wall time is printed beside
it with the load average), memory the peak traced by ``tracemalloc`` and the process's
resident peak. Up to :data:`ORACLE_MAX_N` the event-to-event
:func:`gecko_agents.physics.layer_field.press_pull` (``resolution`` 1e-6 µm) is run too: the
pull-off's relative error and the CPU ratio.
"""

from __future__ import annotations

import argparse
import math
import os
import resource
import time
import tracemalloc
from pathlib import Path

from gecko_agents.physics import layer_field, pad_field
from gecko_agents.provenance import versions
from gecko_agents.studies.probe_test import PILLARS

__all__ = ["ORACLE_MAX_N", "SIZES", "THICKNESSES", "main", "measure", "table"]

SIZES = (64, 128, 256, 512, 1024)
"""Fibres per side of the fields measured."""
THICKNESSES = (160.0, 1120.0)
"""Layer thicknesses [µm]: Kim & Sitti's (2007) two backings."""
ORACLE_MAX_N = 128
"""Largest field also run event to event (its cost grows as N^1.5 or faster)."""
PRELOAD = 0.2  # over N·F_r


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def _timed(fn):
    cpu, wall = _cpu(), time.perf_counter()
    tracemalloc.start()
    try:
        out = fn()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    return out, _cpu() - cpu, time.perf_counter() - wall, peak / 2**20


def measure(n: int, t: float, oracle: bool) -> dict:
    """One field of n² fibres on a layer of thickness ``t`` [µm]: the pad solution's cost and,
    if ``oracle``, the event-to-event one's and the pull-off's relative error."""
    field = pad_field.PadField.from_params(PILLARS, n, thickness=t, modulus=1.413)
    h = layer_field.probe_heights(field, math.inf, 0.0)
    P = PRELOAD * n * n * field.release_force
    r, cpu, wall, peak = _timed(
        lambda: pad_field.press_pull_pad(field, h, P, workers=2, **pad_field.PAD_TOLERANCES)
    )
    row = {
        "n": n,
        "fibres": n * n,
        "t_um": t,
        "pull_off_over_NFr": r.pull_off / (n * n * field.release_force),
        "solves": r.solves,
        "matvecs": r.matvecs,
        "cpu_s": cpu,
        "wall_s": wall,
        "traced_peak_MB": peak,
        "maxrss_MB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        "oracle_cpu_s": None,
        "error": None,
    }
    if oracle:
        small = layer_field.LayerField.from_params(PILLARS, n, thickness=t, modulus=1.413)
        ref, ref_cpu, _, _ = _timed(lambda: layer_field.press_pull(small, h, P, resolution=1e-6))
        row["oracle_cpu_s"], row["error"] = ref_cpu, r.pull_off / ref.pull_off - 1.0
    return row


def table(rows: list[dict], load) -> str:
    """The Markdown page: one row per field, the CPU time over the smallest field's."""
    lines = [
        "# Layer field at pad scale: time and memory against N",
        "",
        "Written by `python -m gecko_agents.bench_pad --docs PATH` (module docstring of",
        "`gecko_agents.bench_pad`). Flat probe, preload 0.2 N·F_r, the backing-layer study's",
        "pillars at a 4 µm pitch, E_b = 1.413 MPa; the pad tolerances of",
        "`gecko_agents.physics.pad_field.PAD_TOLERANCES`. CPU seconds are the process's",
        "(two FFT threads); the machine is shared, the load average during the run was",
        f"{' / '.join(f'{x:.1f}' for x in load)} (1 / 5 / 15 min) on 2 cores, so wall seconds",
        "are an upper bound on the unloaded time. Error: pull-off against the event-to-event",
        "field (`layer_field.press_pull`, resolution 1e-6 µm), where it was run.",
        "",
        "| t [µm] | n | fibres | width [mm] | pull-off / N·F_r | solves | FFT products "
        "| CPU [s] | CPU / smallest | wall [s] | traced peak [MB] "
        "| process resident peak so far [MB] | error vs event-to-event "
        "| event-to-event CPU / pad CPU |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for t in sorted({r["t_um"] for r in rows}):
        sel = [r for r in rows if r["t_um"] == t]
        base = sel[0]["cpu_s"]
        for r in sel:
            err = "" if r["error"] is None else f"{100 * r['error']:+.3f} %"
            speed = "" if r["oracle_cpu_s"] is None else f"{r['oracle_cpu_s'] / r['cpu_s']:.1f}"
            lines.append(
                f"| {t:g} | {r['n']} | {r['fibres']:,} | {r['n'] * 4e-3:.2f} "
                f"| {r['pull_off_over_NFr']:.4f} | {r['solves']} | {r['matvecs']} "
                f"| {r['cpu_s']:.1f} | {r['cpu_s'] / base:.1f} | {r['wall_s']:.0f} "
                f"| {r['traced_peak_MB']:.0f} | {r['maxrss_MB']:.0f} | {err} | {speed} |"
            )
    v = versions()
    lines += ["", "Versions: " + ", ".join(f"{k} {v[k]}" for k in sorted(v)), ""]
    return "\n".join(lines)


def main(argv=None) -> dict:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="32² and 64² only")
    parser.add_argument("--max-n", type=int, default=max(SIZES), help="largest field")
    parser.add_argument("--docs", type=Path, default=None, help="write the Markdown table here")
    args = parser.parse_args(argv)
    sizes = (32, 64) if args.quick else tuple(n for n in SIZES if n <= args.max_n)
    rows = []
    for n in sizes:  # both layers at each size, the page rewritten after each row
        for t in THICKNESSES:
            rows.append(measure(n, t, oracle=n <= ORACLE_MAX_N))
            print({k: (round(v, 5) if isinstance(v, float) else v) for k, v in rows[-1].items()})
            text = table(rows, os.getloadavg())
            if args.docs is not None:
                args.docs.write_text(text, encoding="utf-8")
    print(text)
    return {"rows": rows}


if __name__ == "__main__":
    main()
