"""Press-pull of a setae patch on a measured surface profile, against a flat floor.

The profile file is given on the command line (default: the Dektak stylus scan
``data/surfaces/dektak_profile.csv``, provenance in ``data/surfaces/README.md``). Text/CSV
files are read by the plain reader (:func:`gecko_agents.floor.readers.read_text`); every other
format by SurfaceTopography (``pip install 'gecko_agents[topography]'``; ``--row`` picks the
row of a 2-D map). The profile is detrended, converted to µm and resampled (``--spacing``);
the part from ``--x-start`` lies under the patch. A patch of the paper's array (θ = 60°, rod
mechanics) is pressed and pulled off on it and on a flat floor. ``--quick``: a 5 µm seta,
2 setae.

Outputs (``renders/measured_floor/``): ``sweep.csv`` (pull-off on each floor), ``floor.png``
(the whole scan and its PSD), ``floor_under_patch.png``, ``flat/`` and ``measured/``
histories, ``metadata.json`` (parameters and the floor statistics).
"""

from __future__ import annotations

from pathlib import Path

from gecko_agents import floor, protocol
from gecko_agents.data import DEKTAK_PROFILE
from gecko_agents.floor import readers as profiles
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.render.floor_plots import plot_floor
from gecko_agents.studies.common import (
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

NAME = "measured_floor"
DEFAULT_FILE = DEKTAK_PROFILE


def make_model(params, profile, **kwargs) -> Model:
    """``Model(params, floor_profile=profile, **kwargs)`` (the generated floor if None)."""
    return Model.from_options(params, floor_profile=profile, **kwargs)


def _extra(parser):
    parser.add_argument(
        "profile",
        nargs="?",
        type=Path,
        default=DEFAULT_FILE,
        help="surface profile file (default: the Dektak scan in data/surfaces)",
    )
    parser.add_argument("--row", type=int, default=None, help="row (y index) of a 2-D map")
    parser.add_argument(
        "--unit", default=None, help="length unit of a text file without units in its header"
    )
    parser.add_argument(
        "--spacing",
        type=float,
        default=None,
        help="resampling spacing [µm] (default: the scan's mean spacing)",
    )
    parser.add_argument(
        "--x-start",
        type=float,
        default=0.0,
        help="position along the scan [µm] under the left end of the floor",
    )
    parser.add_argument("--n-sim", type=int, default=None, help="setae in the patch")


def load_profile(args):
    """The measured profile, from the part of the scan beginning at ``--x-start``."""
    kw = {"spacing": args.spacing}
    path = args.profile
    if path.suffix.lower() in profiles.TEXT_SUFFIXES and args.row is None:
        whole = profiles.read_text(path, unit=args.unit, **kw)
    else:
        whole = profiles.read_topography(path, row=args.row, **kw)
    if args.x_start == 0:
        return whole, whole
    part = floor.from_profile(
        whole.x,
        whole.y,
        detrend="none",
        spacing=whole.spacing,
        x_range=(args.x_start, whole.x[-1]),
        source=whole.source,
    )
    return whole, part


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv, extra=_extra)
    out = output_dir(NAME, args)
    whole, part = load_profile(args)
    n_sim = args.n_sim or (2 if args.quick else 16)
    over = {"mechanics": "rod", "floor.sigma": 0.0, "floor.correlation_length": 0.0}
    if args.quick:
        over["seta.L"] = 5.0
    params = PAPER_ARRAY.replace(**over)
    prot = protocol.press_pull(0.5 if args.quick else 1.0, 0.05 if args.quick else 0.02)
    progress = not args.no_progress
    rows, results = [], {}
    for name, prof in (("flat", None), ("measured", part)):
        model = make_model(params, prof, n_sim=n_sim)
        h = model.run(prot, progress=progress)
        h.save(out / name)
        results[name] = {
            "pull_off_uN": h.peak_pull_off,
            "pull_off_per_seta_uN": h.peak_pull_off / n_sim,
            "setae_detached": int(len(h.detachments["seta"])),
        }
        rows.append({"floor": name, **results[name]})
        if name == "measured":
            under = model.profile
    stats_whole = floor.statistics(whole)
    stats_under = floor.statistics(under)
    plot_floor(whole, out / "floor.png", title=f"measured floor: {whole.source}", stats=stats_whole)
    plot_floor(
        under,
        out / "floor_under_patch.png",
        title=f"{whole.source}: the part under the {n_sim}-seta patch",
        stats=stats_under,
    )
    write_table(out / "sweep.csv", rows)
    strip = {"psd_q_per_um", "psd_C_um3"}
    write_json(
        out / "metadata.json",
        {
            "params": params.to_dict(),
            "profile_file": str(args.profile),
            "row": args.row,
            "x_start_um": args.x_start,
            "n_sim": n_sim,
            "floor_statistics_scan": stats_whole,
            "floor_statistics_under_patch": {
                k: v for k, v in stats_under.items() if k not in strip
            },
            "results": results,
        },
    )
    return results


if __name__ == "__main__":
    main()
