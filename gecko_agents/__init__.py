"""gecko_agents: a gecko-inspired setae array pressed onto and pulled off a rough floor.

Units everywhere: µm, µN, µs, ng (see :mod:`gecko_agents.params`).
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("gecko_agents")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+unknown"
