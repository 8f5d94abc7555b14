"""Directional adhesion (beyond the paper): drag the pressed array along or against the seta

The study is :mod:`gecko_agents.studies.directional_adhesion`; ``--help`` lists its options.
"""

from gecko_agents.studies.directional_adhesion import main

if __name__ == "__main__":
    main()
