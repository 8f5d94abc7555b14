"""Frictional adhesion (beyond the paper): load–drag–pull of one seta, sphere and spatula tips.

The study is :mod:`gecko_agents.studies.frictional_adhesion`; ``--help`` lists its options.
"""

from gecko_agents.studies.frictional_adhesion import main

if __name__ == "__main__":
    main()
