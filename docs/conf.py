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
exclude_patterns = ["_build", "gallery/README.rst", "**/*.ipynb", "**/*.py.md5", "**/*.zip"]
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


def setup(app):
    app.connect("autodoc-skip-member", _skip_shadowed)
    app.connect("autodoc-process-docstring", _escape_bars)
    app.connect("missing-reference", _resolve_relative)
