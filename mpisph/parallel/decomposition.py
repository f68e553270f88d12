"""Slab decomposition along one axis: cuts, ownership, migration, rebalancing.

The domain is divided into bins an eighth of the kernel support wide along
the slab axis; cuts between ranks sit on bin edges, chosen from the global
histogram of the work of the particles so that every rank gets about the same
share (with support-wide bins a 3D column 16 supports wide could only be cut
to within 3 % of the half). The work of a particle is its number of neighbour
pairs in the last configuration (walls have none), or 1 for a moving particle
before the first configuration: wall contacts and free surfaces change the
pairs per particle by 10 % and more, so particle counts alone leave ranks
waiting. The first and last cuts are open (-inf, +inf) so every particle has an
owner. A run may not use more ranks than the domain is supports long.
"""

import math

import numpy as np
from mpi4py import MPI

from ..errors import InputError
from ..particles import MOVING
from .exchange import alltoallv_rows, exchange_counts

BINS_PER_SUPPORT = 8


def slab_count(lo, hi, support):
    """How many slabs a kernel's ``support`` wide the domain [lo, hi] along the slab axis holds:
    the most ranks a run can take."""
    return max(1, math.ceil((float(hi) - float(lo)) / support - 1e-9))


class SlabDecomposition:
    """Cuts along ``axis`` between ``comm.size`` slabs."""

    def __init__(self, comm, axis, lo, hi, support):
        self.comm = comm
        self.axis = axis
        self.lo = float(lo)
        slabs = slab_count(lo, hi, support)
        if comm.size > slabs:
            raise InputError(
                f"{comm.size} ranks but the domain has only {slabs} slabs of width "
                f"{support:g} m along axis {'xyz'[axis]}; use at most {slabs} ranks")
        self.bin_width = support / BINS_PER_SUPPORT
        self.nbins = slabs * BINS_PER_SUPPORT
        self.edges = np.arange(comm.size + 1) * (self.nbins // comm.size)
        self.edges[-1] = self.nbins
        self._set_cuts()

    def _set_cuts(self):
        self.cuts = self.lo + self.edges * self.bin_width
        self.cuts[0], self.cuts[-1] = -np.inf, np.inf

    def owner(self, s):
        """Rank owning slab-axis coordinates ``s``."""
        return np.searchsorted(self.cuts[1:-1], s, side="right")

    def bin_of(self, s):
        return np.clip(((s - self.lo) / self.bin_width).astype(np.int64), 0, self.nbins - 1)

    def balance(self, s_local, work):
        """Place the cuts so that each rank gets about the same sum of ``work``.

        ``s_local`` are this rank's particle coordinates along the axis and ``work``
        their weights; the histogram is summed over all ranks, so every rank
        computes the same cuts.
        """
        # float even for a rank with no particles (bincount gives int64 zeros then)
        hist = np.bincount(self.bin_of(s_local), weights=work, minlength=self.nbins).astype(np.float64)
        total = np.empty_like(hist)
        self.comm.Allreduce(hist, total, op=MPI.SUM)
        self.edges = balanced_edges(total, self.comm.size)
        self._set_cuts()

    def imbalance(self, work_local):
        """max/mean - 1 of the work over ranks."""
        counts = np.empty(self.comm.size)
        self.comm.Allgather(np.array([work_local], dtype=np.float64), counts)
        mean = counts.mean()
        return 0.0 if mean == 0 else counts.max() / mean - 1.0

    def slab(self):
        """(lo, hi) of this rank's slab."""
        r = self.comm.rank
        return self.cuts[r], self.cuts[r + 1]


def balanced_edges(work, size):
    """Bin edges (size + 1, from 0 to len(work)) of ``size`` slabs of at least one bin each with
    about equal sums of the per-bin ``work``: each cut sits at the bin edge nearest to its share."""
    nbins = len(work)
    cum = np.cumsum(work)
    edges = np.empty(size + 1, dtype=np.int64)
    edges[0], edges[-1] = 0, nbins
    for k in range(1, size):
        target = cum[-1] * k / size
        e = int(np.searchsorted(cum, target, side="left"))  # cut after bin e, or before it
        if e > 0 and target - cum[e - 1] < cum[e] - target:
            e -= 1
        e += 1
        edges[k] = min(max(e, edges[k - 1] + 1), nbins - (size - k))
    return edges


def migrate(particles, decomp):
    """Send every owned particle that left this rank's slab to its new owner; drops ghosts.

    Particles that stay keep their rows (in order); arrivals are appended in
    the order of their source ranks.
    """
    comm = decomp.comm
    n = particles.n_owned
    dest = decomp.owner(particles.x[:n, decomp.axis])
    leaving = dest != comm.rank
    send_counts = np.bincount(dest[leaving], minlength=comm.size)
    recv_counts = exchange_counts(comm, send_counts)
    leavers = np.nonzero(leaving)[0]
    order = leavers[np.argsort(dest[leavers], kind="stable")]
    names = [f.name for f in particles.fields]
    rows = alltoallv_rows(comm, particles.pack(names, order), send_counts, recv_counts)
    particles.keep_owned(np.nonzero(~leaving)[0], len(rows))
    particles.unpack_into(names, rows, particles.n_owned - len(rows))


def particle_work(particles, start):
    """Work of each owned particle: its neighbour pairs from the CSR offsets ``start`` of the
    current configuration, or 1 per moving particle (0 per wall) when there is none yet."""
    if start is None:
        return (particles.owned("kind") == MOVING).astype(np.float64)
    return np.diff(start).astype(np.float64)
