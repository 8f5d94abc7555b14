"""``python -m gecko_agents.render``."""

import sys

from gecko_agents.render import main

sys.exit(main())
