"""Paper Fig 7: JKR tip contact for seta surface energies γ1 = 4, 40 and 100 mJ/m².

The study is :mod:`gecko_agents.studies.fig7_surface_energy`; ``--help`` lists its options.
"""

from gecko_agents.studies.fig7_surface_energy import main

if __name__ == "__main__":
    main()
