"""Scratch arrays of the step loop, reused from step to step.

The particle count of a rank changes a little every step (migration, a new
halo), so a scratch array is kept with some headroom and handed out as a
view of the first n rows: the step allocates only when a rank grows beyond
what it has had before.

Two kinds: ``get`` names an array that lives from one use to the next (the
frozen positions of a configuration, the correction matrices); ``scratch``
hands out arrays that live for one phase only, all carved from one shared
buffer, so that phases that never overlap (the cell search's sorted copies,
the accelerations from the momentum sum to the kick, the stress-diffusion
rate) take the memory of the largest of them, not of their sum.
"""

import numpy as np

HEADROOM = 1.2
ALIGN = 64  # bytes: every scratch array starts on a cache line


class Workspace:
    """Named float64 arrays of n rows and a fixed shape per row, and one shared scratch buffer."""

    def __init__(self):
        self._arrays = {}
        self._scratch = np.empty(0, np.uint8)

    def get(self, name, n, shape=()):
        """A (n,) + shape view of the array ``name``; its values are left over, not zeroed."""
        a = self._arrays.get(name)
        if a is None or len(a) < n or a.shape[1:] != tuple(shape):
            a = np.empty((int(HEADROOM * n) + 1,) + tuple(shape))
            self._arrays[name] = a
        return a[:n]

    def scratch(self, *specs):
        """Arrays of the given (shape, dtype) specs, values left over, valid until the next call:
        every call hands out the same memory."""
        spans, end = [], 0
        for shape, dtype in specs:
            nbytes = int(np.prod(shape, dtype=np.int64)) * np.dtype(dtype).itemsize
            spans.append((end, nbytes))
            end += -(-nbytes // ALIGN) * ALIGN
        if len(self._scratch) < end + ALIGN:
            self._scratch = np.empty(int(HEADROOM * end) + ALIGN, np.uint8)
        base = -self._scratch.ctypes.data % ALIGN
        return tuple(self._scratch[base + off:base + off + nbytes].view(dtype).reshape(shape)
                     for (off, nbytes), (shape, dtype) in zip(spans, specs))
