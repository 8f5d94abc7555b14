"""Old names of the public API kept working, each with a DeprecationWarning naming its new one.

A renamed function stays callable under its old name until :data:`REMOVED_IN`; the warning says
the new name and the release it goes in, so a user's script can be updated before it breaks.
"""

from __future__ import annotations

import functools
import warnings

REMOVED_IN = "0.3"
"""The release in which the deprecated names go."""


def warn_renamed(old: str, new: str, stacklevel: int = 2) -> None:
    """Warn that ``old`` is now ``new`` (fully qualified names), at the caller's line."""
    warnings.warn(
        f"{old} is deprecated and goes in {REMOVED_IN}: use {new} (the same function, "
        "renamed for what it reads)",
        DeprecationWarning,
        stacklevel=stacklevel + 1,
    )


def renamed(old: str, new: str, func):
    """``func`` under its old name ``old``: the same call, with a DeprecationWarning first."""

    @functools.wraps(func)
    def old_name(*args, **kwargs):
        warn_renamed(old, new, stacklevel=2)
        return func(*args, **kwargs)

    old_name.__name__ = old_name.__qualname__ = old.rsplit(".", 1)[-1]
    old_name.__doc__ = f"Deprecated alias of :func:`{new}`; goes in {REMOVED_IN}."
    return old_name
