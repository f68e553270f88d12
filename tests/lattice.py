"""A square or cubic lattice with its neighbour lists, for tests of pair sums."""

import numpy as np

from mpisph.kernels import Kernel
from mpisph.neighbours import neighbour_lists


def lattice(dim, h_over_dp, n=24, dp=0.01):
    """n^dim particles spaced dp: positions, kinds (all moving), neighbour lists, the Wendland C2
    kernel with h = h_over_dp dp, and the mask of the inner particles (their supports lie inside)."""
    x = (np.arange(n) + 0.5) * dp
    grids = np.meshgrid(*([x] * dim), indexing="ij")
    x = np.stack([g.ravel() for g in grids], axis=1)
    k = Kernel("wendland_c2", h_over_dp * dp, dim)
    kind = np.zeros(len(x), np.int8)
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, np.zeros(dim) - dp)
    inner = np.all(np.abs(x - 0.5 * n * dp) < 0.2 * n * dp, axis=1)
    return x, kind, start, nbr, k, inner
