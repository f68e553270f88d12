"""Ghost particles: copies of particles within the halo width of another slab.

``build`` sends every owned particle (moving or wall) to each rank whose slab
lies within ``width`` of it, and makes periodic images: a particle within
``width`` of a periodic boundary is also sent, shifted by the period, to the
ranks near its image (its own rank included, which is how periodicity works
on a single rank too). It sends the core fields of particles.CORE_FIELDS,
which the neighbour search and the configuration's loops read; every other
field a loop reads from neighbours is sent by ``refresh``, with the send plan
kept from ``build``, right before that loop. Until then those ghost rows hold
NaN, so that a missing refresh shows as a blow-up instead of stale values.
"""

import itertools
import time

import numpy as np

from ..particles import CORE_FIELDS
from .exchange import alltoallv_rows, exchange_counts


class Halo:
    """Ghost exchange for one slab decomposition and a set of periodic axes."""

    def __init__(self, decomp, width, domain_lo, domain_hi, periodic):
        self.decomp = decomp
        self.comm = decomp.comm
        self.width = float(width)
        self.lo = np.asarray(domain_lo, dtype=float)
        self.hi = np.asarray(domain_hi, dtype=float)
        self.periodic = tuple(bool(p) for p in periodic)
        self._plan = None
        self.refresh_seconds = 0.0

    def _images(self, x):
        """Yield (index, shift) for the owned positions ``x`` and their periodic images."""
        n, dim = x.shape
        choices = []
        for a in range(dim):
            options = [(0.0, np.ones(n, bool))]
            if self.periodic[a]:
                length = self.hi[a] - self.lo[a]
                options.append((length, x[:, a] < self.lo[a] + self.width))
                options.append((-length, x[:, a] >= self.hi[a] - self.width))
            choices.append(options)
        for combo in itertools.product(*choices):
            mask = np.ones(n, bool)
            shift = np.zeros(dim)
            for a, (s, m) in enumerate(combo):
                mask &= m
                shift[a] = s
            idx = np.nonzero(mask)[0]
            if len(idx):
                yield idx, shift

    def build(self, particles):
        """Replace the ghosts of ``particles`` by a fresh halo: the core fields are sent, every other
        floating-point field of the ghosts is NaN until ``refresh`` sends it."""
        comm, axis, size, me = self.comm, self.decomp.axis, self.comm.size, self.comm.rank
        x = particles.x[: particles.n_owned]
        dests, indices, shifts = [], [], []
        for idx, shift in self._images(x):
            s = x[idx, axis] + shift[axis]
            r_lo = self.decomp.owner(s - self.width)
            r_hi = self.decomp.owner(s + self.width)
            for k in range(int((r_hi - r_lo).max()) + 1):
                r = r_lo + k
                keep = r <= r_hi
                if not shift.any():
                    keep &= r != me
                dests.append(r[keep])
                indices.append(idx[keep])
                shifts.append(np.broadcast_to(shift, (int(keep.sum()), len(shift))))
        dest = np.concatenate(dests) if dests else np.zeros(0, np.int64)
        index = np.concatenate(indices) if indices else np.zeros(0, np.int64)
        shift = np.concatenate(shifts) if shifts else np.zeros((0, x.shape[1]))
        order = np.argsort(dest, kind="stable")
        index, shift = index[order], shift[order]
        send_counts = np.bincount(dest, minlength=size)
        recv_counts = exchange_counts(comm, send_counts)
        self._plan = (index, send_counts, recv_counts)

        names = [f.name for f in CORE_FIELDS]
        rows = particles.pack(names, index)
        rows[:, _column(particles, names, "x")] += shift
        ghosts = alltoallv_rows(comm, rows, send_counts, recv_counts)
        particles.set_ghost_count(len(ghosts))
        particles.unpack_into(names, ghosts, particles.n_owned)
        for f in particles.fields:
            if f.name not in names and np.issubdtype(f.dtype, np.floating):
                particles.arrays[f.name][particles.n_owned:] = np.nan

    def refresh(self, particles, names):
        """Send the current values of ``names`` to the ghosts made by ``build``."""
        t0 = time.perf_counter()
        index, send_counts, recv_counts = self._plan
        rows = alltoallv_rows(self.comm, particles.pack(names, index), send_counts, recv_counts)
        particles.unpack_into(names, rows, particles.n_owned)
        self.refresh_seconds += time.perf_counter() - t0


def _column(particles, names, name):
    """Slice of the packed row that holds field ``name``."""
    start = particles.width(names[: names.index(name)])
    return slice(start, start + particles.width([name]))
