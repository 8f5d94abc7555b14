"""History: save/load round trip, atomic writes, clear errors on bad run directories."""

import numpy as np
import pytest

from gecko_agents import history as hist
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
    g = hist.load(tmp_path / "run")
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
        hist.load(tmp_path / "nope")
    _toy().save(tmp_path / "run")
    (tmp_path / "run" / "history.csv").write_text("garbage,1\nx,y\n")
    with pytest.raises(ValueError, match="history.csv"):
        hist.load(tmp_path / "run")
    (tmp_path / "run" / "metadata.json").unlink()
    with pytest.raises(FileNotFoundError, match="metadata.json"):
        hist.load(tmp_path / "run")


def test_columns_are_checked():
    with pytest.raises(ValueError, match="lacks columns"):
        hist.History(PAPER_TABLE1, 0, {"time_us": np.zeros(2)})


def test_failed_write_leaves_no_file(tmp_path, monkeypatch):
    target = tmp_path / "x.bin"

    def boom(*a, **k):
        raise OSError("disk full")

    monkeypatch.setattr(hist.os, "replace", boom)
    with pytest.raises(OSError):
        hist.atomic_write_bytes(target, b"abc")
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
    assert not any("energy balance" in s for s in hist.invariant_violations(h, energy_rtol=None))
