"""The design folder and the study's store: what a design search may write into, the record
that makes a folder a study's own, the lock that keeps one command per folder, and a
``--storage`` URL checked before any work.

A folder is a design folder when it holds :data:`RECORD` (``study.json``), written by the
search before its first trial: the study's name (the design file's stem, its digest and its
variant), the design file and where its trials are stored. A search writes into a new or empty
folder, or continues the study its folder's record names; any other folder (a user's files,
another study's outputs) is refused before any work, naming what is there. A folder a search
wrote before the record existed is known by the study names in its ``study.db`` (read,
never written). A design folder keeps the files a user adds: a search writes only
:data:`OUTPUT_FILES`.

One command writes into a design folder at a time (:func:`hold`): it holds an exclusive lock
on the folder, which the system releases when the process ends, however it ends (POSIX
``flock``, Windows ``msvcrt.locking``; on a file system without locks, none); a second
command is refused naming the folder. Processes a command spawns only evaluate designs and
take no lock.
"""

from __future__ import annotations

import contextlib
import json
import os
import sqlite3
import tempfile
from pathlib import Path

__all__ = [
    "DesignFolderError",
    "RECORD",
    "OUTPUT_FILES",
    "saved_studies",
    "check_output",
    "write_record",
    "hold",
    "check_storage",
    "check_database",
    "store_name",
    "storage_full",
]

RECORD = "study.json"
"""The record that makes a folder a design folder: the study a search wrote into it."""

OUTPUT_FILES = (
    RECORD,
    "study.db",
    "trials.csv",
    "best.json",
    "report.md",
    "pareto_front.png",
    "objectives_vs_parameters.png",
    "showcase.png",
    "runs",
)
"""What a design search writes into its output folder (``runs`` a folder of run files)."""


class DesignFolderError(ValueError):
    """An output folder or a store a design search must not use (the command line exits
    with 2, nothing written)."""


def _shown(names: list[str], most: int = 5) -> str:
    return ", ".join(names[:most]) + (f" and {len(names) - most} more" if len(names) > most else "")


def _db_studies(db: Path) -> list[str]:
    """The study names in an Optuna SQLite file (opened read-only); [] for any other file."""
    try:
        con = sqlite3.connect(f"{db.resolve().as_uri()}?mode=ro", uri=True)
        try:
            return [n for (n,) in con.execute("SELECT study_name FROM studies")]
        finally:
            con.close()
    except sqlite3.Error:
        return []


def saved_studies(out: Path) -> dict[str, dict]:
    """The studies a design search wrote into ``out``: study name → its record (the
    :data:`RECORD` file's, or only the name for a folder written before records existed);
    empty for any other folder."""
    out = Path(out)
    try:
        record = json.loads((out / RECORD).read_text())
        if isinstance(record, dict) and isinstance(record.get("study"), str):
            return {record["study"]: record}
    except (OSError, ValueError):
        pass
    if (out / RECORD).exists() or not (out / "study.db").is_file():
        return {}
    return {name: {"study": name} for name in _db_studies(out / "study.db")}


def check_output(out: Path, study: str | None = None, storage: str | None = None) -> None:
    """Refuse, before any trial, an output folder the study ``study`` (a name of
    :func:`gecko_agents.design.search.study_name`; None: any design folder), stored at
    ``storage`` (None: the folder's ``study.db``), must not write into: a file, a dangling
    link, a folder that is not empty and not a design folder, a design folder of another study
    or of this study in another store, or one where a name the search writes is of the other
    kind (a folder where it writes a file). Raises :class:`DesignFolderError`."""
    out = Path(out)
    if out.is_symlink() and not out.exists():
        raise DesignFolderError(
            f"{out}: is a symbolic link to a missing target; choose another --out"
        )
    if out.exists() and not out.is_dir():
        raise DesignFolderError(f"{out}: exists and is not a folder; choose another --out")
    names = sorted(p.name for p in out.iterdir()) if out.is_dir() else []
    if not names:
        return
    saved = saved_studies(out)
    if not saved:
        raise DesignFolderError(
            f"{out}: is not empty ({_shown(names)}) and is not a design folder (a design "
            f"search's {RECORD}); a search writes into a new or empty folder or continues its "
            "own study: choose another --out"
        )
    if study is not None and study not in saved:
        name, record = next(iter(saved.items()))
        source = f" of the design file {record['design_file']}" if "design_file" in record else ""
        raise DesignFolderError(
            f"{out}: holds the study {name}{source}; another study ({study}) would replace its "
            "outputs: give it its own --out (an edited design file or --quick is another study)"
        )
    where = saved.get(study, {}).get("storage")
    here = "study.db" if storage is None else store_name(storage)
    if study is not None and where is not None and store_name(where) != here:
        raise DesignFolderError(
            f"{out}: holds the study {study} stored at {where}, not at {here}: give the same "
            "--storage to continue it, or another --out"
        )
    clash = [n for n in OUTPUT_FILES if (out / n).exists() and (out / n).is_dir() != (n == "runs")]
    if clash:
        raise DesignFolderError(
            f"{out}: {_shown(clash)} is not what a search writes there (a file, or the folder "
            "runs); choose another --out"
        )
    if storage is None and (out / "study.db").is_file():
        check_database(out / "study.db")


def check_database(db: Path, shown: str | None = None) -> None:
    """Refuse an SQLite file SQLite cannot read whole (cut short by a full disk or a copy,
    or not a database), naming it (``shown``: how the command named it). Raises
    :class:`DesignFolderError`."""
    try:
        con = sqlite3.connect(f"{Path(db).resolve().as_uri()}?mode=ro", uri=True)
        try:
            verdict = con.execute("PRAGMA quick_check").fetchone()[0]
        finally:
            con.close()
    except sqlite3.OperationalError:  # locked, or its log not readable here: Optuna will say
        return
    except sqlite3.DatabaseError as err:
        verdict = str(err)
    if verdict != "ok":
        raise DesignFolderError(
            f"{shown or db}: is damaged ({verdict}): restore it, or move it aside to start "
            "its study again"
        )


def write_record(out: Path, spec, study: str, storage: str | None) -> None:
    """Write ``out``/:data:`RECORD` for the study ``study`` of ``spec`` unless it is there."""
    from gecko_agents.output_paths import atomic_write_bytes

    if (Path(out) / RECORD).exists():
        return
    record = {
        "study": study,
        "design_file": str(spec.path),
        "sha256": spec.sha256,
        "quick": spec.quick,
        "storage": "study.db" if storage is None else store_name(storage),
    }
    atomic_write_bytes(Path(out) / RECORD, json.dumps(record, indent=1).encode())


_HELD: dict[str, list] = {}  # folder → [descriptor, depth]: this process's locks


@contextlib.contextmanager
def hold(out: Path):
    """Hold ``out`` (an existing folder) for this process: an exclusive lock the system
    releases when the process ends; nested holds of one folder in one process share it.
    Raises :class:`DesignFolderError` if another process holds it."""
    key = str(Path(out).resolve())
    if key in _HELD:
        _HELD[key][1] += 1
    else:
        _HELD[key] = [_lock(Path(key)), 1]
    try:
        yield
    finally:
        _HELD[key][1] -= 1
        if _HELD[key][1] == 0:
            os.close(_HELD.pop(key)[0])  # closing the descriptor releases the lock


def _lock(folder: Path) -> int:
    busy = DesignFolderError(
        f"{folder}: another design command is writing into this folder (its study is locked); "
        "wait for it to end, or give this one its own --out (commands share a study through a "
        "--storage database URL, each with its own --out)"
    )
    try:
        import fcntl
    except ImportError:  # Windows: a byte of a lock file in the folder
        import msvcrt

        fd = os.open(folder / ".study.lock", os.O_RDWR | os.O_CREAT)
        try:
            msvcrt.locking(fd, msvcrt.LK_NBLCK, 1)
        except OSError:
            os.close(fd)
            raise busy from None
        return fd
    fd = os.open(folder, os.O_RDONLY)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        os.close(fd)
        raise busy from None
    except OSError:  # a file system without locks (some network ones): the folder is not locked
        pass
    return fd


def store_name(url: str) -> str:
    """The store ``url`` names, as a design folder's record keeps it: its password hidden, an
    SQLite file's path made absolute (``sqlite:///designs.db`` given in another folder is
    another file); "study.db", the folder's own file, as it is."""
    from sqlalchemy.engine import make_url

    if url == "study.db":
        return url
    u = make_url(url)
    if u.get_backend_name() == "sqlite" and u.database and not u.database.startswith("file:"):
        u = u.set(database=str(Path(u.database).resolve()))
    return u.render_as_string(hide_password=True)


def check_storage(url: str) -> None:
    """Refuse, before any work, a ``--storage`` value Optuna could not store trials at: not a
    database URL, a database SQLAlchemy or its driver does not know, an SQLite file that is a
    folder, in a missing folder or not writable, or a server that cannot be reached. Raises
    :class:`DesignFolderError` naming the URL (its password hidden)."""
    import sqlalchemy
    from sqlalchemy.engine import make_url
    from sqlalchemy.exc import ArgumentError, NoSuchModuleError, SQLAlchemyError

    try:
        u = make_url(url)
    except ArgumentError:
        raise DesignFolderError(
            f"--storage {url!r} is not a database URL (dialect://user@host/database, e.g. "
            "sqlite:///designs.db or postgresql://user@host/designs)"
        ) from None
    shown = f"--storage {u.render_as_string(hide_password=True)!r}"
    try:
        u.get_dialect().import_dbapi()
    except NoSuchModuleError:
        raise DesignFolderError(
            f"{shown}: SQLAlchemy knows no database {u.drivername!r} (sqlite, postgresql, mysql, …)"
        ) from None
    except ImportError as err:
        raise DesignFolderError(f"{shown}: needs its database driver ({err})") from None
    if u.get_backend_name() == "sqlite":
        _check_sqlite_file(shown, u.database)
        return
    try:
        with sqlalchemy.create_engine(u).connect():
            pass
    except SQLAlchemyError as err:
        reason = str(getattr(err, "orig", None) or err).strip().splitlines()[0]
        raise DesignFolderError(f"{shown}: cannot be reached ({reason})") from None


def _check_sqlite_file(shown: str, database: str | None) -> None:
    if not database or database == ":memory:" or database.startswith("file:"):
        raise DesignFolderError(
            f"{shown}: names no database file; give sqlite:///path/to/designs.db"
        )
    path = Path(database)
    if path.is_dir():
        raise DesignFolderError(f"{shown}: {path} is a folder, not a database file")
    if not path.parent.is_dir():
        raise DesignFolderError(f"{shown}: its folder {path.parent} does not exist")
    try:  # SQLite writes a journal beside the file: the folder must take files
        with tempfile.TemporaryFile(dir=path.parent):
            pass
        if path.exists() and not os.access(path, os.W_OK):
            raise PermissionError("the file is read-only")
    except OSError as err:
        raise DesignFolderError(f"{shown}: cannot be written ({err.strerror or err})") from None
    if path.is_file():
        check_database(path, f"{shown} ({path})")


def storage_full(err: BaseException) -> str | None:
    """The database's own words if ``err`` (or an error it came from) says the store's disk is
    full (SQLite's ``SQLITE_FULL``, an ``ENOSPC``), else None."""
    import errno

    seen = err
    while seen is not None:
        text = str(getattr(seen, "orig", None) or seen)
        if "disk is full" in text or getattr(seen, "errno", None) == errno.ENOSPC:
            return text.strip().splitlines()[0]
        seen = seen.__cause__ or seen.__context__
    return None
