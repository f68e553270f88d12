"""The classic SPH of 002_ for Drucker-Prager soil (Secs. 2-3, 5), the alternative to the Riemann
scheme, and the same SPH for a linear elastic solid (Gray, Monaghan & Swift 2001).

In the papers' sign convention (r_ij = x_i - x_j, grad_i W_ij = W' r_ij / r,
W' <= 0, kernels.py), with v_ij = v_i - v_j and sigma = s - p I (tension
positive, s the deviator, p = -tr(sigma)/3):

    continuity    drho_i/dt = sum_j m_j v_ij . grad_i W_ij                        (002_ Eq. 22)
    momentum      dv_i/dt = g + sum_j m_j (sigma_i/rho_i^2 + sigma_j/rho_j^2 - Pi_ij I) grad_i W_ij
                                                                                  (Eq. 23)
    viscosity     Pi_ij = (-alpha c0 mu_ij + beta mu_ij^2) / rho_bar for v_ij . r_ij < 0, else 0,
                  mu_ij = h v_ij . r_ij / (r^2 + 0.01 h^2)                         (Eq. 25)
    stress rate   Eq. 28 with the plastic multiplier of Eq. 29 from the plain velocity
                  gradient of Eqs. 26-27 (no correction matrix): drucker_prager.py's rate,
                  which is the same law (its alpha_phi is a third of 002_'s, its I1 = -3 p)
    scaling back  after every update of the stress: the tension cut-off of Eq. 19 and the
                  deviator scaled by xi of Eqs. 20-21 (drucker_prager.return_mapping)

Pi_ij is Monaghan's: it acts on approaching pairs only and its power,
-m_i m_j Pi_ij v_ij . grad_i W_ij, is never positive, so it only dissipates.
c_bar of Eq. 25 is the sound speed at rest c0 = sqrt(K/rho0) of every particle
(000_ Eq. 6), the speed the time step is taken with.

Walls are Morris's no-slip ghost particles (Eq. 34, walls.py): a wall partner
moves with v_j such that v_ij = chi (v_i - v_w), chi = min(chi_max, 1 + d_j/d_i),
in the continuity, the momentum (and so in Pi_ij) and the velocity gradient,
and takes the density and stress of particle i. A free-slip wall has no place
in Eq. 34, so the scheme refuses one.

The scheme computes rates only; the integrator advances the stress and the
accumulated plastic strain (``integrated_fields``) and calls ``constrain``
after each update, which scales the stress back (predictor_corrector.py, 002_
Sec. 3's time stepping, and position_verlet.py both do).

``classic_elastic`` takes a linear elastic solid through the same sums: Eq. 28
with no yield surface (the rate of Drucker-Prager with unbounded strength,
alpha_phi = alpha_psi = 0, k_c = infinity, which is the elastic Jaumann rate
of elastic.py on the plain gradient) and nothing to scale back. That is the SPH
elastic dynamics of Gray, Monaghan & Swift 2001, whose artificial stress
(stabiliser ``artificial_stress``) is the SPH-AS of 000_ Table 1 and Fig. 13.
"""

import math

import numpy as np
from numba import njit

from ..errors import InputError
from ..forces import ForceTerm
from ..kernels import pair_dw
from ..materials import DruckerPrager, ElasticSolid
from ..neighbours import pair_difference, pair_offset
from ..particles import MOVING, Field, is_wall
from ..scheme import Scheme
from ..tensors import SYM3, unpack_row
from .drucker_prager import (NO_DIFFUSION, PLASTIC_STRAIN, plastic_stress_rate, return_mapping,
                             strain_of_multiplier, strain_of_return)
from .mu_i import continuity
from .solid import (SOLID_OUTPUT_FIELDS, STRESS, material_pressure, solid_output_fields, strain_energy, tensor_times,
                    velocity_gradient)
from .walls import WALL_DISTANCE, MorrisWalls, morris_relative_velocity, require_wall_distances

MU_EPSILON = 0.01  # the 0.01 h^2 of Eq. 25's mu_ij
UNBOUNDED_STRENGTH = (0.0, 0.0, math.inf)  # (alpha_phi, alpha_psi, k_c) of an elastic solid: Eq. 28 never yields
STRESS_RATE = Field("stress_rate", (6,), np.float64, "Jaumann stress rate of 002_ Eq. 28, packed [Pa/s]")


@njit(cache=True)
def classic_stress_acceleration(n, start, nbr, xc, v, rho, p, stress, mass, kind, normal, wall_distance, chi_max,
                                c0, alpha, beta, h, k, acc):
    """acc += the momentum sum of Eq. 23 with Pi_ij of Eq. 25 (module docstring) of the moving
    particles. sigma_i/rho_i^2 is the same for every pair of i and multiplies
    sum_j m_j grad_i W_ij once."""
    dim = xc.shape[1]
    eps_h2 = MU_EPSILON * h * h
    for i in range(n):
        if kind[i] != MOVING:
            continue
        rho_i2 = rho[i] * rho[i]
        a0 = a1 = a2 = 0.0
        g0 = g1 = g2 = 0.0
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            d0, d1, d2, r = pair_offset(xc, i, j)
            u0, u1, u2 = pair_difference(v, i, j)
            q = j
            if is_wall(kind[j]):  # the wall takes the state of i; walls.py: off the common path
                u0, u1, u2 = morris_relative_velocity(i, j, xc, v, kind, normal, wall_distance, chi_max)
                q = i
            rho_q2 = rho[q] * rho[q]
            vr = u0 * d0 + u1 * d1 + u2 * d2
            pi_ij = 0.0
            if vr < 0.0:
                mu = h * vr / (r * r + eps_h2)
                pi_ij = (-alpha * c0 * mu + beta * mu * mu) / (0.5 * (rho[i] + rho[q]))
            f = mass[j] * pair_dw(k, r, i, j) / r
            t0, t1, t2 = tensor_times(stress, q, p, dim, d0, d1, d2)  # s_q . r_ij
            pressure = p[i] / rho_i2 + p[q] / rho_q2 + pi_ij
            a0 += f * (t0 / rho_q2 - pressure * d0)
            a1 += f * (t1 / rho_q2 - pressure * d1)
            a2 += f * (t2 / rho_q2 - pressure * d2)
            g0 += f * d0
            g1 += f * d1
            g2 += f * d2
        t0, t1, t2 = tensor_times(stress, i, p, dim, g0, g1, g2)
        acc[i, 0] += a0 + t0 / rho_i2
        acc[i, 1] += a1 + t1 / rho_i2
        if dim == 3:
            acc[i, 2] += a2 + t2 / rho_i2


@njit(cache=True)
def classic_stress_rate(n, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, chi_max, k, K, G, alpha_phi,
                        alpha_psi, k_c, stress, stress_rate, plastic_rate):
    """The stress rate of Eq. 28 (packed) and, when ``plastic_rate`` has rows, the rate of the
    accumulated plastic strain, gamma_dot / sqrt(3) (drucker_prager.py), of the material
    particles, from the plain velocity gradient of Eqs. 26-27 with Morris's walls."""
    L = np.empty((3, 3))
    dev = np.empty((3, 3))
    rate = np.empty((3, 3))
    sig = np.empty((3, 3))
    plain = np.zeros((0, 1))  # no correction matrix
    for i in range(n):
        if is_wall(kind[i]):
            continue
        velocity_gradient(i, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, chi_max, plain, k, L)
        unpack_row(stress, i, sig)
        gamma_dot = plastic_stress_rate(L, sig, dev, NO_DIFFUSION, i, K, G, alpha_phi, alpha_psi, k_c, rate)
        for a in range(3):  # symmetric to the bit: every rate term is formed symmetrically
            for b in range(a, 3):
                stress_rate[i, SYM3[a, b]] = rate[a, b]
        if plastic_rate.shape[0] > 0:
            plastic_rate[i] = strain_of_multiplier(gamma_dot)


@njit(cache=True)
def scale_back(n, kind, alpha_phi, k_c, G, stress, plastic_strain):
    """The stress of the material particles back onto the yield surface (Eqs. 19-21); the
    accumulated plastic strain adds sqrt(2/3) |Delta s| / 2G of each correction."""
    sig = np.empty((3, 3))
    dev = np.empty((3, 3))
    for i in range(n):
        if is_wall(kind[i]):
            continue
        unpack_row(stress, i, sig)
        ds = return_mapping(sig, alpha_phi, k_c, dev)
        for a in range(3):
            for b in range(a, 3):
                stress[i, SYM3[a, b]] = sig[a, b]
        plastic_strain[i] += strain_of_return(ds, G)


class ClassicStress(ForceTerm):
    """The momentum sum of Eq. 23 with Monaghan's artificial viscosity (Eq. 25)."""

    name = "classic_stress"

    def __init__(self, scheme):
        self.scheme = scheme

    def add(self, ctx, acc):
        pa, s = ctx.particles, self.scheme
        classic_stress_acceleration(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.rho, pa.p, pa.stress, pa.mass,
                                    pa.kind, pa.normal, pa.wall_distance, s.chi_max, s.material.c0, s.alpha, s.beta,
                                    s.h, ctx.kernel.params, acc)


class ClassicGranular(MorrisWalls, Scheme):
    """Drucker-Prager soil in the classic SPH of 002_ (module docstring). Options
    (``Case.scheme_options``): ``alpha`` and ``beta`` of Eq. 25 (002_ Tables 2 and 4: 1 and 1
    for the soil cylinder, 1 and 0 for the vertical cut) and ``chi_max`` of Eq. 34 (1.5; 002_
    gives 1.5-2)."""

    name = "classic_granular"
    integrator = "predictor_corrector"  # 002_ Sec. 3
    materials = (DruckerPrager,)
    options = {"alpha": 1.0, "beta": 1.0, "chi_max": 1.5}
    state_fields = ("rho", "p", "stress")
    carried_fields = ("v", "rho", "stress")
    integrated_fields = {"stress": "stress_rate", "plastic_strain": "plastic_rate"}
    source = "002_"
    derived = SOLID_OUTPUT_FIELDS
    fields = (
        STRESS,
        STRESS_RATE,
        PLASTIC_STRAIN,
        Field("plastic_rate", (), np.float64, "rate of the accumulated plastic strain [1/s]"),
        WALL_DISTANCE,
    )

    def __init__(self, case, kernel):
        super().__init__(case, kernel)
        self.alpha = float(self.option("alpha"))
        self.beta = float(self.option("beta"))
        self.chi_max = float(self.option("chi_max"))
        if self.alpha < 0.0 or self.beta < 0.0 or self.chi_max < 1.0:
            raise InputError(f"scheme {self.name}: alpha and beta must not be negative and chi_max not below 1, "
                             f"not {self.alpha}, {self.beta}, {self.chi_max}")
        slip = [w.name for w in case.walls if w.slip]
        if slip:
            raise InputError(f"scheme {self.name} has Morris's no-slip walls only (002_ Eq. 34); wall {slip[0]!r} "
                             f"is free-slip")
        require_wall_distances(case, self.name)
        self.h = kernel.h

    def initial_density(self, pressure):
        return np.full_like(pressure, self.material.rho0)

    def forces(self):
        return (ClassicStress(self),)

    def state(self, ctx):
        pa = ctx.particles
        material_pressure(pa.n_owned, pa.kind, pa.stress, pa.p)

    def rates(self, ctx, dt):
        pa, m = ctx.particles, self.material
        n = pa.n_owned
        continuity(n, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.mass, pa.kind, pa.normal, pa.wall_distance, self.chi_max,
                   ctx.kernel.params, pa.drho_dt)
        classic_stress_rate(n, ctx.start, ctx.nbr, ctx.xc, pa.v, pa.mass, pa.rho, pa.kind, pa.normal,
                            pa.wall_distance, self.chi_max, ctx.kernel.params, m.K, m.G, *self.strength(), pa.stress,
                            pa.stress_rate, self.plastic_rate(pa))

    def strength(self):
        """(alpha_phi, alpha_psi, k_c) of the yield surface (000_ Eq. 14)."""
        m = self.material
        return m.alpha_phi, m.alpha_psi, m.k_c

    def plastic_rate(self, pa):
        """The field the stress rate writes the accumulated plastic strain's rate into."""
        return pa.plastic_rate

    def constrain(self, ctx):
        pa, m = ctx.particles, self.material
        scale_back(pa.n_owned, pa.kind, m.alpha_phi, m.k_c, m.G, pa.stress, pa.plastic_strain)

    def report(self):
        return (f"classic SPH ({self.source}): artificial viscosity alpha = {self.alpha:g}, beta = {self.beta:g}; "
                f"Morris walls chi_max = {self.chi_max:g}; sound speed c0 = {self.material.c0:.4g} m/s",)

    def derived_fields(self, pa, n):
        return solid_output_fields(pa.stress, pa.v, n)


class ClassicElastic(ClassicGranular):
    """Linear elastic solid in the classic SPH (module docstring): Gray, Monaghan & Swift 2001.
    Options as ``classic_granular``; no plastic strain, nothing scaled back, and the strain
    energy in the diagnostics as with ``riemann_elastic``."""

    name = "classic_elastic"
    materials = (ElasticSolid,)
    integrated_fields = {"stress": "stress_rate"}
    source = "Gray et al. 2001"
    fields = (STRESS, STRESS_RATE, WALL_DISTANCE)
    observable_names = ("strain_energy",)

    def __init__(self, case, kernel):
        super().__init__(case, kernel)
        self._no_plastic_rate = np.zeros(0)

    def strength(self):
        return UNBOUNDED_STRENGTH

    def plastic_rate(self, pa):
        return self._no_plastic_rate

    def constrain(self, ctx):
        """Nothing to scale back: no yield surface."""

    def observables(self, pa, n):
        deviator = pa.stress[:n].copy()
        deviator[:, :3] += pa.p[:n, None]
        return {"strain_energy": strain_energy(pa, n, deviator, self.material)}
