"""Pillar designs: pull-off per area against preload for tip shapes, aspect ratios and floors.

The study is :mod:`gecko_agents.studies.pillar_designs`; ``--help`` lists its options.
"""

from gecko_agents.studies.pillar_designs import main

if __name__ == "__main__":
    main()
