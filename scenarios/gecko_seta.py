"""One tokay gecko seta branched into spatulae: the study is
:mod:`gecko_agents.studies.gecko_seta`; ``--help`` lists its options."""

from gecko_agents.studies.gecko_seta import main

if __name__ == "__main__":
    main()
