"""The tips of a large model in several pymunk spaces, read, written and stepped on threads.

pymunk's own per-body work (the batch read and write and the semi-implicit Euler integration
of every body) is serial, ~15 ms a step for 10⁵ bodies on this machine, and at 10⁵ setae it
is two thirds of a step. A tip's integration depends on its own body alone (no constraints,
no tip–tip collisions), so :class:`gecko_agents.world.World` can put contiguous blocks of tips
in separate spaces (each with its own floor shapes and collision handlers) and this class
runs the spaces' batch I/O and steps on a thread each: Chipmunk's C code runs without
Python's global interpreter lock (cffi releases it), while the collision callbacks, which do,
are rare events. Every body meets the same arithmetic in its own space, so the history is the
same bit for bit as with one space (``tests/test_world.py``).
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pymunk.batch as pb

__all__ = ["Shards"]


class Shards:
    """Batch I/O and stepping of ``spaces`` (a list of pymunk spaces) on one thread each.

    Rows of the combined batch are the spaces' rows, space by space (each space's in
    Chipmunk's order); ``fields`` are the :class:`pymunk.batch.BodyFields` read, ``width``
    the floats per row they give (BODY_ID goes to the ids).
    """

    def __init__(self, spaces, fields, width: int):
        self.spaces = list(spaces)
        self.fields, self.width = fields, width
        k = len(self.spaces)
        self.pool = ThreadPoolExecutor(max_workers=k, thread_name_prefix="gecko_agents-pymunk")
        self._read_bufs = [pb.Buffer() for _ in range(k)]
        self._force_bufs = [pb.Buffer() for _ in range(k)]
        self._spans: list[tuple[int, int]] = []
        self.ids = np.zeros(0, dtype=np.uintp)
        self.data = np.zeros((0, width))
        self.out = None
        self.forces_pending = False

    # ------------------------------------------------------------------ read
    def _read_one(self, k: int) -> bool:
        """Read space k; copy into the combined arrays if its row count still fits them."""
        buf = self._read_bufs[k]
        buf.clear()
        pb.get_space_bodies(self.spaces[k], self.fields, buf)
        ids = np.frombuffer(buf.int_buf(), dtype=np.uintp)
        if k >= len(self._spans) or self._spans[k][1] - self._spans[k][0] != ids.size:
            return False
        lo, hi = self._spans[k]
        self.ids[lo:hi] = ids
        self.data[lo:hi] = np.frombuffer(buf.float_buf()).reshape(ids.size, self.width)
        return True

    def read(self) -> tuple[np.ndarray, np.ndarray]:
        """(ids, rows) of every body of every space, space by space."""
        fits = list(self.pool.map(self._read_one, range(len(self.spaces))))
        if not all(fits):  # first read, or bodies were added or removed: lay the rows out anew
            sizes = [np.frombuffer(b.int_buf(), dtype=np.uintp).size for b in self._read_bufs]
            ends = np.cumsum(sizes)
            self._spans = [(int(e - s), int(e)) for s, e in zip(sizes, ends, strict=True)]
            total = int(ends[-1])
            self.ids = np.zeros(total, dtype=np.uintp)
            self.data = np.zeros((total, self.width))
            for k, buf in enumerate(self._read_bufs):
                lo, hi = self._spans[k]
                self.ids[lo:hi] = np.frombuffer(buf.int_buf(), dtype=np.uintp)
                self.data[lo:hi] = np.frombuffer(buf.float_buf()).reshape(hi - lo, self.width)
        return self.ids, self.data

    # ------------------------------------------------------------------ write and step
    def set_out(self, out: np.ndarray) -> None:
        """Forces are written from ``out`` (rows as :meth:`read`, columns fx, fy): each space
        gets a view of its rows."""
        self.out = out
        for (lo, hi), buf in zip(self._spans, self._force_bufs, strict=True):
            buf.set_float_buf(out[lo:hi].reshape(-1))

    def _step_one(self, k: int, dt: float, write: bool) -> None:
        if write:
            pb.set_space_bodies(self.spaces[k], pb.BodyFields.FORCE, self._force_bufs[k])
        self.spaces[k].step(dt)

    def step(self, dt: float) -> None:
        """Write the pending forces (if any) and step every space by ``dt`` [µs]."""
        write = self.forces_pending and self.out is not None
        k = range(len(self.spaces))
        list(self.pool.map(self._step_one, k, [dt] * len(k), [write] * len(k)))
        self.forces_pending = False
