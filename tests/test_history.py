"""History: save/load round trip, atomic writes, clear errors on bad run directories."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from gecko_agents import history as hist
from gecko_agents import output_paths
from gecko_agents.params import PAPER_TABLE1


def _toy(n=5, N=3):
    rng = np.random.default_rng(0)
    scalars = {c: rng.normal(size=n) for c in hist.SCALAR_COLUMNS}
    setae = {f: rng.normal(size=(n, N)) for f in hist.PER_SETA_FIELDS}
    setae["state"] = rng.integers(0, 3, size=(n, N)).astype(np.int8)
    geometry = {
        "root_dx_um": np.arange(N) * 4.0,
        "root_dy_um": np.zeros(N),
        "floor_x_um": np.array([-50.0, 50.0]),
        "floor_y_um": np.zeros(2),
    }
    det = {
        "seta": np.array([1]),
        "time_us": np.array([3.0]),
        "plate_y_um": np.array([2.0]),
        "overlap_um": np.array([-0.2]),
        "force_uN": np.array([-1.0]),
    }
    return hist.History(PAPER_TABLE1, 42, scalars, setae, geometry, det, {"dt_us": 0.1})


def test_round_trip(tmp_path):
    h = _toy()
    h.save(tmp_path / "run")
    g = hist.load_history(tmp_path / "run")
    assert g.params == h.params and g.seed == 42 and g.meta["dt_us"] == 0.1
    for c in hist.SCALAR_COLUMNS:
        np.testing.assert_array_equal(g[c], h[c])
    for k in h.setae:
        np.testing.assert_array_equal(g.setae[k], h.setae[k])
    assert g.setae["state"].dtype == np.int8
    np.testing.assert_array_equal(g.detachments["overlap_um"], [-0.2])
    assert "numpy" in g.meta["versions"]
    assert not list((tmp_path / "run").glob("*.tmp"))


def test_missing_and_corrupt_runs(tmp_path):
    with pytest.raises(FileNotFoundError, match="does not exist"):
        hist.load_history(tmp_path / "nope")
    _toy().save(tmp_path / "run")
    (tmp_path / "run" / "history.csv").write_text("garbage,1\nx,y\n")
    with pytest.raises(ValueError, match="history.csv"):
        hist.load_history(tmp_path / "run")
    (tmp_path / "run" / "metadata.json").unlink()
    with pytest.raises(FileNotFoundError, match="metadata.json"):
        hist.load_history(tmp_path / "run")


def test_columns_are_checked():
    with pytest.raises(ValueError, match="lacks columns"):
        hist.History(PAPER_TABLE1, 0, {"time_us": np.zeros(2)})


def test_failed_write_leaves_no_file(tmp_path, monkeypatch):
    target = tmp_path / "x.bin"

    def boom(*a, **k):
        raise OSError("disk full")

    monkeypatch.setattr(output_paths.os, "replace", boom)
    with pytest.raises(OSError):
        output_paths.atomic_write_bytes(target, b"abc")
    assert not target.exists() and not list(tmp_path.iterdir())


def test_invariant_checks_catch_violations():
    h = _toy()
    n = len(h)
    h.scalars["n_attached"] = np.ones(n)
    Fc = h.params.contact.pull_off_force
    h.scalars["force_normal_uN"] = np.full(n, -0.5 * Fc)
    h.scalars["force_tangential_uN"] = np.zeros(n)
    h.setae["state"] = np.ones_like(h.setae["state"])
    h.setae["force_normal_uN"] = np.full((n, 3), -0.1 * Fc)
    h.setae["overlap_um"] = np.zeros((n, 3))
    for c in ("energy_elastic_pJ", "energy_kinetic_pJ", "energy_dissipated_pJ"):
        h.scalars[c] = np.abs(h.scalars[c])
    h.scalars["work_plate_pJ"] = (
        h["energy_elastic_pJ"] + h["energy_kinetic_pJ"] + h["energy_dissipated_pJ"]
    )
    assert hist.invariant_violations(h) == []
    h.scalars["force_normal_uN"][2] = -1.5 * Fc
    h.scalars["energy_kinetic_pJ"][1] = np.nan
    h.setae["overlap_um"][0, 0] = 2 * h.params.contact.snap_off_overlap
    h.scalars["n_attached"][-1] = 0
    v = hist.invariant_violations(h)
    assert any("non-finite" in s for s in v) and any("n_attached·Fc" in s for s in v)
    assert any("δc" in s for s in v) and any("no tip is attached" in s for s in v)


def test_energy_balance_check_catches_a_missing_term():
    h = _toy()
    for c in ("energy_elastic_pJ", "energy_kinetic_pJ", "energy_dissipated_pJ"):
        h.scalars[c] = np.linspace(0.0, 1.0, len(h))
    h.scalars["work_plate_pJ"] = 3.0 * np.linspace(0.0, 1.0, len(h))
    assert hist.energy_balance_error(h) == 0.0
    h.scalars["energy_dissipated_pJ"] = 1.1 * h["energy_dissipated_pJ"]  # over-booked 10 %
    assert hist.energy_balance_error(h) == pytest.approx(0.1 / 3.0)
    assert any("energy balance" in s for s in hist.invariant_violations(h))
    assert not any("energy balance" in s for s in hist.invariant_violations(h, energy_rtol=False))


def test_energy_books_balance_while_a_released_pillar_rings_down():
    """Every step recorded while a flat-punch pillar (Kendall's law) lets go and its seta
    rings down, explicit step: the books balance to 0.5 % of the run's energy scale (0.21 %
    measured; without the dampers' half-step share, Stepping.damping_half_step, the records
    in the ring-down were off by −½dt·c·v², 4.8 %, halving with dt)."""
    from gecko_agents import protocol
    from gecko_agents.model import Model, Numerics
    from gecko_agents.studies import pillar_designs as pd

    p = pd.params_for("flat_punch", 5.0, "flat").replace(
        **{"array.count": 1, "contact.sigma0": float("inf")}
    )
    numerics = Numerics(record_every=1, integrator="explicit")
    h = Model(p, n_sim=1, seed=pd.SEED, numerics=numerics).run(
        protocol.press_pull(0.05 * p.seta.L, speed=0.5), progress=False
    )
    after = h["time_us"] > h.detachments["time_us"][0]
    assert h["energy_kinetic_pJ"][after].max() > 0.05 * h["work_plate_pJ"].max()  # it rings
    assert hist.energy_balance_error(h) < 0.25 * hist.ENERGY_RTOL


# Issue 18, defects 1 and 7: run-directory integrity and load errors ------------------------


def _two_runs(tmp_path):
    a, b = _toy(), _toy()
    b.scalars["force_normal_uN"] = b.scalars["force_normal_uN"] + 1.0
    a.save(tmp_path / "a")
    b.save(tmp_path / "b")
    return tmp_path / "a", tmp_path / "b"


def test_every_file_carries_the_run_id(tmp_path):
    h = _toy()
    d = h.save(tmp_path / "run")
    rid = h.run_id()
    assert len(rid) == 16 and rid == _toy().run_id()  # deterministic
    assert json.loads((d / "metadata.json").read_text())["run_id"] == rid
    assert (d / "history.csv").read_text().splitlines()[0] == ",".join(h.columns)  # plain CSV
    with np.load(d / "setae.npz") as z:
        assert str(z["run_id"]) == rid
    other = _toy()
    other.seed = 43
    assert other.run_id() != rid


def test_truncated_csv_is_refused(tmp_path):
    h = _toy(n=39)
    d = h.save(tmp_path / "run")
    lines = (d / "history.csv").read_text().splitlines(keepends=True)
    (d / "history.csv").write_text("".join(lines[:20]))  # cut at a line boundary
    with pytest.raises(ValueError, match=r"history.csv has 19 data rows.*n_records = 39"):
        hist.load_history(d)


def test_header_only_csv_says_so(tmp_path):
    d = _toy().save(tmp_path / "run")
    lines = (d / "history.csv").read_text().splitlines(keepends=True)
    (d / "history.csv").write_text("".join(lines[:1]))
    with pytest.raises(ValueError, match=r"history.csv has a header and no data rows"):
        hist.load_history(d)


def test_files_of_two_runs_are_refused(tmp_path):
    a, b = _two_runs(tmp_path)
    shutil.copy(b / "history.csv", a / "history.csv")  # new data under old metadata
    with pytest.raises(ValueError, match=r"history.csv is not the file run .* saved"):
        hist.load_history(a)
    a, b = _two_runs(tmp_path / "2")
    shutil.copy(b / "setae.npz", a / "setae.npz")
    with pytest.raises(ValueError, match=r"setae.npz belongs to run"):
        hist.load_history(a)


def test_edited_series_or_parameters_are_refused(tmp_path):
    d = _toy().save(tmp_path / "run")
    meta = json.loads((d / "metadata.json").read_text())
    meta["seed"] = 7
    (d / "metadata.json").write_text(json.dumps(meta))
    with pytest.raises(ValueError, match=r"history.csv does not hold the series"):
        hist.load_history(d)


def test_interrupted_save_onto_an_old_run_does_not_load(tmp_path, monkeypatch):
    a, _ = _two_runs(tmp_path)
    newer = _toy()
    newer.scalars["time_us"] = newer.scalars["time_us"] + 5.0
    real = hist.atomic_write_bytes

    def killed_before_metadata(path, data):
        if Path(path).name == "metadata.json":
            raise KeyboardInterrupt
        real(path, data)

    monkeypatch.setattr(hist, "atomic_write_bytes", killed_before_metadata)
    with pytest.raises(KeyboardInterrupt):
        newer.save(a)
    with pytest.raises((FileNotFoundError, ValueError), match="metadata.json"):
        hist.load_history(a)


def test_garbage_metadata_names_the_file(tmp_path):
    d = _toy().save(tmp_path / "run")
    (d / "metadata.json").write_bytes(b"\xff\xfe\x00garbage\x81")
    with pytest.raises(ValueError, match=r"metadata.json is not a gecko_agents metadata"):
        hist.load_history(d)
    (d / "metadata.json").write_text("[1, 2]")
    with pytest.raises(ValueError, match=r"metadata.json is not a gecko_agents metadata"):
        hist.load_history(d)


@pytest.mark.parametrize("seed", [-3, 2.5, "abc", True])
def test_nonsense_seed_in_metadata_is_refused(tmp_path, seed):
    d = _toy().save(tmp_path / "run")
    meta = json.loads((d / "metadata.json").read_text())
    meta["seed"] = seed
    (d / "metadata.json").write_text(json.dumps(meta))
    with pytest.raises(ValueError, match=r"metadata.json .*seed = "):
        hist.load_history(d)


def test_truncated_npz_names_the_file(tmp_path):
    d = _toy().save(tmp_path / "run")
    data = (d / "setae.npz").read_bytes()
    (d / "setae.npz").write_bytes(data[: len(data) // 2])
    with pytest.raises(ValueError, match=r"setae.npz is corrupt or truncated") as err:
        hist.load_history(d)
    assert type(err.value) is ValueError


def test_saving_a_new_run_removes_stale_files_of_the_old_one(tmp_path):
    a, b = _two_runs(tmp_path)
    (a / "detachment.gif").write_bytes(b"GIF89a old run")
    (a / "notes.txt").write_text("mine")
    hist.load_history(b).save(a)
    assert not (a / "detachment.gif").exists()  # drawn from the previous run
    assert (a / "notes.txt").read_text() == "mine"  # not a run file: left alone
    assert hist.load_history(a).run_id() == hist.load_history(b).run_id()
    # Re-saving the same run keeps what was drawn from it.
    (a / "detachment.gif").write_bytes(b"GIF89a this run")
    hist.load_history(a).save(a)
    assert (a / "detachment.gif").exists()


def test_runs_saved_before_run_ids_still_load(tmp_path):
    d = _toy().save(tmp_path / "run")
    meta = json.loads((d / "metadata.json").read_text())
    del meta["run_id"], meta["files"]
    (d / "metadata.json").write_text(json.dumps(meta))
    (d / "setae.npz").unlink()
    assert len(hist.load_history(d)) == 5


def test_quasistatic_results_speak_the_same_vocabulary(tmp_path):
    from gecko_agents import quasistatic as qs
    from gecko_agents import render
    from gecko_agents.params import PAPER_ARRAY

    p = PAPER_ARRAY.replace(**{"array.count": 5})
    heights = np.random.default_rng(0).normal(0.0, 0.5, 5)
    res = qs.press_pull(p, heights, 0.5, record_setae=True)
    h = hist.History.from_quasistatic(res, p, seed=3)
    assert set(h.scalars) == set(hist.SCALAR_COLUMNS) and h.meta["solver"] == "quasistatic"
    np.testing.assert_array_equal(h["force_normal_uN"], res.force_normal)
    np.testing.assert_array_equal(h["plate_y_um"], res.plate_y)
    assert h.peak_pull_off == pytest.approx(res.pull_off)
    assert hist.invariant_violations(h) == []
    assert h.detachments["seta"].size == len(res.releases)
    render.plot_history(h, tmp_path / "qs.png")  # the agent's plot takes it
    h.save(tmp_path / "run")
    g = hist.load_history(tmp_path / "run")
    np.testing.assert_array_equal(g["force_normal_uN"], h["force_normal_uN"])


def test_runs_saved_before_a_parameter_field_existed_still_load(tmp_path, monkeypatch):
    """A run saved by a version whose parameters lacked a field (here contact.shear_coupling,
    added later) loads with the field at its default; editing its parameters is still
    refused."""
    from gecko_agents.params import SetaArray

    real = SetaArray.to_dict

    def older(self):
        d = real(self)
        del d["contact"]["shear_coupling"]
        return d

    monkeypatch.setattr(SetaArray, "to_dict", older)
    d = _toy().save(tmp_path / "run")
    monkeypatch.setattr(SetaArray, "to_dict", real)
    assert "shear_coupling" not in json.loads((d / "metadata.json").read_text())["params"]
    h = hist.load_history(d)
    assert len(h) == 5 and h.params.contact.shear_coupling == "none"
    meta = json.loads((d / "metadata.json").read_text())
    meta["params"]["contact"]["R"] = 5.0
    (d / "metadata.json").write_text(json.dumps(meta))
    with pytest.raises(ValueError, match=r"history.csv does not hold the series"):
        hist.load_history(d)
