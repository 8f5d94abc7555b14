"""Pads at the experiments' size: pull-off per area against the pad's width for Kim & Sitti's
and Booth et al.'s backings.

The study is :mod:`gecko_agents.studies.pad_scale`; ``--help`` lists its options.
"""

from gecko_agents.studies.pad_scale import main

if __name__ == "__main__":
    main()
