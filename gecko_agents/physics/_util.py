"""Private helpers of the physics modules."""

from __future__ import annotations

import sys

__all__ = ["jitable", "register_jitables"]

_PENDING: list = []


def _register(fn) -> None:
    try:
        from numba.extending import register_jitable
    except ImportError:  # numba is optional: then the function stays a plain function
        return
    register_jitable(fn)


def jitable(fn):
    """Mark a scalar formula for numba's per-seta loops, returning ``fn`` unchanged.

    numba's ``register_jitable`` only attaches an overload to the function object, so the
    registration is deferred until a compiled loop is imported (``register_jitables``):
    importing the physics does not import numba.
    """
    if "numba" in sys.modules:
        _register(fn)
    else:
        _PENDING.append(fn)
    return fn


def register_jitables() -> None:
    """Register every marked formula with numba; the compiled loops call it on import."""
    while _PENDING:
        _register(_PENDING.pop())
