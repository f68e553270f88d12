"""The cheapest useful neighbour pass on this machine: the bound for every pair loop of mpisph.

    .venv/bin/python benchmarks/ceiling.py [--particles 100000] [--dim 2]

Density summation rho_i = sum_j m_j W(r_ij) with the Wendland C2 kernel
(h = 1.3 dp, support 2h) over a cell-linked list, particles sorted by cell so
that the candidates of a row of cells are contiguous in memory: no neighbour
list is stored, nothing but the kernel sum is computed, one core. A step of
an SPH scheme that makes P passes over its neighbours cannot run faster than
ceiling / P particle-steps per second; throughput.py prints each case's
fraction of that bound.
"""

import argparse
import math
import time

import numpy as np
from numba import njit


@njit(cache=True)
def _sort_by_cell(x, cell):
    """Particles sorted by cell (x fastest); returns sorted positions, cell start offsets, grid extent."""
    n, dim = x.shape
    ext = np.ones(3, np.int64)
    for a in range(dim):
        ext[a] = int(x[:, a].max() / cell) + 1
    cid = np.empty(n, np.int64)
    for i in range(n):
        c = 0
        for a in range(dim - 1, -1, -1):
            c = c * ext[a] + int(x[i, a] / cell)
        cid[i] = c
    order = np.argsort(cid, kind="mergesort")
    start = np.zeros(ext[0] * ext[1] * ext[2] + 1, np.int64)
    for i in range(n):
        start[cid[i] + 1] += 1
    for k in range(len(start) - 1):
        start[k + 1] += start[k]
    xs = np.zeros((n, 3))
    for k in range(n):
        for a in range(dim):
            xs[k, a] = x[order[k], a]
    return xs, start, ext


@njit(cache=True)
def density_pass(xs, start, ext, cell, mass, h, sigma, dim, rho):
    """rho_i = sum_j m W_ij, self included, Wendland C2, branch-free inside the pair loop."""
    n = len(xs)
    support2 = 4.0 * h * h
    z_lo, z_hi = (-1, 1) if dim == 3 else (0, 0)
    for i in range(n):
        c0 = int(xs[i, 0] / cell)
        c1 = int(xs[i, 1] / cell)
        c2 = int(xs[i, 2] / cell) if dim == 3 else 0
        acc = 0.0
        for dz in range(z_lo, z_hi + 1):
            cz = c2 + dz
            if cz < 0 or cz >= ext[2]:
                continue
            for dy in range(-1, 2):
                cy = c1 + dy
                if cy < 0 or cy >= ext[1]:
                    continue
                row = ext[0] * (cy + ext[1] * cz)
                lo = row + max(c0 - 1, 0)
                hi = row + min(c0 + 1, ext[0] - 1)
                for s in range(start[lo], start[hi + 1]):
                    d0 = xs[i, 0] - xs[s, 0]
                    d1 = xs[i, 1] - xs[s, 1]
                    d2 = xs[i, 2] - xs[s, 2]
                    r2 = d0 * d0 + d1 * d1 + d2 * d2
                    q = math.sqrt(min(r2, support2)) / h
                    t = 1.0 - 0.5 * q
                    acc += t * t * t * t * (2.0 * q + 1.0)
        rho[i] = mass * sigma * acc


def ceiling(n_target=100_000, dim=2, repeats=7):
    """(particle-passes per second, pairs within the support per second) on one core."""
    side = round(n_target ** (1.0 / dim))
    dp = 1.0 / side
    h = 1.3 * dp
    rng = np.random.default_rng(0)
    grid = np.stack(np.meshgrid(*[np.arange(side)] * dim, indexing="ij"), -1).reshape(-1, dim)
    x = (grid + 0.5 + rng.uniform(-0.1, 0.1, grid.shape)) * dp
    cell = 2.0 * h
    xs, start, ext = _sort_by_cell(x, cell)
    sigma = 7.0 / (4.0 * math.pi * h * h) if dim == 2 else 21.0 / (16.0 * math.pi * h ** 3)
    rho = np.empty(len(x))
    density_pass(xs, start, ext, cell, dp ** dim, h, sigma, dim, rho)  # compile
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        density_pass(xs, start, ext, cell, dp ** dim, h, sigma, dim, rho)
        best = min(best, time.perf_counter() - t0)
    inner = rho[(np.abs(x - 0.5) < 0.4).all(1)]
    assert abs(inner.mean() - 1.0) < 0.02, "density summation is wrong: the ceiling would time a bug"
    sample = rng.choice(len(x), 200, replace=False)  # pairs within the support per particle, sampled
    d2 = ((x[:, None, :] - x[None, sample, :]) ** 2).sum(-1)
    pairs = np.count_nonzero(d2 < 4 * h * h) / 200
    return len(x) / best, len(x) * pairs / best


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--particles", type=int, default=100_000)
    ap.add_argument("--dim", type=int, choices=(2, 3), default=2)
    a = ap.parse_args()
    rate, pairs = ceiling(a.particles, a.dim)
    print(f"ceiling {a.dim}D: {rate:.4g} particle-passes/s on one core ({pairs / 1e6:.0f} M pairs/s), "
          f"density summation over a cell-linked list sorted by cell  "
          f"[.venv/bin/python benchmarks/ceiling.py --particles {a.particles} --dim {a.dim}]")


if __name__ == "__main__":
    main()
