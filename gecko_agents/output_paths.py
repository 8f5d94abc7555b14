"""Output folders and files: folders checked before any work starts, files written atomically.

Folders: a run, a sweep, a study or a report that
cannot write its results must say so before it computes them.

:func:`check_output_dir` refuses, naming the value: an empty path (it would write into the
current folder), an existing file, a path under a file, and a folder that cannot be created or
written to (a temporary file cannot be made in its nearest existing ancestor). It leaves
nothing behind, so a refused or failed command leaves nothing behind; :func:`output_dir_arg` is the
same check as an ``argparse`` ``type=``.
"""

from __future__ import annotations

import argparse
import os
import tempfile
from pathlib import Path

__all__ = ["check_output_dir", "output_dir_arg", "atomic_write_bytes"]


def check_output_dir(value, name: str = "--out") -> Path:
    """``value`` as a Path if a folder can be written there, else ValueError naming ``name``."""
    text = str(value)
    if not text.strip():
        raise ValueError(f"{name} {text!r} is empty: give an output folder")
    path = Path(text)
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


def atomic_write_bytes(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` via a temporary file in the same directory and a rename."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o644)  # mkstemp makes it owner-only; results are meant to be shared
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
