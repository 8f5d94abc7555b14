"""Misalignment: a pad's pull-off / (N·Fc) against the angle between backing and floor, for a

The study is :mod:`gecko_agents.studies.misalignment`; ``--help`` lists its options.
"""

from gecko_agents.studies.misalignment import main

if __name__ == "__main__":
    main()
