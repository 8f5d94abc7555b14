"""The design folder (gecko_agents.design.folder): a folder is a study's own only when a search
wrote it, one process holds it at a time, a --storage URL is checked before any work; and the
bounds a design file gives are those its study can run."""

import math
import os

import pytest
from test_design import BASE, design, needs_optuna

from gecko_agents.design import folder, load_design, search
from gecko_agents.design.schema import SEED_MAX
from gecko_agents.runfiles.schema import RunFileError


def test_a_design_folder_takes_its_own_study_and_keeps_a_users_file(tmp_path):
    spec = load_design(design(tmp_path))
    other = load_design(design(tmp_path, BASE.replace("seed = 0", "seed = 1"), "e.toml"))
    out = tmp_path / "out"
    out.mkdir()
    name = search.study_name(spec)
    folder.write_record(out, spec, name, None)
    (out / "notes.txt").write_text("mine")
    folder.check_output(out, name)  # its own study, a user's note beside it
    with pytest.raises(folder.DesignFolderError, match=f"holds the study {name}.*d.toml"):
        folder.check_output(out, search.study_name(other))
    (out / "report.md").mkdir()  # where the search writes a file
    with pytest.raises(folder.DesignFolderError, match="report.md"):
        folder.check_output(out, name)


def test_a_folder_of_a_users_files_is_no_design_folder_even_with_a_study_db(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    (out / "study.db").write_text("my own database notes")
    with pytest.raises(folder.DesignFolderError, match=r"\(study.db\) and is not a design folder"):
        folder.check_output(out)
    assert (out / "study.db").read_text() == "my own database notes"


@needs_optuna
def test_a_folder_a_search_wrote_before_records_is_known_by_its_study_db(tmp_path):
    """``run_search`` writes the store alone (no record): the store's study names decide,
    read without a write."""
    spec = load_design(design(tmp_path))
    out = tmp_path / "out"
    search.run_search(spec, out, trials=2)
    assert not (out / folder.RECORD).exists()
    before = (out / "study.db").read_bytes()
    name = search.study_name(spec)
    assert list(folder.saved_studies(out)) == [name]
    folder.check_output(out, name)
    with pytest.raises(folder.DesignFolderError, match=f"holds the study {name}"):
        folder.check_output(out, name + "-quick")
    assert (out / "study.db").read_bytes() == before


def test_one_process_holds_a_design_folder_at_a_time(tmp_path):
    """A second open of the folder (another process's, or another file description of this
    one) is refused while the folder is held, and takes it once released."""
    with folder.hold(tmp_path), folder.hold(tmp_path):  # nested holds share one lock
        with pytest.raises(folder.DesignFolderError, match=f"{tmp_path}: another design"):
            folder._lock(tmp_path)
    os.close(folder._lock(tmp_path))


@pytest.mark.parametrize(
    "url, names",
    [
        ("sqlite://", ("names no database file",)),
        ("sqlite:///:memory:", ("names no database file",)),
        ("postgresql+nosuchdriver://u:secret@host/db", ("postgresql+nosuchdriver",)),
    ],
)
@needs_optuna  # the check opens the URL with SQLAlchemy, which Optuna installs
def test_storage_urls_that_cannot_hold_a_study_are_refused(url, names):
    with pytest.raises(folder.DesignFolderError) as err:
        folder.check_storage(url)
    for n in names:
        assert n in str(err.value)
    assert "secret" not in str(err.value)


@needs_optuna
@pytest.mark.skipif(os.geteuid() == 0, reason="root writes a read-only file")
def test_a_read_only_storage_file_is_refused(tmp_path):
    db = tmp_path / "ro.db"
    db.write_bytes(b"")
    db.chmod(0o444)
    with pytest.raises(folder.DesignFolderError, match="cannot be written"):
        folder.check_storage(f"sqlite:///{db}")


@needs_optuna
def test_a_new_sqlite_file_in_a_writable_folder_is_taken_and_nothing_written(tmp_path):
    folder.check_storage(f"sqlite:///{tmp_path / 'designs.db'}")
    assert list(tmp_path.iterdir()) == []


@needs_optuna
def test_the_largest_seed_the_samplers_take_runs_and_one_more_is_refused(tmp_path):
    spec = load_design(design(tmp_path, BASE.replace("seed = 0", f"seed = {SEED_MAX}")))
    assert len(search.completed(search.run_search(spec, tmp_path / "out", trials=1))) == 1
    with pytest.raises(RunFileError, match=f"seed.*{SEED_MAX + 1}.*\\[0, {SEED_MAX}\\]"):
        load_design(design(tmp_path, BASE.replace("seed = 0", f"seed = {SEED_MAX + 1}")))


def test_a_gap_bound_is_refused_just_above_the_widest_gap_the_space_holds(tmp_path):
    """At a fill fraction f the pitch is r·√(π/f), so the gap r·(√(π/f) − 2) is widest at the
    largest radius: 5·(√(π/0.2) − 2) = 9.817 µm."""
    widest = 5.0 * (math.sqrt(math.pi / 0.2) - 2.0)
    load_design(design(tmp_path, BASE + f"\n[constraints]\nmin_gap_um = {0.999 * widest}\n"))
    with pytest.raises(RunFileError, match=r"min_gap_um.*leaves no design.*9.817 µm"):
        load_design(design(tmp_path, BASE + f"\n[constraints]\nmin_gap_um = {1.001 * widest}\n"))


def test_a_confirmation_the_engine_cannot_run_is_a_row_with_its_reason(tmp_path, monkeypatch):
    from gecko_agents.design import confirm, report
    from gecko_agents.protocol import PressLimitError

    def press_fails(spec, values, i, tilt, flagged):
        raise PressLimitError("Press(preload=1e+04 µN) was not reached")

    monkeypatch.setattr(confirm, "_engine_run", press_fails)
    spec = load_design(design(tmp_path))
    eng = confirm.confirm_design(spec, {"tip": "flat_punch", "radius_um": 2.0})
    assert math.isnan(eng["mean"]) and eng["runs"] == []
    assert eng["error"] == "PressLimitError: Press(preload=1e+04 µN) was not reached"
    row = {"label": "design_1", "trial": 3, "design": {"radius_um": 2.0}, "ratio": math.nan}
    row |= {"screen": {"pull_off_per_area": 50.0}, "engine": eng}
    text = report.report_text(spec, [row], {}, 4, {})
    assert "- design_1 (trial 3): PressLimitError: Press(preload=1e+04 µN)" in text
    assert "| design_1 | 2 | 50 | failed (below) | — | — |" in text


@needs_optuna
def test_a_study_continues_only_in_the_store_it_was_started_in(tmp_path):
    spec = load_design(design(tmp_path))
    out, name = tmp_path / "out", search.study_name(spec)
    out.mkdir()
    url = f"sqlite:///{tmp_path / 'shared.db'}"
    folder.write_record(out, spec, name, url)
    folder.check_output(out, name, url)
    with pytest.raises(folder.DesignFolderError, match=f"stored at {url}, not at study.db"):
        folder.check_output(out, name)
