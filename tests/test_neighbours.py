"""Cell-linked lists find exactly the brute-force neighbours, in canonical order."""

import numpy as np
import pytest

from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL


@pytest.mark.parametrize("dim", [2, 3])
def test_same_as_brute_force(dim):
    rng = np.random.default_rng(1)
    n = 600 if dim == 2 else 900
    x = rng.uniform(-1.0, 1.0, (n, dim))
    gid = rng.permutation(n).astype(np.int64) * 7
    kind = np.where(rng.uniform(size=n) < 0.2, WALL, MOVING).astype(np.int8)
    n_owned = n - 100  # the last 100 play the ghosts
    radius = 0.23
    start, nbr = neighbour_lists(x, gid, kind, n_owned, radius, np.full(dim, -1.3))
    d = np.linalg.norm(x[:, None, :] - x[None, :, :], axis=2)
    for i in range(n_owned):
        found = nbr[start[i]:start[i + 1]]
        if kind[i] != MOVING:
            assert len(found) == 0
            continue
        expected = np.nonzero((d[i] < radius) & (np.arange(n) != i))[0]
        assert sorted(found) == sorted(expected)


def test_order_independent_of_storage_order():
    """The neighbour sequence (by gid) does not depend on where particles are stored."""
    rng = np.random.default_rng(2)
    n = 400
    x = rng.uniform(0.0, 1.0, (n, 2))
    gid = np.arange(n, dtype=np.int64)
    kind = np.zeros(n, np.int8)
    s1, n1 = neighbour_lists(x, gid, kind, n, 0.12, np.zeros(2))
    perm = rng.permutation(n)
    s2, n2 = neighbour_lists(x[perm], gid[perm], kind, n, 0.12, np.zeros(2))
    inv = np.argsort(perm)
    for i in range(n):
        a = gid[n1[s1[i]:s1[i + 1]]]
        k = inv[i]
        b = gid[perm][n2[s2[k]:s2[k + 1]]]
        np.testing.assert_array_equal(a, b)
