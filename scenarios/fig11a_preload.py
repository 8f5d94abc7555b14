"""Fig 11a: maximum pull-off of the paper's 10⁷-seta array vs preload (σ = 1 µm).

The study is :mod:`gecko_agents.studies.fig11a_preload`; ``--help`` lists its options.
"""

from gecko_agents.studies.fig11a_preload import main

if __name__ == "__main__":
    main()
