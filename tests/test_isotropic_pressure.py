"""The mu(I) scheme's isotropic pressure (``pressure_form = isotropic``, physics/mu_i.py): on a
sheared lattice the symmetric pressure pairs of Eq. 27 carry a uniform pressure's shear across a
plane, the isotropic ones do not; their pairs conserve linear momentum."""

import numpy as np
import pytest

from mpisph.correction import correction_matrix
from mpisph.kernels import Kernel
from mpisph.neighbours import neighbour_lists
from mpisph.physics.mu_i import isotropic_pressure_stress, momentum
from mpisph.physics.mu_i_law import MEAN_HARMONIC
from mpisph.physics.viscous_stress import stress_divergence
from mpisph.tensors import size

DP, RHO = 0.01, 1000.0


def block(dim, shear, jitter=0.0, n=16, seed=3):
    """n^dim particles on a square lattice sheared by x += shear * (last coordinate), jittered by
    ``jitter`` dp; positions, kinds, masses, densities, the kernel and the full neighbour lists."""
    axis = (np.arange(n) + 0.5) * DP
    x = np.stack([g.ravel() for g in np.meshgrid(*([axis] * dim), indexing="ij")], axis=1)
    x += jitter * DP * np.random.default_rng(seed).uniform(-1.0, 1.0, x.shape)
    x[:, 0] += shear * x[:, -1]
    k = Kernel("wendland_c2", 1.3 * DP, dim)
    kind = np.zeros(len(x), np.int8)
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, x.min(axis=0) - DP)
    return x, kind, np.full(len(x), RHO * DP**dim), np.full(len(x), RHO), k, start, nbr


def accelerations(x, kind, mass, rho, k, start, nbr, p, form, B):
    """The pressure accelerations of the pairs in (start, nbr), symmetric (Eq. 27) or isotropic."""
    n, dim = x.shape
    acc = np.zeros((n, dim))
    zeros, normal = np.zeros(n), np.zeros((n, dim))
    if form == "symmetric":
        momentum(n, start, nbr, x, np.zeros((n, dim)), rho, p, zeros, zeros, mass, kind, normal, zeros, 1.5, 0.0,
                 1.0, True, 0.0, MEAN_HARMONIC, k.params, acc)
    else:
        T = np.zeros((n, dim, dim))
        isotropic_pressure_stress(n, kind, p, B, T)
        stress_divergence(n, start, nbr, x, rho, T, mass, kind, normal, k.params, acc)
    return acc


@pytest.mark.parametrize("dim", [2, 3])
def test_a_uniform_pressure_carries_no_shear_across_a_sheared_lattice(dim):
    """The force the particles above a plane exert on those below, in the block's middle: the
    symmetric pairs (virial -p A, A = B^-1 of 000_ Eq. 24, off-diagonal on the sheared lattice)
    pass on a shear traction of 0.4-0.5 % of the normal one at this shear; the isotropic pairs (virial
    -p tr(A) / D I) none, to round-off."""
    x, kind, mass, rho, k, start, nbr = block(dim, shear=0.3)
    n = len(x)
    B = np.zeros((n, size(dim)))
    correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
    plane = 8 * DP
    middle = np.all(np.abs(x[:, :-1] - x[:, :-1].mean(axis=0)) < 2 * DP, axis=1)
    below = middle & (x[:, -1] < plane) & (x[:, -1] > plane - k.support)
    lists = [[j for j in nbr[start[i]:start[i + 1]] if x[j, -1] > plane] if below[i] else [] for i in range(n)]
    across = np.concatenate([[0], np.cumsum([len(a) for a in lists])]).astype(start.dtype)
    above = np.concatenate([np.asarray(a, dtype=nbr.dtype) for a in lists])
    p = np.full(n, 100.0)
    traction = {form: (mass[:, None] * accelerations(x, kind, mass, rho, k, across, above, p, form, B)).sum(axis=0)
                for form in ("symmetric", "isotropic")}
    symmetric, isotropic = traction["symmetric"], traction["isotropic"]
    assert abs(symmetric[0]) > 0.003 * abs(symmetric[-1])
    assert abs(isotropic[0]) < 1e-12 * abs(isotropic[-1])
    assert isotropic[-1] == pytest.approx(symmetric[-1], rel=0.05)


@pytest.mark.parametrize("dim", [2, 3])
def test_isotropic_pressure_pairs_conserve_linear_momentum(dim):
    """sum_i m_i a_i = 0 for a jittered block under a varying pressure, free surfaces included
    (the pair force m_i m_j (T_i + T_j) g_ij / (rho_i rho_j) is antisymmetric)."""
    x, kind, mass, rho, k, start, nbr = block(dim, shear=0.0, jitter=0.2, n=10)
    n = len(x)
    rho = rho * (1.0 + 0.05 * np.sin(40.0 * x[:, 0]))
    B = np.zeros((n, size(dim)))
    correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
    p = 100.0 + 50.0 * x[:, -1] / DP
    acc = accelerations(x, kind, mass, rho, k, start, nbr, p, "isotropic", B)
    total = (mass[:, None] * acc).sum(axis=0)
    assert np.abs(total).max() < 1e-12 * (mass[:, None] * np.abs(acc)).sum()
