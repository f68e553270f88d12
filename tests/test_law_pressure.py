"""The pressure of the mu(I) law with ``law_pressure = carried_mean`` (physics/mu_i.py,
kernel_mean.py): the law's shear stress is concave in the pressure, so a scattered pressure
carries less shear than its mean by the fraction the docstring derives; taken from a particle's
own carried pressure the law is the state's; the kernel mean keeps a smooth pressure and takes a
grain-to-grain scatter out; the frames' inertial number and friction are the law's."""

import numpy as np
import pytest

from lattice import lattice
from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.physics.kernel_mean import kernel_mean
from mpisph.physics.mu_i import granular_state, inertial_number_and_friction, law_viscosity
from mpisph.physics.mu_i_law import friction


def incline_material():
    module = load_case_module("inclined_plane")
    return build_case(module, resolve_params(module, {"H": "0.02", "dp": "0.002", "columns": "16"})).material


def test_the_law_of_a_grains_own_carried_pressure_is_the_states():
    """law_viscosity from s p, I formed with Eq. 6, gives the viscosity granular_state gives, I from
    Eq. 8's volume fraction: the two agree at the root of Eq. 44."""
    material = incline_material()
    m = material.params
    n, s = 4, 0.93
    rho = material.rho_s0 * np.array([0.57, 0.58, 0.585, 0.59])
    gamma_dot = np.array([5.0, 30.0, 60.0, 120.0])
    kind, B = np.zeros(n, np.int8), np.tile([1.0 / s, 1.0 / s, 0.0], (n, 1))
    state = {}
    for store in (False, True):
        rho_s, p, eta, law_p = np.full(n, material.rho_s0), np.zeros(n), np.zeros(n), np.zeros(n if store else 0)
        granular_state(n, kind, rho, gamma_dot, B, True, rho_s, p, eta, 2, m, law_p)
        if store:
            assert law_p == pytest.approx(s * p, rel=1e-14)
            law_viscosity(n, kind, rho_s, gamma_dot, law_p, eta, 2, m)
        state[store] = eta
    assert np.all(state[False] > 0.0)
    assert state[True] == pytest.approx(state[False], rel=1e-9)


def test_the_frames_inertial_number_and_friction_are_the_laws():
    """With law_pressure = carried_mean the frames' I and mu(I) are the ones law_viscosity takes, I
    of Eq. 6 from the law's pressure, so that mu times that pressure is the shear stress eta
    gamma_dot the law gives (the regularisation let go, m_0 gamma_dot >> 1); without it, I is Eq.
    8's of the volume fraction, as granular_state takes it."""
    m = incline_material().params
    n = 3
    kind, rho_s = np.zeros(n, np.int8), np.full(n, m.rho_s0)
    rho = m.rho_s0 * np.array([0.57, 0.58, 0.59])
    gamma_dot, law_p = np.array([60.0, 120.0, 240.0]), np.array([80.0, 130.0, 200.0])
    eta = np.zeros(n)
    law_viscosity(n, kind, rho_s, gamma_dot, law_p, eta, 2, m)
    I, mu = np.zeros(n), np.zeros(n)
    inertial_number_and_friction(n, kind, rho, rho_s, gamma_dot, law_p, 2, m, I, mu)
    assert I == pytest.approx(gamma_dot * m.d0 / np.sqrt(law_p / m.rho_s0), rel=1e-12)
    assert mu * law_p == pytest.approx(eta * gamma_dot, rel=1e-6)
    inertial_number_and_friction(n, kind, rho, rho_s, gamma_dot, np.zeros(0), 2, m, I, mu)
    assert I == pytest.approx((m.phi_max - rho / rho_s) / (m.phi_max - m.phi_min), rel=1e-12)


@pytest.mark.parametrize("sigma", [0.1, 0.2])
def test_a_scattered_pressure_carries_less_shear_than_its_mean(sigma):
    """Two grains at the same strain rate and pressures P (1 -+ sigma): their mean shear stress
    eta gamma_dot (the regularisation let go, m_0 gamma_dot >> 1) falls short of that of the mean
    pressure by sigma^2 I_0 (3 I + I_0) / (8 (I + I_0)^2) of its mu_2 - mu_s part, to O(sigma^4)."""
    material = incline_material()
    m = material.params
    P, gamma_dot = 130.0, 60.0
    I = gamma_dot * m.d0 / np.sqrt(P / m.rho_s0)
    kind, rho_s = np.zeros(3, np.int8), np.full(3, m.rho_s0)
    pressures, eta = P * np.array([1.0 - sigma, 1.0 + sigma, 1.0]), np.zeros(3)
    law_viscosity(3, kind, rho_s, np.full(3, gamma_dot), pressures, eta, 2, m)
    tau = eta * gamma_dot
    assert tau[2] == pytest.approx(friction(I, m) * P, rel=1e-6)
    deficit = (tau[2] - tau[:2].mean()) / (tau[2] - m.mu_s * P)
    assert deficit == pytest.approx(sigma**2 * m.I_0 * (3 * I + m.I_0) / (8 * (I + m.I_0) ** 2), rel=0.5 * sigma**2)


@pytest.mark.parametrize("dim", [2, 3])
def test_the_kernel_mean_keeps_a_linear_pressure_and_takes_out_a_checkerboard(dim):
    x, kind, start, nbr, k, inner = lattice(dim, 1.3, n=12)
    n, rho = len(x), 1000.0
    mass, rho_all = np.full(n, rho * 0.01**dim), np.full(n, rho)
    linear = (100.0 + 2000.0 * x[:, -1]).reshape(-1, 1)
    out = np.zeros((n, 1))
    kernel_mean(n, start, nbr, x, rho_all, mass, kind, linear, k.params, out)
    assert out[inner, 0] == pytest.approx(linear[inner, 0], rel=1e-12)
    checkerboard = 100.0 * (1.0 + 0.5 * (-1.0) ** np.round(x / 0.01 - 0.5).sum(axis=1)).reshape(-1, 1)
    kernel_mean(n, start, nbr, x, rho_all, mass, kind, checkerboard, k.params, out)
    scatter = np.abs(out[inner, 0] - 100.0).max() / 50.0
    assert scatter < 0.2
