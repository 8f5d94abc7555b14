"""Patch pull-off against the roughness spectrum: Hurst exponent H and RMS height of the floor.

The study is :mod:`gecko_agents.studies.roughness_spectrum`; ``--help`` lists its options.
"""

from gecko_agents.studies.roughness_spectrum import main

if __name__ == "__main__":
    main()
