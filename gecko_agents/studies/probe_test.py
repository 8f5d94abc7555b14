"""Spherical-probe test: a rigid sphere of radius R_p pressed into a row of vertical pillars to
a preload and retracted; the pull-off against preload and probe radius, beside the closed form
of independent fibrils (:mod:`gecko_agents.physics.fibril_probe`).

The row is the paper's polyurethane (E = 1.413 MPa) as vertical pillars, r = 1.5 µm,
L = 20 µm, pitch 4 µm, each ending in a flat punch of radius 1.5 µm (Kendall's pull-off
F_r = √(8πE*wa³) = 4.66 µN, Sneddon's stiffness 2E*a in series with the pillar's Ka), stuck
by friction (μ = 0.5), on a rigid backing, pressed and pulled at 0.01 µm/µs. A free pillar
trails its root by v·c/Ka, 0.02 µm at that speed, well below the probe's height steps from
pillar to pillar; at 0.04 µm/µs the trailing pillars swing down onto the probe when the press
stops and attach where the closed form has none. The probe is the floor
(:mod:`gecko_agents.floor.probe`); the row lies in a plane through its centre.

Three cases side by side, one model each:

* **flat punch, rigid backing** — the case the closed form describes: each pillar a linear
  spring that lets go at F_r. Preload and pull-off are what a load cell reads, the plate's
  vertical force (:func:`~gecko_agents.analysis.pull.plate_pull_off`; the sum of the
  contacts' normal forces is kept as ``contact_pull_off_uN``), and the closed form is
  evaluated at the preload the press reached. Measured: within 0.7 % where the attached
  pillars stand where the probe slopes less than ~10° (R_p = 30 µm at 0.1 and 1 µN, 100 µm at
  0.5 and 3 µN); 3.5 % above it at R_p = 30 µm and 3 µN, where the outer pillars sit on a 15°
  slope, stuck by friction: the plate weighs the vertical parts of their tilted normal and
  friction forces, which the closed form (vertical fibrils) does not have (the contact normal
  forces alone are 1.9 % above it; ``tests/test_designs.py`` holds those to 1 % at smaller
  slopes).
* **JKR sphere tips** (R = 1.5 µm) — the paper's tip on the same pillars: a contact that
  stiffens as it is pressed and lets go at its fold.
* **flat punch, elastic backing** — the pillars on a 50 µm polyurethane strip held by a stiff
  handle (:mod:`gecko_agents.backing.elastic`): the backing spreads the probe's load.

The pull-off rises with the preload while more pillars are brought into contact, then saturates
once the preload no longer reaches new pillars (the row is finite); a larger probe touches more
pillars at a given preload. The field under a real probe, ``field_pull_off_uN``, is the same
closed form on the square lattice of pillars under the probe's footprint
(:func:`~gecko_agents.physics.fibril_probe_halfspace.square_lattice`, rigid backing) at the
preload reached. The row's pillars weighted as rings 2πr·n
(:func:`~gecko_agents.physics.fibril_probe.ring_weights`) are not used for it: that estimate
differs from the lattice by −19 % to +56 % at the study's points and passes the continuum's
saturated pull-off. A row under a probe is no uniform patch of an array, so its forces are not
scaled to ``array.count`` (the run warns where ``n_sim`` < ``array.count``).

Beside them, Bettscheider et al.'s open model of the test (J Mech Phys Solids 2021, 104365;
:mod:`gecko_agents.physics.fibril_probe_halfspace`): the same springs, on a rigid backing (the
closed form) and on an elastic half-space of the backing's polyurethane that couples them, for
the row and for the square field under the probe (``probe_booth.csv``; the row on the
half-space is drawn dotted), with one more, saturating preload (1.5× the continuum's saturated
pull-off π·n·R_p·F_r²/k) in the full run.

Output: ``probe_test.csv`` (one row per case, radius and preload), ``probe_booth.csv``,
``probe_test.png`` (pull-off
against preload, one panel per probe radius), ``detachment.gif`` (the largest probe at the
largest preload, flat punches on the rigid backing) and ``metadata.json``.

``--quick``: 5 pillars, one probe radius (30 µm), two preloads, the first case only, no
animation.
"""

from __future__ import annotations

import time

import numpy as np

from gecko_agents import protocol, render
from gecko_agents.analysis.pull import plate_pull_off, pull_off, pull_start
from gecko_agents.floor.probe import probe_heights
from gecko_agents.model import Model
from gecko_agents.params import PAPER_ARRAY
from gecko_agents.physics import fibril_probe, punch
from gecko_agents.physics import fibril_probe_halfspace as halfspace
from gecko_agents.studies.common import (
    command_line,
    output_dir,
    parse_args,
    write_json,
    write_table,
)

NAME = "probe_test"
PILLARS = PAPER_ARRAY.replace(
    **{
        "seta.theta_deg": 90.0,
        "tip": "flat_punch",
        "contact.R": 1.5,
        "floor.sigma": 0.0,
        "floor.kind": "probe",
        "friction.mu": 0.5,
    }
)
CASES = {
    "flat punch, rigid backing": {},
    "JKR sphere tips": {"tip": "sphere"},
    "flat punch, elastic backing": {"backing.kind": "elastic", "backing.drive": "uniform"},
}
SPEED, SEED = 0.01, 0
COLOURS = ("black", "#1f77b4", "#d62728")


def config(quick: bool) -> dict:
    if quick:
        return {
            "n": 5,
            "radii_um": [30.0],
            "preloads_uN": [0.1, 1.0],
            "cases": list(CASES)[:1],
            "animate": False,
            "booth_saturation": False,
        }
    return {
        "n": 11,
        "radii_um": [30.0, 100.0],
        "preloads_uN": [0.05, 0.2, 0.5, 1.0, 3.0],
        "cases": list(CASES),
        "animate": True,
        "booth_saturation": True,
    }


def fibril_stiffness(params) -> float:
    """A pillar and its punch in series: 1/(1/Ka + 1/(2E*a)) [µN/µm] (eq 17; Sneddon 1965)."""
    c = params.contact
    return 1.0 / (1.0 / params.axial_stiffness + 1.0 / float(punch.punch_stiffness(c.R, c.E_star)))


def closed_form(model: Model, params, preload_reached: float) -> dict:
    """The independent-fibril pull-off [µN] of the simulated row (each pillar once,
    :mod:`gecko_agents.physics.fibril_probe`) and of the square field of pillars under the
    probe's footprint (pitch ``array.pitch``, :func:`~gecko_agents.physics.fibril_probe_halfspace.
    square_lattice`, on a rigid backing), each pressed to ``preload_reached``."""
    c, pitch, R_p = params.contact, params.array.pitch, params.floor.probe_radius
    x = model.world.rest_dx
    h = probe_heights(x, R_p, 0.5 * (x.min() + x.max()))
    k = fibril_stiffness(params)
    F_r = float(punch.kendall_pull_off(c.R, c.work_of_adhesion, c.E_star))
    d_max = fibril_probe.depth_for_preload(preload_reached, h, k)
    x_f, y_f = halfspace.square_lattice(pitch, R_p)
    h_f = probe_heights(np.hypot(x_f, y_f), R_p)
    field = halfspace.probe_test(h_f, np.eye(x_f.size) / k, F_r, preload_reached)
    return {"row": fibril_probe.probe_pull_off(h, k, F_r, d_max), "field": field.pull_off}


def booth_point(radius: float, preload: float, n: int) -> dict:
    """Bettscheider et al.'s model of the test (:mod:`~gecko_agents.physics.fibril_probe_halfspace`)
    for the study's pillars: pull-offs [µN] of the simulated row of ``n`` pillars and of the
    square field (pitch ``array.pitch``) under the probe's footprint, each on a rigid backing
    (the closed form) and on a half-space of the backing's polyurethane (E_b, ν_b); and the
    continuum's saturated pull-off π·n_A·R_p·F_r²/k. Each pillar is the engine's spring k
    (pillar and punch in series) letting go at Kendall's F_r; the probe the exact sphere."""
    p = PILLARS
    c, b, pitch = p.contact, p.backing, p.array.pitch
    k = fibril_stiffness(p)
    F_r = float(punch.kendall_pull_off(c.R, c.work_of_adhesion, c.E_star))
    row = {"probe_radius_um": radius, "preload_uN": preload}
    x_row = (np.arange(n) - (n - 1) / 2.0) * pitch
    x_field, y_field = halfspace.square_lattice(pitch, radius)
    for name, (x, y) in {"row": (x_row, 0.0 * x_row), "field": (x_field, y_field)}.items():
        h = probe_heights(np.hypot(x, y), radius)
        fibrils = np.eye(x.size) / k
        backing = halfspace.halfspace_compliance(x, y, p.seta.r, b.E_b, b.nu_b)
        rigid = halfspace.probe_test(h, fibrils, F_r, preload)
        soft = halfspace.probe_test(h, fibrils + backing, F_r, preload)
        row |= {
            f"{name}_rigid_uN": rigid.pull_off,
            f"{name}_halfspace_uN": soft.pull_off,
            f"{name}_attached_rigid": rigid.attached_max,
            f"{name}_attached_halfspace": soft.attached_max,
        }
    row["continuum_saturation_uN"] = float(
        halfspace.saturation_pull_off_continuum(radius, 1.0 / pitch**2, k, F_r)
    )
    return row


def booth_table(cfg) -> list[dict]:
    """:func:`booth_point` over the study's radii and preloads, plus (``booth_saturation``) a
    preload of 1.5× the continuum's saturated pull-off for each radius."""
    rows = []
    for radius in cfg["radii_um"]:
        preloads = list(cfg["preloads_uN"])
        if cfg["booth_saturation"]:
            preloads.append(1.5 * booth_point(radius, preloads[0], 1)["continuum_saturation_uN"])
        rows += [booth_point(radius, preload, cfg["n"]) for preload in preloads]
    return rows


def run_point(case: str, n: int, radius: float, preload: float, record: bool = False):
    """One press to ``preload`` [µN] and pull of ``n`` pillars under a probe of ``radius``
    [µm] for ``case`` (:data:`CASES`); returns (table row, history)."""
    p = PILLARS.replace(**{"array.count": n, "floor.probe_radius": radius, **CASES[case]})
    m = Model(p, n_sim=n, seed=SEED, record_setae=record)
    h = m.run(protocol.preload_pull(preload, speed=SPEED), progress=False)
    # What a load cell reads: the plate's vertical force (the contacts' normals tilt with the
    # probe's slope), largest over the press and the pull's first record (the press ends on the
    # first step past the preload, which the records may miss). Not over the pull: a pillar
    # letting go rings, and its ring-down pushes the plate.
    press = slice(0, pull_start(h) + 1)
    reached = float(np.max(h["plate_force_y_uN"][press]))
    row = {
        "case": case,
        "n": n,
        "probe_radius_um": radius,
        "preload_uN": preload,
        "preload_reached_uN": reached,
        "pull_off_uN": plate_pull_off(h),
        "contact_pull_off_uN": pull_off(h).adhesion,
        "attached_max": int(np.max(h["n_attached"])),
    }
    if case == "flat punch, rigid backing":
        cf = closed_form(m, p, reached)
        row |= {
            "closed_form_uN": cf["row"],
            "field_pull_off_uN": cf["field"],
            "off_closed_form": row["pull_off_uN"] / cf["row"] - 1.0,
        }
    return row, h


def draw(rows, cfg, out, booth=()) -> None:
    import matplotlib as mpl
    from matplotlib.figure import Figure

    radii = cfg["radii_um"]
    with mpl.rc_context(render.STYLE_RC):
        fig = Figure(figsize=(4.2 * len(radii) + 0.6, 4.2), layout="constrained")
        axes = np.atleast_1d(fig.subplots(1, len(radii), sharey=True))
        for ax, radius in zip(axes, radii, strict=True):
            for case, colour in zip(cfg["cases"], COLOURS, strict=False):
                sel = [r for r in rows if r["case"] == case and r["probe_radius_um"] == radius]
                ax.plot(
                    [r["preload_reached_uN"] for r in sel],
                    [r["pull_off_uN"] for r in sel],
                    "o-",
                    color=colour,
                    label=f"model: {case}",
                )
                if "closed_form_uN" in sel[0]:
                    ax.plot(
                        [r["preload_reached_uN"] for r in sel],
                        [r["closed_form_uN"] for r in sel],
                        "k--",
                        lw=1,
                        label="closed form: independent fibrils",
                    )
            sel = [r for r in booth if r["probe_radius_um"] == radius]
            sel = [r for r in sel if r["preload_uN"] <= max(cfg["preloads_uN"])]
            if sel:
                ax.plot(
                    [r["preload_uN"] for r in sel],
                    [r["row_halfspace_uN"] for r in sel],
                    "k:",
                    lw=1.2,
                    label="Bettscheider et al.: row on a half-space",
                )
            ax.set_xscale("log")
            ax.set_xlabel("preload [µN]")
            ax.set_title(f"probe R_p = {radius:g} µm, {cfg['n']} pillars")
        axes[0].set_ylabel("pull-off [µN]")
        axes[0].legend(fontsize="small")
        render.save_figure(fig, out / f"{NAME}.png")


@command_line
def main(argv=None) -> dict:
    args = parse_args(__doc__, argv)
    out = output_dir(NAME, args)
    cfg = config(args.quick)
    t0 = time.perf_counter()
    rows = []
    for case in cfg["cases"]:
        for radius in cfg["radii_um"]:
            for preload in cfg["preloads_uN"]:
                rows.append(run_point(case, cfg["n"], radius, preload)[0])
    write_table(out / f"{NAME}.csv", rows)
    booth = booth_table(cfg)
    write_table(out / "probe_booth.csv", booth)
    draw(rows, cfg, out, booth)
    if cfg["animate"]:
        h = run_point(
            cfg["cases"][0], cfg["n"], max(cfg["radii_um"]), max(cfg["preloads_uN"]), record=True
        )[1]
        render.animate(h, out / "detachment.gif", window=cfg["n"], frames=120)
    worst = max(abs(r["off_closed_form"]) for r in rows if "off_closed_form" in r)
    results = {
        "largest_off_closed_form": worst,
        "runtime_s": time.perf_counter() - t0,
        "booth": booth,
    }
    write_json(
        out / "metadata.json",
        {
            "scenario": NAME,
            "quick": args.quick,
            "params": PILLARS.to_dict(),
            "cases": CASES,
            "config": cfg,
            "speed_um_per_us": SPEED,
            "seed": SEED,
            "rows": rows,
            "results": results,
        },
    )
    (out / "section.md").write_text(_section(cfg, worst, booth))
    print(
        f"{NAME}: model vs independent fibrils within {100 * worst:.2f} %; "
        f"{results['runtime_s']:.0f} s → {out}"
    )
    return results


def _section(cfg: dict, worst: float, booth: list[dict]) -> str:
    """section.md: the closed-form agreement and the half-space's shift of the row's pull-off."""
    same = np.array([r["row_attached_halfspace"] == r["row_attached_rigid"] for r in booth])
    shifts = np.array([100 * (r["row_halfspace_uN"] / r["row_rigid_uN"] - 1.0) for r in booth])
    more = shifts[~same]
    tail = (
        f", and by up to {more.max():+.1f} % where the backing's compliance lets the press "
        f"reach more ({more.size} of {shifts.size} points)."
        if more.size
        else "."
    )
    lines = [
        "## Beyond the paper: spherical-probe test",
        "",
        f"{cfg['n']} vertical pillars with flat punches under a rigid probe "
        "(`probe_test/probe_test.png`, table `probe_test.csv`): the time-stepped model "
        f"against the closed form of independent fibrils, largest difference "
        f"{100 * worst:.2f} % over {len(cfg['radii_um'])} probe radii and "
        f"{len(cfg['preloads_uN'])} preloads.",
        "Bettscheider et al.'s model (`probe_booth.csv`): on an elastic half-space the row's "
        f"pull-off moves by {shifts[same].min():+.1f} to {shifts[same].max():+.1f} % where "
        "the same pillars attach as on a rigid backing" + tail,
        "",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    main()
