"""A sweep's points on Dask distributed: the ``--dask`` argument and the Dask backend.

``dask="local"`` starts a LocalCluster of single-threaded worker processes on loopback;
``dask="tcp://host:port"`` uses a running scheduler, whose workers must have gecko_agents
installed (a point function from a plain file module is shipped to them). Needs
``pip install -e '.[dask]'``; nothing here imports Dask until a sweep asks for it.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from urllib.parse import urlsplit

from gecko_agents.sweep.workers import collect, run_point

__all__ = ["DaskArgError", "parse_dask_arg", "import_distributed", "run_dask"]

_DASK_HINT = "install it with: pip install -e '.[dask]'"


def import_distributed():
    """The ``distributed`` module, or an ImportError saying how to install it."""
    try:
        import distributed
    except ImportError as err:
        raise ImportError(f"running a sweep on Dask needs dask.distributed; {_DASK_HINT}") from err
    return distributed


class DaskArgError(ValueError, argparse.ArgumentTypeError):
    """A bad ``--dask`` value (a ValueError that argparse reports with its own message)."""


def parse_dask_arg(s: str | None) -> str | None:
    """Check a ``--dask`` value: ``None`` (local processes), ``"local"`` or ``"tcp://host:port"``.

    Usable as ``argparse`` ``type=``; returns the value unchanged (``""`` → ``None``).
    """
    if s is None or s == "":
        return None
    if s == "local":
        return s
    if not isinstance(s, str):
        raise DaskArgError(f"--dask {s!r} must be None, 'local' or 'tcp://host:port'")
    try:
        parts = urlsplit(s)
        port = parts.port
    except ValueError:
        port = None
        parts = None
    if (
        parts is None
        or parts.scheme != "tcp"
        or not parts.hostname
        or port is None
        or parts.path not in ("", "/")
    ):
        raise DaskArgError(
            f"--dask {s!r} must be 'local' (a LocalCluster on this machine) or "
            f"'tcp://host:port' (the address of a running dask scheduler)"
        )
    return s


def run_dask(address: str, n_workers: int, todo, fn, fn_name, fn_kwargs, finish) -> None:
    """Run the points ``todo`` (pairs of point and key) on Dask at ``address`` ("local" or
    "tcp://host:port"); ``finish(record)`` is called as each point completes."""
    distributed = import_distributed()
    cluster = None
    if address == "local":
        cluster = distributed.LocalCluster(
            n_workers=min(n_workers, len(todo)),
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
        )
        address = cluster
    try:
        with distributed.Client(address) as client:
            if cluster is None:
                _ship_file_module(client, fn)
            futures = {
                client.submit(
                    run_point, fn, fn_name, fn_kwargs, p, k, pure=False, key=f"sweep-point-{k}"
                ): (p, k)
                for p, k in todo
            }
            for fut in distributed.as_completed(futures):
                finish(collect(fut, fn_name, fn_kwargs, *futures[fut]))
    finally:
        if cluster is not None:
            cluster.close()


def _ship_file_module(client, fn) -> None:
    """Send ``fn``'s module to a remote scheduler's workers if it is a plain file module.

    A point function from a module outside any package (a script's helper module) is
    importable here only because its folder is on ``sys.path``; workers started elsewhere get
    the file with :meth:`distributed.Client.upload_file`. Package modules (gecko_agents itself)
    must be installed on the workers.
    """
    module = sys.modules.get(getattr(fn, "__module__", "") or "")
    path = getattr(module, "__file__", None)
    if module is None or path is None or "." in module.__name__ or module.__name__ == "__main__":
        return
    if getattr(module, "__package__", "") or Path(path).name == "__init__.py":
        return
    client.upload_file(path)
