"""The classic SPH of 002_ (mpisph/physics/classic_granular.py): momentum of Eq. 23 with the
artificial viscosity of Eq. 25, the stress rate of Eq. 28 from the plain gradient, the scaling
back of Eqs. 19-21, the predictor-corrector, the soil cylinder of Sec. 5 at CI size, and the
same SPH for an elastic solid (classic_elastic, Gray et al. 2001)."""

import numpy as np
import pytest

from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.errors import InputError
from mpisph.granular_flow import mu_i_params
from mpisph.kernels import Kernel
from mpisph.materials import DruckerPrager
from mpisph.neighbours import neighbour_lists
from mpisph.parts import make_parts
from mpisph.physics.classic_granular import (UNBOUNDED_STRENGTH, classic_stress_acceleration, classic_stress_rate,
                                             scale_back)
from mpisph.physics.solid import material_pressure
from mpisph.tensors import packed, unpacked
from mpisph.io.diagnostics import read_diagnostics
from mpirun import mpisph

DP = 0.01
SOIL = DruckerPrager(rho0=1850.0, E=1.5e6, nu=0.2, cohesion=5.0e3, phi=20.0)


def cloud(seed, n=14, jitter=0.25):
    """A jittered square of moving particles (no walls), its lists and the cubic spline, h = 1.5 dp."""
    rng = np.random.default_rng(seed)
    g = (np.arange(n) + 0.5) * DP
    x = np.stack([a.ravel() for a in np.meshgrid(g, g, indexing="ij")], axis=1)
    x += rng.uniform(-jitter, jitter, x.shape) * DP
    k = Kernel("cubic_spline", 1.5 * DP, 2)
    kind = np.zeros(len(x), np.int8)
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, len(x), k.support, np.zeros(2) - DP)
    mass = np.full(len(x), SOIL.rho0 * DP**2)
    rho = SOIL.rho0 * rng.uniform(0.97, 1.03, len(x))
    return rng, x, kind, start, nbr, k, mass, rho


def acceleration(x, kind, start, nbr, k, mass, rho, v, stress, alpha, beta):
    n = len(x)
    p = np.zeros(n)
    material_pressure(n, kind, stress, p)
    acc = np.zeros((n, 2))
    classic_stress_acceleration(n, start, nbr, x, v, rho, p, stress, mass, kind, np.zeros_like(x), np.zeros(n),
                                1.5, SOIL.c0, alpha, beta, k.h, k.params, acc)
    return acc


def test_momentum_sum_conserves_linear_momentum():
    """Eq. 23 with Pi_ij: each pair's force is antisymmetric, so sum_i m_i dv_i/dt = 0."""
    rng, x, kind, start, nbr, k, mass, rho = cloud(1)
    v = rng.normal(size=x.shape)
    stress = packed(rng.normal(size=(len(x), 3, 3)) * 1e4 + np.eye(3) * -2e4)
    stress = packed(0.5 * (unpacked(stress, 3) + unpacked(stress, 3).transpose(0, 2, 1)))
    acc = acceleration(x, kind, start, nbr, k, mass, rho, v, stress, 1.0, 1.0)
    scale = np.abs(mass[:, None] * acc).sum()
    assert scale > 0.0
    assert np.abs((mass[:, None] * acc).sum(axis=0)).max() < 1e-12 * scale


@pytest.mark.parametrize("alpha, beta", [(1.0, 0.0), (1.0, 1.0), (0.0, 2.0)])
def test_artificial_viscosity_only_dissipates(alpha, beta):
    """With no stress the momentum sum is Pi_ij alone: its power sum_i m_i v_i . dv_i/dt is
    negative (approaching pairs exist) and equals minus the pair sum of Pi_ij over approaching
    pairs; a field of separating pairs (uniform expansion) feels none."""
    rng, x, kind, start, nbr, k, mass, rho = cloud(2)
    zero = np.zeros((len(x), 6))
    v = rng.normal(size=x.shape)
    acc = acceleration(x, kind, start, nbr, k, mass, rho, v, zero, alpha, beta)
    power = float(np.sum(mass[:, None] * v * acc))
    assert power < 0.0
    # Eq. 25 written out over the ordered pairs (i, j): Pi_ij for approaching pairs, with
    # mu_ij = h v_ij . x_ij / (r^2 + 0.01 h^2), the force on i -m_j Pi_ij W'(r) x_ij / r
    i = np.repeat(np.arange(len(x)), np.diff(start))
    j = nbr[: start[-1]]
    dx, dv = x[i] - x[j], v[i] - v[j]
    r = np.linalg.norm(dx, axis=1)
    vr = np.sum(dv * dx, axis=1)
    mu = k.h * vr / (r**2 + 0.01 * k.h**2)
    pi = np.where(vr < 0, (-alpha * SOIL.c0 * mu + beta * mu**2) / (0.5 * (rho[i] + rho[j])), 0.0)
    pair_power = -mass[i] * mass[j] * pi * k.derivative(r) / r * np.sum(dx * v[i], axis=1)
    assert power == pytest.approx(pair_power.sum(), rel=1e-10)
    expanding = 3.0 * (x - x.mean(axis=0))
    acc = acceleration(x, kind, start, nbr, k, mass, rho, expanding, zero, alpha, beta)
    assert np.all(acc == 0.0)


def test_stress_rate_is_hookes_law_in_the_interior_under_a_uniform_gradient():
    """An elastic state (inside the yield surface) under v = A x: the plain gradient of Eqs.
    26-27 is A in the interior of a lattice (up to the cubic spline's lattice sum at h = 1.5 dp),
    so the rate is 2 G D + (K - 2G/3) tr D I plus the Jaumann terms of the (isotropic) stress."""
    _, x, kind, start, nbr, k, mass, rho = cloud(0, n=16, jitter=0.0)
    rho = np.full(len(x), SOIL.rho0)
    A = np.array([[1e-3, 4e-3], [-2e-3, -1e-3]])
    v = x @ A.T
    sigma0 = -1e4 * np.eye(3)
    stress = np.tile(packed(sigma0[None])[0], (len(x), 1))
    rate, plastic = np.zeros((len(x), 6)), np.zeros(len(x))
    classic_stress_rate(len(x), start, nbr, x, v, mass, rho, kind, np.zeros_like(x), np.zeros(len(x)), 1.5,
                        k.params, SOIL.K, SOIL.G, SOIL.alpha_phi, SOIL.alpha_psi, SOIL.k_c, stress, rate, plastic)
    L = np.zeros((3, 3))
    L[:2, :2] = A
    D = 0.5 * (L + L.T)
    expected = 2 * SOIL.G * D + (SOIL.K - 2 * SOIL.G / 3) * np.trace(D) * np.eye(3)  # isotropic sigma: no spin
    inner = np.all(np.abs(x - 0.08) < 0.03, axis=1)
    got = unpacked(rate[inner], 3)
    np.testing.assert_allclose(got, np.broadcast_to(expected, got.shape), atol=2e-2 * np.abs(expected).max())
    assert np.all(plastic == 0.0)


def test_elastic_stress_rate_is_hookes_law_where_soil_would_yield():
    """classic_elastic's strength (alpha_phi, alpha_psi, k_c) = (0, 0, infinity) under a pure strain rate v = A x (A symmetric,
    no spin, so no Jaumann terms): from a stress far outside the soil's yield surface the rate is
    still 2 G D + (K - 2G/3) tr D I in the interior, where the soil's rate is cut by yielding."""
    _, x, kind, start, nbr, k, mass, rho = cloud(0, n=16, jitter=0.0)
    rho = np.full(len(x), SOIL.rho0)
    A = np.array([[1e-3, 2e-3], [2e-3, 3e-3]])  # loading: s : D > 0 and tr D > 0
    v = x @ A.T
    sigma0 = np.diag([-3e5, -1e5, -3e5])  # sqrt(J2) = 1.15e5 Pa, above the soil's limit k_c - alpha I1
    L = np.zeros((3, 3))
    L[:2, :2] = A
    D = 0.5 * (L + L.T)
    expected = 2 * SOIL.G * D + (SOIL.K - 2 * SOIL.G / 3) * np.trace(D) * np.eye(3)
    inner = np.all(np.abs(x - 0.08) < 0.03, axis=1)
    rates = {}
    for name, strength, plastic in (("elastic", UNBOUNDED_STRENGTH, np.zeros(0)),
                                    ("soil", (SOIL.alpha_phi, SOIL.alpha_psi, SOIL.k_c), np.zeros(len(x)))):
        stress = np.tile(packed(sigma0[None])[0], (len(x), 1))
        rate = np.zeros((len(x), 6))
        classic_stress_rate(len(x), start, nbr, x, v, mass, rho, kind, np.zeros_like(x), np.zeros(len(x)), 1.5,
                            k.params, SOIL.K, SOIL.G, *strength, stress, rate, plastic)
        rates[name] = unpacked(rate[inner], 3)
    tolerance = 2e-2 * np.abs(expected).max()
    np.testing.assert_allclose(rates["elastic"], np.broadcast_to(expected, rates["elastic"].shape), atol=tolerance)
    assert np.abs(rates["soil"] - expected).max() > 10 * tolerance


def test_scaling_back_lands_on_the_yield_surface_and_leaves_admissible_stresses():
    """Eqs. 19-21: p >= -k_c/alpha and sqrt(J2) <= alpha p + k_c afterwards (002_'s alpha_phi,
    three times mpisph's); a stress inside the surface keeps its bits."""
    rng = np.random.default_rng(4)
    n = 400
    s = rng.normal(size=(n, 3, 3)) * 3e4
    s = 0.5 * (s + s.transpose(0, 2, 1)) + np.eye(3) * rng.uniform(-3e4, 1e5, n)[:, None, None]
    stress = packed(s)
    before = stress.copy()
    kind = np.zeros(n, np.int8)
    plastic = np.zeros(n)
    scale_back(n, kind, SOIL.alpha_phi, SOIL.k_c, SOIL.G, stress, plastic)
    sig = unpacked(stress, 3)
    p = -np.trace(sig, axis1=1, axis2=2) / 3
    dev = sig + p[:, None, None] * np.eye(3)
    sqrt_j2 = np.sqrt(0.5 * np.sum(dev * dev, axis=(1, 2)))
    alpha = 3.0 * SOIL.alpha_phi
    assert np.all(p >= -SOIL.k_c / alpha - 1e-9 * SOIL.k_c)
    assert np.all(sqrt_j2 <= alpha * p + SOIL.k_c + 1e-9 * SOIL.k_c)
    moved = np.any(stress != before, axis=1)
    assert 0 < moved.sum() < n
    p0 = -before[:, :3].sum(axis=1) / 3
    dev0 = unpacked(before, 3) + p0[:, None, None] * np.eye(3)
    inside = (np.sqrt(0.5 * np.sum(dev0 * dev0, axis=(1, 2))) < alpha * p0 + SOIL.k_c) & (p0 > -SOIL.k_c / alpha)
    assert not np.any(moved & inside)
    assert np.all(plastic[moved] > 0.0) and np.all(plastic[~moved] == 0.0)


def vertical_cut(**overrides):
    """The vertical cut's Case and parameter values at dp = 0.1 m, with ``overrides`` (text)."""
    module = load_case_module("vertical_cut")
    values = resolve_params(module, {"dp": "0.1", "stabiliser": "none", **overrides})
    return build_case(module, values), values


def test_predictor_corrector_refuses_a_scheme_that_advances_its_stress_itself():
    case, values = vertical_cut()
    case.integrator = "predictor_corrector"
    with pytest.raises(InputError, match="advances its stress"):
        make_parts(case, values)


def test_classic_scheme_refuses_free_slip_walls():
    case, values = vertical_cut(scheme="classic_granular")
    make_parts(case, values)
    case.walls[0].slip = True
    with pytest.raises(InputError, match="no-slip walls only"):
        make_parts(case, values)


def test_soil_cylinder_spreads_after_impact_and_levels_off(tmp_path):
    """002_ Sec. 5 at dp = 1 mm, to 10 ms: the width stays D - dp until the impact (gap /
    speed = 0.3 ms), grows by more than 10 % of D, and changes by less than 1 % of D over the
    last 3 ms (scripts/validate.py asserts the same at 002_'s dp = 0.5 mm)."""
    r = mpisph(["soil_cylinder_impact", "--set", "dp=0.001", "--out", tmp_path, "--quiet"], timeout=600)
    assert r.returncode == 0, r.stderr
    d = read_diagnostics(tmp_path / "diagnostics.csv")
    t, spread = d["t"], 2.0 * d["front"]
    before = spread[t <= 0.0003]
    np.testing.assert_allclose(before, 0.048, rtol=1e-6)
    assert spread[-1] > 0.05 * 1.1 + 0.001
    last = spread[t >= t[-1] - 0.003]
    assert last.max() - last.min() < 0.01 * 0.05


def test_clamped_particles_evolve_their_density():
    """The classic schemes' continuity (mu_i.continuity) gives a clamped particle, held in place, the
    density rate it would have as a moving one, as the Riemann solids' does (particles.py)."""
    from mpisph.particles import CLAMPED
    from mpisph.physics.mu_i import continuity

    rng, x, kind, start, nbr, k, mass, rho = cloud(3)
    v = rng.normal(size=x.shape)
    n = len(x)
    rates = []
    for clamped in (False, True):
        kinds = kind.copy()
        if clamped:
            kinds[: n // 3] = CLAMPED
        drho_dt = np.zeros(n)
        continuity(n, start, nbr, x, v, mass, kinds, np.zeros_like(x), np.zeros(n), 1.5, k.params, drho_dt)
        rates.append(drho_dt)
    assert np.abs(rates[0][: n // 3]).min() > 0.0
    assert np.array_equal(rates[0], rates[1])


@pytest.mark.parametrize("case_name, overrides, integrator", [
    ("vertical_cut", {"scheme": "classic_granular"}, "predictor_corrector"),
    ("vertical_cut", {}, "position_verlet"),
    ("lube_collapse_2d", {}, "symplectic_verlet"),
    ("dam_break_2d", {}, "position_verlet")])
def test_a_case_that_names_no_integrator_is_stepped_by_its_schemes(case_name, overrides, integrator):
    """Case.integrator None: the scheme's own (002_'s predictor-corrector for the classic schemes,
    004_'s symplectic Verlet for mu_i), where a case of one's own with scheme="mu_i" was stepped by
    position Verlet unless it named symplectic_verlet too."""
    module = load_case_module(case_name)
    values = resolve_params(module, {"dp": "0.1" if case_name != "lube_collapse_2d" else "0.01", **overrides})
    case = build_case(module, values)
    assert case.integrator is None
    assert make_parts(case, values).integrator.name == integrator


@pytest.mark.parametrize("case_name", ["inclined_plane", "lube_collapse_2d"])
def test_mu_i_cases_take_004s_single_time_step_from_the_schemes_parameters(case_name):
    """004_ takes one time step of its Eq. 39: granular_flow.mu_i_params gives time_stepping=single to
    every case that takes the scheme's options, where a case of one's own that took them got the
    run parameters' dual criteria."""
    assert mu_i_params("", "explicit")["time_stepping"].default == "single"
    module = load_case_module(case_name)
    values = resolve_params(module, {})
    assert values["time_stepping"] == "single"
    assert make_parts(build_case(module, values), values).criteria.single
