"""Cell-linked neighbour search producing lists in canonical order.

The cell grid is anchored at the domain origin, so a particle falls in the
same cell on every rank count. Neighbour cells are visited in a fixed order
and particles inside a cell in increasing global id, so the list of particle
i (and every sum over it) is the same whatever the decomposition: that is
what makes runs on 1, 2 and 3 ranks agree bit for bit.

Lists are in CSR form: the neighbours of particle i are
``index[start[i]:start[i + 1]]``; owned material particles (moving or
clamped) get lists, wall particles none.
"""

import numpy as np
from numba import njit

from .particles import is_wall


def neighbour_lists(x, gid, kind, n_owned, radius, origin):
    """Neighbours within ``radius`` (strictly) of each owned material particle."""
    by_gid = np.argsort(gid, kind="stable")
    return _build(x, kind, n_owned, float(radius), np.asarray(origin, dtype=np.float64), by_gid)


@njit(cache=True)
def pair_distance(x, i, j):
    """|x_i - x_j|."""
    r2 = 0.0
    for a in range(x.shape[1]):
        d = x[i, a] - x[j, a]
        r2 += d * d
    return np.sqrt(r2)


@njit(cache=True)
def unit_offset(x, i, j, e):
    """Fill ``e`` with e_ij = (x_i - x_j)/|x_i - x_j| and return |x_i - x_j|."""
    r = 0.0
    for a in range(x.shape[1]):
        e[a] = x[i, a] - x[j, a]
        r += e[a] * e[a]
    r = np.sqrt(r)
    for a in range(x.shape[1]):
        e[a] /= r
    return r


@njit(cache=True)
def _cells(x, radius, origin):
    n, dim = x.shape
    c = np.empty((n, 3), dtype=np.int64)
    c[:, :] = 0
    for i in range(n):
        for a in range(dim):
            c[i, a] = np.int64(np.floor((x[i, a] - origin[a]) / radius))
    return c


@njit(cache=True)
def _build(x, kind, n_owned, radius, origin, by_gid):
    n, dim = x.shape
    c = _cells(x, radius, origin)
    lo = np.empty(3, np.int64)
    ext = np.ones(3, np.int64)
    for a in range(3):
        lo[a] = 0
    if n > 0:
        for a in range(dim):
            lo[a] = c[:, a].min()
            ext[a] = c[:, a].max() - lo[a] + 1
    ncell = ext[0] * ext[1] * ext[2]
    cell_id = np.empty(n, np.int64)
    for i in range(n):
        cell_id[i] = (c[i, 0] - lo[0]) + ext[0] * ((c[i, 1] - lo[1]) + ext[1] * (c[i, 2] - lo[2]))

    # counting sort by cell, stable over particles taken in gid order
    cell_start = np.zeros(ncell + 1, np.int64)
    for i in range(n):
        cell_start[cell_id[i] + 1] += 1
    for k in range(ncell):
        cell_start[k + 1] += cell_start[k]
    fill = cell_start[:-1].copy()
    sorted_idx = np.empty(n, np.int64)
    for k in range(n):
        i = by_gid[k]
        sorted_idx[fill[cell_id[i]]] = i
        fill[cell_id[i]] += 1

    r2max = radius * radius
    dz_lo = -1 if dim == 3 else 0
    dz_hi = 1 if dim == 3 else 0
    start = np.zeros(n_owned + 1, np.int64)
    for sweep in range(2):
        if sweep == 1:
            for i in range(n_owned):
                start[i + 1] += start[i]
            index = np.empty(start[n_owned], np.int64)
        else:
            index = np.empty(0, np.int64)
        for i in range(n_owned):
            if is_wall(kind[i]):
                continue
            count = 0
            for dz in range(dz_lo, dz_hi + 1):
                cz = c[i, 2] - lo[2] + dz
                if cz < 0 or cz >= ext[2]:
                    continue
                for dy in range(-1, 2):
                    cy = c[i, 1] - lo[1] + dy
                    if cy < 0 or cy >= ext[1]:
                        continue
                    for dx in range(-1, 2):
                        cx = c[i, 0] - lo[0] + dx
                        if cx < 0 or cx >= ext[0]:
                            continue
                        k = cx + ext[0] * (cy + ext[1] * cz)
                        for s in range(cell_start[k], cell_start[k + 1]):
                            j = sorted_idx[s]
                            if j == i:
                                continue
                            r2 = 0.0
                            for a in range(dim):
                                d = x[i, a] - x[j, a]
                                r2 += d * d
                            if r2 < r2max:
                                if sweep == 1:
                                    index[start[i] + count] = j
                                else:
                                    start[i + 1] += 1
                                count += 1
    return start, index
