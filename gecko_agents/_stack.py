"""Where a warning should point: the first frame outside the package, i.e. the user's line.

A warning raised deep in a run (a validity item found after ``Model.run``'s last step, a
linear beam bent too far inside a step) is about the call the user made. ``warnings.warn``
takes a fixed ``stacklevel``, which breaks whenever the call path inside the package changes;
:func:`user_stacklevel` counts the frames instead (Python 3.12's ``skip_file_prefixes`` does
the same, and the package supports 3.11).
"""

from __future__ import annotations

import os
import sys

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__)) + os.sep


def user_stacklevel() -> int:
    """The ``stacklevel`` for a ``warnings.warn`` in the calling function that attributes the
    warning to the first frame outside ``gecko_agents`` (1 if the caller itself is outside).
    Under ``python -m gecko_agents.…`` the frame past the package is the interpreter's
    ``runpy``, which says nothing: the package's outermost frame is named instead."""
    frame = sys._getframe(1)
    level = 1
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_DIR):
        frame = frame.f_back
        level += 1
    if frame is not None and level > 1 and frame.f_globals.get("__name__") == "runpy":
        level -= 1
    return level
