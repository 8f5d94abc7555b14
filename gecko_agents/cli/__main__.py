"""``python -m gecko_agents.cli``: the command line (:func:`gecko_agents.cli.main`)."""

import sys

from gecko_agents.cli import main

if __name__ == "__main__":
    sys.exit(main())
