"""Sums over all particles of all ranks that do not depend on how the particles are split.

A floating-point sum depends on the order of its terms, so a plain
``Allreduce(SUM)`` of per-rank partial sums gives different last bits on 1, 2
and 3 ranks. Where such a sum steers the particles (the step length of an
iterative solver), the runs would part. Here every term is first cut into two
integers on a grid common to all ranks, and integers add exactly in any order:

    M = max |x| over all terms (an exact MPI maximum), 2^(e-1) <= M < 2^e,
    x = hi q1 + lo q2 + (rounding below q2),   q1 = 2^(e-32), q2 = 2^(e-64),

hi the truncation of x / q1 (|hi| < 2^32, and x - hi q1 is exact), lo the
nearest integer to the rest over q2. The int64 sums of hi and lo cannot
overflow below 2^31 terms; the result, (sum hi) q1 + (sum lo) q2, carries the
sum to 2^-64 M per term and is the same number on any number of ranks.
"""

import math

import numpy as np
from mpi4py import MPI
from numba import njit

BITS = 32  # bits per integer part: 2^31 terms fit in an int64


@njit(cache=True)
def _largest(terms, out):
    """out[k] = max |terms[k, i]|."""
    for k in range(terms.shape[0]):
        m = 0.0
        for i in range(terms.shape[1]):
            m = max(m, abs(terms[k, i]))
        out[k] = m


@njit(cache=True)
def _integer_parts(terms, q1, q2, out):
    """out[k] = (sum of hi, sum of lo) of the terms of row k on the grid q1[k], q2[k]."""
    for k in range(terms.shape[0]):
        hi_sum = 0
        lo_sum = 0
        if q1[k] > 0.0:
            for i in range(terms.shape[1]):
                x = terms[k, i]
                hi = np.int64(x / q1[k])  # truncation towards zero: x - hi q1 is exact
                hi_sum += hi
                lo_sum += np.int64(np.rint((x - hi * q1[k]) / q2[k]))
        out[k, 0] = hi_sum
        out[k, 1] = lo_sum


def global_sums(comm, terms):
    """The sums over all ranks of each row of ``terms`` (k, n_local), independent of the split of
    the terms between ranks and of their order (module docstring)."""
    terms = np.ascontiguousarray(terms, dtype=np.float64)
    local = np.empty(terms.shape[0])
    _largest(terms, local)
    largest = np.empty_like(local)
    comm.Allreduce(local, largest, op=MPI.MAX)
    q1 = np.array([math.ldexp(1.0, math.frexp(m)[1] - BITS) if m > 0.0 else 0.0 for m in largest])
    q2 = q1 * 2.0**-BITS
    parts = np.empty((terms.shape[0], 2), np.int64)
    _integer_parts(terms, q1, q2, parts)
    total = np.empty_like(parts)
    comm.Allreduce(parts, total, op=MPI.SUM)
    return total[:, 0] * q1 + total[:, 1] * q2
