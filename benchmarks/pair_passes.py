"""Milliseconds per call of the solid and mu(I) pair passes that build gradients and blocks, on a
jittered lattice with walls of both kinds: the figures of docs/PERFORMANCE.md's kernel rewrites.

    .venv/bin/python benchmarks/pair_passes.py [--repeat 15] [--save OUT.npz]

A 22^3 lattice (10 648 particles) and a 150^2 one (22 500), each point moved by up to 0.1 dp, the
Wendland C2 kernel at h = 1.3 dp; the bottom three layers are walls, no-slip on one half and
free-slip on the other, with a unit normal along the last axis. Velocities, B, eta and densities
are random. Each pass is called ``--repeat`` times, the fastest printed. ``--save`` writes every
pass's output, so that two versions of the code (PYTHONPATH set to each tree, run from outside
both) can be compared to the bit.
"""

import argparse
import time

import numpy as np
from numba import njit

from mpisph.kernels import Kernel
from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL, WALL_SLIP
from mpisph.physics.implicit_viscosity import viscous_pairs
from mpisph.physics.solid import velocity_gradient
from mpisph.physics.viscous_stress import strain_rate, stress_blocks


@njit  # not cached: a cache would keep the velocity_gradient of whichever tree compiled it first
def all_velocity_gradients(n, start, nbr, x, v, mass, rho, kind, normal, wall_distance, beta_max, B, k, out):
    """solid.velocity_gradient of every moving particle, as the solids' stress updates call it."""
    L = np.zeros((3, 3))
    for i in range(n):
        if kind[i] == MOVING:
            velocity_gradient(i, start, nbr, x, v, mass, rho, kind, normal, wall_distance, beta_max, B, k, L)
            out[i] = L


def lattice(dim, nx, rng):
    """The jittered lattice and its fields (module docstring)."""
    g = np.stack(np.meshgrid(*[np.arange(nx)] * dim, indexing="ij"), -1).reshape(-1, dim) * 1.0
    x = g + rng.uniform(-0.1, 0.1, g.shape)
    n = len(x)
    k = Kernel("wendland_c2", 1.3, dim)
    kind = np.full(n, MOVING, dtype=np.int8)
    bottom = g[:, -1] < 3
    kind[bottom & (g[:, 0] < nx / 2)] = WALL
    kind[bottom & (g[:, 0] >= nx / 2)] = WALL_SLIP
    start, nbr = neighbour_lists(x, np.arange(n, dtype=np.int64), kind, n, k.support, x.min(0) - 1)
    normal = np.zeros((n, dim))
    normal[:, -1] = 1.0
    return dict(n=n, x=x, k=k.params, kind=kind, start=start, nbr=nbr, normal=normal,
                wall_distance=np.where(kind != MOVING, 3 - g[:, -1], 0.0), v=rng.normal(size=(n, dim)),
                rho=1 + 0.01 * rng.random(n), mass=np.ones(n), eta=rng.random(n), gamma_dot=rng.random(n),
                B=rng.normal(size=(n, 6 if dim == 3 else 3)))


def passes(p):
    """{name: call returning its outputs} of one lattice."""
    n, dim = p["n"], p["x"].shape[1]
    B, no_B = p["B"], np.zeros((0, p["B"].shape[1]))
    common = (p["start"], p["nbr"], p["x"])

    def gradient(beta_max, B):
        out = np.zeros((n, 3, 3))
        all_velocity_gradients(n, *common, p["v"], p["mass"], p["rho"], p["kind"], p["normal"], p["wall_distance"],
                               beta_max, B, p["k"], out)
        return (out,)

    def rate(B):
        strain, gamma_dot = np.zeros((n, B.shape[1])), np.zeros(n)
        strain_rate(n, *common, p["v"], p["rho"], p["mass"], p["kind"], p["normal"], p["wall_distance"], 1.5, B,
                    p["k"], strain, gamma_dot)
        return strain, gamma_dot

    def blocks():
        inverse = np.zeros((n, dim, dim))
        stress_blocks(n, *common, p["rho"], p["eta"], B, p["mass"], p["kind"], p["k"], 1e-3, inverse)
        return (inverse,)

    def pairs():
        coef, inverse = np.zeros(len(p["nbr"])), np.zeros((n, dim, dim))
        viscous_pairs(n, *common, p["rho"], p["eta"], p["gamma_dot"], p["mass"], p["kind"], p["normal"],
                      p["wall_distance"], 1.5, 1.0, 1.0, 5.0 / 3.0, 0, p["k"], 1e-3, coef, inverse)
        return coef, inverse

    return {"velocity_gradient mirrored, with B": lambda: gradient(0.0, B),
            "velocity_gradient Morris, plain": lambda: gradient(1.5, no_B),
            "strain_rate with B (mirrored)": lambda: rate(B),
            "strain_rate plain (Morris)": lambda: rate(no_B),
            "stress_blocks": blocks,
            "viscous_pairs (deviatoric)": pairs}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--save", help="write every pass's output to this .npz")
    args = ap.parse_args()
    rng = np.random.default_rng(1)
    saved = {}
    for dim, nx in ((3, 22), (2, 150)):
        p = lattice(dim, nx, rng)
        for name, call in passes(p).items():
            for a, out in enumerate(call()):  # the first call compiles, or loads the cache
                saved[f"{dim}D {name} {a}"] = out
            best = np.inf
            for _ in range(args.repeat):
                t0 = time.perf_counter()
                call()
                best = min(best, time.perf_counter() - t0)
            print(f"{dim}D {p['n']:6d} particles  {name:36s} {1e3 * best:7.2f} ms")
    if args.save:
        np.savez(args.save, **saved)


if __name__ == "__main__":
    main()
