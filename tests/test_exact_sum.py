"""Partition-independent global sums (parallel/exact_sum.py)."""

import math

import numpy as np
from mpi4py import MPI

from mpisph.parallel.exact_sum import BITS, _integer_parts, global_sums


def terms(seed=0, n=10000):
    rng = np.random.default_rng(seed)
    return np.stack([rng.normal(size=n) * 10.0 ** rng.uniform(-8, 3, n), rng.uniform(0, 1, n) ** 9])


def test_sum_does_not_depend_on_the_order_of_its_terms():
    t = terms()
    once = global_sums(MPI.COMM_SELF, t)
    rng = np.random.default_rng(1)
    for _ in range(5):
        again = global_sums(MPI.COMM_SELF, t[:, rng.permutation(t.shape[1])])
        np.testing.assert_array_equal(once, again)


def test_integer_parts_of_pieces_add_up_to_those_of_the_whole():
    """What Allreduce(SUM) does with the parts of the ranks: any split gives the same integers."""
    t = terms()
    largest = np.abs(t).max(axis=1)
    q1 = np.array([math.ldexp(1.0, math.frexp(m)[1] - BITS) for m in largest])
    q2 = q1 * 2.0**-BITS
    whole = np.empty((2, 2), np.int64)
    _integer_parts(t, q1, q2, whole)
    for cuts in ([3000], [17, 5000, 9999], [1, 2, 3]):
        total = np.zeros((2, 2), np.int64)
        for piece in np.split(t, cuts, axis=1):
            part = np.empty((2, 2), np.int64)
            _integer_parts(np.ascontiguousarray(piece), q1, q2, part)
            total += part
        np.testing.assert_array_equal(total, whole)


def test_sum_is_exact_to_the_last_bits():
    t = terms()
    exact = np.array([math.fsum(row) for row in t])
    scale = np.abs(t).max(axis=1) * t.shape[1] * 2.0 ** (-2 * BITS)
    assert np.all(np.abs(global_sums(MPI.COMM_SELF, t) - exact) <= scale + 1e-16 * np.abs(exact))


def test_zero_terms_sum_to_zero():
    np.testing.assert_array_equal(global_sums(MPI.COMM_SELF, np.zeros((2, 5))), [0.0, 0.0])
