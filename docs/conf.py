"""Sphinx configuration of the gecko_agents documentation site.

Build (from the repository root, after ``pip install -e '.[docs]'``)::

    sphinx-build -W --keep-going -n -b html docs docs/_build/html

``-W`` turns every warning into an error (a broken docstring, an unknown section), ``-n``
(nitpicky) makes every internal reference (``:func:``, ``:class:``, ``:mod:``) that does not
resolve a warning, so the API reference's internal links are checked by the same build.
"""

import sys
import types
from pathlib import Path

import gecko_agents
from gecko_agents import __version__

# The command-line entry points (``python -m gecko_agents[.render|.sweep|.calibrate]``) run on
# import; autosummary's walk over the subpackages imports every submodule, so each is
# registered as an empty module first and left out of the reference.
_PKG = Path(gecko_agents.__file__).resolve().parent
for _main in _PKG.rglob("__main__.py"):
    _name = ".".join(("gecko_agents", *_main.relative_to(_PKG).with_suffix("").parts))
    sys.modules.setdefault(_name, types.ModuleType(_name))

project = "gecko_agents"
author = "the gecko_agents authors"
copyright = "gecko_agents authors, MIT licence"  # noqa: A001 (Sphinx's name)
release = version = __version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = [
    "_build",
    "_generated",
    "gallery/README.rst",
    "**/*.ipynb",
    "**/*.py.md5",
    "**/*.zip",
]
templates_path = ["_templates"]

# API reference: one page per public module, from the docstrings (numpydoc style).
autosummary_generate = True
autodoc_typehints = "none"  # types are given in the numpydoc Parameters sections
autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "undoc-members": True}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
nitpicky = True

# Markdown pages (the README, docs/physics.md).
myst_enable_extensions = ["dollarmath", "colon_fence"]
myst_heading_anchors = 3

# The gallery: docs/gallery/plot_*.py run at build time, figures captured from pyplot.
sphinx_gallery_conf = {
    "examples_dirs": "gallery",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "furo"
html_title = f"gecko_agents {version}"

# Objects of other packages: without network access at build time there is no intersphinx
# inventory to resolve them against, so only references into gecko_agents are checked.
nitpick_ignore_regex = [
    (
        r"py:.*",
        r"(numpy|np|matplotlib|mpl|scipy|pymunk|pandas|pd|dask|distributed|tqdm|numba"
        r"|SurfaceTopography|itertools|concurrent|pathlib|argparse|dataclasses|warnings|json"
        r"|multiprocessing|typing|collections|tomllib|os|sys|io|csv)(\..*)?",
    ),
]

_BARS = __import__("re").compile(r"(``.*?``|:\w+:`[^`]*`|`[^`]*`)|\|")


_documenting = {"module": ""}


def _escape_bars(app, what, name, obj, options, lines):
    """The docstrings write absolute values as |F| (plain text): escape the bars outside
    literals and roles, so reStructuredText does not read them as substitutions."""
    if what == "module":
        _documenting["module"] = name
    for i, line in enumerate(lines):
        if "|" in line:
            lines[i] = _BARS.sub(lambda m: m.group(1) or r"\|", line)


def _shared(a: str, b: str) -> int:
    """How many leading dotted parts two names share."""
    k = 0
    for x, y in zip(a.split("."), b.split("."), strict=False):
        if x != y:
            break
        k += 1
    return k


def _resolve_relative(app, env, node, contnode):
    """Resolve a Python reference the docstrings write relative to their package
    (``jkr.force_from_radius``, ``SetaArray``, ``quasistatic``): the documented object whose
    full name ends with it, the one nearest the referring module if several. A name that
    matches nothing documented stays unresolved, and ``-n`` reports it."""
    from sphinx.util.nodes import make_refnode

    if node.get("refdomain") != "py":
        return None
    target = node["reftarget"].lstrip("~.")
    domain = env.get_domain("py")
    entries = {n: (e.docname, e.node_id) for n, e in domain.objects.items()}
    entries |= {n: (e.docname, e.node_id) for n, e in domain.modules.items()}
    found = [n for n in entries if n == target or n.endswith("." + target)]
    if not found:
        return None
    here = node.get("py:module") or ""
    best = max(found, key=lambda n: (_shared(n, here), -len(n)))
    docname, node_id = entries[best]
    return make_refnode(app.builder, node["refdoc"], docname, node_id, contnode, best)


def _skip_shadowed(app, what, name, obj, skip, options):
    """A package re-exporting a function under the name of its own submodule
    (``gecko_agents.quasistatic.solve``): document it on the submodule's page only."""
    import importlib.util

    package = _documenting["module"]
    if skip or not package or getattr(obj, "__module__", None) != f"{package}.{name}":
        return None
    return True if importlib.util.find_spec(f"{package}.{name}") else None


# Generated reference pages ------------------------------------------------------------------
# docs/_generated/*.md are written from the code on every build (git-ignored) and included by
# the reference pages, so the command line, parameter, column and validity references cannot
# drift from the code. A name the code has and this file does not describe is a build warning
# (an error under -W).
_GENERATED = Path(__file__).resolve().parent / "_generated"

_HISTORY_COLUMNS = {
    "time_us": "simulated time of the record [µs]",
    "plate_x_um": "plate position along the backing, +x the direction the setae lean [µm]",
    "plate_y_um": "plate height above the floor's mean plane [µm]; the pressing displacement is "
    "d = touch-down height − plate_y_um (> 0 pressed)",
    "force_normal_uN": "total normal contact force of the floor on the simulated tips, > 0 in "
    "compression, < 0 in adhesion (tension) [µN]",
    "force_tangential_uN": "total tangential contact force on the tips, > 0 along +x [µN]",
    "plate_force_x_uN": "force the setae exert on the plate along x [µN]",
    "plate_force_y_uN": "force the setae exert on the plate, > 0 up (equals the contact force "
    "in the quasi-static limit) [µN]",
    "n_attached": "tips in contact (sticking or sliding)",
    "n_sliding": "attached tips sliding at their Coulomb cap",
    "energy_elastic_pJ": "energy stored in the seta springs and the contacts [pJ]",
    "energy_kinetic_pJ": "kinetic energy of the tips [pJ]",
    "energy_dissipated_pJ": "energy dissipated so far: damping, sliding, snap-off losses and "
    "the implicit step's numerical dissipation [pJ]",
    "work_plate_pJ": "work the plate has done on the setae so far [pJ]",
    "strip_front_x_um": "elastic backing: x of the detachment front along the strip [µm]",
    "strip_setae_force_x_uN": "elastic backing: force of the setae on the strip along x [µN]",
    "strip_setae_force_y_uN": "elastic backing: force of the setae on the strip along y [µN]",
}
_SETA_FIELDS = {
    "tip_x_um": "tip centre x [µm]",
    "tip_y_um": "tip centre y [µm]",
    "force_normal_uN": "the tip's normal contact force, > 0 compression [µN]",
    "force_tangential_uN": "the tip's tangential contact force, > 0 along +x [µN]",
    "overlap_um": "overlap δ, > 0 pressed into the floor [µm]",
    "state": "0 free, 1 attached and sticking, 2 attached and sliding",
    "film_front_x_um": "spatula tips: x of the film's peel front, NaN while free [µm]",
    "film_attached_um": "spatula tips: floor length the pad still covers, NaN while free [µm]",
    "strip_node_x_um": "elastic backing: x of the strip's nodes [µm]",
    "strip_node_y_um": "elastic backing: y of the strip's nodes [µm]",
}


def _cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def _table(header, rows) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(_cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def _described(kind: str, names, docs: dict) -> list:
    from sphinx.util import logging

    missing = [n for n in names if n not in docs]
    if missing:
        logging.getLogger(__name__).warning(
            "docs/conf.py: %s without a description: %s", kind, ", ".join(missing)
        )
    return [(f"`{n}`", docs.get(n, "")) for n in names]


def _write_cli() -> str:
    """``gecko-agents --help`` and each subcommand's ``--help``, as the installed command prints
    them (100 columns)."""
    import os

    from gecko_agents import cli

    os.environ["COLUMNS"] = "100"
    parser = cli.build_parser()
    out = ["## gecko-agents\n", "```text", parser.format_help().rstrip(), "```\n"]
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    for name, p in sub.choices.items():
        out += [f"## gecko-agents {name}\n", "```text", p.format_help().rstrip(), "```\n"]
    return "\n".join(out)


def _write_parameters() -> str:
    from gecko_agents.params import PAPER_ARRAY
    from gecko_agents.params.table import parameter_table
    from gecko_agents.runfiles.schema import PRESETS, preset_docs

    out = ["## Presets\n"]
    docs = preset_docs()
    out.append(
        _table(
            ["preset", "what it is"],
            [(f"`{n}`", docs.get(n, "").split("\n\n")[0]) for n in PRESETS],
        )
    )
    out.append("\n## Every parameter, with the values of `PAPER_ARRAY`\n")
    rows = [
        (f"`{name}`", value, unit, meaning, eq)
        for name, value, unit, meaning, eq in parameter_table(PAPER_ARRAY)
    ]
    out.append(_table(["name", "value", "unit", "meaning", "paper"], rows))
    base = dict((r[0], r[1]) for r in parameter_table(PAPER_ARRAY))
    for name, preset in PRESETS.items():
        if name == "PAPER_ARRAY":
            continue
        diff = [
            (f"`{n}`", v, base.get(n, ""))
            for n, v, *_ in parameter_table(preset)
            if base.get(n) != v
        ]
        out.append(f"\n## `{name}`: what differs from `PAPER_ARRAY`\n")
        out.append(_table(["name", name, "PAPER_ARRAY"], diff))
    return "\n".join(out)


def _write_history() -> str:
    from gecko_agents import history
    from gecko_agents.backing import elastic

    out = ["## Columns of `history.csv`\n"]
    out.append(
        _table(
            ["column", "meaning"],
            _described("history column", history.SCALAR_COLUMNS, _HISTORY_COLUMNS),
        )
    )
    out.append('\nWith the elastic backing (`backing.kind = "elastic"`), after these:\n')
    out.append(
        _table(
            ["column", "meaning"],
            _described("history column", elastic.STRIP_COLUMNS, _HISTORY_COLUMNS),
        )
    )
    out.append("\n## Per-seta arrays of `setae.npz` (shape: records × setae)\n")
    names = history.PER_SETA_FIELDS + history.FILM_FIELDS + elastic.STRIP_ARRAYS
    out.append(_table(["array", "meaning"], _described("per-seta field", names, _SETA_FIELDS)))
    return "\n".join(out)


def _write_validity() -> str:
    import re

    from gecko_agents import diagnostics

    doc = diagnostics.__doc__ or ""
    rows = []
    for item, (relation, limit) in diagnostics.LIMITS.items():
        m = re.search(rf"``{item}``\n((?:    .*\n?)+)", doc)
        text = " ".join(m.group(1).split()) if m else ""
        first = text.split(". ")[0].rstrip(".") + "." if text else ""
        rows.append((f"`{item}`", f"value {relation} {limit:g}", first))
    return _table(["item", "rule", "what it measures"], rows)


def _write_runfiles() -> str:
    from gecko_agents.runfiles.schema import PRESETS, PROTOCOL_PRESETS, SEGMENTS
    from gecko_agents.sweep.points import POINT_FUNCTIONS

    out = ["## Protocol segments (`[[protocol]]`, key `segment`)\n"]
    out.append(
        _table(
            ["segment", "class", "keys → arguments"],
            [
                (
                    f"`{n}`",
                    f"{{py:class}}`{c.__module__}.{c.__qualname__}`",
                    ", ".join(f"`{k}` → `{v}`" for k, v in keys.items()),
                )
                for n, (c, keys) in SEGMENTS.items()
            ],
        )
    )
    out.append("\n## Preset protocols (`[protocol]`, key `preset`)\n")
    out.append(
        _table(
            ["preset", "function", "keys → arguments"],
            [
                (
                    f"`{n}`",
                    f"{{py:func}}`{f.__module__}.{f.__qualname__}`",
                    ", ".join(f"`{k}` → `{v}`" for k, v in keys.items()),
                )
                for n, (f, keys) in PROTOCOL_PRESETS.items()
            ],
        )
    )
    out.append("\n## Parameter presets (key `preset`)\n")
    out.append(", ".join(f"`{n}`" for n in PRESETS) + "\n")
    out.append("\n## Sweep point functions (key `point`)\n")
    out.append(
        _table(
            ["point", "function"],
            [
                (f"`{n}`", f"{{py:func}}`{f.__module__}.{f.__qualname__}`")
                for n, f in POINT_FUNCTIONS.items()
            ],
        )
    )
    return "\n".join(out)


def _write_validation() -> str:
    """The literature comparison's rows as read (the verdicts need the runs: see the page)."""
    from gecko_agents.studies.validation_rows import ROWS

    rows = []
    for r in ROWS:
        how = {"value": "magnitude", "trend": "direction"}.get(r["compare"], "")
        if r["compare"] == "value" and (r["in_words"] or r["kind"] == "self-consistency"):
            how = "value (counted apart)"
        ours = f"`{r['ours']}`" if r["ours"] else f"not scored: {r.get('unscored', '')}"
        rows.append((f"`{r['id']}`", r["source"], r["measured"], r["theirs"], how, ours))
    return _table(["row", "source", "measured", "theirs", "compared", "ours from"], rows)


def _generate() -> None:
    _GENERATED.mkdir(exist_ok=True)
    for name, make in {
        "cli": _write_cli,
        "parameters": _write_parameters,
        "history": _write_history,
        "validity": _write_validity,
        "runfiles": _write_runfiles,
        "validation": _write_validation,
    }.items():
        text = make()
        path = _GENERATED / f"{name}.md"
        if not path.exists() or path.read_text(encoding="utf-8") != text:
            path.write_text(text, encoding="utf-8")


def setup(app):
    app.connect("builder-inited", lambda app: _generate())
    app.connect("autodoc-skip-member", _skip_shadowed)
    app.connect("autodoc-process-docstring", _escape_bars)
    app.connect("missing-reference", _resolve_relative)
