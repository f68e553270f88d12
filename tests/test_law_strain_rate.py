"""The strain rate of the mu(I) law with ``law_strain_rate = kernel_mean`` and
``deviatoric_kernel_mean`` (physics/mu_i.py, kernel_mean.py): the modulus of the kernel mean of
eps is the modulus of a smooth strain rate, and it takes most of the bias out of the modulus of a
noisy one; the modulus of its deviator leaves out a change of volume."""

import numpy as np
import pytest

from lattice import lattice
from mpisph.correction import correction_matrix
from mpisph.physics.kernel_mean import kernel_mean, rate_modulus
from mpisph.physics.viscous_stress import strain_rate
from mpisph.tensors import size

DP, RHO, RATE = 0.01, 1000.0, 3.0


def rates(dim, v, deviatoric=False):
    """(own gamma_dot, gamma_dot of the kernel mean of eps, or of its deviator) of the inner
    particles of a lattice moving with velocities ``v``, the gradient corrected by B (000_ Eq. 24)."""
    x, kind, start, nbr, k, inner = lattice(dim, 1.3, n=16, dp=DP)
    n = len(x)
    mass, rho = np.full(n, RHO * DP**dim), np.full(n, RHO)
    B = np.zeros((n, size(dim)))
    correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
    strain, own, mean = np.zeros((n, size(dim))), np.zeros(n), np.zeros(n)
    normal, zeros = np.zeros((n, dim)), np.zeros(n)
    strain_rate(n, start, nbr, x, v(x), rho, mass, kind, normal, zeros, 1.5, B, k.params, strain, own)
    mean_strain = np.zeros_like(strain)
    kernel_mean(n, start, nbr, x, rho, mass, kind, strain, k.params, mean_strain)
    rate_modulus(n, kind, mean_strain, deviatoric, dim, mean)
    return own[inner], mean[inner]


def shear(x):
    """Simple shear along x with the rate RATE across the last axis."""
    v = np.zeros_like(x)
    v[:, 0] = RATE * x[:, -1]
    return v


@pytest.mark.parametrize("dim", [2, 3])
def test_the_kernel_mean_keeps_a_uniform_shear_rate(dim):
    own, mean = rates(dim, shear)
    assert own == pytest.approx(RATE, rel=1e-10)
    assert mean == pytest.approx(RATE, rel=1e-10)


@pytest.mark.parametrize("dim", [2, 3])
def test_the_kernel_mean_filters_the_bias_of_grain_scale_waves_and_keeps_resolved_ones(dim):
    """A wave u_x = a sin(2 pi x / lambda) on the shear has no mean strain rate but adds its
    eps_xx^2 to the modulus, whose mean over the lattice rises (0.5 % at lambda = 3 dp, 3.8 % at
    12 dp for a k = 0.3 RATE). The kernel mean is a low-pass filter: it removes more than 80 % of
    that rise at 3 dp, the jostle of neighbouring grains, and less than 20 % at 12 dp, a wave the
    particles resolve."""
    def biases(wavelength):
        k = 2.0 * np.pi / (wavelength * DP)

        def v(x):
            u = shear(x)
            u[:, 0] += 0.3 * RATE / k * np.sin(k * x[:, 0])
            return u
        own, mean = rates(dim, v)
        return own.mean() / RATE - 1.0, mean.mean() / RATE - 1.0

    own, mean = biases(3)
    assert own > 0.003 and 0.0 < mean < 0.2 * own
    own, mean = biases(12)
    assert own > 0.03 and 0.8 * own < mean < own


@pytest.mark.parametrize("dim", [2, 3])
def test_the_deviator_keeps_the_shear_and_leaves_out_a_change_of_volume(dim):
    """A uniform expansion at the rate a on the shear: eps = a I + the shear's, whose modulus
    sqrt(RATE^2 + 2 D a^2) counts the expansion as shear; its deviator's modulus is RATE."""
    a = 0.5 * RATE

    def expanding(x):
        return shear(x) + a * (x - x.mean(axis=0))
    _, full = rates(dim, expanding)
    _, deviatoric = rates(dim, expanding, deviatoric=True)
    assert full == pytest.approx(np.sqrt(RATE**2 + 2 * dim * a**2), rel=1e-10)
    assert deviatoric == pytest.approx(RATE, rel=1e-10)
