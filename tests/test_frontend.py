"""What a user sees: warnings as short lines ending in a validity summary, progress bars that end
at exactly their totals, plain history files checked by their SHA-256."""

import re
import subprocess
import sys
import warnings

import extras
import numpy as np
import pytest

from gecko_agents import protocol
from gecko_agents.console import WarningLog, summary_line
from gecko_agents.diagnostics import ValidityWarning
from gecko_agents.model import Model, Numerics
from gecko_agents.params import PAPER_ARRAY, PAPER_TABLE1

STUBBY = PAPER_ARRAY.replace(**{"array.count": 3, "seta.L": 5.0, "floor.sigma": 0.3})
PY_WARNING = re.compile(r"\.py:\d+: \w*Warning|warnings\.warn\(")


# Warnings and the validity summary ----------------------------------------------------------


@pytest.mark.slow
def test_the_main_job_prints_no_python_warning_and_ends_with_the_validity_summary(tmp_path):
    out = subprocess.run(
        [sys.executable, "-m", "gecko_agents", "reproduce", "--quick", "--no-progress",
         "--out", str(tmp_path)],
        capture_output=True, text=True, timeout=900, check=True,
    )  # fmt: skip
    text = out.stdout + out.stderr
    assert not PY_WARNING.search(text), [ln for ln in text.splitlines() if PY_WARNING.search(ln)]
    last = out.stdout.strip().splitlines()[-1]
    pattern = r"validity: (\d+ items? outside range|every item within range) in \d+ runs?"
    assert re.match(pattern, last)
    assert "paper_comparison.md" in last
    # every warning line is short: one per item per study
    assert max(len(ln) for ln in out.stderr.splitlines() or [""]) < 300


def _warn(name, value):
    message = f"validity: {name} = {value} violates value ≤ 1: why [src]"
    warnings.warn(ValidityWarning(message), stacklevel=2)


def test_one_line_per_item_per_family_and_quiet_prints_none(capsys):
    with WarningLog(1) as log:
        log.family("fig10")
        for v in (2.0, 7.5, 3.0):
            _warn("time_step", v)
        warnings.warn("something else", stacklevel=2)
        log.family("fig8")
        _warn("time_step", 1.5)
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith("fig10: time_step = 2–7.5 (limit ≤ 1) in 3 runs: ")
    assert err[1] == "fig10: warning: something else"
    assert err[2].startswith("fig8: time_step = 1.5 (limit ≤ 1) in 1 run: ")
    assert len(err) == 3
    with WarningLog(0):
        _warn("time_step", 2.0)
    assert capsys.readouterr().err == ""


def test_library_users_still_filter_validity_warnings():
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        _warn("tabor", 0.5)
    assert len(rec) == 1 and issubclass(rec[0].category, ValidityWarning)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ValidityWarning)
        with pytest.raises(ValidityWarning):
            _warn("tabor", 0.5)


def test_summary_line_counts_items_and_runs():
    runs = [{"violations": ["a_over_R", "quasi_static"]}, {"violations": ["a_over_R"]}]
    line = summary_line(runs, "the table")
    assert line.startswith("validity: 2 items outside range in 2 runs (a_over_R in 2, ")
    assert line.endswith("see the table")
    assert summary_line([{"violations": []}], "x") == "validity: every item within range in 1 run"


# Progress bars ------------------------------------------------------------------------------


class _FakeBar:
    made: list = []

    def __init__(self, total=None, **kw):
        self.total, self.n, self.desc, self.seen = total, 0, kw.get("desc", ""), []
        self.total_while_running = total
        _FakeBar.made.append(self)

    def update(self, k):
        self.n += k
        self.seen.append((self.n, self.total))

    def refresh(self):
        pass

    def close(self):
        pass


@pytest.fixture
def fake_tqdm(monkeypatch):
    import tqdm.auto

    _FakeBar.made = []
    monkeypatch.setattr(tqdm.auto, "tqdm", _FakeBar)
    return _FakeBar.made


def _check_bars(bars, kinds, spinners):
    assert [b.desc.split()[2] for b in bars] == kinds
    for b in bars:
        assert b.total is not None and b.n == b.total  # exactly 100 % at the end
        assert all(n <= t for n, t in b.seen if t is not None)  # never past the total
        is_spinner = b.desc.split()[2] in spinners
        assert (b.total_while_running is None) == is_spinner


def test_every_segment_bar_ends_at_exactly_its_total(fake_tqdm):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = Model(STUBBY, seed=1)
        m.run([protocol.PressTo(0.3, 0.02), protocol.Hold(7.3), protocol.PullOff(0.02)])
        _check_bars(fake_tqdm, ["PressTo", "Hold", "PullOff"], {"PullOff"})
        fake_tqdm.clear()
        Model(STUBBY, seed=1).run([protocol.Press(m.Fc, 0.02), protocol.PullOff(0.02)])
        _check_bars(fake_tqdm, ["Press", "PullOff"], {"Press", "PullOff"})


# Plain files ---------------------------------------------------------------------------------


@pytest.fixture(scope="module")
def saved_run(tmp_path_factory):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        big = STUBBY.replace(**{"array.count": 10_000_000})  # 3 simulated, scaled up
        h = Model(big, n_sim=3, seed=2).run(protocol.press_pull(0.3, 0.02), progress=False)
    return h, h.save(tmp_path_factory.mktemp("run"))


def test_pandas_reads_history_csv_with_default_arguments(saved_run):
    import numpy as np

    pd = extras.require("pandas")
    from gecko_agents.history import SCALAR_COLUMNS, History

    h, d = saved_run
    df = pd.read_csv(d / "history.csv")
    assert tuple(df.columns) == h.columns and h.columns[: len(SCALAR_COLUMNS)] == SCALAR_COLUMNS
    for c in h.columns:  # the values round-trip exactly (repr of a float64)
        np.testing.assert_array_equal(df[c].to_numpy(dtype=float), h[c])
    loaded = History.load(d)
    assert loaded.run_id() == h.run_id() and len(loaded) == len(h)


def test_a_tampered_file_is_refused_by_its_checksum(saved_run, tmp_path):
    import shutil

    from gecko_agents.history import History

    _, d = saved_run
    for name in ("history.csv", "setae.npz"):
        copy = tmp_path / name.replace(".", "_")
        shutil.copytree(d, copy)
        data = bytearray((copy / name).read_bytes())
        i = len(data) // 2 if name.endswith("npz") else data.rindex(b"0")
        data[i] = ord("1") if data[i] != ord("1") else ord("2")  # one byte: same length
        (copy / name).write_bytes(bytes(data))
        with pytest.raises(ValueError, match=f"{name} .*(SHA-256|corrupt)"):
            History.load(copy)


def test_directories_saved_with_the_run_id_comment_line_still_load(saved_run, tmp_path):
    import json
    import shutil

    from gecko_agents.history import History

    h, d = saved_run
    old = tmp_path / "old"
    shutil.copytree(d, old)
    meta = json.loads((old / "metadata.json").read_text())
    del meta["files"]
    (old / "metadata.json").write_text(json.dumps(meta))
    text = (old / "history.csv").read_text()
    (old / "history.csv").write_text(f"# run_id: {meta['run_id']}\n{text}")
    assert History.load(old).run_id() == h.run_id()
    (old / "history.csv").write_text(f"# run_id: 0123456789abcdef\n{text}")
    with pytest.raises(ValueError, match="belongs to run 0123456789abcdef"):
        History.load(old)


def test_a_floor_without_a_spectrum_gets_no_empty_panel(tmp_path):
    import numpy as np

    from gecko_agents import floor
    from gecko_agents.render.floor_plots import plot_floor

    x = np.linspace(0.0, 100.0, 201)
    flat = floor.Profile(x, np.zeros_like(x), spacing=0.5, source="flat")
    assert len(plot_floor(flat, tmp_path / "flat.png").axes) == 1
    rough = floor.Profile(x, 0.1 * np.sin(x), spacing=0.5, source="sine")
    assert len(plot_floor(rough, tmp_path / "rough.png").axes) == 2


def test_the_force_figure_names_the_simulated_count_and_the_scale(saved_run):
    from gecko_agents.render.force_plots import _count_title

    h, _ = saved_run
    n_sim, count = h.meta["n_sim"], h.params.array.count
    assert n_sim == 3 and count != n_sim
    numbers = [int(s.replace(" ", "")) for s in re.findall(r"\d[\d ]*\d|\d", _count_title(h))]
    assert numbers == [n_sim, count]


# The quasi-static diagnostic against measured speed halving -----------------------------------

_STIFF = PAPER_TABLE1.replace(**{"seta.L": 5.0})
_FLAT20 = PAPER_ARRAY.replace(**{"floor.sigma": 0.0, "seta.L": 20.0})
QS_CASES = {  # name: (params, n_sim, press depth [µm])
    "sphere_linear": (_STIFF, 1, 0.3),
    "sphere_rod": (_STIFF.replace(**{"mechanics": "rod", "array.count": 2}), 2, 0.3),
    "array_linear": (_FLAT20, 1, 0.5),
    "array_rod": (_FLAT20.replace(mechanics="rod"), 1, 0.5),
}


def _pull_branch(h):
    """Plate height and total normal force from the deepest point to the pull-off peak."""
    f, y = h["force_normal_uN"], h["plate_y_um"]
    i0, ipk = int(np.argmin(y)), int(np.argmin(f))
    return y[i0 : ipk + 1], f[i0 : ipk + 1]


@pytest.mark.slow
@pytest.mark.parametrize("case", list(QS_CASES))
def test_quasi_static_value_predicts_the_change_of_halving_the_speed(case):
    """q = ζ·Ky·v·T/(π·Fc) is the force the moving plate costs a held tip over Fc: halving
    the speed must move the pull's force curve (at the plate height where the slower run
    holds half its pull-off) by q/2 of n·Fc, within a factor of 3."""
    params, n, depth = QS_CASES[case]
    v = 0.4  # µm/µs: fast enough for the change to stand clear of the step's resolution
    runs = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for speed in (v, v / 2):
            m = Model(params, n_sim=n, seed=1, numerics=Numerics(record_every=1))
            runs.append(m.run(protocol.press_pull(depth, speed=speed), progress=False))
    fast, slow = runs
    q = fast.meta["validity"]["items"]["quasi_static"]["value"]
    y_s, f_s = _pull_branch(slow)
    k = int(np.argmax(f_s <= -0.5 * n * m.Fc))
    y_f, f_f = _pull_branch(fast)
    order = np.argsort(y_f)
    measured = abs(np.interp(y_s[k], y_f[order], f_f[order]) - f_s[k]) / (n * m.Fc)
    assert q / 2 / 3 <= measured <= 3 * q / 2, (q / 2, measured)


def test_quasi_static_is_not_judged_for_a_peeling_film_or_a_tip_without_adhesion():
    spatula = PAPER_ARRAY.replace(**{"tip": "spatula", "mechanics": "rod", "floor.sigma": 0.0})
    for params in (spatula, _STIFF.replace(tip="hertz")):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            h = Model(params, n_sim=1, seed=1).run(protocol.press_pull(0.3, 0.2), progress=False)
        item = h.meta["validity"]["items"]["quasi_static"]
        assert item["value"] is None and item["ok"] is None
        assert item["plate_speed_um_per_us"] > 0


# Help and advice -----------------------------------------------------------------------------


def test_params_lines_fit_100_columns_and_every_parameter_has_a_meaning(capsys):
    from gecko_agents.cli import main
    from gecko_agents.params.table import parameter_table
    from gecko_agents.runfiles.run import PRESETS, preset_docs

    assert main(["params"]) == 0
    listing = capsys.readouterr().out
    for name, doc in preset_docs().items():  # each preset's first paragraph, whole
        words = doc.split("\n\n", 1)[0].split()
        assert " ".join(words) in " ".join(listing.split()), name
    for name in PRESETS:
        assert main(["params", name]) == 0
        text = capsys.readouterr().out
        assert max(map(len, text.splitlines())) <= 100
        assert all(row[3] for row in parameter_table(PRESETS[name])), name


def test_a_nested_params_table_gets_advice_in_toml(tmp_path, capsys):
    import tomllib

    from gecko_agents.cli import main

    run = tmp_path / "nested.toml"
    run.write_text(
        'preset = "PAPER_TABLE1"\n[params.seta]\nL = 5.0\nr = 1.5\n'
        '[[protocol]]\nsegment = "press_to"\ndepth_um = 0.3\n'
    )
    assert main(["run", str(run), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    advice = err.split("instead: ", 1)[1].strip().replace("; ", "\n")
    assert tomllib.loads(advice) == {"seta.L": 5.0, "seta.r": 1.5}
