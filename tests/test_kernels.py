"""Kernels integrate to one, their derivative is the slope of their value, and an unknown
kernel is an error; the adaptive B-spline of 002_ integrates to one for every knot, is the cubic
spline at a = 1, puts the peak of |W'| at a b h / (a + b), and its pair kernel is symmetric."""

import numpy as np
import pytest

from mpisph.errors import InputError
from mpisph.kernels import (KERNELS, AdaptiveKernelParams, Kernel, knot_coefficients, knot_dw, knot_w, pair_dw,
                            pair_w)

KNOTS = [0.2, 0.7, 1.0, 1.5, 1.9, 2.0]


def knot_values(r, h, a, dim, derivative=False):
    f = knot_dw if derivative else knot_w
    inner, outer = knot_coefficients(a, h, dim)
    return np.array([f(x, h, a, inner, outer) for x in r])


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


@pytest.mark.parametrize("a", KNOTS)
@pytest.mark.parametrize("dim", [1, 2, 3])
def test_adaptive_b_spline_integrates_to_one_for_every_knot(a, dim):
    h = 0.7
    r = np.linspace(0.0, 2.0 * h, 40001)
    shell = {1: 2.0 * np.ones_like(r), 2: 2 * np.pi * r, 3: 4 * np.pi * r**2}[dim]
    assert np.trapezoid(knot_values(r, h, a, dim) * shell, r) == pytest.approx(1.0, rel=1e-6)


@pytest.mark.parametrize("dim", [1, 2, 3])
def test_adaptive_b_spline_at_a_1_is_the_cubic_spline(dim):
    kernel, r = Kernel("cubic_spline", 0.7, dim), np.linspace(0.0, 1.5, 61)
    np.testing.assert_allclose(knot_values(r, 0.7, 1.0, dim), kernel.value(r), rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(knot_values(r, 0.7, 1.0, dim, True), kernel.derivative(r), rtol=1e-13, atol=1e-15)


@pytest.mark.parametrize("a", KNOTS)
def test_adaptive_b_spline_slope_and_the_peak_of_its_gradient(a):
    h, b, eps = 1.3, 2.0, 1e-6
    r = np.linspace(0.01, 2.6, 300)
    fd = (knot_values(r + eps, h, a, 2) - knot_values(r - eps, h, a, 2)) / (2 * eps)
    np.testing.assert_allclose(knot_values(r, h, a, 2, True), fd, atol=1e-6)
    fine = np.linspace(0.0, 2.0 * h, 200001)
    peak = fine[np.argmin(knot_values(fine, h, a, 2, True))]
    assert peak == pytest.approx(a * b * h / (a + b), abs=2e-5)


def test_a_pair_of_different_knots_weighs_the_same_from_both_sides():
    knots = np.array([0.2, 1.8])
    k = AdaptiveKernelParams(*Kernel("cubic_spline", 0.5, 2).fixed_params, 2, knots,
                             np.array([knot_coefficients(a, 0.5, 2) for a in knots]))
    for r in (0.1, 0.4, 0.8):
        mean = 0.5 * (knot_values([r], 0.5, 0.2, 2)[0] + knot_values([r], 0.5, 1.8, 2)[0])
        assert pair_w(k, r, 0, 1) == pair_w(k, r, 1, 0) == mean
        assert pair_dw(k, r, 0, 1) == pair_dw(k, r, 1, 0)


def test_only_the_cubic_spline_adapts():
    with pytest.raises(InputError, match="adapts the cubic B-spline"):
        Kernel("wendland_c2", 1.0, 2, adaptive=True)
