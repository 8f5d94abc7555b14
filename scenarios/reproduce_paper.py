"""Run every paper-figure scenario and write renders/paper_comparison.md, claim by claim.

The study is :mod:`gecko_agents.studies.reproduce_paper`; ``--help`` lists its options.
"""

from gecko_agents.studies.reproduce_paper import main

if __name__ == "__main__":
    main()
