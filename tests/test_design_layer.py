"""The design search on a backing layer (the field model as a screening fidelity, the engine's
layer as its confirmation) and its workers: limits the layer's closed forms pin, the sampler's
constraint and seeds, the batched workers."""

import math

import numpy as np
import pytest
from test_design import BASE, design, needs_optuna

from gecko_agents.design import load_design, screen, search
from gecko_agents.design.space import KPA
from gecko_agents.physics import fibril_probe, layer

LAYER = BASE.replace(
    'tip = "flat_punch"',
    'tip = "flat_punch"\nbacking = "layer"\nbacking_thickness_um = [1.0, 1000.0]\n'
    "backing_modulus_MPa = [0.01, 100.0]",
)
ROUGH = LAYER.replace(
    'kind = "flat"', 'kind = "gaussian"\nsigma_um = 0.3\ncorrelation_length_um = 5.0'
).replace("fill_fraction = 0.2", "fill_fraction = 0.05")


def _row(tmp_path, text, **values):
    spec = load_design(design(tmp_path, text))
    v = {"tip": "flat_punch", "backing": "layer", "radius_um": 2.0, **values}
    p = screen.design_params(spec, v)
    preload = spec.test["preload_kPa"] * KPA * p.array.count * p.array.pitch**2
    return spec, v, p, screen.row_heights(spec, p, 0), preload


def test_a_layer_of_no_compliance_is_the_rigid_backings_closed_form(tmp_path):
    """With C = 0 the field model's event-driven test is the independent-fibril closed form
    (fibril_probe) exactly, on a rough floor: pull-off, the pillar's peak and the force that
    brings every tip down."""
    spec, v, p, h, P = _row(tmp_path, ROUGH, backing_thickness_um=50.0, backing_modulus_MPa=1.0)
    zero = np.zeros((h.size, h.size))
    rigid = p.replace(**{"backing.kind": "rigid"})
    assert np.ptp(h) > 0.1  # a rough row: tips touch one after another
    F, top = screen.layer_pull_off(p, h, P, zero)
    assert F == pytest.approx(screen.pull_off(rigid, h, P)[0], rel=1e-12)
    assert top == pytest.approx(screen.pull_off(rigid, h, P)[1], rel=1e-12)
    assert screen.full_contact_force(p, h, zero) == pytest.approx(
        screen.full_contact_force(rigid, h), rel=1e-12
    )


@pytest.mark.parametrize("E_b", [0.01, 0.1])
def test_a_thin_layer_is_a_bed_of_springs_of_its_confined_modulus(tmp_path, E_b):
    """A layer much thinner than the pitch (t = 1 µm, s = 15.9 µm) carries each root on its
    own cell as a spring of stiffness M·s²/t (M the confined modulus, the layer's thin limit,
    physics.layer): the row is then the rigid backing's closed form with that spring in series
    with each pillar, softer than the pillar itself at E_b = 0.01 MPa."""
    spec, v, p, h, P = _row(tmp_path, ROUGH, backing_thickness_um=1.0, backing_modulus_MPa=E_b)
    k, F_r = screen.field_fibril(p)
    s = p.array.pitch
    k_layer = s * s / layer.thin_layer_compliance(1.0, E_b, p.backing.nu_b)
    k_series = 1.0 / (1.0 / k + 1.0 / k_layer)
    hh = h - h.max()
    d_max = fibril_probe.depth_for_preload(P, hh, k_series)
    expected = fibril_probe.probe_pull_off(hh, k_series, F_r, d_max)
    F, _ = screen.layer_pull_off(p, h, P, screen.layer_compliance(p))
    assert F == pytest.approx(expected, rel=2e-4)  # the cells' edges: O(t/s) of the layer's part
    rigid = screen.pull_off(p.replace(**{"backing.kind": "rigid"}), h, P)[0]
    assert abs(F / rigid - 1.0) > 10 * 2e-4  # the layer's own compliance matters here


def test_on_a_flat_floor_a_thick_soft_layer_shares_the_load_unequally(tmp_path):
    """On a flat floor equal sharing holds N·F_r; no layer holds more. A stiff layer comes
    within 1e-3 of it; a thick soft one loads the row's ends first (the layer's kernel couples
    the roots, the ends having fewer neighbours), so the pull-off falls with the thickness."""
    found = []
    for t, E_b in ((1.0, 100.0), (10.0, 1.413), (100.0, 1.413), (1000.0, 1.413)):
        spec, v, p, h, P = _row(tmp_path, LAYER, backing_thickness_um=t, backing_modulus_MPa=E_b)
        n, s = p.array.count, p.array.pitch
        equal = n * screen.field_fibril(p)[1] / (n * s * s) / KPA
        found.append(screen.evaluate(spec, v)["objectives"]["pull_off_per_area"] / equal)
    assert all(f <= 1.0 + 1e-12 for f in found)
    assert found[0] == pytest.approx(1.0, abs=1e-3)
    assert found == sorted(found, reverse=True) and found[-1] < 0.95


def test_the_largest_preload_bound_counts_from_the_lowest_point(tmp_path):
    """Every tip is down once the one over the lowest point touches: each pillar is then
    pressed by h_i − min h, so floor heights (0, 0, −1) µm take 2k, not k."""
    spec = load_design(design(tmp_path, BASE))
    p = screen.design_params(spec, {"tip": "flat_punch", "backing": "rigid", "radius_um": 2.0})
    k = screen.fibril_stiffness(p)
    assert screen.full_contact_force(p, np.array([0.0, 0.0, -1.0])) == pytest.approx(2 * k)


def test_a_layer_design_is_refused_or_built_naming_its_knobs(tmp_path):
    from gecko_agents.runfiles.schema import RunFileError

    rigid = LAYER.replace('backing = "layer"', 'backing = "rigid"')
    with pytest.raises(RunFileError, match=r"backing_thickness_um.*'elastic' or 'layer'"):
        load_design(design(tmp_path, rigid))
    spec = load_design(design(tmp_path, LAYER))
    p = screen.design_params(
        spec, {"tip": "flat_punch", "backing": "layer", "radius_um": 2.0,
               "backing_thickness_um": 30.0, "backing_modulus_MPa": 2.0},
    )  # fmt: skip
    assert (p.backing.kind, p.backing.t_b, p.backing.E_b, p.mechanics) == (
        "layer", 30.0, 2.0, "rod",  # the engine's layer holds linear or rod pillars
    )  # fmt: skip


def test_the_samplers_constraint_keeps_feasibility_and_the_summed_violation():
    assert search.violation([-1.0, -0.5]) == -0.5
    assert search.violation([0.2, -1.0, 0.3]) == pytest.approx(0.5)
    assert search.violation([0.0, -1.0]) == 0.0


def test_each_worker_draws_with_its_own_seed(tmp_path):
    spec = load_design(design(tmp_path, BASE))
    seeds = [search.sampler_seed(spec, k) for k in range(4)]
    assert seeds[0] == spec.seed and len(set(seeds)) == 4
    assert seeds == [search.sampler_seed(spec, k) for k in range(4)]


@pytest.mark.slow
@needs_optuna
def test_a_layer_design_is_confirmed_on_the_engines_layer(tmp_path):
    """The engine runs the design on its backing layer (rod pillars, the explicit step) and
    the run file says so; on a flat floor the two fidelities agree within the report's
    threshold."""
    from gecko_agents.design import confirm

    text = LAYER.replace("pillars = 10", "pillars = 4\nengine_pillars = 4\nengine_seeds = 1")
    spec, v, p, h, P = _row(tmp_path, text, backing_thickness_um=50.0, backing_modulus_MPa=1.413)
    eng = confirm.confirm_design(spec, v)
    screened = screen.evaluate(spec, v)["objectives"]["pull_off_per_area"]
    assert eng["release"] is None and len(eng["runs"]) == 1
    assert abs(eng["mean"] / screened - 1.0) <= confirm.DISAGREE
    text = confirm.run_file_text(spec, v, "design_1")
    assert '"backing.kind" = "layer"' in text and '"mechanics" = "rod"' in text


@pytest.mark.slow
@needs_optuna
def test_the_worker_benchmark_times_one_against_two_workers_on_new_stores(tmp_path):
    from gecko_agents.design.benchmark import benchmark_workers

    spec = load_design(design(tmp_path, BASE))
    b = benchmark_workers(spec, trials=6, pairs=1)
    assert b["trials"] == 6 and b["workers"] == 2
    assert b["ratio"] == pytest.approx(b["many_s"][0] / b["one_s"][0])
    assert len(b["machine"]) == len(b["cpu_ratios"]) == 1 and b["cpu_ratios"][0] > 0
    assert not list(tmp_path.glob("**/study.db"))  # nothing left behind
    with pytest.raises(ValueError, match="workers = 1"):
        benchmark_workers(spec, workers=1)
    assert math.isfinite(b["ratio"])


def test_the_showcase_bound_is_the_flat_floor_screen_at_the_gap_and_peaks_at_one_and_a_half_gaps(
    tmp_path,
):
    """Flat punches on a flat floor and a rigid backing share the load equally, so the screen
    at pitch 2a + g is the bound F(a)/(2a + g)² exactly; without σ₀, F ∝ a^{3/2} and
    a^{3/2}/(2a + g)² peaks at a = 1.5·g."""
    from gecko_agents.design.showcase import gap_bound

    text = BASE.replace("fill_fraction = 0.2", "spacing_um = [2.0, 50.0]")
    spec = load_design(design(tmp_path, text))
    g, a = 2.0, 3.0
    v = {"tip": "flat_punch", "backing": "rigid", "radius_um": a, "spacing_um": 2 * a + g}
    c = screen.design_params(spec, v).contact
    bound = float(gap_bound(a, g, c.work_of_adhesion, c.E_star))
    assert screen.evaluate(spec, v)["objectives"]["pull_off_per_area"] == pytest.approx(
        bound, rel=1e-12
    )
    r = np.linspace(0.5, 10.0, 19001)
    peak = r[np.argmax(gap_bound(r, g, c.work_of_adhesion, c.E_star))]
    assert peak == pytest.approx(1.5 * g, abs=1e-3)


@needs_optuna
@pytest.mark.parametrize("workers", [1, 2])
def test_a_local_study_stores_every_finished_trial_and_resumes_from_them(
    tmp_path, monkeypatch, workers
):
    """The local study (sampled in memory, each finished trial written to the file) keeps a
    refused design as a failed trial with its reason, and a second run continues from the
    file's trials; one worker's study is the database storage's, draw for draw."""
    from gecko_agents.design import local

    spec = load_design(design(tmp_path, BASE))
    real = search.evaluate

    def refuse_large(s, values):
        if values["radius_um"] > 4.0:
            raise ValueError("radius_um: refused for the test")
        return real(s, values)

    monkeypatch.setattr(search, "evaluate", refuse_large)  # this process's, not a spawned one's
    out = tmp_path / "local"
    store = local.run_local(spec, out, trials=12, workers=workers)
    fails = search.failed(store)
    assert len(search.completed(store)) + len(fails) == 12
    assert all("refused for the test" in t.user_attrs["error"] for t in fails)
    if workers == 1:
        assert fails  # the seed draws radii above 4 µm among its first 12
        rdb = search.completed(search.run_search(spec, tmp_path / "rdb", trials=12))
        assert [t.params for t in search.completed(store)] == [
            t.params for t in rdb if t.params["radius_um"] <= 4.0
        ]
    kept = {t.number: t.params for t in search.completed(store)}
    again = local.run_local(spec, out, trials=len(kept) + 3, workers=workers)
    assert {t.number: t.params for t in search.completed(again)}.items() >= kept.items()
    n_again = len(search.completed(again)) + len(search.failed(again))
    assert n_again == len(kept) + len(fails) + 3  # three more trials, a refused one failing


def test_a_hand_started_worker_is_numbered_only_on_a_shared_store(tmp_path, capsys):
    from gecko_agents.cli import main

    path = design(tmp_path, BASE)
    assert main(["design", str(path), "--worker", "1", "--out", str(tmp_path / "o")]) == 2
    assert "--worker 1" in capsys.readouterr().err
    assert main(["design", str(path), "--worker", "-1", "--out", str(tmp_path / "o")]) == 2


def test_a_design_no_worker_has_begun_is_taken_back_the_last_handed_first():
    """Designs handed to the workers but not begun are cancelled there and evaluated by the
    drawing process; a design a worker has begun stays with it."""
    import concurrent.futures as cf

    from gecko_agents.design.local import _steal

    begun, waiting_1, waiting_2 = cf.Future(), cf.Future(), cf.Future()
    assert begun.set_running_or_notify_cancel()
    running = {begun: "a", waiting_1: "b", waiting_2: "c"}
    assert _steal(running) is waiting_2 and waiting_2.cancelled()
    running.pop(waiting_2)
    assert _steal(running) is waiting_1
    running.pop(waiting_1)
    assert _steal(running) is None and not begun.cancelled()


@needs_optuna
def test_two_workers_evaluate_every_drawn_design_once(tmp_path):
    """With Optuna's random sampler the draws do not depend on the results, so two workers
    (designs queued, the ones not begun taken back at the end) store the one worker's designs
    and objectives, each once (numbered in the order they finish)."""
    from gecko_agents.design import local

    optuna = search.require_optuna()
    spec = load_design(design(tmp_path, BASE))

    def stored(workers):
        sampler = optuna.samplers.RandomSampler(seed=spec.seed)
        store = local.run_local(spec, tmp_path / f"w{workers}", 24, workers, sampler=sampler)
        return sorted(
            (tuple(sorted(t.params.items())), tuple(t.values)) for t in search.completed(store)
        )

    one, two = stored(1), stored(2)
    assert len(one) == 24
    assert two == one
