"""Workspace: named arrays persist; scratch arrays of successive phases share one buffer."""

import numpy as np

from mpisph.workspace import ALIGN, Workspace


def test_scratch_arrays_are_aligned_disjoint_and_shared_between_phases():
    w = Workspace()
    ids, xs = w.scratch(((10,), np.int32), ((10, 3), np.float64))
    assert ids.shape == (10,) and ids.dtype == np.int32 and xs.shape == (10, 3) and xs.dtype == np.float64
    assert ids.ctypes.data % ALIGN == 0 and xs.ctypes.data % ALIGN == 0
    ids[:] = 7
    xs[:] = -1.0
    assert np.all(ids == 7)  # no overlap inside one phase
    rate, = w.scratch(((5, 6), np.float64))  # the next phase reuses the same memory
    assert rate.ctypes.data == ids.ctypes.data
    bigger, = w.scratch(((1000, 6), np.float64))  # and grows when a phase needs more
    assert bigger.shape == (1000, 6)


def test_named_arrays_keep_their_values_and_grow():
    w = Workspace()
    a = w.get("x", 5, (2,))
    a[:] = 3.0
    assert np.all(w.get("x", 5, (2,)) == 3.0)
    assert w.get("x", 50, (2,)).shape == (50, 2)
