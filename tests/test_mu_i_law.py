"""The mu(I) law of 004_ and its pieces: friction, grain density, regularised viscosity,
material checks, the uniform-flow reference, and the viscous pair term on lattices."""

import math

import numpy as np
import pytest

from mpisph import references
from mpisph.errors import InputError
from mpisph.kernels import Kernel
from mpisph.materials import MuIGranular
from mpisph.physics.mu_i import momentum, pair_term_factors
from mpisph.physics.mu_i_stress import bulk_factor, granular_stress
from mpisph.physics.viscous_stress import strain_rate, stress_divergence, viscous_force_tensor
from mpisph.physics.mu_i_law import (MEAN_ARITHMETIC, MEAN_HARMONIC, MEAN_SECANT, friction, grain_density_ratio,
                                     pair_viscosity, regularised_shear_rates, regularised_viscosity,
                                     residual_viscosity)
from mpisph.correction import correction_matrix
from mpisph.tensors import SYM3, size

from lattice import lattice


def beads(**changes):
    """Glass beads of 004_ Tables 1 and 2."""
    g = references.MU_I_MATERIALS["glass_beads"]
    t = references.INCLINED_PLANE_TABLE_2
    kw = dict(rho_s0=t["rho_s0"], d0=g["d"], mu_s=math.tan(math.radians(g["mu_s_deg"])),
              mu_2=math.tan(math.radians(g["mu_2_deg"])), I_0=g["I_0"], K_t=t["K_t"], tau_0=t["tau_0"],
              m_0=t["m_0"])
    kw.update(changes)
    return MuIGranular(**kw)


def test_friction_rises_from_mu_s_to_mu_2_as_eq_7():
    m = beads().params
    assert friction(0.0, m) == m.mu_s
    assert friction(m.I_0, m) == pytest.approx(0.5 * (m.mu_s + m.mu_2))  # Eq. 13 as printed would give the same
    assert friction(1e9, m) == pytest.approx(m.mu_2, rel=1e-8)
    assert friction(0.1, m) < friction(0.2, m)  # Eq. 13 as printed (1 + I/I_0) would decrease


def test_shift_of_eq_18_raises_the_static_friction():
    m = beads(scale_length=0.01).params
    assert m.I_s == pytest.approx(2.61 * 0.5e-3 / 0.01)
    assert friction(0.0, m) == pytest.approx(m.mu_s + (m.mu_2 - m.mu_s) * m.I_s / (m.I_s + m.I_0))


@pytest.mark.parametrize("rho_over_ref", [0.97, 1.0, 1.003])
def test_grain_density_at_rest_is_the_packing_or_the_unconfined_grain(rho_over_ref):
    mat = beads()
    rho = rho_over_ref * mat.rho0
    x = grain_density_ratio(rho, 0.0, 1.0, 2, mat.params)
    assert x == max(1.0, rho / mat.rho0)


@pytest.mark.parametrize("rho_over_ref", [0.98, 1.0, 1.002])
@pytest.mark.parametrize("gamma_dot", [0.5, 30.0, 400.0])
def test_grain_density_is_the_physical_root_of_the_cubic_of_eq_44(rho_over_ref, gamma_dot):
    mat = beads()
    m = mat.params
    rho = rho_over_ref * mat.rho0
    x = grain_density_ratio(rho, gamma_dot, 1.0, 2, m)
    r = rho / m.rho_s0
    a = gamma_dot**2 * m.rho_s0 * m.K_t * (m.phi_max - m.phi_min) ** 2 * m.d0**2 / m.phi_max**2
    cubic = [1.0, -(1.0 + 2.0 * r / m.phi_max + a), r * (r + 2.0 * m.phi_max) / m.phi_max**2, -(r / m.phi_max) ** 2]
    assert abs(np.polyval(cubic, x)) <= 1e-12 * x**3
    assert x > max(1.0, r / m.phi_max)
    roots = np.roots(cubic)
    nearest = int(np.argmin(np.abs(roots - x)))
    assert abs(roots[nearest] - x) <= 1e-6 * x  # np.roots is coarse near a double root
    others = [z.real for k, z in enumerate(roots) if k != nearest and abs(z.imag) < 1e-9]
    assert all(z < r / m.phi_max for z in others)  # phi > phi_max: the roots the paper discards


@pytest.mark.parametrize("dim", [2, 3])
def test_grain_density_closes_the_law(dim):
    """phi = rho/rho_s from Eq. 8 and I = gamma_dot d sqrt(rho_s/p) (Eq. 6) agree at the root,
    with d = d0 (rho_s0/rho_s)^(1/D) (Eq. 43 in 2D)."""
    mat = beads()
    m = mat.params
    gamma_dot, rho = 80.0, 1.001 * mat.rho0
    x = grain_density_ratio(rho, gamma_dot, 1.0, dim, m)
    rho_s, p = x * m.rho_s0, (x - 1.0) / m.K_t
    I_phi = (m.phi_max - rho / rho_s) / (m.phi_max - m.phi_min)
    I_def = gamma_dot * m.d0 * x ** (-1.0 / dim) * math.sqrt(rho_s / p)
    assert I_phi == pytest.approx(I_def, rel=1e-9)
    assert grain_density_ratio(rho, gamma_dot, 1.3 * x, dim, m) == pytest.approx(x, rel=1e-14)  # any guess


def literal_m_p(tau_y, eta_0, gamma_dot, m_0, tau_0):
    """m_p of 004_ Eq. 55 as printed."""
    e = eta_0 * gamma_dot
    return m_0 + math.log(1.0 + e * (tau_y - tau_0) / (tau_0 * (tau_y + e))) / gamma_dot


def literal_viscosity(mat, p, gamma_dot):
    """Eqs. 12, 46-47 and 55 as printed, with mu_2/mu_s - 1 in Eq. 47 (mu_i_law.py)."""
    tau_y = mat.mu_s * p
    yield_rate = mat.I_0 / mat.d0 * math.sqrt(tau_y / (mat.mu_s * mat.rho_s0))
    eta_0 = (mat.mu_2 / mat.mu_s - 1.0) * tau_y / (gamma_dot + yield_rate)
    m_p = literal_m_p(tau_y, eta_0, gamma_dot, mat.m_0, mat.tau_0)
    return eta_0 + tau_y * (1.0 - math.exp(-m_p * gamma_dot)) / gamma_dot, eta_0 + tau_y / gamma_dot


@pytest.mark.parametrize("p", [5.0, 190.0 / math.tan(math.radians(20.9)), 2000.0])
@pytest.mark.parametrize("gamma_dot", [0.3, 4.0, 150.0])
def test_closed_form_regularisation_is_eqs_46_and_55(p, gamma_dot):
    mat = beads()
    m = mat.params
    I = gamma_dot * m.d0 / math.sqrt(p / m.rho_s0)
    eta_hat, eta = literal_viscosity(mat, p, gamma_dot)
    assert regularised_viscosity(p, gamma_dot, I, m.rho_s0, m.d0, m) == pytest.approx(eta_hat, rel=1e-9)
    assert eta == pytest.approx(friction(I, m) * p / gamma_dot, rel=1e-12)  # the Bingham split of Eq. 11
    eta_0 = residual_viscosity(p, I, m.rho_s0, m.d0, m)
    assert 1.0 - eta_hat / eta == pytest.approx(math.exp(-m.m_0 * gamma_dot) * m.tau_0 / (m.tau_0 + eta_0 * gamma_dot),
                                                rel=1e-6, abs=1e-12)


def test_regularised_viscosity_at_rest_is_eq_53_and_table_2():
    mat = beads()
    m = mat.params
    for tau_y in (1.0, 50.0, 190.0, 900.0):
        p = tau_y / m.mu_s
        assert regularised_viscosity(p, 0.0, 0.0, m.rho_s0, m.d0, m) == pytest.approx(mat.eta_max(tau_y), rel=1e-12)
        assert regularised_viscosity(p, 1e-7, 0.0, m.rho_s0, m.d0, m) == pytest.approx(mat.eta_max(tau_y), rel=1e-6)
    # 004_ Table 2: eta_max = 190.3 Pa s at tau_0 = 190 Pa, m_0 = 1 s (Eq. 47 with mu_2/mu_s)
    assert mat.eta_max(mat.tau_0) == pytest.approx(references.INCLINED_PLANE_TABLE_2["eta_max"], abs=0.05)


def test_regularised_shear_rate_carries_the_stress():
    """The rate at which the regularised law carries a stress: far below the yield stress mu_s p it
    creeps at tau / eta_max (at rates where m_0 gamma_dot << 1); well above it, where
    exp(-m_0 gamma_dot) is negligible, it flows at the friction law's rate, mu(I) p = tau."""
    m = beads(m_0=0.2).params
    p = np.array([50.0, 50.0, 50.0, 2000.0])
    tau = np.array([0.0, 0.02, 1.1, 1.1]) * m.mu_s * p
    rates = regularised_shear_rates(tau, p, m)
    assert rates[0] == 0.0
    for k in (1, 2, 3):
        I = rates[k] * m.d0 / math.sqrt(p[k] / m.rho_s0)
        carried = regularised_viscosity(p[k], rates[k], I, m.rho_s0, m.d0, m) * rates[k]
        assert carried == pytest.approx(tau[k], rel=1e-9)
    assert rates[1] == pytest.approx(tau[1] / regularised_viscosity(p[1], 0.0, 0.0, m.rho_s0, m.d0, m), rel=0.05)
    I = rates[3] * m.d0 / math.sqrt(p[3] / m.rho_s0)
    assert m.m_0 * rates[3] > 20 and friction(I, m) * p[3] == pytest.approx(tau[3], rel=1e-6)


def test_regularised_viscosity_stays_positive_where_eq_55_gives_negative_m_p():
    mat = beads()
    m = mat.params
    p, gamma_dot = 1e-4, 0.01  # tau_y = 4e-5 Pa, below eta_0/m_0 = 1.3e-4 Pa
    I = gamma_dot * m.d0 / math.sqrt(p / m.rho_s0)
    eta_0 = residual_viscosity(p, I, m.rho_s0, m.d0, m)
    tau_y = m.mu_s * p
    assert literal_m_p(tau_y, eta_0, gamma_dot, m.m_0, m.tau_0) < 0.0
    assert 0.0 < regularised_viscosity(p, gamma_dot, I, m.rho_s0, m.d0, m) <= eta_0 + tau_y / gamma_dot
    assert regularised_viscosity(0.0, gamma_dot, I, m.rho_s0, m.d0, m) == 0.0


@pytest.mark.parametrize("change, words", [
    ({"mu_2": 0.3}, "mu_2"), ({"phi_min": 0.6}, "phi_min"), ({"phi_max": 0.4}, "phi_min"),
    ({"d0": 0.0}, "d0"), ({"K_t": -1e-5}, "K_t"), ({"tau_0": 0.0}, "tau_0")])
def test_bad_parameters_are_one_line_errors(change, words):
    with pytest.raises(InputError) as e:
        beads(**change)
    assert words in str(e.value) and "\n" not in str(e.value)


def test_uniform_flow_down_the_incline():
    """I_u = 0.1330 for the glass beads at 25 deg (004_ Sec. 5.1); the profile integrates
    gamma_dot = I_u sqrt(p/rho_s)/d with hydrostatic p, so u'(z) and u(H) follow."""
    mat, g, H, theta = beads(), 9.81, 0.1, 25.0
    I_u, phi_u = mat.uniform_flow(theta)
    assert I_u == pytest.approx(0.1330, abs=5e-5)
    assert phi_u == pytest.approx(0.6 - 0.1 * I_u)
    assert references.inclined_plane_surface_velocity(mat, theta, H, g) == pytest.approx(12.81, abs=0.01)
    z = np.linspace(0.0, 0.99 * H, 50)
    dz = 1e-6
    du = (references.inclined_plane_velocity(mat, theta, H, g, z + dz)
          - references.inclined_plane_velocity(mat, theta, H, g, z - dz)) / (2 * dz)
    p = references.inclined_plane_pressure(mat, theta, H, g, z)
    np.testing.assert_allclose(du, I_u * np.sqrt(p / mat.rho_s0) / mat.d0, rtol=1e-6)
    with pytest.raises(ValueError):
        mat.uniform_flow(35.0)  # tan 35 deg > mu_2
    with pytest.raises(ValueError):
        mat.uniform_flow(20.0)  # below mu_s: the layer stays at rest


@pytest.mark.parametrize("H", [0.02, 0.1])
def test_layer_approaches_uniform_flow_with_the_relaxation_time(H):
    """The layer's mean speed U under rho H dU/dt = rho g H (sin - mu(I_u U / U_u) cos), integrated
    with the full law from U = 0.99 U_u, closes the gap by e in the time
    references.inclined_plane_relaxation_time gives: 1.35 s at H = 0.02 m, 15 s at H = 0.1 m."""
    mat, g, theta = beads(), 9.81, 25.0
    I_u, _ = mat.uniform_flow(theta)
    U_u = 0.6 * references.inclined_plane_surface_velocity(mat, theta, H, g)
    T = references.inclined_plane_relaxation_time(mat, theta, H, g)
    s, c = math.sin(math.radians(theta)), math.cos(math.radians(theta))
    U, t, dt = 0.99 * U_u, 0.0, T / 2000
    while U_u - U > 0.01 * U_u / math.e:
        k1 = g * (s - friction(I_u * U / U_u, mat.params) * c)
        k2 = g * (s - friction(I_u * (U + 0.5 * dt * k1) / U_u, mat.params) * c)
        U, t = U + dt * k2, t + dt
    assert t == pytest.approx(T, rel=0.005)  # the law's curvature over the 1 % gap
    assert T == pytest.approx({0.02: 1.35, 0.1: 15.1}[H], rel=0.01)


def viscous_acceleration(dim, h_over_dp, corrected):
    """dv_x/dt of u = (y^2, 0[, 0]) with eta = 2 Pa s, rho = 1000 (exact: 2 eta/rho) on a lattice."""
    x, kind, start, nbr, k, inner = lattice(dim, h_over_dp)
    n = len(x)
    rho, eta = np.full(n, 1000.0), np.full(n, 2.0)
    mass = rho * 0.01**dim
    v = np.zeros((n, dim))
    v[:, 0] = x[:, 1] ** 2
    zeros, acc = np.zeros(n), np.zeros((n, dim))
    if corrected:
        B = np.zeros((n, size(dim)))
        correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
        strain, gamma_dot = np.zeros((n, size(dim))), np.zeros(n)
        strain_rate(n, start, nbr, x, v, rho, mass, kind, np.zeros((n, dim)), zeros, 1.5, B, k.params, strain,
                    gamma_dot)
        T = np.zeros((n, dim, dim))
        viscous_force_tensor(n, kind, strain, eta, B, False, T)
        stress_divergence(n, start, nbr, x, rho, T, mass, kind, np.zeros((n, dim)), k.params, acc)
    else:
        momentum(n, start, nbr, x, v, rho, zeros, eta, zeros, mass, kind, np.zeros((n, dim)), zeros, 1.5, 0.0, 1.0, True,
                 *pair_term_factors(dim, False), MEAN_HARMONIC, k.params, acc)
    return acc[inner, 0] / (2 * 2.0 / 1000.0)


def lattice_share(dim, h_over_dp, dp=0.01):
    """The share of eta d2u/dy2 that Eq. 27's pair term gives for u = (y^2, 0[, 0]) on a whole lattice:
    with s = x_j - x_i, v_ij . r_ij = (2 y_i s_y + s_y^2) s_x and grad_i W = -W'(r) s / r, the terms odd
    in s cancel and -(D + 2) sum_j dp^D s_x^2 s_y^2 W'(r) / r^3 is left (1 as the kernel is resolved)."""
    kernel = Kernel("wendland_c2", h_over_dp * dp, dim)
    reach = int(np.ceil(kernel.support / dp))
    m = np.arange(-reach, reach + 1)
    s = dp * np.stack(np.meshgrid(*([m] * dim), indexing="ij"), axis=-1).reshape(-1, dim)
    r = np.linalg.norm(s, axis=1)
    s, r = s[r > 0], r[r > 0]
    return -(dim + 2) * dp**dim * np.sum(s[:, 0] ** 2 * s[:, 1] ** 2 * kernel.derivative(r) / r**3)


@pytest.mark.parametrize("dim", [2, 3])
def test_pair_viscosity_of_eq_27_takes_2_d_plus_2(dim):
    """The factor 2 (D + 2) (8 in 2D as Eq. 27 prints, 10 in 3D) gives div(eta grad v) as the
    kernel is resolved; at h = 1.3 dp the square lattice gets only its lattice sum's share, 81 % (2D)
    and 87 % (3D)."""
    np.testing.assert_allclose(viscous_acceleration(dim, 3.0, False), 1.0, atol=0.01)
    low = viscous_acceleration(dim, 1.3, False)
    np.testing.assert_allclose(low, lattice_share(dim, 1.3), rtol=1e-9)
    assert lattice_share(dim, 1.3) == pytest.approx({2: 0.809, 3: 0.869}[dim], abs=0.002)
    assert lattice_share(dim, 3.0) == pytest.approx(1.0, abs=0.01)


@pytest.mark.parametrize("dim", [2, 3])
def test_artificial_viscosity_of_eq_38_is_the_pair_viscosity_of_eq_27(dim):
    """Eq. 38's term on every pair gives the accelerations of Eq. 27's viscous pair term with
    eta = rho alpha h c0 / (2 (D + 2)) (references.pair_viscosity_of_alpha), on a sheared lattice."""
    x, kind, start, nbr, k, inner = lattice(dim, 1.3)
    n = len(x)
    rho = np.full(n, 1000.0)
    mass, zeros = rho * 0.01**dim, np.zeros(n)
    v = np.zeros((n, dim))
    v[:, 0] = x[:, 1] ** 2 + 0.3 * x[:, 0] * x[:, 1]
    alpha, c0 = 0.05, 20.0
    eta = np.full(n, 1000.0 * references.pair_viscosity_of_alpha(alpha, k.h, c0, dim))
    by_alpha, by_eta = np.zeros((n, dim)), np.zeros((n, dim))
    momentum(n, start, nbr, x, v, rho, zeros, zeros, zeros, mass, kind, np.zeros((n, dim)), zeros, 1.5, alpha, c0,
             False, 0.0, 1.0, 0.0, MEAN_HARMONIC, k.params, by_alpha)
    momentum(n, start, nbr, x, v, rho, zeros, eta, zeros, mass, kind, np.zeros((n, dim)), zeros, 1.5, 0.0, c0,
             False, *pair_term_factors(dim, False), MEAN_HARMONIC, k.params, by_eta)
    assert np.abs(by_alpha[inner, 0]).min() > 1e-3  # about 0.8 of 2 nu, the lattice's share
    np.testing.assert_allclose(by_alpha, by_eta, rtol=1e-12, atol=1e-12 * np.abs(by_eta).max())


def viscous_divergences(dim, h_over_dp, v_of_x):
    """dv/dt of the velocity field v_of_x(x) at eta = 2 Pa s, rho = 1000 on a lattice's inner
    particles: the deviatoric corrected stress's divergence (exact for a quadratic field), the
    deviatoric pair term and Eq. 27's."""
    x, kind, start, nbr, k, inner = lattice(dim, h_over_dp)
    n = len(x)
    rho, eta, zeros, normal = np.full(n, 1000.0), np.full(n, 2.0), np.zeros(n), np.zeros((n, dim))
    mass, v = rho * 0.01**dim, v_of_x(x)
    B = np.zeros((n, size(dim)))
    correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
    strain, T = np.zeros((n, size(dim))), np.zeros((n, dim, dim))
    strain_rate(n, start, nbr, x, v, rho, mass, kind, normal, zeros, 1.5, B, k.params, strain, np.zeros(n))
    viscous_force_tensor(n, kind, strain, eta, B, True, T)
    exact = np.zeros((n, dim))
    stress_divergence(n, start, nbr, x, rho, T, mass, kind, normal, k.params, exact)
    pairs = {}
    for deviatoric in (True, False):
        pairs[deviatoric] = np.zeros((n, dim))
        momentum(n, start, nbr, x, v, rho, zeros, eta, zeros, mass, kind, normal, zeros, 1.5, 0.0, 1.0, False,
                 *pair_term_factors(dim, deviatoric), MEAN_HARMONIC, k.params, pairs[deviatoric])
    return exact[inner], pairs[True][inner], pairs[False][inner]


@pytest.mark.parametrize("dim", [2, 3])
def test_deviatoric_pair_term_is_the_divergence_of_2_eta_dev_eps(dim):
    """On v = (x y, 0[, 0]), lap v = 0 and grad div v = (0, 1[, 0]): the deviatoric stress gives
    eta (1 - 2 / D) grad div v, none in 2D, and so does the deviatoric pair term: none to round-off
    in 2D (the lattice's kernel sums are even), in 3D the square lattice's share at h = 1.3 dp of it
    (0.869, as Eq. 27's above); Eq. 27's gives 2 eta grad div v, its bulk viscosity
    (1 + 2 / D) eta. On a general quadratic field, resolved (h = 3 dp), the deviatoric pair term
    gives eta (lap v + (1 - 2 / D) grad div v) and Eq. 27's eta (lap v + 2 grad div v)
    (physics/mu_i.pair_term_factors)."""
    def shear_free(x):
        v = np.zeros_like(x)
        v[:, 0] = x[:, 0] * x[:, 1]
        return v

    exact, deviatoric, eq_27 = viscous_divergences(dim, 1.3, shear_free)
    target = 2.0 / 1000.0 * (1.0 - 2.0 / dim)  # eta / rho (1 - 2 / D)
    np.testing.assert_allclose(exact[:, 1], target, atol=1e-9 * 2.0 / 1000.0)
    if dim == 2:
        assert np.abs(deviatoric).max() < 1e-12 * 2.0 / 1000.0
    else:
        np.testing.assert_allclose(deviatoric[:, 0::2], 0.0, atol=1e-12 * target)
        np.testing.assert_allclose(deviatoric[:, 1] / target, lattice_share(dim, 1.3), rtol=1e-9)
    np.testing.assert_allclose(eq_27[:, 1], 2 * 2.0 / 1000.0 * lattice_share(dim, 1.3), rtol=1e-9)  # 2 eta / rho

    lap, grad_div = {2: ([2.6, 0.8], [1.0, 1.7]), 3: ([3.4, 0.8, -0.6], [1.7, 1.7, 0.0])}[dim]
    lap, grad_div = np.array(lap) * 2.0 / 1000.0, np.array(grad_div) * 2.0 / 1000.0  # times eta / rho
    _, deviatoric, eq_27 = viscous_divergences(dim, 3.0, quadratic_velocity)
    scale = np.abs(lap).max()
    np.testing.assert_allclose(deviatoric, np.broadcast_to(lap + (1.0 - 2.0 / dim) * grad_div, deviatoric.shape),
                               atol=0.01 * scale)
    np.testing.assert_allclose(eq_27, np.broadcast_to(lap + 2.0 * grad_div, eq_27.shape), atol=0.01 * scale)


@pytest.mark.parametrize("dim", [2, 3])
def test_deviatoric_pair_term_brakes_a_rigid_rotation(dim):
    """A lattice block turning as a rigid body (v = omega x r about the last axis) strains nowhere:
    Eq. 27's central pair forces vanish pair by pair; the deviatoric pair term's part along v_ij is
    not central and, where the kernel is cut by the block's faces, brakes the rotation with a
    torque, while the total force stays zero (its pairs are antisymmetric)."""
    x, kind, start, nbr, k, _ = lattice(dim, 1.3, n=12)
    n = len(x)
    rho, eta, zeros, normal = np.full(n, 1000.0), np.full(n, 2.0), np.zeros(n), np.zeros((n, dim))
    mass, r = rho * 0.01**dim, x - x.mean(axis=0)
    v = np.zeros((n, dim))
    v[:, 0], v[:, 1] = -r[:, 1], r[:, 0]  # omega = 1 rad/s
    for deviatoric in (False, True):
        acc = np.zeros((n, dim))
        momentum(n, start, nbr, x, v, rho, zeros, eta, zeros, mass, kind, normal, zeros, 1.5, 0.0, 1.0, False,
                 *pair_term_factors(dim, deviatoric), MEAN_HARMONIC, k.params, acc)
        force = mass[:, None] * acc
        torque = np.sum(r[:, 0] * force[:, 1] - r[:, 1] * force[:, 0])
        scale = 2.0 * (0.12**dim)  # eta omega over the block's volume [N m]
        np.testing.assert_allclose(force.sum(axis=0), 0.0, atol=1e-12 * scale / 0.12)
        if deviatoric:
            assert torque < -0.1 * scale
        else:
            np.testing.assert_allclose(acc, 0.0, atol=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_corrected_viscous_stress_is_exact_at_the_papers_resolution(dim):
    np.testing.assert_allclose(viscous_acceleration(dim, 1.3, True), 1.0, rtol=1e-9)


def test_pair_viscosity_at_the_free_surface_and_next_to_grains_at_rest():
    """eta = mu p / gamma_dot with a hydrostatic p: the harmonic mean of Eq. 37 vanishes with the
    surface grain's viscosity, the arithmetic and secant means do not (the arithmetic one is the
    midpoint value); next to a grain at rest (eta_max, a small strain rate) the arithmetic mean
    takes half of eta_max, the secant one stays near the flowing grain's."""
    mu, gamma_dot, rho_g = 0.6, 5.0, 1560.0 * 9.81
    eta = lambda depth: mu * rho_g * depth / gamma_dot  # noqa: E731
    for surface, below in ((0.0, 0.003), (0.003, 0.006), (0.01, 0.013)):
        pair = pair_viscosity(1.0, eta(surface), eta(below), gamma_dot, gamma_dot, MEAN_ARITHMETIC)
        assert pair == pytest.approx(eta(0.5 * (surface + below)), rel=1e-12)
        secant = pair_viscosity(1.0, eta(surface), eta(below), gamma_dot, gamma_dot, MEAN_SECANT)
        assert secant == pytest.approx(pair, rel=1e-12)  # one strain rate: the two agree
    assert pair_viscosity(1.0, eta(0.0), eta(0.003), gamma_dot, gamma_dot, MEAN_HARMONIC) == 0.0
    flowing, at_rest = (10.0, 50.0), (900.0, 0.01)  # (eta, gamma_dot)
    assert pair_viscosity(1.0, flowing[0], at_rest[0], flowing[1], at_rest[1], MEAN_ARITHMETIC) == 455.0
    secant = pair_viscosity(1.0, flowing[0], at_rest[0], flowing[1], at_rest[1], MEAN_SECANT)
    assert flowing[0] < secant < 1.2 * flowing[0]
    for mean in (MEAN_HARMONIC, MEAN_ARITHMETIC, MEAN_SECANT):
        assert pair_viscosity(3.0, 2.0, 2.0, 1.0, 4.0, mean) == pytest.approx(6.0, rel=1e-15)
    assert pair_viscosity(1.0, 2.0, 4.0, 0.0, 0.0, MEAN_SECANT) == 3.0  # neither strained: arithmetic


def frame_stress_and_force(dim, corrected, deviatoric, alpha):
    """(x, sigma, rho dv/dt) on the inner particles of a lattice under ``quadratic_velocity``: the
    frames' stress (physics/mu_i_stress.py, zero pressure) and the force density of the viscous term
    it stands for, eta = 2 Pa s uniform (or none, where ``alpha`` > 0: Eq. 38's term alone), the
    strain rate corrected as the scheme takes it. The corrected stress is exact at the papers'
    h = 1.3 dp; the pair terms tend to their limits as the kernel is resolved, here at h = 3 dp."""
    x, kind, start, nbr, k, inner = lattice(dim, 1.3 if corrected else 3.0)
    n = len(x)
    rho, zeros, normal = np.full(n, 1000.0), np.zeros(n), np.zeros((n, dim))
    eta = np.full(n, 0.0 if alpha > 0 else 2.0)
    mass, v, c0 = rho * 0.01**dim, quadratic_velocity(x), 20.0
    B = np.zeros((n, size(dim)) if corrected else (0, 1))
    if corrected:
        correction_matrix(n, start, nbr, x, mass, rho, kind, k.params, B)
    strain = np.zeros((n, size(dim)))
    strain_rate(n, start, nbr, x, v, rho, mass, kind, normal, zeros, 1.5, B, k.params, strain, np.zeros(n))
    acc = np.zeros((n, dim))
    if corrected:
        T = np.zeros((n, dim, dim))
        viscous_force_tensor(n, kind, strain, eta, B, deviatoric, T)
        stress_divergence(n, start, nbr, x, rho, T, mass, kind, normal, k.params, acc)
    else:
        momentum(n, start, nbr, x, v, rho, zeros, eta, zeros, mass, kind, normal, zeros, 1.5, alpha, c0, False,
                 *pair_term_factors(dim, deviatoric), MEAN_HARMONIC, k.params, acc)
    stress = np.zeros((n, 6))
    granular_stress(n, kind, zeros, rho, strain, eta, bulk_factor(dim, corrected, deviatoric),
                    references.pair_viscosity_of_alpha(alpha, k.h, c0, dim), stress)
    return x[inner], stress[inner], rho[inner, None] * acc[inner]


def quadratic_velocity(x):
    """A quadratic velocity field with shear, rotation and a varying divergence."""
    v = np.zeros_like(x)
    v[:, 0] = x[:, 1] ** 2 + 0.5 * x[:, 0] * x[:, 1] + 0.3 * x[:, 0] ** 2
    v[:, 1] = -0.2 * x[:, 0] ** 2 + 0.4 * x[:, 0] * x[:, 1] + 0.6 * x[:, 1] ** 2
    if x.shape[1] == 3:
        v[:, 2] = 0.7 * x[:, 0] * x[:, 2] - 0.3 * x[:, 1] ** 2
        v[:, 0] += 0.4 * x[:, 2] ** 2 + 0.2 * x[:, 1] * x[:, 2]
    return v


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("corrected, deviatoric, alpha", [(True, False, 0.0), (True, True, 0.0),
                                                           (False, False, 0.0), (False, True, 0.0),
                                                           (False, False, 0.05)])
def test_frames_stress_is_the_one_the_viscous_term_takes_the_divergence_of(dim, corrected, deviatoric, alpha):
    """The stress a mu_i frame holds (mu_i_stress.py) is, for each viscous form and stress and for
    Eq. 38's artificial viscosity, the stress whose divergence the momentum sum gives: on a quadratic
    velocity the stress is linear in x, and its divergence from a least-squares fit over the inner
    particles is rho dv/dt, to round-off for the corrected stress and to 1 % for the pair terms at
    h = 3 dp; in 2D sigma_zz is -p and there is no out-of-plane shear."""
    x, stress, force = frame_stress_and_force(dim, corrected, deviatoric, alpha)
    basis = np.column_stack([np.ones(len(x)), x])
    coefficients = np.linalg.lstsq(basis, stress, rcond=None)[0]
    assert np.abs(basis @ coefficients - stress).max() < 1e-6 * np.abs(stress).max()  # linear, as it must be
    slopes = coefficients[1:]  # d sigma_c / d x_a, (dim, 6)
    divergence = np.array([sum(slopes[b, SYM3[a, b]] for b in range(dim)) for a in range(dim)])
    scale = np.abs(force).max()
    assert scale > 0
    np.testing.assert_allclose(force, np.broadcast_to(divergence, force.shape), atol=(1e-9 if corrected else 0.01) * scale)
    if dim == 2:
        assert np.all(stress[:, [2, 4, 5]] == 0.0)  # zz = -p = 0 and no out-of-plane shear
