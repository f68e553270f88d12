"""The linear stability of a uniform shear flow of 004_'s grains (mpisph/shear_stability.py): the
eigenproblem against the closed-form waves of a Newtonian fluid, the long waves against Barker et al.'s
incompressible criterion on both sides of the sand's window, and the short waves against the
closed-form bound of the compressible equations (mpisph/well_posedness.py)."""

import math

import numpy as np
import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.physics.mu_i_law import friction
from mpisph.shear_stability import LinearisedShear, directions, growth_curve, handover_wavelength, shear_state
from mpisph.well_posedness import bulk_part, compressible_bulk_friction_bound, ill_posedness, rate_exponents

STRESSES = [("cleary", "full"), ("corrected_stress", "full"), ("corrected_stress", "deviatoric")]


def sand(dim):
    module = load_case_module("lube_collapse_3d" if dim == 3 else "lube_collapse_2d")
    return build_case(module, resolve_params(module, {})).material.params


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("c_b", [0.0, 0.5, 1.0])
def test_a_newtonian_fluid_has_its_closed_form_waves(dim, c_b):
    """With J = 2 eta S and R = -c^2 I (eta constant, p = c^2 (rho - rho_0)) the eigenvalues are the
    D - 1 shear waves -eta k^2 / rho_0 and the sound waves rho_0 l^2 + zeta k^2 l + rho_0 c^2 k^2 = 0,
    zeta = 2 eta (1 - 1 / D + c_b): none grows."""
    rho, eta, c2 = 1500.0, 20.0, 70.0
    lin = object.__new__(LinearisedShear)
    lin.dim, lin.rho = dim, rho
    identity = np.eye(dim)
    lin.J = np.zeros((dim, dim, dim, dim))
    for a in range(dim):
        for b in range(dim):
            e = 0.5 * (np.outer(identity[a], identity[b]) + np.outer(identity[b], identity[a]))
            lin.J[:, :, a, b] = 2.0 * eta * (e - np.trace(e) / dim * identity + c_b * np.trace(e) * identity)
    lin.R = -c2 * identity
    zeta = 2.0 * eta * (1.0 - 1.0 / dim + c_b)
    for k in (1.0, 1e3, 1e6):
        growth = lin.growth(k, directions(dim, 101))
        sound = np.roots([rho, zeta * k * k, rho * c2 * k * k]).real.max()
        assert growth == pytest.approx(np.full_like(growth, max(-eta * k * k / rho, sound)), rel=1e-9)


@pytest.mark.parametrize("I", [0.01, 0.3, 0.6, 1.0, 1.5, 2.5])
def test_long_waves_grow_where_the_incompressible_law_is_ill_posed(I):
    """At k = 1 1/m the grains are as good as incompressible: the growth rate has the sign of Barker et
    al.'s C(I), below the sand's window (0.432 < I < 1.82), inside it and above it, and rises as k^2."""
    m = sand(2)
    lin = LinearisedShear(I, 500.0, 2, m, bulk_part("cleary", "full", 2))
    dirs = directions(2)
    slow, fast = lin.growth(1.0, dirs).max(), lin.growth(10.0, dirs).max()
    assert math.copysign(1.0, slow) == math.copysign(1.0, float(ill_posedness(I, m)))
    assert fast == pytest.approx(100.0 * slow, rel=1e-3)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("form,stress", STRESSES)
@pytest.mark.parametrize("I", [0.003, 0.03, 0.1])
def test_short_waves_follow_the_bound_of_the_compressible_equations(dim, form, stress, I):
    """At k = 1e6 1/m a stress with the least bulk friction (c_b mu) levels off (the rate at 1e6 within
    1 % of that at 1e5), one without it grows as k^2, at the closed-form rate of the stretching
    axis's longitudinal wave, -(p / (rho gamma_dot)) (2 mu_b - n + mu (n + nu_b + (D - 2) / 3)), when
    that is the fastest."""
    m, p = sand(dim), 500.0
    c_b = bulk_part(form, stress, dim)
    lin = LinearisedShear(I, p, dim, m, c_b)
    dirs = directions(dim, 721 if dim == 2 else 2000)
    rate_5, rate_6 = lin.growth(1e5, dirs).max(), lin.growth(1e6, dirs).max()
    rho, g, x = shear_state(I, p, dim, m)
    mu = friction(I, m)
    n, nu_b = rate_exponents(I, x, m, dim)
    bound = compressible_bulk_friction_bound(mu, n, nu_b, dim)
    if c_b * mu >= bound:
        assert rate_6 == pytest.approx(rate_5, rel=0.01)
    else:
        stretching = np.full((1, dim), 0.0)
        stretching[0, :2] = 1.0 / math.sqrt(2.0)
        closed = -(p / (rho * g)) * (2.0 * c_b * mu - n + mu * (n + nu_b + (dim - 2.0) / 3.0))
        assert lin.growth(1e6, stretching)[0] / 1e12 == pytest.approx(closed, rel=1e-3)
        assert rate_6 / 1e12 >= closed * (1.0 - 0.01)  # the grid of directions passes the axis within 1-2 degrees


def test_the_handover_wavelength_of_the_sand():
    """Eq. 27's pair term on the planar sand at 500 Pa, I = 0.01: the growth levels off at about 409
    1/s, half of it reached at a wavelength of about 11 mm; the deviatoric stress has no plateau."""
    m = sand(2)
    ks = np.logspace(0, 6, 61)
    dirs = directions(2)
    pair = growth_curve(LinearisedShear(0.01, 500.0, 2, m, bulk_part("cleary", "full", 2)), ks, dirs)
    assert pair[-1] == pytest.approx(409.0, rel=0.01)
    assert handover_wavelength(ks, pair) == pytest.approx(0.0108, rel=0.03)
    deviatoric = growth_curve(LinearisedShear(0.01, 500.0, 2, m, 0.0), ks, dirs)
    assert handover_wavelength(ks, deviatoric) is None
