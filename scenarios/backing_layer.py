"""Backing layer: a pad's pull-off against the thickness and modulus of its backing layer.

The study is :mod:`gecko_agents.studies.backing_layer`; ``--help`` lists its options.
"""

from gecko_agents.studies.backing_layer import main

if __name__ == "__main__":
    main()
