"""The design search (gecko_agents.design): design files refused before any trial, the search
finding what closed forms know, a killed study resuming, and the quick example end to end."""

import math

import extras
import pytest

from gecko_agents.design import load_design, search
from gecko_agents.design.space import KPA
from gecko_agents.physics import flaw_tolerance, jkr, punch
from gecko_agents.runfiles.schema import RunFileError

needs_optuna = extras.needs("design")

E, NU, W = 1.413, 0.3, 0.165

BASE = f"""
seed = 0
trials = 40
confirm = 0
objectives = "pull_off_per_area"

[material]
E_MPa = {E}
nu = {NU}
w_J_per_m2 = {W}

[surface]
kind = "flat"

[test]
preload_kPa = 10.0
floor_seeds = 1
pillars = 10

[space]
tip = "flat_punch"
radius_um = [1.0, 5.0]
aspect_ratio = 2.0
lean_deg = 90.0
fill_fraction = 0.2
"""


def design(tmp_path, text=BASE, name="d.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def E_star():
    return float(jkr.effective_modulus(E, NU, 55_000.0, 0.25))


@pytest.mark.parametrize(
    "old,new,names",
    [
        ("preload_kPa = 10.0", "preload_kPa = -1.0", ("[test] preload_kPa", "-1.0", "[0.001")),
        ("pillars = 10", "pillars = 1", ("[test] pillars", "1", "[2, 2000]")),
        ('tip = "flat_punch"', 'tip = "suction"', ("[space] tip", "suction", "flat_punch")),
        ("radius_um = [1.0, 5.0]", "radius_um = [5.0, 1.0]", ("[space] radius_um", "low")),
        ("lean_deg = 90.0", "lean_deg = 95.0", ("[space] lean_deg", "95", "[10, 90]")),
        ("fill_fraction = 0.2", "spacing_um = 4.0\nfill_fraction = 0.2", ("spacing_um",)),
        ('kind = "flat"', 'kind = "measured"\nfile = "nowhere.csv"', ("[surface] file",)),
        ("w_J_per_m2", "gamma", ("[material]", "unknown key 'gamma'")),
        ('objectives = "pull_off_per_area"', 'objectives = "grip"', ("objectives", "grip")),
        ("aspect_ratio = 2.0", "aspect_ratio = 2.0\nbacking_thickness_um = 50.0",
         ("backing_thickness_um", "elastic")),
    ],
)  # fmt: skip
def test_bad_design_files_are_refused_naming_key_value_and_range(tmp_path, old, new, names):
    assert old in BASE
    with pytest.raises(RunFileError) as err:
        load_design(design(tmp_path, BASE.replace(old, new)))
    for n in names:
        assert n in str(err.value)


def test_the_quick_variant_and_the_constraints_are_checked_too(tmp_path):
    quick = BASE + "\n[quick.test]\nfloor_seeds = 0\n"
    with pytest.raises(RunFileError, match=r"\[quick.test\] floor_seeds.*--quick variant"):
        load_design(design(tmp_path, quick))
    none_left = BASE + "\n[constraints]\nmin_radius_um = 6.0\n"
    with pytest.raises(RunFileError, match=r"min_radius_um.*leaves no design"):
        load_design(design(tmp_path, none_left))
    spatula = BASE.replace('"flat_punch"', '"spatula"').replace(
        'kind = "flat"', 'kind = "measured"\nfile = "dektak"'
    )
    with pytest.raises(RunFileError, match=r"\[space\] tip.*'spatula'.*measured"):
        load_design(design(tmp_path, spatula))
    small_probe = BASE.replace(
        "preload_kPa", 'probe = "sphere"\nprobe_radius_um = 3.0\nengine_pillars = 10\npreload_kPa'
    )
    with pytest.raises(RunFileError, match=r"radius_um = 5.*not a valid parameter set.*probe"):
        load_design(design(tmp_path, small_probe))


def best_trial(spec, tmp_path):
    study = search.run_search(spec, tmp_path / "out")
    return search.ranked(spec, search.completed(study))[0]


@needs_optuna
def test_without_interface_strength_the_best_punch_is_the_smallest_allowed(tmp_path):
    """Kendall's pull-off per area at a fixed fill fraction f: n·√(8πE*wa³) over n·s²,
    s = a·√(π/f), falls as a^(-1/2); the smallest radius the process allows wins."""
    a_min = 1.5
    spec = load_design(design(tmp_path, BASE + f"\n[constraints]\nmin_radius_um = {a_min}\n"))
    best = best_trial(spec, tmp_path)
    a = best.params["radius_um"]
    assert a_min <= a < 1.1 * a_min
    s = a * math.sqrt(math.pi / 0.2)
    kendall = float(punch.kendall_pull_off(a, W, E_star())) / s**2 / KPA
    assert best.values[0] == pytest.approx(kendall, rel=1e-9)
    at_bound = float(punch.kendall_pull_off(a_min, W, E_star())) * 0.2 / (math.pi * a_min**2)
    assert best.values[0] == pytest.approx(at_bound / KPA, rel=0.05)


@needs_optuna
def test_with_a_buckling_preload_the_best_aspect_ratio_sits_on_the_constraint(tmp_path):
    """On a rough floor a longer pillar reaches more of it (the row holds more), until the
    equal share of the bound's pressure, p·s², reaches the clamped-clamped Euler load
    4π²EI/L²: L_max = √(4π²EI/(p s²)), the best aspect ratio L_max/(2r)."""
    p_c, r, f = 20.0, 1.5, 0.2
    text = (
        BASE.replace('kind = "flat"', 'kind = "gaussian"\nsigma_um = 0.3')
        .replace("radius_um = [1.0, 5.0]", f"radius_um = {r}")
        .replace("aspect_ratio = 2.0", "aspect_ratio = [1.0, 20.0]")
        .replace("pillars = 10", "pillars = 30")
        .replace("trials = 40", "trials = 50")
    ) + f"\n[constraints]\nno_buckling_below_kPa = {p_c}\n"
    spec = load_design(design(tmp_path, text))
    s = r * math.sqrt(math.pi / f)
    EI = E * math.pi * r**4 / 4.0
    ar_max = math.sqrt(4 * math.pi**2 * EI / (p_c * KPA * s * s)) / (2 * r)
    assert 1.0 < ar_max < 20.0
    best = best_trial(spec, tmp_path)
    assert 0.95 * ar_max <= best.params["aspect_ratio"] <= ar_max


@needs_optuna
def test_a_killed_study_resumes_with_every_finished_trial(tmp_path):
    optuna = extras.require("design")
    spec = load_design(design(tmp_path))
    out = tmp_path / "out"
    first = search.run_search(spec, out, trials=5)
    kept = [(t.number, t.params, t.values) for t in search.completed(first)]
    first.ask()  # a trial cut off by a kill: left running in the store
    study = search.run_search(spec, out, trials=8)
    done = search.completed(study)
    assert len(done) == 8
    assert [(t.number, t.params, t.values) for t in done[:5]] == kept
    states = [t.state for t in study.get_trials(deepcopy=False)]
    assert states.count(optuna.trial.TrialState.FAIL) == 1
    assert optuna.trial.TrialState.RUNNING not in states
    for t in done:
        rec = t.user_attrs["record"]
        assert rec["floor_seeds"] == [0] and rec["study_seed"] == 0
        assert rec["code_version"] and len(rec["code_fingerprint"]) == 16
        assert t.user_attrs["design"]["radius_um"] == t.params["radius_um"]


@needs_optuna
def test_a_fixed_seed_gives_the_same_study(tmp_path):
    spec = load_design(design(tmp_path))
    runs = [search.completed(search.run_search(spec, tmp_path / d, trials=12)) for d in "ab"]
    assert [t.params for t in runs[0]] == [t.params for t in runs[1]]
    assert [t.values for t in runs[0]] == [t.values for t in runs[1]]


@pytest.mark.slow
@needs_optuna
def test_the_quick_example_runs_in_well_under_a_minute_and_its_run_file_reproduces(tmp_path):
    import json
    import time
    from pathlib import Path

    from gecko_agents.analysis.pull import pull_off
    from gecko_agents.cli import main
    from gecko_agents.runfiles.run import read_run_file

    example = Path(__file__).resolve().parents[1] / "examples" / "design_pillars.toml"
    out = tmp_path / "design"
    cpu = time.process_time()  # its own work: the shared machine's load does not count
    assert main(["design", str(example), "--quick", "--out", str(out)]) == 0
    assert time.process_time() - cpu < 30.0
    for name in ("report.md", "trials.csv", "pareto_front.png", "objectives_vs_parameters.png"):
        assert (out / name).stat().st_size > 0
    best = json.loads((out / "best.json").read_text())["best"][0]
    run = read_run_file(out / "runs" / "design_1.toml")
    h = run.build_model().run(run.protocol, progress=False)
    area = run.params.array.count * run.params.array.pitch**2
    assert pull_off(h).adhesion / area / KPA == pytest.approx(best["engine"]["runs"][0], rel=1e-9)


def test_a_run_file_floor_table_is_the_scan_from_its_offset(tmp_path):
    from gecko_agents.data import DEKTAK_PROFILE
    from gecko_agents.floor import readers
    from gecko_agents.runfiles.run import read_run_file

    text = 'preset = "PAPER_TABLE1"\n[floor]\nfile = "dektak"\noffset_um = 100.0\n'
    text += '[protocol]\npreset = "press_pull"\ndepth_um = 0.5\n'
    spec = read_run_file(design(tmp_path, text, "run.toml"))
    scan = readers.read_text(DEKTAK_PROFILE)
    k = int(scan.x.searchsorted(scan.x[0] + 100.0))
    assert spec.floor_profile.x[0] == 0.0
    assert list(spec.floor_profile.y) == list(scan.y[k:])
    with pytest.raises(RunFileError, match=r"\[floor\] offset_um.*outside the scan"):
        read_run_file(design(tmp_path, text.replace("100.0", "1e9"), "run.toml"))


@pytest.mark.parametrize(
    "tips,surface,extra",
    [
        ('["flat_punch", "sphere"]', 'kind = "self_affine"\nsigma_um = 0.2', ""),
        ('["spatula", "hertz"]', 'kind = "gaussian"\nsigma_um = 0.2', ""),
        ('"flat_punch"', 'kind = "measured"\nfile = "dektak"', ""),
        ('"flat_punch"', 'kind = "flat"', 'probe = "sphere"\nengine_pillars = 10\n'),
    ],
)
def test_every_tip_kind_and_surface_is_screened(tmp_path, tips, surface, extra):
    """Each tip kind on each surface kind gives finite objectives; Hertz holds nothing."""
    from gecko_agents.design.screen import evaluate

    text = BASE.replace('"flat_punch"', tips).replace('kind = "flat"', surface)
    spec = load_design(design(tmp_path, text.replace("preload_kPa", extra + "preload_kPa")))
    for tip in spec.choices["tip"]:
        res = evaluate(spec, {"tip": tip, "backing": "rigid", "radius_um": 2.0})
        assert all(math.isfinite(v) for v in res["objectives"].values())
        held = res["objectives"]["pull_off_per_area"]
        assert held == 0.0 if tip == "hertz" else held > 0.0


def test_ranking_keeps_each_feasible_design_once_and_puts_the_front_first(tmp_path):
    from types import SimpleNamespace as T

    spec = load_design(
        design(tmp_path, BASE.replace('"pull_off_per_area"', '["pull_off_per_area", "spread"]'))
    )
    ok = {"record": {"constraint_values": [-1.0]}}
    trials = [
        T(number=0, params={"r": 1}, values=[10.0, 0.5], user_attrs=ok),
        T(number=1, params={"r": 2}, values=[8.0, 0.1], user_attrs=ok),
        T(number=2, params={"r": 3}, values=[7.0, 0.3], user_attrs=ok),  # dominated by 1
        T(number=3, params={"r": 1}, values=[10.0, 0.5], user_attrs=ok),  # drawn again
        T(
            number=4,
            params={"r": 4},
            values=[99.0, 0.0],
            user_attrs={"record": {"constraint_values": [0.2]}},
        ),
    ]
    assert [t.number for t in search.ranked(spec, trials)] == [0, 1, 2]


@pytest.mark.slow
@needs_optuna
def test_two_worker_processes_fill_one_study(tmp_path):
    from gecko_agents.design import run_design

    spec = load_design(design(tmp_path, BASE))
    summary = run_design(spec, tmp_path / "out", trials=16, workers=2, say=lambda s: None)
    assert 16 <= summary["trials"] <= 17  # a worker may finish one trial past the target
    study = search.open_study(spec, tmp_path / "out")
    assert len({tuple(t.params.items()) for t in search.completed(study)}) >= 8


def test_design_command_refuses_bad_arguments_before_any_trial(tmp_path, capsys):
    from gecko_agents.cli import main

    path = design(tmp_path)
    assert main(["design", str(path), "--workers", "0", "--out", str(tmp_path / "o")]) == 2
    assert "--workers 0" in capsys.readouterr().err
    bad = design(tmp_path, BASE.replace("pillars = 10", "pillars = 1.5"), "bad.toml")
    assert main(["design", str(bad), "--out", str(tmp_path / "o")]) == 2
    assert "[test] pillars" in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_a_row_longer_than_the_measured_scan_is_refused(tmp_path):
    text = BASE.replace('kind = "flat"', 'kind = "measured"\nfile = "dektak"').replace(
        "pillars = 10", "pillars = 400"
    )
    with pytest.raises(RunFileError, match=r"\[test\] pillars.*400 pillars.*scan is 1500 µm"):
        load_design(design(tmp_path, text))


def test_the_largest_preload_bound_is_the_force_that_brings_every_tip_down(tmp_path):
    """On a floor tilted by α a row of linear fibrils of stiffness k touches everywhere once
    pressed by Σ k·(h_max − h_i) = k·tan α·s·Σ(n − 1 − i) = k·tan α·s·n(n − 1)/2."""
    from gecko_agents.design.screen import design_params, evaluate, fibril_stiffness

    text = BASE.replace("pillars = 10", "pillars = 6").replace(
        "floor_seeds = 1", "floor_seeds = 1\nmisalignment_spread_deg = 0.5"
    )
    spec = load_design(design(tmp_path, text + "\n[constraints]\nmax_preload_kPa = 1.0\n"))
    values = {"tip": "flat_punch", "backing": "rigid", "radius_um": 2.0}
    res = evaluate(spec, values)
    p = design_params(spec, values)
    n, s = 6, p.array.pitch
    force = fibril_stiffness(p) * math.tan(math.radians(0.5)) * s * n * (n - 1) / 2
    assert res["metrics"]["full_contact_kPa"] == pytest.approx(force / (n * s * s) / KPA)
    assert res["constraints"]["max_preload_kPa"] == pytest.approx(
        res["metrics"]["full_contact_kPa"] / 1.0 - 1.0
    )


@pytest.mark.slow
@needs_optuna
def test_a_local_dask_cluster_fills_and_confirms_one_study(tmp_path):
    extras.require("dask")
    from gecko_agents.design import run_design

    spec = load_design(design(tmp_path, BASE.replace("confirm = 0", "confirm = 1")))
    out = tmp_path / "out"
    summary = run_design(spec, out, trials=8, workers=2, dask="local", say=lambda s: None)
    assert 8 <= summary["trials"] <= 9
    assert summary["best"][0]["engine"]["mean"] > 0
    assert (out / "runs" / "design_1.toml").is_file()


@needs_optuna
def test_a_search_refuses_a_folder_of_someone_elses_files(tmp_path, capsys):
    from gecko_agents.cli import main

    mine = tmp_path / "notes"
    mine.mkdir()
    (mine / "thesis.tex").write_text("keep")
    assert main(["design", str(design(tmp_path)), "--out", str(mine)]) == 2
    assert "thesis.tex" in capsys.readouterr().err
    assert sorted(p.name for p in mine.iterdir()) == ["thesis.tex"]


@pytest.mark.parametrize(
    "surface",
    ['kind = "gaussian"\nsigma_um = 0.2', 'kind = "self_affine"\nsigma_um = 0.2',
     'kind = "measured"\nfile = "dektak"'],
)  # fmt: skip
def test_the_screen_stands_on_the_engines_floor(tmp_path, surface):
    """A row as long as the engine's meets the heights the engine's tips meet, every seed."""
    import numpy as np

    from gecko_agents.design.confirm import engine_setup
    from gecko_agents.design.screen import design_params, row_heights
    from gecko_agents.model import Model

    text = BASE.replace('kind = "flat"', surface).replace("pillars = 10", "pillars = 5")
    spec = load_design(design(tmp_path, text))
    values = {"tip": "flat_punch", "backing": "rigid", "radius_um": 2.0}
    for i in (0, 1):
        p, kw, _ = engine_setup(spec, values, i)
        prof = Model(p, **kw).profile
        x = (np.arange(5) - 2) * p.array.pitch
        engine = prof.pad_heights if prof.pad_heights is not None else prof.height_at(x)
        screen = row_heights(spec, design_params(spec, values, 5), i)
        np.testing.assert_allclose(screen, engine, rtol=0, atol=1e-12)


@pytest.mark.slow
@needs_optuna
def test_a_study_killed_mid_trial_resumes_with_no_finished_trial_lost(tmp_path):
    import signal
    import subprocess
    import sys
    import time

    path = design(tmp_path, BASE.replace("trials = 40", "trials = 100000"))
    spec = load_design(path)
    out = tmp_path / "out"
    cmd = [sys.executable, "-m", "gecko_agents", "design", str(path), "--out", str(out)]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline:
            time.sleep(0.5)
            if (out / search.STUDY_DB).exists():
                try:
                    if (
                        len(
                            search.completed(
                                search.open_study(spec, out, search.local_storage(out))
                            )
                        )
                        >= 10
                    ):
                        break
                except Exception:  # the store is being created
                    continue
        proc.send_signal(signal.SIGKILL)
    finally:
        proc.wait(timeout=30)
    before = search.completed(search.open_study(spec, out, search.local_storage(out)))
    assert len(before) >= 10
    kept = {t.number: (t.params, t.values) for t in before}
    study = search.run_search(spec, out, trials=len(before) + 3)
    after = {t.number: (t.params, t.values) for t in search.completed(study)}
    assert len(after) == len(before) + 3
    assert all(after[n] == v for n, v in kept.items())


@needs_optuna
def test_with_an_interface_strength_the_best_punch_is_flaw_tolerant(tmp_path):
    """With σ₀ finite a punch below the flaw-tolerant radius a_cr = 8E*w/(πσ₀²) lets go at
    σ₀·πa² (Tang, Hui & Glassmaker 2005), so its pull-off per area is σ₀ times the fill
    fraction at every such radius: the best design sits at or below a_cr and reaches σ₀·f."""
    sigma0, f = 0.3, 0.2
    a_cr = float(flaw_tolerance.flaw_tolerant_radius(sigma0, E_star(), W))
    assert 1.0 < a_cr < 20.0
    text = BASE.replace("radius_um = [1.0, 5.0]", "radius_um = [1.0, 20.0]").replace(
        "[material]", f"[material]\nsigma0_MPa = {sigma0}"
    )
    best = best_trial(load_design(design(tmp_path, text)), tmp_path)
    assert best.params["radius_um"] <= a_cr
    assert best.values[0] == pytest.approx(sigma0 * f / KPA, rel=1e-6)


def test_the_interface_strength_defaults_to_none(tmp_path):
    spec = load_design(design(tmp_path))
    assert spec.material["sigma0_MPa"] == math.inf


@needs_optuna
def test_a_mushroom_with_an_intact_rim_grows_its_flange_to_the_gap_the_process_allows(tmp_path):
    """A sharp 45° rim is not singular (the wedge's eigenproblem), so with no defect the
    flange lets go uniformly at σ₀: F = σ₀·π(βr)², and per area σ₀·π(βr)²/s² grows with the
    flange ratio β until the flanges come within the smallest gap, β_max = (s − g)/(2r)."""
    sigma0, r, f, gap = 0.3, 2.0, 0.2, 1.0
    s = r * math.sqrt(math.pi / f)
    beta_max = (s - gap) / (2 * r)
    assert 1.0 < beta_max < 3.0
    text = (
        BASE.replace("[material]", f"[material]\nsigma0_MPa = {sigma0}")
        .replace(
            'tip = "flat_punch"', 'tip = "mushroom"\nmushroom_rim = "sharp"\nrim_angle_deg = 45.0'
        )
        .replace("radius_um = [1.0, 5.0]", f"radius_um = {r}\nflange_ratio = [1.0, 3.0]")
    ) + f"\n[constraints]\nmin_gap_um = {gap}\n"
    best = best_trial(load_design(design(tmp_path, text)), tmp_path)
    beta = best.params["flange_ratio"]
    assert 0.97 * beta_max <= beta <= beta_max
    assert best.values[0] == pytest.approx(
        sigma0 * math.pi * (beta * r) ** 2 / s**2 / KPA, rel=1e-6
    )


@pytest.mark.parametrize(
    "tip, backing, dropped",
    [
        (
            "flat_punch",
            "rigid",
            {
                "flange_ratio",
                "mushroom_rim",
                "rim_angle_deg",
                "backing_thickness_um",
                "backing_modulus_MPa",
            },
        ),
        ("mushroom", "layer", {"rim_angle_deg"}),
        ("sphere", "layer", {"flange_ratio", "mushroom_rim", "rim_angle_deg"}),
    ],
)
def test_a_design_lists_only_the_knobs_that_act_on_it(tip, backing, dropped):
    """The report and the command line show a design's knobs that act on it: dropping the
    others leaves the parameters the model is built from unchanged."""
    from gecko_agents.design.space import in_use, overrides_of

    values = {
        "tip": tip,
        "backing": backing,
        "radius_um": 2.0,
        "aspect_ratio": 3.0,
        "fill_fraction": 0.2,
        "flange_ratio": 1.5,
        "mushroom_rim": "flawed",
        "rim_angle_deg": 30.0,
        "backing_thickness_um": 50.0,
        "backing_modulus_MPa": 1.4,
    }
    kept = in_use(values)
    assert set(values) - set(kept) == dropped
    if tip != "mushroom":
        assert overrides_of(kept) == overrides_of(values)
