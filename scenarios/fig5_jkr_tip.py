"""Paper Fig 5: one JKR tip (R = 4 µm) — force vs contact radius and force vs overlap.

The study is :mod:`gecko_agents.studies.fig5_jkr_tip`; ``--help`` lists its options.
"""

from gecko_agents.studies.fig5_jkr_tip import main

if __name__ == "__main__":
    main()
