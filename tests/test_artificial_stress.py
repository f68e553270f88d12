"""Monaghan's artificial stress (mpisph/stabilisers/artificial_stress.py): R from the principal
tensions only, rotated back, the in-plane block in 2D; for a fluid from the pressure, as from the
stress -p I; a repulsion between particles in tension and none in compression; no net force on a
cloud (momentum conserved); the same bits on 1 and 2 ranks."""

import numpy as np
import pytest

from mpisph.io.frames import list_frames, read_frame
from mpisph.kernels import AdaptiveKernelParams, Kernel, knot_coefficients
from mpisph.neighbours import neighbour_lists
from mpisph.particles import MOVING, WALL
from mpisph.stabilisers.artificial_stress import (EPSILON, EXPONENT, artificial_stress_acceleration,
                                                  artificial_stress_tensors, pressure_artificial_stress_tensors)
from mpisph.tensors import packed, unpacked
from mpirun import mpisph

RHO = 1850.0


def tensors(stress, dim, kind=None):
    n = len(stress)
    kind = np.full(n, MOVING, np.int8) if kind is None else kind
    R = np.empty((n, 6))
    artificial_stress_tensors(n, kind, packed(stress), np.full(n, RHO), EPSILON, dim, R)
    return unpacked(R, 3)


def rotation(seed):
    q, _ = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))
    return q


def test_only_principal_tensions_count_and_r_turns_with_the_stress():
    principal = np.array([2.0e4, -5.0e4, 1.0e3])  # tension, compression, tension
    for seed in range(5):
        q = rotation(seed)
        stress = (q * principal) @ q.T
        expected = (q * np.where(principal > 0, -EPSILON * principal / RHO**2, 0.0)) @ q.T
        np.testing.assert_allclose(tensors(stress[None], 3)[0], expected, atol=1e-12 * abs(expected).max())
    assert not tensors(np.diag([-1.0, -2.0, -3.0])[None], 3).any()


def test_in_2d_the_in_plane_block_alone_counts():
    stress = np.array([[[-1.0e4, 3.0e3, 0.0], [3.0e3, 2.0e4, 0.0], [0.0, 0.0, 5.0e4]]])  # zz in tension
    R = tensors(stress, 2)[0]
    values, q = np.linalg.eigh(stress[0, :2, :2])
    expected = (q * np.where(values > 0, -EPSILON * values / RHO**2, 0.0)) @ q.T
    np.testing.assert_allclose(R[:2, :2], expected, atol=1e-15)
    assert not R[2].any() and not R[:, 2].any()
    assert not tensors(stress, 2, kind=np.array([WALL], np.int8)).any()


def pair_force(stress, dim, dp=0.01, r=0.009, knots=None, exponent=EXPONENT):
    """The artificial acceleration of particle 0 from particle 1 at distance r along x: with the
    Wendland kernel, or with ``knots`` (a_0, a_1) 002_'s adaptive spline at h = 1.5 dp."""
    x = np.zeros((2, dim))
    x[1, 0] = r
    if knots is None:
        kernel = Kernel("wendland_c2", 1.3 * dp, dim).params
    else:
        h = 1.5 * dp
        coefficients = np.array([knot_coefficients(a, h, dim) for a in knots])
        kernel = AdaptiveKernelParams(*Kernel("cubic_spline", h, dim).params, dim, np.array(knots), coefficients)
    start, nbr = neighbour_lists(x, np.arange(2), np.zeros(2, np.int8), 2, 2.6 * dp, np.full(dim, -0.1))
    kind = np.full(2, MOVING, np.int8)
    R = np.empty((2, 6))
    artificial_stress_tensors(2, kind, packed(np.repeat(stress[None], 2, axis=0)), np.full(2, RHO), EPSILON,
                              dim, R)
    acc = np.zeros((2, dim))
    artificial_stress_acceleration(2, start, nbr, x, np.full(2, RHO * dp**dim), kind, np.zeros((2, dim)), R,
                                   dp, exponent, kernel, acc)
    return acc


def test_a_pair_in_tension_is_pushed_apart_and_one_in_compression_is_not():
    for dim in (2, 3):
        acc = pair_force(np.diag([1.0e4, 0.0, 0.0]), dim)
        assert acc[0, 0] < 0.0 < acc[1, 0]  # particle 1 sits at +x of particle 0
        np.testing.assert_allclose(acc[0], -acc[1], rtol=1e-14)
        assert not pair_force(np.diag([-1.0e4, -1.0e4, -1.0e4]), dim).any()


def test_at_the_initial_spacing_f_is_one_whatever_the_knots_of_the_adaptive_kernel():
    """f_ij = W_ij(r) / W_ij(dp) takes the pair's kernel in both (module docstring): at r = dp the
    repulsion is that of f = 1 (exponent 0), for every pair of knots; nearer, f > 1."""
    tension = np.diag([1.0e4, 2.0e3, 5.0e2])
    for dim in (2, 3):
        for knots in ((1.0, 1.0), (0.2, 0.2), (2.0, 2.0), (0.2, 1.78)):
            at_dp = pair_force(tension, dim, r=0.01, knots=knots)
            np.testing.assert_allclose(at_dp, pair_force(tension, dim, r=0.01, knots=knots, exponent=0), rtol=1e-13)
            near = pair_force(tension, dim, r=0.008, knots=knots)
            assert abs(near[0, 0]) > abs(pair_force(tension, dim, r=0.008, knots=knots, exponent=0)[0, 0])


def test_no_net_force_on_a_cloud_in_random_stress():
    rng = np.random.default_rng(4)
    n, dim, dp = 300, 3, 0.01
    x = rng.uniform(0.0, 8 * dp, (n, dim))
    stress = rng.normal(scale=1e4, size=(n, 3, 3))
    stress = stress + stress.transpose(0, 2, 1)
    kind = np.full(n, MOVING, np.int8)
    kernel = Kernel("wendland_c2", 1.3 * dp, dim).params
    start, nbr = neighbour_lists(x, np.arange(n), kind, n, 2.6 * dp, np.zeros(dim))
    rho = rng.uniform(0.9, 1.1, n) * RHO
    mass = rng.uniform(0.9, 1.1, n) * RHO * dp**dim
    R = np.empty((n, 6))
    artificial_stress_tensors(n, kind, packed(stress), rho, EPSILON, dim, R)
    acc = np.zeros((n, dim))
    artificial_stress_acceleration(n, start, nbr, x, mass, kind, np.zeros((n, dim)), R, dp, EXPONENT, kernel, acc)
    total = (mass[:, None] * acc).sum(axis=0)
    assert np.abs(acc).max() > 0.0
    assert np.abs(total).max() < 1e-12 * (mass[:, None] * np.abs(acc)).sum()


@pytest.mark.ranks
def test_the_cohesive_cut_with_artificial_stress_has_the_same_bits_on_one_and_two_ranks(tmp_path):
    args = ["cohesive_failure_2d", "--set", "dp=0.1", "stabiliser=artificial_stress", "--t-end", "0.2",
            "--output-interval", "0.1", "--quiet"]
    ends = {}
    for ranks in (1, 2):
        r = mpisph([*args, "--out", tmp_path / f"r{ranks}"], ranks=ranks, timeout=300)
        assert r.returncode == 0, r.stderr
        ends[ranks] = read_frame(list_frames(tmp_path / f"r{ranks}")[-1])
    assert ends[1]["step"] > 20
    for k in ("x", "v", "stress", "rho"):
        assert np.array_equal(ends[1][k], ends[2][k]), k


def test_the_jacobi_eigen_decomposition_matches_numpy():
    from mpisph.stabilisers.artificial_stress import symmetric_eigen
    rng = np.random.default_rng(7)
    for dim in (2, 3):
        for _ in range(20):
            A = rng.normal(size=(dim, dim))
            A = A + A.T
            D, V = A.copy(), np.empty((dim, dim))
            symmetric_eigen(D, V)
            np.testing.assert_allclose(V @ np.diag(np.diag(D)) @ V.T, A, atol=1e-13)
            np.testing.assert_allclose(np.sort(np.diag(D)), np.linalg.eigvalsh(A), atol=1e-13)
            np.testing.assert_allclose(V.T @ V, np.eye(dim), atol=1e-14)


def test_a_fluid_takes_r_from_its_pressure_as_from_the_stress_minus_p_i():
    p = np.array([-300.0, 0.0, 250.0, -1.0e-3])
    kind = np.array([MOVING, MOVING, MOVING, WALL], np.int8)
    rho = np.array([990.0, 1000.0, 1010.0, 1000.0])
    for dim in (2, 3):
        from_pressure, from_stress = np.empty((4, 6)), np.empty((4, 6))
        pressure_artificial_stress_tensors(4, kind, p, rho, EPSILON, dim, from_pressure)
        stress = -p[:, None, None] * np.eye(3)
        artificial_stress_tensors(4, kind, packed(stress), rho, EPSILON, dim, from_stress)
        np.testing.assert_allclose(from_pressure, from_stress, rtol=1e-14, atol=0.0)
        R = unpacked(from_pressure, 3)
        expected = np.zeros((3, 3))
        expected[:dim, :dim] = EPSILON * p[0] / rho[0] ** 2 * np.eye(dim)
        np.testing.assert_allclose(R[0], expected, rtol=1e-14)
        assert not R[1:].any()  # no tension, compression, a wall


@pytest.mark.parametrize("case, dp, from_pressure", [("cohesive_failure_2d", 0.2, False),
                                                     ("rotating_square_patch", 0.1, True)])
def test_a_case_sets_epsilon_and_a_fluid_takes_r_from_its_pressure(case, dp, from_pressure):
    from mpisph.case import build_case, load_case_module, resolve_params
    from mpisph.parts import make_parts
    from mpisph.stabilisers.artificial_stress import ArtificialStressForce
    module = load_case_module(case)
    values = resolve_params(module, {"dp": str(dp), "stabiliser": "artificial_stress",
                                     "artificial_stress_epsilon": "0.6"})
    parts = make_parts(build_case(module, values), values)
    [term] = [t for t in parts.forces.terms if isinstance(t, ArtificialStressForce)]
    assert term.epsilon == 0.6 and term.dp == dp
    assert term.from_pressure == from_pressure
    assert term.ghost_fields == (("p",) if from_pressure else ("stress",))
