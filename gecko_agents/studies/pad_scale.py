"""Pads at the experiments' size: pull-off per area against the pad's width, from 0.1 mm to
millimetres, for Kim & Sitti's two backings and Booth et al.'s misaligned (and aligned) pair.

The model is the backing-layer field (:mod:`gecko_agents.physics.layer_field`) solved at pad
scale (:func:`gecko_agents.physics.pad_field.press_pull_pad`, its tolerances
:data:`~gecko_agents.physics.pad_field.PAD_TOLERANCES`, ≤ 0.5 % on the pull-off): an n×n
field of the backing-layer study's pillars (:data:`gecko_agents.studies.probe_test.PILLARS`:
polyurethane, r = 1.5 µm, L = 20 µm, pitch s = 4 µm, flat-punch tips letting go at Kendall's
F_r = 4.66 µN) on a layer of E = 1.413 MPa (the paper's polyurethane), ν = 0.3, bonded to a
rigid holder, pressed by a flat probe to 0.2 N·F_r and pulled off. The pad is n·s wide.

Sources (abstracts only were readable; reading notes in ``/work/shared/literature``):

* Kim & Sitti 2007 (Appl Phys Lett 91:161905): polyurethane fibres with spatulated tips on
  160 µm and 1120 µm backings; the thin one held nine times more (≈ 22 N/cm²). Cited: the
  thicknesses. Assumed: the fibres (ours are flat punches), the layer's modulus, the pad's
  width (not in the abstract; "the experiments' size" is taken as 4.1 mm, n = 1024, and the
  trend with width is the table's).
* Booth, Bacca, McMeeking & Foster 2018: the thickest backing, 3.1× as compliant as the
  thinnest, held 43 % more at 0.4° of misalignment; aligned, the thinnest held most. Cited:
  the angle and the compliance ratio (taken as the thickness ratio: a thin layer's
  compliance is t/M). Assumed: the thinner layer's 100 µm (the other 310 µm), the fibres,
  the pad's width (as above).

Output: ``pad_scale.csv`` (case, n, width, pull-off per area [kPa], over N·F_r, solves, CPU
and wall seconds), ``pad_scale_ratios.csv`` (the sources' ratios against width),
``pad_scale.png`` and ``metadata.json``. ``--quick``: fields of 16 and 32 (64 and 128 µm).
``--max-n``: the largest field of the full run (default 1024; each 1024² point takes minutes).
"""

from __future__ import annotations

import math
import os
import resource
import time

from gecko_agents import render
from gecko_agents.physics import pad_field
from gecko_agents.physics.pad_probe import pad_heights
from gecko_agents.studies.common import (
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)
from gecko_agents.studies.probe_test import PILLARS

NAME = "pad_scale"
MODULUS, PRELOAD = 1.413, 0.2  # layer modulus [MPa]; preload over N·F_r [-]
CASES = {
    "Kim & Sitti, 160 µm": (160.0, 0.0),
    "Kim & Sitti, 1120 µm": (1120.0, 0.0),
    "Booth, 100 µm, 0.4°": (100.0, 0.4),
    "Booth, 310 µm, 0.4°": (310.0, 0.4),
    "Booth, 100 µm, aligned": (100.0, 0.0),
    "Booth, 310 µm, aligned": (310.0, 0.0),
}
"""Layer thickness t [µm] and misalignment [deg] of each case."""
RATIOS = {
    "Kim & Sitti: 160 / 1120 µm": ("Kim & Sitti, 160 µm", "Kim & Sitti, 1120 µm", 9.0),
    "Booth 0.4°: 310 / 100 µm": ("Booth, 310 µm, 0.4°", "Booth, 100 µm, 0.4°", 1.43),
    "Booth aligned: 100 / 310 µm": ("Booth, 100 µm, aligned", "Booth, 310 µm, aligned", None),
}
"""Each source's ratio: numerator case, denominator case, the measured value (None: a
direction only, > 1)."""
EXPERIMENT_N = 1024
"""Fibres per side of the pad taken as the experiments' size (4.1 mm at 4 µm; assumed)."""


def _cpu_seconds() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def pad_point(case: str, n: int) -> dict:
    """One press and pull of an n×n pad for ``case`` (:data:`CASES`)."""
    t, tilt = CASES[case]
    field = pad_field.PadField.from_params(PILLARS, n, thickness=t, modulus=MODULUS)
    h = pad_heights(field, math.inf, tilt)
    N_Fr = n * n * field.release_force
    cpu, wall = _cpu_seconds(), time.perf_counter()
    r = pad_field.press_pull_pad(field, h, PRELOAD * N_Fr, workers=2, **pad_field.PAD_TOLERANCES)
    area = (n * field.pitch) ** 2  # µm²
    return {
        "case": case,
        "t_um": t,
        "tilt_deg": tilt,
        "n": n,
        "width_mm": n * field.pitch * 1e-3,
        "pull_off_uN": r.pull_off,
        "pull_off_kPa": 1e3 * r.pull_off / area,  # µN/µm² = MPa
        "pull_off_over_NFr": r.pull_off / N_Fr,
        "attached_max": r.attached_max,
        "solves": r.solves,
        "matvecs": r.matvecs,
        "cpu_s": _cpu_seconds() - cpu,
        "wall_s": time.perf_counter() - wall,
    }


def ratio_rows(rows: list[dict]) -> list[dict]:
    """Each source's ratio (:data:`RATIOS`) at every width both cases were run."""
    by = {(r["case"], r["n"]): r for r in rows}
    out = []
    for name, (top, bottom, measured) in RATIOS.items():
        for n in sorted({r["n"] for r in rows}):
            if (top, n) in by and (bottom, n) in by:
                out.append(
                    {
                        "ratio": name,
                        "n": n,
                        "width_mm": by[top, n]["width_mm"],
                        "ours": by[top, n]["pull_off_uN"] / by[bottom, n]["pull_off_uN"],
                        "measured": measured,
                    }
                )
    return out


def _ratio_at(case_pair, quick: bool, width_mm: float | None) -> tuple[float, int]:
    n = 64 if quick else EXPERIMENT_N
    if width_mm is not None:
        n = max(2, round(1e3 * width_mm / PILLARS.array.pitch))
    top, bottom = (pad_point(c, n)["pull_off_uN"] for c in case_pair)
    return top / bottom, n


def kim_sitti_pad(quick: bool = True, width_mm: float | None = None) -> dict:
    """Pull-off on a 160 µm layer over that on a 1120 µm one, at the experiments' pad size
    (:data:`EXPERIMENT_N`; quick: 64², 0.26 mm) or ``width_mm`` [mm]."""
    value, n = _ratio_at(RATIOS["Kim & Sitti: 160 / 1120 µm"][:2], quick, width_mm)
    return {"value": value, "text": f"×{value:.3f} ({n}×{n} fibres, {n * 4e-3:.2f} mm)"}


def booth_pad_misaligned(quick: bool = True, width_mm: float | None = None) -> dict:
    """Pull-off at 0.4° on a 310 µm layer over that on a 100 µm one (3.1× as compliant)."""
    value, n = _ratio_at(RATIOS["Booth 0.4°: 310 / 100 µm"][:2], quick, width_mm)
    return {"value": value, "text": f"×{value:.3f} ({n}×{n} fibres, {n * 4e-3:.2f} mm)"}


def booth_pad_aligned(quick: bool = True, width_mm: float | None = None) -> dict:
    """Pull-off aligned on a 100 µm layer over that on a 310 µm one."""
    value, n = _ratio_at(RATIOS["Booth aligned: 100 / 310 µm"][:2], quick, width_mm)
    return {"value": value, "text": f"×{value:.4f} ({n}×{n} fibres, {n * 4e-3:.2f} mm)"}


def draw(rows, ratios, out) -> None:
    import matplotlib as mpl
    from matplotlib.figure import Figure

    styles = ("o-", "s--", "^-", "v--", "^:", "v-.")
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(11.0, 4.5), layout="constrained")
        ax = fig.subplots(1, 2)
        for case, style in zip(CASES, styles, strict=True):
            sel = [r for r in rows if r["case"] == case]
            ax[0].plot([r["width_mm"] for r in sel], [r["pull_off_kPa"] for r in sel], style,
                       label=case)  # fmt: skip
        ax[0].set_xscale("log")
        ax[0].set_xlabel("pad width [mm]")
        ax[0].set_ylabel("pull-off per area [kPa]")
        ax[0].legend(fontsize="small")
        ax[0].set_title("flat probe, preload 0.2 N·F_r, E_b = 1.413 MPa")
        for (name, (_, _, measured)), colour in zip(
            RATIOS.items(), ("C0", "C2", "C4"), strict=True
        ):
            sel = [r for r in ratios if r["ratio"] == name]
            ax[1].plot([r["width_mm"] for r in sel], [r["ours"] for r in sel], "o-",
                       color=colour, label=name)  # fmt: skip
            if measured is not None:
                ax[1].axhline(measured, color=colour, ls=":", label=f"measured ×{measured:g}")
        ax[1].axhline(1.0, color="grey", lw=0.8)
        ax[1].set_xscale("log")
        ax[1].set_yscale("log")
        ax[1].set_xlabel("pad width [mm]")
        ax[1].set_ylabel("pull-off ratio [-]")
        ax[1].legend(fontsize="small")
        render.save_figure(fig, out / f"{NAME}.png")


def _extra(parser) -> None:
    parser.add_argument("--max-n", type=int, default=EXPERIMENT_N,
                        help="largest field of the full run (fibres per side)")  # fmt: skip


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv, _extra)
    out = output_dir(NAME, args)
    sizes = [16, 32] if args.quick else [n for n in (25, 64, 128, 256, 512, 1024)
                                          if n <= args.max_n]  # fmt: skip
    t0 = time.perf_counter()
    rows = [pad_point(case, n) for n in sizes for case in CASES]
    ratios = ratio_rows(rows)
    write_table(out / f"{NAME}.csv", rows)
    write_table(out / f"{NAME}_ratios.csv", ratios)
    draw(rows, ratios, out)
    results = {
        "ratios_at_largest": {r["ratio"]: r["ours"] for r in ratios if r["n"] == max(sizes)},
        "runtime_s": time.perf_counter() - t0,
        "load_average": os.getloadavg(),  # the machine is shared: times are under this load
    }
    write_json(
        out / "metadata.json",
        {
            "scenario": NAME,
            "quick": args.quick,
            "params": PILLARS.to_dict(),
            "modulus_MPa": MODULUS,
            "preload_over_NFr": PRELOAD,
            "cases": CASES,
            "sizes": sizes,
            "tolerances": pad_field.PAD_TOLERANCES,
            "rows": rows,
            "ratios": ratios,
            "results": results,
        },
    )
    print(
        f"{NAME}: at {max(sizes)}² ("
        + ", ".join(f"{k} ×{v:.3f}" for k, v in results["ratios_at_largest"].items())
        + f"); {results['runtime_s']:.0f} s → {out}"
    )
    return results


if __name__ == "__main__":
    main()
