"""Kernels integrate to one, their derivative is the slope of their value, and an unknown
kernel is an error."""

import numpy as np
import pytest

from mpisph.errors import InputError
from mpisph.kernels import KERNELS, Kernel


@pytest.mark.parametrize("name", list(KERNELS))
@pytest.mark.parametrize("dim", [1, 2, 3])
def test_unit_integral(name, dim):
    kernel = Kernel(name, 0.7, dim)
    r = np.linspace(0.0, kernel.support, 20001)
    shell = {1: 2.0 * np.ones_like(r), 2: 2 * np.pi * r, 3: 4 * np.pi * r**2}[dim]
    assert np.trapezoid(kernel.value(r) * shell, r) == pytest.approx(1.0, rel=1e-6)


@pytest.mark.parametrize("name", list(KERNELS))
def test_derivative_matches_finite_difference(name):
    kernel, eps = Kernel(name, 1.3, 2), 1e-6
    r = np.linspace(0.05, 2.5, 40)
    fd = (kernel.value(r + eps) - kernel.value(r - eps)) / (2 * eps)
    np.testing.assert_allclose(kernel.derivative(r), fd, atol=1e-7)
    assert kernel.value(kernel.support) == 0.0 and kernel.derivative(kernel.support) == 0.0


@pytest.mark.parametrize("dim", [2, 3])
def test_lattice_sum_is_near_one(dim):
    """V0 sum W over a full lattice approximates the integral of W: within 3 % at h = 1.3 dp."""
    kernel = Kernel("wendland_c2", 1.3, dim)
    assert kernel.lattice_sum(1.0) == pytest.approx(1.0, rel=0.03)


def test_unknown_kernel_is_an_error():
    with pytest.raises(InputError, match="kernel must be one of"):
        Kernel("gaussian", 1.0, 2)
