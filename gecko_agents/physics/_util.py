"""Private helpers of the physics modules."""

from __future__ import annotations

__all__ = ["jitable"]

try:  # a scalar formula marked with it is compiled into numba's per-seta loops where called
    from numba.extending import register_jitable as jitable
except ImportError:  # numba is optional: then it is a plain function

    def jitable(fn):
        return fn
