"""``python -m gecko_agents.calibrate``."""

import sys

from gecko_agents.calibrate import main

sys.exit(main())
