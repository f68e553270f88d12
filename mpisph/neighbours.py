"""Cell-linked neighbour search producing lists in canonical order.

The cell grid is anchored at the domain origin, so a particle falls in the
same cell on every rank count. Neighbour cells are visited in a fixed order
and particles inside a cell in increasing global id, so the list of particle
i (and every sum over it) is the same whatever the decomposition: that is
what makes runs on 1, 2 and 3 ranks agree bit for bit.

Lists are in CSR form: the neighbours of particle i are
``index[start[i]:start[i + 1]]`` (int32: a rank holds fewer than 2**31
particles, and the lists are the largest array of a 3D run); owned material
particles (moving or clamped) get lists, wall particles none.
"""

import numpy as np
from numba import njit

from .particles import is_wall
from .workspace import Workspace

# Search cells are radius / CELLS_PER_RADIUS wide: with 2, the 5 x 5 (x 5) block of cells around a
# particle covers 30 % (2D) to 42 % (3D) fewer candidates than 3 x 3 (x 3) cells of width radius.
CELLS_PER_RADIUS = 2


PAIRS_PER_PARTICLE = {2: 24, 3: 80}  # first guess of the list length per owned particle


def neighbour_lists(x, gid, kind, n_owned, radius, origin, workspace=None):
    """(start, index): neighbours within ``radius`` (strictly) of each owned material particle.

    The search's transients (cell ids, the particles sorted by cell and their
    positions) are ``workspace.scratch`` when a Workspace is given (the solver's:
    the step then allocates only the lists).
    """
    n, dim = x.shape
    radius = float(radius)
    origin = np.asarray(origin, dtype=np.float64)
    lo, ext = _grid(x, radius / CELLS_PER_RADIUS, origin)
    ncell = int(ext[0] * ext[1] * ext[2])  # < 2**31: int32 cell ids and counts
    scratch = (workspace or Workspace()).scratch(((n,), np.int32), ((ncell + 1,), np.int32), ((ncell,), np.int32),
                                                 ((n,), np.int32), ((n, 3), np.float64))
    start = np.empty(n_owned + 1, np.int64)
    index = np.empty(max(16, PAIRS_PER_PARTICLE[dim] * n_owned), np.int32)  # 4 bytes per pair
    index, count = _search(x, gid, kind, n_owned, radius, origin, lo, ext, *scratch, start, index)
    return start, index[:count]


def cell_order(x, n, radius, origin):
    """Permutation of the particles [0, n) that sorts them by cell of the search grid (x fastest).

    Storing particles in this order keeps the neighbours of a particle close in memory; the sums
    do not depend on it (lists are in canonical order).
    """
    c = _cells(x[:n], float(radius), np.asarray(origin, dtype=np.float64))
    return np.lexsort((c[:, 0], c[:, 1], c[:, 2]))


@njit(inline="always")
def pair_difference(a, i, j):
    """a_i - a_j of a 2- or 3-vector field as three scalars (the third is 0 in 2D).

    Pair loops work on scalars rather than scratch vectors: LLVM keeps them
    in registers, and the same code serves 2D and 3D.
    """
    return a[i, 0] - a[j, 0], a[i, 1] - a[j, 1], (a[i, 2] - a[j, 2] if a.shape[1] == 3 else 0.0)


@njit(inline="always")
def pair_offset(x, i, j):
    """x_i - x_j as three scalars (``pair_difference``) and |x_i - x_j|."""
    d0, d1, d2 = pair_difference(x, i, j)
    return d0, d1, d2, np.sqrt(d0 * d0 + d1 * d1 + d2 * d2)


@njit(inline="always")
def pair_distance(x, i, j):
    """|x_i - x_j| (``pair_offset``, inlined into the pair loops)."""
    return pair_offset(x, i, j)[3]


@njit(inline="always")
def _cell(x, i, a, width, origin):
    """Cell coordinate of particle i along axis a (0 for the missing third axis in 2D)."""
    return np.int64(np.floor((x[i, a] - origin[a]) / width)) if a < x.shape[1] else 0


@njit(cache=True)
def _cells(x, radius, origin):
    n, dim = x.shape
    c = np.zeros((n, 3), dtype=np.int32)
    for i in range(n):
        for a in range(dim):
            c[i, a] = _cell(x, i, a, radius, origin)
    return c


@njit(cache=True)
def _grid(x, width, origin):
    """(lo, ext): the first cell and the number of cells along each axis of the grid that spans
    the particles' cells (lo = 0, ext = 1 on the missing third axis in 2D)."""
    n, dim = x.shape
    lo = np.zeros(3, np.int64)
    ext = np.ones(3, np.int64)
    if n > 0:
        hi = np.zeros(3, np.int64)
        for a in range(dim):
            lo[a] = hi[a] = _cell(x, 0, a, width, origin)
        for i in range(1, n):
            for a in range(dim):
                ca = _cell(x, i, a, width, origin)
                lo[a] = min(lo[a], ca)
                hi[a] = max(hi[a], ca)
        for a in range(dim):
            ext[a] = hi[a] - lo[a] + 1
    return lo, ext


@njit(cache=True)
def _search(x, gid, kind, n_owned, radius, origin, lo, ext, cell_id, cell_start, fill, sorted_idx, xs,
            start, index):
    """Fill the lists of ``neighbour_lists`` into ``start`` and ``index`` (grown if too short);
    the other arrays are scratch of the right sizes. Returns (index, pair count)."""
    n, dim = x.shape
    width = radius / CELLS_PER_RADIUS
    ncell = len(fill)
    # cell coordinates are recomputed where needed rather than stored
    for i in range(n):
        cell_id[i] = ((_cell(x, i, 0, width, origin) - lo[0]) + ext[0] * ((_cell(x, i, 1, width, origin) - lo[1])
                      + ext[1] * (_cell(x, i, 2, width, origin) - lo[2])))

    # counting sort by cell, then by gid inside each cell (insertion sort: a cell holds a
    # particle or two); positions copied in that order so that the candidates of a row of
    # cells are contiguous in memory
    cell_start[:] = 0
    for i in range(n):
        cell_start[cell_id[i] + 1] += 1
    for k in range(ncell):
        cell_start[k + 1] += cell_start[k]
    fill[:] = cell_start[:-1]
    for i in range(n):
        sorted_idx[fill[cell_id[i]]] = i
        fill[cell_id[i]] += 1
    for k in range(ncell):
        for s in range(cell_start[k] + 1, cell_start[k + 1]):
            i = sorted_idx[s]
            t = s
            while t > cell_start[k] and gid[sorted_idx[t - 1]] > gid[i]:  # stable: equal gids keep their order
                sorted_idx[t] = sorted_idx[t - 1]
                t -= 1
            sorted_idx[t] = i
    for s in range(n):
        for a in range(3):
            xs[s, a] = x[sorted_idx[s], a] if a < dim else 0.0

    r2max = radius * radius
    reach = CELLS_PER_RADIUS
    dz_lo = -reach if dim == 3 else 0
    dz_hi = reach if dim == 3 else 0
    count = 0
    for i in range(n_owned):
        start[i] = count
        if is_wall(kind[i]):
            continue
        xi0 = x[i, 0]
        xi1 = x[i, 1]
        xi2 = x[i, 2] if dim == 3 else 0.0
        cx = _cell(x, i, 0, width, origin) - lo[0]
        cy0 = _cell(x, i, 1, width, origin) - lo[1]
        cz0 = _cell(x, i, 2, width, origin) - lo[2]
        x_lo = max(cx - reach, 0)
        x_hi = min(cx + reach, ext[0] - 1)
        for dz in range(dz_lo, dz_hi + 1):
            cz = cz0 + dz
            if cz < 0 or cz >= ext[2]:
                continue
            for dy in range(-reach, reach + 1):
                cy = cy0 + dy
                if cy < 0 or cy >= ext[1]:
                    continue
                row = ext[0] * (cy + ext[1] * cz)
                # the cells (cx - reach .. cx + reach, cy, cz) are consecutive: one range of candidates
                s0 = cell_start[row + x_lo]
                s1 = cell_start[row + x_hi + 1]
                if count + s1 - s0 > len(index):
                    index = _grown(index, count + s1 - s0)
                for s in range(s0, s1):
                    # branch-free: always store, advance only for a neighbour (a hit is
                    # too unpredictable for the branch predictor)
                    d0 = xs[s, 0] - xi0
                    d1 = xs[s, 1] - xi1
                    d2 = xs[s, 2] - xi2
                    j = sorted_idx[s]
                    index[count] = j
                    count += (d0 * d0 + d1 * d1 + d2 * d2 < r2max) & (j != i)
    start[n_owned] = count
    return index, count


@njit(cache=True)
def _grown(a, need):
    """``a`` copied into an array at least twice as long and of at least ``need`` rows."""
    b = np.empty(max(2 * len(a), need), a.dtype)
    b[: len(a)] = a
    return b
