"""The compressible mu(I) equations' well-posedness (mpisph/well_posedness.py, after Heyman et al.
2017): the closed-form least bulk friction against the eigenvalues of the linearised stress over
every direction of wave and velocity, Heyman et al.'s published bounds, the rate exponents of 004_'s
grains against finite differences of the solver's own grain density, and the solver's bulk
frictions against the continuum limits of its viscous pair terms."""

import math

import numpy as np
import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.particles import MOVING
from mpisph.physics.mu_i import pair_term_factors
from mpisph.physics.mu_i_law import friction, grain_density_ratio, inertial_number
from mpisph.shear_stability import shear_state
from mpisph.well_posedness import compressible_bulk_friction_bound, compressible_ill_posed_share, \
    rate_exponents, solver_bulk_friction


def least_eigenvalue(dim, mu, mu_b, n, nu_b, directions):
    """The least real part of the eigenvalues of M(k), M v = (linearised stress of the velocity
    gradient v (x) k) k, over the unit wave vectors ``directions``, about the simple shear D_0 with
    D_0[0, 1] = D_0[1, 0] = 1/2 (|D_0| = 1/2), per unit p: the stress -p I + mu p dev(D) / |D| +
    mu_b p tr(D) / |D| I with p and mu rising as |D|^n and |D|^nu_b."""
    D0 = np.zeros((dim, dim))
    D0[0, 1] = D0[1, 0] = 0.5
    s = 0.5
    least = math.inf
    for k in directions:
        M = np.empty((dim, dim))
        for j in range(dim):
            dD = 0.5 * (np.outer(np.eye(dim)[j], k) + np.outer(k, np.eye(dim)[j]))
            r = (D0 * dD).sum() / (2.0 * s * s)  # d|D| / |D|
            dev = dD - np.trace(dD) / dim * np.eye(dim)
            stress = -n * r * np.eye(dim) + mu * (dev + (nu_b + n - 1.0) * r * D0) / s \
                + mu_b * np.trace(dD) / s * np.eye(dim)
            M[:, j] = stress @ k
        least = min(least, np.linalg.eigvals(M).real.min())
    return least


def directions(dim):
    if dim == 2:
        return [np.array([math.cos(t), math.sin(t)]) for t in np.linspace(0.0, math.pi, 181)]
    return [np.array([math.sin(a) * math.cos(b), math.sin(a) * math.sin(b), math.cos(a)])
            for a in np.linspace(0.0, math.pi, 31) for b in np.linspace(0.0, math.pi, 31)]


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("mu,n,nu_b", [(0.59, 2.0, 0.0), (0.84, 2.0, 0.0), (0.59, 0.3, 0.05), (0.7, 1.0, 0.2),
                                       (1.25, 0.05, 0.01), (0.5, 0.0, 0.0)])
def test_no_direction_needs_more_bulk_friction_than_the_stretching_axis(dim, mu, n, nu_b):
    """At the closed-form bound every eigenvalue over all directions is non-negative, and 0.01 below
    it one is negative: the longitudinal wave along the stretching axis decides."""
    bound = compressible_bulk_friction_bound(mu, n, nu_b, dim)
    ks = directions(dim)
    assert least_eigenvalue(dim, mu, bound, n, nu_b, ks) >= -1e-12
    assert least_eigenvalue(dim, mu, bound - 0.01, n, nu_b, ks) < -1e-4


@pytest.mark.parametrize("mu", [0.5, 0.59, 0.84, 1.0])
def test_stiff_grains_give_heyman_et_al_s_bounds(mu):
    """Pressure from phi(I) (n = 2, nu_b = 0): 1 - 7 mu / 6 in 3D (Heyman et al. 2017's abstract),
    and 2 - 2 mu, 3 - 7 mu / 2 with the bulk term on tr(D) / D (their arXiv v1's, 2D and 3D)."""
    assert compressible_bulk_friction_bound(mu, 2.0, 0.0, 3) == pytest.approx(1.0 - 7.0 * mu / 6.0, abs=1e-15)
    assert 2 * compressible_bulk_friction_bound(mu, 2.0, 0.0, 2) == pytest.approx(2.0 - 2.0 * mu, abs=1e-15)
    assert 3 * compressible_bulk_friction_bound(mu, 2.0, 0.0, 3) == pytest.approx(3.0 - 3.5 * mu, abs=1e-14)


def sand(dim, **changes):
    module = load_case_module("lube_collapse_3d" if dim == 3 else "lube_collapse_2d")
    return build_case(module, resolve_params(module, {k: str(v) for k, v in changes.items()}))


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("I,p", [(1e-3, 500.0), (0.01, 800.0), (0.1, 300.0), (0.5, 1500.0)])
def test_rate_exponents_match_the_grain_density_of_the_solver(dim, I, p):
    """n and nu_b from the closed form against d ln p, d ln mu over d ln gamma_dot at fixed bulk
    density, by central differences of mu_i_law.grain_density_ratio, the root the solver takes."""
    m = sand(dim).material.params
    rho, gamma_dot, x = shear_state(I, p, dim, m)
    assert grain_density_ratio(rho, gamma_dot, x, dim, m) == pytest.approx(x, rel=1e-12)

    def state(log_rate):
        y = grain_density_ratio(rho, gamma_dot * math.exp(log_rate), x, dim, m)
        return math.log((y - 1.0) / m.K_t), math.log(friction(inertial_number(rho, y * m.rho_s0, m), m))

    step = 1e-5
    (p_hi, mu_hi), (p_lo, mu_lo) = state(step), state(-step)
    n, nu_b = rate_exponents(I, x, m, dim)
    assert n == pytest.approx((p_hi - p_lo) / (2 * step), rel=1e-6)
    assert nu_b == pytest.approx((mu_hi - mu_lo) / (2 * step), rel=1e-6)


def test_rate_exponents_limits():
    """Stiff grains (x = 1) give Heyman et al.'s n = 2, nu_b = 0; at I = 0 both vanish."""
    m = sand(3).material.params
    assert rate_exponents(0.1, 1.0, m, 3) == (2.0, 0.0)
    assert rate_exponents(0.0, 1.01, m, 3) == (0.0, 0.0)


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("deviatoric", [False, True])
def test_the_pair_terms_bulk_friction_is_their_continuum_limits(dim, deviatoric):
    """pair_term_factors' force tends to eta (c1 lap v + c2 grad div v), c1 = factor (radial / (D + 2)
    + along) / 2, c2 = factor radial / (D + 2); as div(2 eta dev(D) + xi tr(D) I) that is c1 = 1 and
    xi / eta = c2 - 1 + 2 / D, and mu_b = xi mu / (2 eta)."""
    factor, radial, along = pair_term_factors(dim, deviatoric)
    c1, c2 = factor * (radial / (dim + 2) + along) / 2, factor * radial / (dim + 2)
    assert c1 == pytest.approx(1.0, rel=1e-15)
    xi_over_eta = c2 - 1.0 + 2.0 / dim
    stress = "deviatoric" if deviatoric else "full"
    assert solver_bulk_friction(0.6, "cleary", stress, dim) == pytest.approx(0.3 * xi_over_eta, abs=1e-15)


def test_the_share_counts_the_dissipation_of_grains_short_of_the_bound():
    """Three grains of the 3D sand at 800 Pa and I = 0.1, 0.3 and 0.001: the bound is positive at the
    first two (n = 0.9 and 1.5) and negative at the third (n = 0.02), so the deviatoric stress (mu_b =
    0) falls short at the first two (2 and 1 W of 4 W); Eq. 27's pair term (mu_b = 5 mu / 6) nowhere."""
    case = sand(3, viscous_stress="deviatoric")
    m = case.material.params
    frame = {"kind": np.array([MOVING] * 3), "inertial_number": np.array([0.1, 0.3, 0.001]),
             "rho_s": m.rho_s0 * (1.0 + m.K_t * np.array([800.0, 800.0, 800.0])),
             "eta": np.array([2.0, 1.0, 1.0]), "gamma_dot": np.ones(3), "mass": np.ones(3), "rho": np.ones(3)}
    n, nu_b = rate_exponents(frame["inertial_number"], frame["rho_s"] / m.rho_s0, m, 3)
    bound = compressible_bulk_friction_bound(friction(frame["inertial_number"], m), n, nu_b, 3)
    assert bound[0] > 0.0 and bound[1] > 0.0 and bound[2] < 0.0
    assert compressible_ill_posed_share(frame, case) == pytest.approx(0.75, rel=1e-15)
    assert compressible_ill_posed_share(frame, sand(3)) == 0.0
    assert math.isnan(compressible_ill_posed_share(dict(frame, gamma_dot=np.zeros(3)), case))
