"""What the command line's handlers share: exit codes, the program name, usage errors."""

from __future__ import annotations

import sys
from pathlib import Path

from gecko_agents.output_paths import check_output_dir

__all__ = [
    "EXIT_OK",
    "EXIT_FAILURE",
    "EXIT_USAGE",
    "EXIT_INTERRUPTED",
    "PROG",
    "HELP_WIDTH",
    "UsageError",
    "error",
    "checked",
]

EXIT_OK, EXIT_FAILURE, EXIT_USAGE, EXIT_INTERRUPTED = 0, 1, 2, 130
PROG = "gecko-agents"
HELP_WIDTH = 100  # longest line ``params`` prints


class UsageError(Exception):
    """Bad input found by a handler (exit code 2)."""


def error(message: str) -> None:
    print(f"{PROG}: error: {message}", file=sys.stderr)


def checked(out: Path) -> Path:
    """A default output folder, checked as ``--out`` is (a usage error if it cannot be written)."""
    try:
        return check_output_dir(out, "the default output folder")
    except ValueError as err:
        raise UsageError(f"{err}; give --out") from None
