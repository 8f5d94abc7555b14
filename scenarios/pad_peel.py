"""Pad peel: the steady peel force per width of a pad on an elastic strip against the peel

The study is :mod:`gecko_agents.studies.pad_peel`; ``--help`` lists its options.
"""

from gecko_agents.studies.pad_peel import main

if __name__ == "__main__":
    main()
