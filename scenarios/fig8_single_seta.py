"""Fig 8: one seta of Table 1 pressed onto a flat floor and pulled off, agent model vs quasi-static.

The study is :mod:`gecko_agents.studies.fig8_single_seta`; ``--help`` lists its options.
"""

from gecko_agents.studies.fig8_single_seta import main

if __name__ == "__main__":
    main()
