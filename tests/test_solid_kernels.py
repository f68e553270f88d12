"""Kernels of the solid scheme: correction matrix, velocity gradient, return mapping, constants."""

import math

import numpy as np
import pytest

from mpisph.correction import correction_matrix
from mpisph.kernels import Kernel
from mpisph.materials import DruckerPrager, ElasticSolid
from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL, WALL_SLIP
from mpisph.physics.drucker_prager import geostatic_stress, return_mapping
from mpisph.physics.solid import shear_force_tensor, stress_acceleration, velocity_gradient
from mpisph.tensors import packed, unpacked
from repo_script import load_script

DP = 0.01
H = 1.3 * DP
KERNEL = Kernel("wendland_c2", H, 2).params


def block(nx=12, ny=10):
    gx, gy = (np.arange(nx) + 0.5) * DP, (np.arange(ny) + 0.5) * DP
    x = np.stack([a.ravel() for a in np.meshgrid(gx, gy, indexing="ij")], axis=1)
    n = len(x)
    kind = np.zeros(n, np.int8)
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, np.zeros(2))
    return x, kind, np.full(n, 1000 * DP**2), np.full(n, 1000.0), start, nbr


def corrections(x, kind, mass, rho, start, nbr):
    """B of every particle, packed (xx, yy, xy) as the solver stores it."""
    B = np.zeros((len(x), 3))
    correction_matrix(len(x), start, nbr, x, mass, rho, kind, KERNEL, B)
    return B


def gradients(x, v, mass, rho, kind, B, start, nbr):
    """L of Eq. 23 of every particle, from the one-particle ``velocity_gradient``."""
    L = np.zeros((len(x), 3, 3))
    for i in range(len(x)):
        velocity_gradient(i, start, nbr, x, v, mass, rho, kind, np.zeros_like(x), np.zeros(0), 0.0, B,
                          KERNEL, L[i])
    return L


def test_correction_matrix_is_identity_inside_and_corrects_edges():
    x, kind, mass, rho, start, nbr = block()
    B = unpacked(corrections(x, kind, mass, rho, start, nbr), 2)
    inner = np.all((x > 3 * DP) & (x < np.array([9, 7]) * DP), axis=1)
    # isotropic: the inverse of the lattice sum -sum_j dp^2 r_ij (x) grad W_ij = a I over the whole
    # support, a = -(1/2) sum_j dp^2 r_ij W'(r_ij), which departs from the integral's 1 by 2.7 % at h = 1.3 dp
    np.testing.assert_allclose(B[inner], np.broadcast_to(B[inner][0], B[inner].shape), atol=1e-12)
    m = np.arange(-3, 4)
    offsets = DP * np.stack(np.meshgrid(m, m, indexing="ij"), axis=-1).reshape(-1, 2)
    r = np.linalg.norm(offsets, axis=1)
    r = r[(r > 0) & (r < 2 * H)]
    a = -0.5 * DP**2 * np.sum(r * Kernel("wendland_c2", H, 2).derivative(r))
    assert 1 / a == pytest.approx(1.0268, abs=1e-4)
    np.testing.assert_allclose(B[inner][0], np.eye(2) / a, rtol=1e-12, atol=1e-12)
    edge = (x[:, 1] < DP) & (x[:, 0] > 3 * DP) & (x[:, 0] < 9 * DP)
    assert np.all(B[edge, 1, 1] > 1.5)  # half a support: the normal gradient is doubled back


def test_velocity_gradient_of_a_linear_field_is_exact_up_to_the_corners():
    x, kind, mass, rho, start, nbr = block()
    A = np.array([[0.3, -1.2], [0.7, 0.1]])
    v = x @ A.T
    B = corrections(x, kind, mass, rho, start, nbr)
    L = gradients(x, v, mass, rho, kind, B, start, nbr)
    corner = np.minimum(x[:, 0], 0.12 - x[:, 0]) + np.minimum(x[:, 1], 0.10 - x[:, 1]) < 2.5 * DP
    np.testing.assert_allclose(L[~corner, :2, :2], np.broadcast_to(A, L[~corner, :2, :2].shape), atol=1e-9)
    assert np.all(np.isfinite(L)) and np.all(L[:, 2, :] == 0.0)


def test_shear_force_is_the_adjoint_of_the_corrected_velocity_gradient():
    """Power of the shear forces = minus the stress power on L of Eq. 23, on a disordered block
    with free edges (B far from I there): kinetic + strain energy is conserved in space."""
    rng = np.random.default_rng(3)
    x, kind, mass, rho, start, nbr = block()
    x = x + rng.uniform(-0.2, 0.2, x.shape) * DP
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), 2 * H, np.zeros(2) - DP)
    rho = rho * rng.uniform(0.95, 1.05, len(x))
    n = len(x)
    v = rng.normal(size=(n, 2))
    shear = rng.normal(size=(n, 3, 3)) * 1e3
    shear = shear + shear.transpose(0, 2, 1)
    shear -= np.trace(shear, axis1=1, axis2=2)[:, None, None] / 3 * np.eye(3)
    shear[:, 2, :2] = shear[:, :2, 2] = 0.0
    B = corrections(x, kind, mass, rho, start, nbr)
    L = gradients(x, v, mass, rho, kind, B, start, nbr)
    acc = np.zeros((n, 2))
    # c0 = 0: no Riemann dissipation; p = 0: the pure shear part
    T = np.zeros((n, 2, 2))
    shear_force_tensor(n, kind, packed(shear), np.zeros(n), B, T)
    stress_acceleration(n, start, nbr, x, v, rho, np.zeros(n), T, mass, kind, np.zeros_like(x),
                        0.0, -1.0, 1.0, KERNEL, acc)
    power = np.sum(mass[:, None] * v * acc)
    stress_power = np.sum(mass / rho * np.einsum("iab,iab->i", shear, L))
    assert abs(stress_power) > 1.0
    assert power == pytest.approx(-stress_power, rel=1e-10)


def test_uncorrected_shear_force_from_the_stress_is_eq_25():
    """Granular materials pass the packed stress itself and s = sigma + p I is formed pair by pair:
    the same accelerations as the tensor s_i summed as (s_i + s_j) e_ij W' (Eq. 25), wall
    partners included (they take the state of i)."""
    rng = np.random.default_rng(5)
    x, kind, mass, rho, start, nbr = block()
    x = x + rng.uniform(-0.2, 0.2, x.shape) * DP
    kind[x[:, 1] < DP] = 1  # a no-slip floor row
    n = len(x)
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, np.zeros(2) - DP)
    v, p = rng.normal(size=(n, 2)), rng.normal(size=n) * 1e3
    stress = rng.normal(size=(n, 3, 3)) * 1e3
    stress = stress + stress.transpose(0, 2, 1)
    normal = np.zeros_like(x)
    normal[:, 1] = 1.0
    args = (mass, kind, normal, 30.0, 40.0, 1.0, KERNEL)
    on_the_fly, from_tensor = np.zeros((n, 2)), np.zeros((n, 2))
    stress_acceleration(n, start, nbr, x, v, rho, p, packed(stress), *args, on_the_fly)
    s = stress[:, :2, :2] + p[:, None, None] * np.eye(2)
    stress_acceleration(n, start, nbr, x, v, rho, p, s, *args, from_tensor)
    moving = kind == 0
    assert np.abs(on_the_fly[moving]).max() > 1.0
    np.testing.assert_array_equal(on_the_fly[moving], from_tensor[moving])


def test_degenerate_neighbourhood_gets_a_finite_correction():
    x = np.array([[0.0, 0.0], [DP, 0.0]])  # a pair: A has rank one
    kind = np.zeros(2, np.int8)
    start, nbr = neighbour_lists(x, np.arange(2), kind, 2, 2 * H, np.zeros(2) - DP)
    B = corrections(x, kind, np.full(2, 0.1), np.full(2, 1000.0), start, nbr)
    assert np.all(np.isfinite(B)) and np.abs(B).max() < 1e3


def soil(c=5e3, phi=25.0):
    return DruckerPrager(rho0=1850.0, E=1.8e6, nu=0.3, cohesion=c, phi=phi, psi=0.0)


def yield_function(sig, m):
    i1 = np.trace(sig)
    s = sig - i1 / 3 * np.eye(3)
    return m.alpha_phi * i1 + math.sqrt(0.5 * np.sum(s * s)) - m.k_c


def test_return_mapping_lands_on_the_yield_surface():
    m = soil()
    sig = np.diag([-20e3, -50e3, -20e3]) + 30e3 * (np.eye(3)[[1, 0, 2]] * [1, 1, 0])
    assert yield_function(sig, m) > 0
    ds = return_mapping(sig, m.alpha_phi, m.k_c, np.empty((3, 3)))
    assert ds > 0 and yield_function(sig, m) == pytest.approx(0.0, abs=1e-6 * 50e3)


def test_return_mapping_keeps_admissible_stress_and_cuts_tension_to_the_apex():
    m = soil()
    inside = np.diag([-30e3, -40e3, -30e3])
    before = inside.copy()
    assert return_mapping(inside, m.alpha_phi, m.k_c, np.empty((3, 3))) == 0.0
    np.testing.assert_array_equal(inside, before)
    tension = np.diag([50e3, 60e3, 50e3])
    return_mapping(tension, m.alpha_phi, m.k_c, np.empty((3, 3)))
    np.testing.assert_allclose(tension, np.eye(3) * m.k_c / m.alpha_phi / 3, rtol=1e-12)


def test_frictionless_cohesionless_soil_does_not_divide_by_zero():
    m = soil(c=0.0, phi=0.0)
    assert m.alpha_phi == 0.0 and m.k_c == 0.0
    sig = np.diag([-1e3, -3e3, -2e3])
    return_mapping(sig, m.alpha_phi, m.k_c, np.empty((3, 3)))
    np.testing.assert_allclose(sig, -2e3 * np.eye(3))  # a fluid: no deviator left


def test_material_constants():
    e = ElasticSolid(rho0=1000.0, E=2e6, nu=0.3975)
    assert e.c0 == pytest.approx(math.sqrt(2e6 / (3 * (1 - 2 * 0.3975) * 1000)))
    m = soil()
    t = math.tan(math.radians(25.0))
    assert m.alpha_phi == pytest.approx(t / math.sqrt(9 + 12 * t * t))
    assert m.k_c == pytest.approx(3 * 5e3 / math.sqrt(9 + 12 * t * t))
    sig = geostatic_stress(np.array([[0.0, 0.5]]), 2.0, m, 9.8)[0]
    assert sig[1, 1] == pytest.approx(-1850 * 9.8 * 1.5)
    assert sig[0, 0] == sig[2, 2] == pytest.approx((1 - math.sin(math.radians(25))) * sig[1, 1])


@pytest.mark.parametrize("lateral", [(0.0, 1.0 - math.sin(math.radians(25.0))), (0.0, 0.0)])
def test_the_cube_yields_below_the_depth_production_gives(lateral):
    """scripts/production.py's yield_depth: a column at rest with the lateral stresses ``lateral``
    times sigma_v (a free face, a free edge) is inside the Drucker-Prager surface of return_mapping
    just above that depth and beyond it just below."""
    params = {"rho0": 1850.0, "E": 1.8e6, "nu": 0.3, "cohesion": 5e3, "phi": 25.0, "psi": 0.0, "g": 9.8}
    depth = load_script("production").yield_depth(params, lateral)
    m = soil()
    for z, yields in ((0.99 * depth, False), (1.01 * depth, True)):
        sig = -1850 * 9.8 * z * np.diag([*lateral, 1.0])
        assert (return_mapping(sig, m.alpha_phi, m.k_c, np.empty((3, 3))) > 0.0) == yields


def test_initial_stress_profiles():
    """The other starts of a soil block on a floor at y = 0.2, 2 m high: none at all, and the
    inverted profile of the authors' code, zero at the floor and rho0 g H at the top."""
    m = soil()
    x = np.array([[0.0, 0.2], [0.0, 1.2], [0.0, 2.2]])
    assert not geostatic_stress(x, 2.2, m, 9.8, profile="none").any()
    inverted = geostatic_stress(x, 2.2, m, 9.8, profile="inverted", base=0.2)
    at_rest = geostatic_stress(x, 2.2, m, 9.8)
    np.testing.assert_allclose(inverted[:, 1, 1], [0.0, -1850 * 9.8, -1850 * 9.8 * 2.0])
    np.testing.assert_allclose(inverted, at_rest[::-1])  # the geostatic column turned upside down
    assert inverted[2, 0, 0] == inverted[2, 2, 2] == pytest.approx(m.k0 * inverted[2, 1, 1])


def test_a_free_slip_wall_exerts_no_shear_traction():
    """A particle in pure shear (s_xy only) dp/2 above a floor of three wall rows (normal y): with
    a free-slip floor its wall partners, mirror images with s_xy reversed, add nothing along x; a
    no-slip floor, whose partners carry s_xy itself, pushes it along x (the traction 2 s_xy)."""
    gx, gy = np.meshgrid((np.arange(9) - 4.0) * DP, -(np.arange(3) + 0.5) * DP, indexing="ij")
    x = np.concatenate([[[0.0, 0.5 * DP]], np.column_stack([gx.ravel(), gy.ravel()])])
    n = len(x)
    stress = np.zeros((n, 3, 3))
    stress[0, 0, 1] = stress[0, 1, 0] = 1e3
    normal = np.zeros_like(x)
    normal[:, 1] = 1.0
    mass, rho = np.full(n, 1000 * DP**2), np.full(n, 1000.0)
    along = {}
    for name, wall in (("no-slip", WALL), ("free-slip", WALL_SLIP)):
        kind = np.full(n, wall, np.int8)
        kind[0] = MOVING
        start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2 * H, x.min(axis=0) - DP)
        acc = np.zeros((n, 2))
        stress_acceleration(n, start, nbr, x, np.zeros((n, 2)), rho, np.zeros(n), packed(stress), mass, kind,
                            normal, 30.0, 40.0, 1.0, KERNEL, acc)
        along[name] = acc[0, 0]
    assert abs(along["no-slip"]) > 1.0
    assert abs(along["free-slip"]) < 1e-12 * abs(along["no-slip"])


def test_geostatic_stress_under_a_sloping_surface():
    """``top`` as a function of position: each particle carries the column above it, under a 2 m
    crest (x < 1) falling at 45 degrees to 1 m (x > 2)."""
    m = soil()
    x = np.array([[0.5, 0.5], [1.5, 0.5], [2.5, 0.5]])
    surface = lambda x: np.clip(3.0 - x[:, 0], 1.0, 2.0)  # noqa: E731
    sig = geostatic_stress(x, surface, m, 9.8)
    np.testing.assert_allclose(sig[:, 1, 1], -1850 * 9.8 * np.array([1.5, 1.0, 0.5]))
    np.testing.assert_allclose(sig[:, 0, 0], m.k0 * sig[:, 1, 1])
    np.testing.assert_array_equal(geostatic_stress(x[:1], 2.0, m, 9.8), sig[:1])  # level where it is level
