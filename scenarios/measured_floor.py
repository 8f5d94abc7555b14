"""Press-pull of a setae patch on a measured surface profile, against a flat floor.

The study is :mod:`gecko_agents.studies.measured_floor`; ``--help`` lists its options.
"""

from gecko_agents.studies.measured_floor import main

if __name__ == "__main__":
    main()
