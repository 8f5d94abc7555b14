"""Fig 10: force vs pressing displacement of the paper's array on a σ = 1 µm floor.

The study is :mod:`gecko_agents.studies.fig10_array_pulloff`; ``--help`` lists its options.
"""

from gecko_agents.studies.fig10_array_pulloff import main

if __name__ == "__main__":
    main()
