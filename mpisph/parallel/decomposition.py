"""Slab decomposition along one axis: cuts, ownership, migration, rebalancing.

The domain is divided into bins as wide as the kernel support along the slab
axis; cuts between ranks sit on bin edges, chosen from the global histogram of
moving-particle counts so that every rank owns about the same number of
moving particles. The first and last cuts are open (-inf, +inf) so every
particle has an owner. A rank needs at least one bin, so a run may not use
more ranks than the domain has bins.
"""

import math

import numpy as np
from mpi4py import MPI

from ..errors import InputError
from ..particles import MOVING
from .exchange import alltoallv_rows, exchange_counts


class SlabDecomposition:
    """Cuts along ``axis`` between ``comm.size`` slabs."""

    def __init__(self, comm, axis, lo, hi, bin_width):
        self.comm = comm
        self.axis = axis
        self.lo = float(lo)
        self.bin_width = float(bin_width)
        self.nbins = max(1, math.ceil((float(hi) - self.lo) / self.bin_width - 1e-9))
        if comm.size > self.nbins:
            raise InputError(
                f"{comm.size} ranks but the domain has only {self.nbins} slabs of width "
                f"{self.bin_width:g} m along axis {'xyz'[axis]}; use at most {self.nbins} ranks")
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

    def balance(self, s_local):
        """Place the cuts so that each rank gets about the same number of ``s_local``.

        ``s_local`` are this rank's moving-particle coordinates along the axis;
        the histogram is summed over all ranks, so every rank computes the
        same cuts.
        """
        hist = np.bincount(self.bin_of(s_local), minlength=self.nbins).astype(np.int64)
        total = np.empty_like(hist)
        self.comm.Allreduce(hist, total, op=MPI.SUM)
        cum = np.cumsum(total)
        size = self.comm.size
        edges = np.empty(size + 1, dtype=np.int64)
        edges[0], edges[-1] = 0, self.nbins
        for k in range(1, size):
            target = cum[-1] * k / size
            e = int(np.searchsorted(cum, target, side="left")) + 1
            edges[k] = min(max(e, edges[k - 1] + 1), self.nbins - (size - k))
        self.edges = edges
        self._set_cuts()

    def imbalance(self, n_moving_local):
        """max/mean - 1 of the moving-particle counts over ranks."""
        counts = np.empty(self.comm.size, dtype=np.int64)
        self.comm.Allgather(np.array([n_moving_local], dtype=np.int64), counts)
        mean = counts.mean()
        return 0.0 if mean == 0 else counts.max() / mean - 1.0

    def slab(self, rank=None):
        r = self.comm.rank if rank is None else rank
        return self.cuts[r], self.cuts[r + 1]


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


def moving_coordinates(particles, axis):
    """Slab-axis coordinates of the owned moving particles."""
    n = particles.n_owned
    return particles.x[:n, axis][particles.kind[:n] == MOVING]
