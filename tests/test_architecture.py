"""The library stands alone and reads in one direction.

* No module of ``gecko_agents`` imports ``scenarios`` (or any top-level script module), at module
  level or inside a function, and none touches ``sys.path``: an installed wheel runs its own
  studies and examples.
* Each ``scenarios/*.py`` is a thin command line over a study of the library.
* Modules stay of one concept: none over 450 lines of code (docstrings, comments and blank
  lines not counted, so prose is never squeezed to fit), no function over 80 lines of code,
  no class over 300 lines of code.
"""

import ast
import io
import sys
import tokenize
from pathlib import Path

import pytest

import gecko_agents

PKG = Path(gecko_agents.__file__).resolve().parent
MODULES = sorted(PKG.rglob("*.py"))
MAX_MODULE_CODE_LINES = 450
MAX_CLASS_CODE_LINES = 300
MAX_FUNCTION_LINES = 80
DATA_MODULES: dict[str, int] = {}
"""Modules that are mostly literal data, with their own cap (none: data lives in data files)."""
THIRD_PARTY = {
    # pyproject.toml's dependencies and optional extras, by import name
    "pymunk", "numpy", "scipy", "matplotlib", "tqdm",
    "numba", "distributed", "pandas", "SurfaceTopography", "imageio_ffmpeg",
    "PIL",  # Pillow, matplotlib's own dependency: its GIF writer
    "optuna", "sqlalchemy",  # the design extra (sqlalchemy: Optuna's own dependency)
}  # fmt: skip


def _tree(path: Path) -> ast.Module:
    return ast.parse(path.read_text(), filename=str(path))


def _imported_modules(tree: ast.Module) -> set[str]:
    """Every module an ``import``/``from … import`` anywhere in the tree names (absolute)."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module)
    return names


def _dynamic_import_targets(tree: ast.Module) -> set[str]:
    """String arguments of ``importlib.import_module(...)`` / ``__import__(...)`` calls."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and node.args and isinstance(node.args[0], ast.Constant):
            fn = node.func
            name = fn.attr if isinstance(fn, ast.Attribute) else getattr(fn, "id", "")
            if name in ("import_module", "__import__") and isinstance(node.args[0].value, str):
                out.add(node.args[0].value)
    return out


def test_the_checks_see_function_level_and_dynamic_imports():
    tree = ast.parse(
        "def f():\n    import scenarios.x\n    from _common import y\n"
        "    importlib.import_module('_preload')\n    sys.path.insert(0, 'a')\n"
    )
    assert {"scenarios.x", "_common"} <= _imported_modules(tree)
    assert _dynamic_import_targets(tree) == {"_preload"}
    assert _touches_sys_path(tree)


def _touches_sys_path(tree: ast.Module) -> bool:
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Attribute)
            and node.attr == "path"
            and isinstance(node.value, ast.Name)
            and node.value.id == "sys"
        ):
            return True
    return False


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PKG)))
def test_no_module_imports_outside_the_package_or_edits_sys_path(path):
    tree = _tree(path)
    for name in _imported_modules(tree) | _dynamic_import_targets(tree):
        top = name.split(".")[0]
        allowed = top == "gecko_agents" or top in sys.stdlib_module_names or top in THIRD_PARTY
        assert allowed, (
            f"{path} imports {name}: not the package, the standard library or a dependency"
        )
    assert not _touches_sys_path(tree), f"{path} reads or edits sys.path"


def test_every_dynamic_import_of_the_package_resolves():
    import importlib

    for path in MODULES:
        for name in _dynamic_import_targets(_tree(path)):
            if name.startswith("gecko_agents"):
                importlib.import_module(name)


def _code_lines(src: str) -> set[int]:
    """Line numbers that hold code: not blank, not only a comment, not a docstring (a string
    statement: a module's, class's or function's docstring, or an attribute's)."""
    prose = set()
    for node in ast.walk(ast.parse(src)):
        if (isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant)
                and isinstance(node.value.value, str)):  # fmt: skip
            prose.update(range(node.lineno, node.end_lineno + 1))
    code = set()
    skip = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT,
            tokenize.ENDMARKER}  # fmt: skip
    for tok in tokenize.generate_tokens(io.StringIO(src).readline):
        if tok.type not in skip:
            code.update(range(tok.start[0], tok.end[0] + 1))
    return code - prose


def test_code_lines_skip_docstrings_comments_and_blanks():
    src = (
        '"""Doc."""\n\nx = 1  # c\n# only a comment\n\n'
        'def f():\n    """Doc\n    more."""\n    return x\n'
    )
    assert sorted(_code_lines(src)) == [3, 6, 9]


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PKG)))
def test_modules_and_functions_stay_short(path):
    src = path.read_text()
    code = _code_lines(src)
    cap = DATA_MODULES.get(path.relative_to(PKG).as_posix(), MAX_MODULE_CODE_LINES)
    assert len(code) <= cap, f"{path}: {len(code)} lines of code"
    big = [
        (node.name, n)
        for node in ast.walk(ast.parse(src))
        if isinstance(node, ast.ClassDef)
        and (n := len(code & set(range(node.lineno, node.end_lineno + 1)))) > MAX_CLASS_CODE_LINES
    ]
    assert not big, f"{path}: classes over {MAX_CLASS_CODE_LINES} lines of code: {big}"
    long = [
        (node.name, n)
        for node in ast.walk(ast.parse(src))
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
        and (n := len(code & set(range(node.lineno, node.end_lineno + 1)))) > MAX_FUNCTION_LINES
    ]
    assert not long, f"{path}: functions over {MAX_FUNCTION_LINES} lines of code: {long}"


def test_scenario_scripts_are_thin_command_lines():
    scripts = sorted((PKG.parent / "scenarios").glob("*.py"))
    if not scripts:
        pytest.skip("no scenarios/ folder beside the package (an installed copy)")
    for script in scripts:
        tree = _tree(script)
        imports = [n for n in tree.body if isinstance(n, ast.ImportFrom)]
        assert [n.module for n in imports] == [f"gecko_agents.studies.{script.stem}"], script
        defs = [n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef | ast.ClassDef)]
        assert not defs, f"{script} defines {[d.name for d in defs]}: it belongs in the study"


def _package_imports(path: Path) -> set[str]:
    """The package's modules that ``path`` imports anywhere (``from a.b import c`` names a.b,
    and a.b.c where that is a module)."""
    names = set()
    for node in ast.walk(_tree(path)):
        if isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module)
            names |= {f"{node.module}.{a.name}" for a in node.names}
        elif isinstance(node, ast.Import):
            names |= {a.name for a in node.names}
    return {n for n in names if n in MODULE_NAMES}


def _module_name(path: Path) -> str:
    parts = ("gecko_agents", *path.relative_to(PKG).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULE_NAMES = {_module_name(p): p for p in MODULES}


def test_backing_sits_below_the_model():
    """A backing is built by the model from the setup and the parts it acts on; it never
    imports the model's modules."""
    for name, path in MODULE_NAMES.items():
        if name.startswith("gecko_agents.backing"):
            up = {m for m in _package_imports(path) if m.startswith("gecko_agents.model")}
            assert not up, f"{name} imports {sorted(up)}"


def test_no_import_circles():
    """Modules import in one direction: no two modules reach each other through imports (a
    package's ``__init__`` counts as the module of its name)."""
    graph = {name: _package_imports(path) - {name} for name, path in MODULE_NAMES.items()}
    allowed = {frozenset({"gecko_agents.params", "gecko_agents.params.presets"})}
    circles = []
    for start in graph:
        seen, todo = set(), list(graph[start])
        while todo:
            m = todo.pop()
            if m == start:
                circles.append(start)
                break
            if m not in seen:
                seen.add(m)
                todo.extend(graph.get(m, ()))
    flagged = [c for c in circles if not any(c in pair for pair in allowed)]
    assert not flagged, f"modules on an import circle: {sorted(flagged)}"


ENGINE = ("gecko_agents.model", "gecko_agents.backing", "gecko_agents.numerics",
          "gecko_agents.protocol")  # fmt: skip
NAMEDTUPLE_API = {"_replace", "_asdict", "_fields", "_make"}


def _private_names_defined(tree: ast.Module) -> set[str]:
    """Private names a module defines: its functions, classes and the attributes it assigns
    (``x._name = …`` on any object)."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            names.add(node.name)
        elif isinstance(node, ast.Attribute) and isinstance(node.ctx, ast.Store):
            names.add(node.attr)
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
    return {n for n in names if n.startswith("_")}


def _foreign_private_reads(tree: ast.Module) -> list[tuple[int, str]]:
    """(line, name) of each ``x._name`` on an object other than ``self``/``cls`` whose name the
    module does not define itself: another module's private attribute."""
    own = _private_names_defined(tree) | NAMEDTUPLE_API
    return [
        (node.lineno, node.attr)
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute)
        and node.attr.startswith("_")
        and not node.attr.startswith("__")
        and not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls"))
        and node.attr not in own
    ]


def test_the_private_read_check_sees_a_foreign_attribute():
    tree = ast.parse("def f(m):\n    m._mine = 1\n    return m._mine + m._theirs + self._x\n")
    assert _foreign_private_reads(tree) == [(3, "_theirs")]


@pytest.mark.parametrize(
    "name", sorted(n for n in MODULE_NAMES if n.startswith(ENGINE)), ids=lambda n: n
)
def test_the_engine_reads_no_other_modules_private_attributes(name):
    """The engine's parts talk through public names: a model's parts, the steppers and the
    backings read no private attribute defined in another module."""
    found = _foreign_private_reads(_tree(MODULE_NAMES[name]))
    assert not found, f"{name} reads private attributes of other modules: {found}"


def test_the_architecture_page_names_the_tree():
    """docs/explanation/architecture.md names every folder and public top-level module of the
    package, and every public module of the engine's folders (model/, backing/)."""
    page = PKG.parent / "docs" / "explanation" / "architecture.md"
    if not page.exists():
        pytest.skip("no docs/ beside the package (an installed copy)")
    text = page.read_text()
    names = [f"`{p.name}/`" for p in PKG.iterdir() if p.is_dir() and (p / "__init__.py").exists()]
    names += [f"`{p.name}`" for p in PKG.glob("*.py") if not p.name.startswith("_")]
    for folder in ("model", "backing"):
        names += [f"`{p.stem}`" for p in (PKG / folder).glob("*.py") if not p.name.startswith("_")]
    missing = sorted(n for n in names if n not in text)
    assert not missing, f"{page.name} does not name {missing}"


ENGINE_FOLDERS = ("model", "backing")
ENGINE_FILES = ("numerics.py", "protocol.py", "history.py", "render/scene.py")


@pytest.mark.parametrize(
    "path",
    [p for p in MODULES if p.relative_to(PKG).parts[0] in ENGINE_FOLDERS
     or p.relative_to(PKG).as_posix() in ENGINE_FILES],
    ids=lambda p: str(p.relative_to(PKG)),
)  # fmt: skip
def test_the_engines_rooms_hold_whole_in_view(path):
    """The engine's classes and functions, docstrings included, stay a size a reader holds in
    view: no class over 300 lines, no function over 80 (split by responsibility)."""
    tree = ast.parse(path.read_text())
    big = [
        (node.name, n)
        for node in ast.walk(tree)
        if isinstance(node, ast.ClassDef)
        and (n := node.end_lineno - node.lineno + 1) > MAX_CLASS_CODE_LINES
    ]
    long = [
        (node.name, n)
        for node in ast.walk(tree)
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
        and (n := node.end_lineno - node.lineno + 1) > MAX_FUNCTION_LINES
    ]
    assert not big and not long, f"{path}: classes {big}, functions {long} (lines)"
