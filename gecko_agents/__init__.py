"""gecko_agents: a gecko-inspired setae array pressed onto and pulled off a rough floor.

Units everywhere: µm, µN, µs, ng (see :mod:`gecko_agents.params`).

The public API in one import, each name loaded on first use (``import gecko_agents`` imports
neither pymunk nor numba)::

    import gecko_agents as ga

    params = ga.PAPER_TABLE1.replace(mechanics="rod")
    history = ga.Model(params, seed=1).run(ga.protocol.press_pull(depth=1.0))
    history.save("my_run")
    same = ga.load_history("my_run")

``dir(gecko_agents)`` and ``__all__`` list the public names only. The old names ``load`` (now
``load_history``: a run directory) and ``load_run`` (now ``read_run_file``: a TOML run file)
still work, with a DeprecationWarning, until 0.3.
"""

from importlib import import_module as _import_module
from importlib.metadata import PackageNotFoundError as _PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("gecko_agents")
except _PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.0.0+unknown"

# name -> (module, attribute or None for the module itself)
_LAZY = {
    "Model": ("gecko_agents.model", "Model"),
    "Numerics": ("gecko_agents.numerics", "Numerics"),
    "History": ("gecko_agents.history", "History"),
    "load_history": ("gecko_agents.history", "load_history"),
    "read_run_file": ("gecko_agents.runfiles.run", "read_run_file"),
    "SetaArray": ("gecko_agents.params", "SetaArray"),
    "PAPER_TABLE1": ("gecko_agents.params", "PAPER_TABLE1"),
    "PAPER_ARRAY": ("gecko_agents.params", "PAPER_ARRAY"),
    "PAPER_FIG5_READING": ("gecko_agents.params", "PAPER_FIG5_READING"),
    "params": ("gecko_agents.params", None),
    "protocol": ("gecko_agents.protocol", None),
    "quasistatic": ("gecko_agents.quasistatic", None),
    "floor": ("gecko_agents.floor", None),
}

# old name -> new name: each still works, with a DeprecationWarning, until 0.3
_RENAMED = {"load": "load_history", "load_run": "read_run_file"}

__all__ = ["__version__", *_LAZY]


def __getattr__(name: str):
    if name in _RENAMED:  # not cached: every use of an old name warns
        from gecko_agents._deprecation import warn_renamed

        warn_renamed(f"gecko_agents.{name}", f"gecko_agents.{_RENAMED[name]}")
        return __getattr__(_RENAMED[name])
    try:
        module, attribute = _LAZY[name]
    except KeyError:
        raise AttributeError(f"module 'gecko_agents' has no attribute {name!r}") from None
    value = _import_module(module)
    if attribute is not None:
        value = getattr(value, attribute)
    globals()[name] = value
    return value


def __dir__():
    """The public API only (``__all__``; not the helpers this module imports)."""
    return sorted(__all__)
