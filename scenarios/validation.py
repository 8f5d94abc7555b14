"""Validation against published experiments: the literature comparison (literature_comparison.md).

The study is :mod:`gecko_agents.studies.validation`; ``--help`` lists its options.
"""

from gecko_agents.studies.validation import main

if __name__ == "__main__":
    main()
