"""The studies: the source paper's figures, one study each, and the studies beyond it.

Each module has ``main(argv=None) -> dict`` (its command line: ``--quick``, ``--out DIR``,
``--no-progress``, and its own options), writes only into its output folder (default
``renders/<study>/`` under the current directory) and returns its key numbers;
:mod:`gecko_agents.studies.reproduce_paper` runs them and writes the claim-by-claim report.
``scenarios/<study>.py`` in the repository and ``gecko-agents reproduce`` are command lines
over them.
"""
