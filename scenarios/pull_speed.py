"""Pull-off against pull speed (beyond the paper): the elastic JKR tip and crack kinetics.

The study is :mod:`gecko_agents.studies.pull_speed`; ``--help`` lists its options.
"""

from gecko_agents.studies.pull_speed import main

if __name__ == "__main__":
    main()
