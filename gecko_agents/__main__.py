"""``python -m gecko_agents COMMAND …`` is the ``gecko-agents`` command line
(:mod:`gecko_agents.cli`), e.g. ``python -m gecko_agents sweep SWEEPFILE.toml``."""

import sys

from gecko_agents.cli import main

if __name__ == "__main__":
    sys.exit(main())
