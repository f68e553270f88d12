"""The pressure of the mu(I) scheme's pairs (physics/mu_i.py). ``pressure_form = isotropic``: on a
sheared lattice the symmetric pressure pairs of Eq. 27 carry a uniform pressure's shear across a
plane, the isotropic ones do not; their pairs conserve linear momentum. ``law_pressure =
carried``: the share s = tr(A) / D of the pressure that the pairs carry, and the friction law
evaluated with it."""

import numpy as np
import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.correction import correction_matrix
from mpisph.kernels import Kernel
from mpisph.neighbours import neighbour_lists
from mpisph.physics.mu_i import carried_fraction, granular_state, isotropic_pressure_stress, momentum
from mpisph.physics.mu_i_law import MEAN_HARMONIC, friction
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
                 1.0, True, 0.0, 1.0, 0.0, MEAN_HARMONIC, k.params, acc)
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


@pytest.mark.parametrize("dim", [2, 3])
def test_carried_fraction_is_the_trace_of_the_kernel_moment(dim):
    """s_i = tr(B_i^-1) / D equals tr(A_i) / D, A_i = -sum_j V_j r_ij (x) grad W_ij summed here
    directly, on a jittered block's inner particles; 0.974 (2D) and 0.979 (3D) at h = 1.3 dp on
    the perfect lattice."""
    scratch = np.empty((dim, dim)), np.empty((dim, dim))
    for jitter in (0.0, 0.2):
        x, kind, mass, rho, k, start, nbr = block(dim, shear=0.0, jitter=jitter, n=10)
        n = len(x)
        B = np.zeros((n, size(dim)))
        correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
        inner = np.all(np.abs(x - x.mean(axis=0)) < 2.5 * DP, axis=1)
        for i in np.flatnonzero(inner):
            j = nbr[start[i]:start[i + 1]]
            r = x[i] - x[j]
            dist = np.linalg.norm(r, axis=1)
            trace = -np.sum(mass[j] / rho[j] * k.derivative(dist) * dist)
            assert carried_fraction(B, i, *scratch) == pytest.approx(trace / dim, rel=1e-12)
        if jitter == 0.0:
            assert carried_fraction(B, int(np.flatnonzero(inner)[0]), *scratch) == pytest.approx(
                {2: 0.974, 3: 0.979}[dim], abs=1e-3)


def test_the_law_takes_the_carried_pressure():
    """With law_pressure = carried a grain whose pairs carry s = 0.9 of its pressure p has the
    shear stress eta gamma_dot = mu(I) s p, I formed with s p (the inertial number that Eq. 8's
    volume fraction then gives), where the regularisation has let go (m_0 gamma_dot >> 1)."""
    module = load_case_module("inclined_plane")
    material = build_case(module, resolve_params(module, {"H": "0.02", "dp": "0.002", "columns": "16"})).material
    m = material.params
    s, gamma_dot, rho = 0.9, 60.0, 0.58 * material.rho_s0
    B = np.array([[1.0 / s, 1.0 / s, 0.0]])
    out = {}
    for carried in (False, True):
        rho_s, p, eta = np.array([material.rho_s0]), np.zeros(1), np.zeros(1)
        granular_state(1, np.zeros(1, np.int8), np.array([rho]), np.array([gamma_dot]), B, carried, rho_s, p, eta,
                       2, m, np.zeros(0))
        x = rho_s[0] / material.rho_s0
        I = gamma_dot * material.d0 * x ** -0.5 / np.sqrt((s if carried else 1.0) * p[0] / rho_s[0])
        assert 1.0 - rho / rho_s[0] / material.phi_max == pytest.approx(
            (material.phi_max - material.phi_min) * I / material.phi_max, rel=1e-9)  # Eq. 8
        out[carried] = eta[0] * gamma_dot / ((s if carried else 1.0) * p[0]), friction(I, m)
    for carried, (ratio, mu) in out.items():
        assert ratio == pytest.approx(mu, rel=1e-3)
    assert out[True][1] > out[False][1]  # the carried pressure is lower: larger I, larger friction
