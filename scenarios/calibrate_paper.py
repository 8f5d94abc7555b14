"""Fit the parameters the paper's figures imply, and validate seta stiffness against measurements.

The study is :mod:`gecko_agents.studies.calibrate_paper`; ``--help`` lists its options.
"""

from gecko_agents.studies.calibrate_paper import main

if __name__ == "__main__":
    main()
