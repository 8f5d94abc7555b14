"""Fig 11b: maximum pull-off of the 10⁷-seta array vs preload for σ = 0.5, 1, 1.5 µm.

The study is :mod:`gecko_agents.studies.fig11b_roughness`; ``--help`` lists its options.
"""

from gecko_agents.studies.fig11b_roughness import main

if __name__ == "__main__":
    main()
