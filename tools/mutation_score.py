"""The mutation score per module, read from ``mutmut results --all true`` on stdin.

A mutant counts as detected when the fast tier killed it or made it time out; "no tests" are
mutants no fast test calls (their function is not reached by the fast tier); mutants a run
restricted to some names left out ("not checked") are not counted. Prints one row per
module: killed, timeout, survived, no tests, and detected / (all with tests) in per cent. Run by
tools/mutation.sh.
"""

import re
import sys
from collections import Counter, defaultdict

LINE = re.compile(r"^\s*(?P<name>\S+?)__mutmut_\d+:\s*(?P<status>.+?)\s*$")
COLUMNS = ("killed", "timeout", "survived", "no tests")


def module_of(name: str) -> str:
    """``pkg.mod.x_func`` or ``pkg.mod.xǁClassǁmethod`` → ``pkg.mod``."""
    return re.split(r"\.x[_ǁ]", name, maxsplit=1)[0]


def main() -> None:
    rows: dict[str, Counter] = defaultdict(Counter)
    for line in sys.stdin:
        m = LINE.match(line)
        if m and m["status"] != "not checked":  # a run restricted to some names
            rows[module_of(m["name"])][m["status"]] += 1
    total: Counter = Counter()
    print(f"{'module':48s} {'killed':>7s} {'timeout':>7s} {'survived':>8s} {'no tests':>8s}  score")
    for mod in sorted(rows):
        c = rows[mod]
        total.update(c)
        print(_row(mod, c))
    print(_row("all", total))


def _row(name: str, c: Counter) -> str:
    tested = sum(c.values()) - c["no tests"]
    detected = c["killed"] + c["timeout"]
    score = f"{100 * detected / tested:5.1f} %" if tested else "    –"
    other = sum(v for k, v in c.items() if k not in COLUMNS)
    extra = f"  (+{other} other: {dict((k, v) for k, v in c.items() if k not in COLUMNS)})"
    cells = " ".join(f"{c[k]:>{max(len(k), 7)}d}" for k in COLUMNS)
    return f"{name:48s} {cells}  {score}" + (extra if other else "")


if __name__ == "__main__":
    main()
