"""Paper Fig 6: JKR tip contact for seta moduli E1 = 0.1, 1 and 10 MPa.

The study is :mod:`gecko_agents.studies.fig6_modulus`; ``--help`` lists its options.
"""

from gecko_agents.studies.fig6_modulus import main

if __name__ == "__main__":
    main()
