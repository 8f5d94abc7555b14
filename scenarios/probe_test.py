"""Spherical-probe test: pull-off against preload and probe radius on vertical pillars.

The study is :mod:`gecko_agents.studies.probe_test`; ``--help`` lists its options.
"""

from gecko_agents.studies.probe_test import main

if __name__ == "__main__":
    main()
