"""Scratch arrays of the step loop, reused from step to step.

The particle count of a rank changes a little every step (migration, a new
halo), so a scratch array is kept with some headroom and handed out as a
view of the first n rows: the step allocates only when a rank grows beyond
what it has had before.
"""

import numpy as np

HEADROOM = 1.2


class Workspace:
    """Named float64 scratch arrays of n rows and a fixed shape per row."""

    def __init__(self):
        self._arrays = {}

    def get(self, name, n, shape=()):
        """A (n,) + shape view of the scratch array ``name``; its values are left over, not zeroed."""
        a = self._arrays.get(name)
        if a is None or len(a) < n or a.shape[1:] != tuple(shape):
            a = np.empty((int(HEADROOM * n) + 1,) + tuple(shape))
            self._arrays[name] = a
        return a[:n]
