"""How hard dummy walls push back: the wall particles' kernel-gradient sum in front of a wall, over
that of the continuous region the particles stand for.

A material particle i under pressure p beside dummy wall particles j is pushed off them by
-(2 p / rho_i) sum_j V_j grad_i W_ij (physics/solid.py, physics/fluid.py). Along a normal n
pointing into the material, ``push`` is sum_j V_j grad_i W_ij . n, negative (grad_i W_ij points
from i to j). ``continuous_region`` samples the region behind the wall surfaces within the wall's
depth on a lattice ``spacing`` fine, so that ``push_over_continuous`` is 1 where the particles fill
that region as it should be filled: below 1 the wall has a hole and pushes too little, above 1 it
has more particles than the region holds. A flat wall of whole lattice layers gives 1.02 to 1.05
(the lattice's sum against the integral). The joints of walls in different frames are where it
matters (meshes.py, tests/test_meshes.py, scripts/flume_walls.py).
"""

import numpy as np

from .meshes import joined, nearest_on_parts


def continuous_region(surfaces, lo, hi, spacing, depth):
    """The points of a lattice ``spacing`` fine in the box [lo, hi] that lie behind one of the
    ``surfaces`` (meshes.Surface) nearer than ``depth``: the region wall layers of that depth fill.
    The lattice's cells have their faces on the planes x, y, z = k spacing, so that a surface on
    such a plane (a level floor at z = 0) bounds whole cells."""
    first, last = np.floor(np.asarray(lo) / spacing), np.ceil(np.asarray(hi) / spacing)
    axes = [(np.arange(a, b) + 0.5) * spacing for a, b in zip(first, last)]
    x = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    dist, _, behind = nearest_on_parts(x, *joined(surfaces), len(surfaces))
    return x[np.any(behind & (dist < depth), axis=1)]


def push(points, volume, probes, normals, kernel):
    """sum_j V_j grad W(probe - x_j) . n over ``points`` (each of volume ``volume``) at each probe,
    with n its row of ``normals`` and W the ``kernel`` (kernels.Kernel); the probes and the points
    within the kernel's support of their box as one dense array, so the caller passes a few probes."""
    near = points[np.all((points > probes.min(axis=0) - kernel.support)
                         & (points < probes.max(axis=0) + kernel.support), axis=1)]
    d = probes[:, None, :] - near[None]
    r = np.linalg.norm(d, axis=2)
    dw = kernel.derivative(np.minimum(r, kernel.support))
    return volume * np.einsum("pj,pjk,pk->p", dw / np.maximum(r, 1e-300), d, normals)


def push_over_continuous(surfaces, walls, dp, depth, probes, normals, kernel, chunk=64):
    """``push`` of the wall particles ``walls`` (spacing dp) at the probes over that of the
    continuous region ``depth`` deep behind ``surfaces``, sampled dp/4 fine about each ``chunk``
    of probes in turn."""
    out = np.zeros(len(probes))
    for a in range(0, len(probes), chunk):
        p, n = probes[a:a + chunk], normals[a:a + chunk]
        margin = kernel.support + dp
        region = continuous_region(surfaces, p.min(axis=0) - margin, p.max(axis=0) + margin, dp / 4, depth)
        out[a:a + chunk] = push(walls, dp**3, p, n, kernel) / push(region, (dp / 4) ** 3, p, n, kernel)
    return out
