"""Kernels integrate to one and their derivative is the slope of their value."""

import numpy as np
import pytest

from mpisph.kernels import CUBIC_SPLINE, WENDLAND_C2, dw, normalisation, w


@pytest.mark.parametrize("kernel", [WENDLAND_C2, CUBIC_SPLINE])
@pytest.mark.parametrize("dim", [2, 3])
def test_unit_integral(kernel, dim):
    h = 0.7
    r = np.linspace(0.0, 2.0 * h, 20001)
    sigma = normalisation(kernel, h, dim)
    values = np.array([w(ri, h, sigma, kernel) for ri in r])
    shell = 2 * np.pi * r if dim == 2 else 4 * np.pi * r**2
    assert np.trapezoid(values * shell, r) == pytest.approx(1.0, rel=1e-6)


@pytest.mark.parametrize("kernel", [WENDLAND_C2, CUBIC_SPLINE])
def test_derivative_matches_finite_difference(kernel):
    h, eps = 1.3, 1e-6
    sigma = normalisation(kernel, h, 2)
    for r in np.linspace(0.05, 2.5, 40):
        fd = (w(r + eps, h, sigma, kernel) - w(r - eps, h, sigma, kernel)) / (2 * eps)
        assert dw(r, h, sigma, kernel) == pytest.approx(fd, abs=1e-7)
    assert w(2 * h, h, sigma, kernel) == 0.0 and dw(2 * h, h, sigma, kernel) == 0.0
