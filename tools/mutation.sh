#!/bin/sh
# Mutation testing of the physics modules with mutmut (config: [tool.mutmut] in pyproject.toml).
# Outside CI (CPU heavy: 1675 mutants, ~45 min with MUTMUT_CHILDREN=2 on a busy 2-core machine).
# Install: pip install -e ".[mutation,dev]".
#
#   tools/mutation.sh            # mutate, test, print the score (killed / all)
#   mutmut results               # the survivors; `mutmut show <name>` shows one's diff
#
# numba is disabled (NUMBA_DISABLE_JIT=1): mutmut swaps each function for a trampoline that
# numba cannot compile, and the interpreted kernels run the same formulas. mutmut does not
# mutate decorated functions (friction.stick_stiffness, friction.friction_cap,
# base.branch_radius are @jitable): tests/test_oracles_hand.py pins those by hand numbers.
# Work happens in ./mutants/ (a copy of the tree; delete it afterwards). A timeout (a mutant
# that makes a run hang) counts as detected. Survivors that stay are listed, with the reason
# each is equivalent, in tests/test_mutation_survivors.py's module docstring.
set -e
cd "$(dirname "$0")/.."
export NUMBA_DISABLE_JIT=1
nice -n 10 mutmut run --max-children "${MUTMUT_CHILDREN:-1}" "$@"
mutmut export-cicd-stats >/dev/null 2>&1 || true
python - <<'PY'
import json, pathlib
p = pathlib.Path("mutants/mutmut-cicd-stats.json")
if p.exists():
    s = json.loads(p.read_text())
    total = s["killed"] + s["survived"] + s.get("timeout", 0) + s.get("suspicious", 0)
    print(f"killed {s['killed']} of {total} ({100 * s['killed'] / max(total, 1):.1f} %), "
          f"survived {s['survived']}, no tests {s.get('no_tests', 0)}")
PY
