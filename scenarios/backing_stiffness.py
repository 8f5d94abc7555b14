"""Backing stiffness: a pad's pull-off / (N·Fc) against the ratio of backing to seta stiffness.

The study is :mod:`gecko_agents.studies.backing_stiffness`; ``--help`` lists its options.
"""

from gecko_agents.studies.backing_stiffness import main

if __name__ == "__main__":
    main()
