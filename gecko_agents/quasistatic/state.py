"""What the quasi-static solver carries for every seta from one plate position to the next.

Contact states are those of :mod:`gecko_agents.history` (FREE, STICK, SLIP). Units: µm.
"""

from __future__ import annotations

import numpy as np

from gecko_agents.history import STATE_FREE as FREE
from gecko_agents.history import STATE_STICK as STICK


class State:
    """Per-seta state during a solve: contact state, slide direction, tip offset u = x − x0."""

    def __init__(self, n):
        self.state = np.zeros(n, dtype=np.int8)
        self.sigma = np.zeros(n)
        self.u = np.zeros(n)

    def copy(self):
        c = State(0)
        c.state, c.sigma, c.u = self.state.copy(), self.sigma.copy(), self.u.copy()
        return c


def jump_in(st: State, delta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Free tips that now touch the floor (overlap δ ≥ 0) attach, sticking at rest.

    Updates ``st`` in place; returns (the masks of the tips that jumped in, of all attached).
    """
    was = st.state != FREE
    jump = delta >= 0.0
    jump &= ~was
    if jump.any():
        st.state[jump] = STICK
        st.u[jump] = 0.0
        st.sigma[jump] = 0.0
    return jump, was | jump


def concat_states(states):
    """One state holding the setae of several states one after another."""
    out = type(states[0])(0)
    for k in vars(out):
        setattr(out, k, np.concatenate([getattr(s, k) for s in states]))
    return out


def take_state(st, idx):
    """The setae ``idx`` of a state (a copy)."""
    out = type(st)(0)
    for k in vars(out):
        setattr(out, k, getattr(st, k)[idx].copy())
    return out
