#!/bin/sh
# Mutation testing of every law with mutmut (config: [tool.mutmut] in pyproject.toml), scored by
# the fast tier alone (pytest -m "not slow"). Outside CI: CPU heavy, hours for the whole list
# on a busy 2-core machine; name a part to run only it. Install: pip install -e ".[mutation,dev]".
#
#   tools/mutation.sh                                  # every mutant, then the score per module
#   tools/mutation.sh "gecko_agents.physics.punch*"    # only these (fnmatch on mutant names)
#   tools/mutation.sh "gecko_agents.model.implicit.xǁImplicitStepǁcorrect*"   # one method
#   mutmut results                                     # the survivors; `mutmut show <name>`
#   MUTATION_TESTS="tests/test_implicit_jacobian.py" tools/mutation.sh "gecko_agents.model.implicit*"
#       # score a costly module by the fast tests written for it (a part of the fast tier, so
#       # a lower bound on the tier's score); delete ./mutants before changing the selection
#
# numba is disabled (NUMBA_DISABLE_JIT=1): mutmut swaps each function for a trampoline that
# numba cannot compile, and the interpreted kernels run the same formulas. The one fast test
# that pins a compiled history bit for bit is deselected here (the interpreted loop rounds
# differently). mutmut does not mutate decorated functions (the @jitable closed forms, the
# spatula's and the sheared sphere's @njit scalar laws): tests/test_oracles_hand.py pins those
# by hand-planted mutants. Work happens in ./mutants/ (a copy of the tree; delete it
# afterwards). A timeout (a mutant that makes a run hang) counts as detected. Survivors that
# stay are listed, with the reason each changes no physics, in docs/testing.md.
set -e
cd "$(dirname "$0")/.."
export NUMBA_DISABLE_JIT=1
nice -n 10 mutmut run --max-children "${MUTMUT_CHILDREN:-1}" "$@"
mutmut export-cicd-stats >/dev/null 2>&1 || true
mutmut results --all true 2>/dev/null | python tools/mutation_score.py
