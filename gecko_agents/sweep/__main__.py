"""``python -m gecko_agents.sweep``."""

import sys

# The command line lives above the sweep engine (gecko_agents.cli), which imports it; the engine
# does not import the command line back.
print(
    "the sweep command is: python -m gecko_agents sweep SWEEPFILE.toml "
    "(or gecko-agents sweep SWEEPFILE.toml)",
    file=sys.stderr,
)
sys.exit(2)
