"""Output folders and files: folders checked before any work starts, files written atomically,
a study's files written all or nothing.

Folders: a run, a sweep, a study or a report that
cannot write its results must say so before it computes them.

:func:`check_output_dir` refuses, naming the value: an empty path (it would write into the
current folder), an existing file, a path under a file, and a folder that cannot be created or
written to (a temporary file cannot be made in its nearest existing ancestor). It leaves
nothing behind, so a refused or failed command leaves nothing behind; :func:`output_dir_arg` is the
same check as an ``argparse`` ``type=``.

Files: :func:`atomic_write_bytes` (and the figure and animation writers, through
:func:`replace_into`) write a temporary file and rename it, so no file is ever half-written.
Inside :func:`all_or_nothing` every file a command writes is journaled: if the command fails or
is interrupted, the files it replaced get their old contents back and the files and folders it
created are removed, so a study that could not finish leaves its output folder as it found it.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import secrets
import shutil
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

__all__ = [
    "check_output_dir",
    "output_dir_arg",
    "atomic_write_bytes",
    "replace_into",
    "make_dir",
    "all_or_nothing",
]


def check_output_dir(value, name: str = "--out") -> Path:
    """``value`` as a Path if a folder can be written there, else ValueError naming ``name``."""
    text = str(value)
    if not text.strip():
        raise ValueError(f"{name} {text!r} is empty: give an output folder")
    path = Path(text)
    if path.is_symlink() and not path.exists():
        raise ValueError(f"{name} {text!r} is a symbolic link to a missing target")
    if path.exists() and not path.is_dir():
        raise ValueError(f"{name} {text!r} is an existing file, not a folder")
    probe = path
    while not probe.exists():  # the nearest existing ancestor decides whether mkdir can work
        if probe.parent == probe:
            break
        probe = probe.parent
    if not probe.is_dir():
        raise ValueError(f"{name} {text!r} lies under {str(probe)!r}, which is a file")
    try:  # a real probe: permission bits say nothing for root or on read-only file systems
        with tempfile.TemporaryFile(dir=probe):
            pass
    except OSError as err:
        where = "it" if probe == path else f"its parent {str(probe)!r}"
        reason = err.strerror or type(err).__name__
        raise ValueError(
            f"{name} {text!r} cannot be written: {where} refuses files ({reason})"
        ) from None
    return path


def output_dir_arg(value: str) -> Path:
    """:func:`check_output_dir` as an ``argparse`` ``type=`` (a usage error, exit 2)."""
    try:
        return check_output_dir(value, "")
    except ValueError as err:
        raise argparse.ArgumentTypeError(str(err).strip()) from None


@dataclass
class _Unit:
    """One :func:`all_or_nothing` block: the files it replaced or created (each with the
    hard-linked backup of its old contents, or None) and the folders it created."""

    files: list = field(default_factory=list)
    seen: set = field(default_factory=set)
    dirs: list = field(default_factory=list)


_UNITS: list[_Unit] = []  # the open blocks, innermost last


@contextlib.contextmanager
def all_or_nothing():
    """Run a block whose files count only together (module docstring): on an exception
    (Ctrl-C included) every file it wrote is restored or removed, every folder it created and
    left empty removed, and the exception goes on. A block inside another commits on its own
    (a study finished inside a report keeps its outputs)."""
    unit = _Unit()
    _UNITS.append(unit)
    try:
        yield
    except BaseException:
        _roll_back(unit)
        raise
    else:
        for _, backup in unit.files:
            if backup is not None:
                backup.unlink(missing_ok=True)
    finally:
        _UNITS.remove(unit)


def _roll_back(unit: _Unit) -> None:
    for path, backup in reversed(unit.files):
        with contextlib.suppress(OSError):
            if backup is None:
                path.unlink(missing_ok=True)
            else:
                os.replace(backup, path)
    for folder in reversed(unit.dirs):
        with contextlib.suppress(OSError):
            folder.rmdir()  # only if empty: a user's files are never removed


def _journal(path: Path) -> None:
    """Note ``path`` in the innermost open block before it is replaced or created."""
    if not _UNITS or path in _UNITS[-1].seen:
        return
    unit = _UNITS[-1]
    backup = None
    if path.exists():
        backup = path.with_name(f".{path.name}.{os.getpid()}-{secrets.token_hex(4)}.bak")
        try:
            os.link(path, backup)  # the old contents survive the rename onto path
        except OSError:
            shutil.copy2(path, backup)
    unit.seen.add(path)
    unit.files.append((path, backup))


def make_dir(path) -> Path:
    """``path.mkdir(parents=True, exist_ok=True)``, the folders it creates journaled."""
    path = Path(path)
    missing = []
    probe = path
    while not probe.exists() and probe.parent != probe:
        missing.append(probe)
        probe = probe.parent
    path.mkdir(parents=True, exist_ok=True)
    if _UNITS:
        _UNITS[-1].dirs.extend(reversed(missing))
    return path


def replace_into(tmp, path) -> None:
    """``os.replace(tmp, path)``, journaled in the innermost :func:`all_or_nothing` block."""
    _journal(Path(path))
    os.replace(tmp, path)


def atomic_write_bytes(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` via a temporary file in the same directory and a rename."""
    path = Path(path)
    make_dir(path.parent)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o644)  # mkstemp makes it owner-only; results are meant to be shared
        replace_into(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
