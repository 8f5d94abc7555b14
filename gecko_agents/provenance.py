"""Which code produced a result: a fingerprint of the package's source, and the versions of
the package and the libraries it ran with.

A cached result (a sweep point, a scenario's stored point) may only be reused by the code that
computed it: keys include :func:`code_fingerprint`, so any change to the package's source —
physics or not — makes old points recompute instead of being silently reused. Changes to
comments count too; recomputing is the safe side of that trade.
"""

from __future__ import annotations

import functools
import hashlib
import inspect
import platform
from pathlib import Path

__all__ = ["code_fingerprint", "source_fingerprint"]

_PACKAGE = Path(__file__).resolve().parent


@functools.cache
def code_fingerprint() -> str:
    """16 hex digits: sha256 over the package's ``*.py`` files (names and bytes, sorted)."""
    digest = hashlib.sha256()
    for path in sorted(_PACKAGE.rglob("*.py")):
        digest.update(str(path.relative_to(_PACKAGE)).encode())
        digest.update(b"\0")
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def source_fingerprint(fn) -> str | None:
    """16 hex digits of the source file that defines ``fn`` when it lies outside the package
    (a scenario's point function), else None (covered by :func:`code_fingerprint`)."""
    try:
        path = Path(inspect.getsourcefile(fn) or "").resolve()
    except TypeError:
        return None
    if not path.is_file() or _PACKAGE in path.parents:
        return None
    return hashlib.sha256(path.read_bytes()).hexdigest()[:16]


def versions() -> dict:
    """Versions of the package and the libraries that produced a result."""
    from importlib.metadata import PackageNotFoundError, version

    out = {"python": platform.python_version()}
    for name in ("gecko_agents", "numpy", "scipy", "pymunk", "matplotlib"):
        try:
            out[name] = version(name)
        except PackageNotFoundError:
            out[name] = None
    return out
