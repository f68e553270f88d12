"""Linear elastic solid in the updated-Lagrangian Riemann SPH of 000_ Sec. 3.1.2.

Pressure from the equation of state p = c0^2 (rho - rho0) with c0 of Eq. 6
(Eqs. 3, 5); the shear stress is integrated from its rate (Eqs. 7-8),

    dsigma^s/dt = 2 G (D - tr(D)/3 I) + sigma^s W^T + W sigma^s,

with D and W the symmetric and skew parts of the corrected velocity gradient
(Eqs. 9, 23); in 2D, D is plane strain (D_zz = 0) and sigma^s_zz evolves,
so the in-plane stiffness is E / (1 - nu^2) as in the beam theory of Eq. 47.
Eq. 8 takes the deviator with 1/d, d the dimension; in plane strain the stress is
3D, and its deviator takes tr(D)/3 in 2D as well.
The rotation terms (the Jaumann rate of Eq. 10) keep the rate objective when
the body rotates, as the beam's root section does; for small rotations they
vanish and the rate is Eq. 8. Continuity is Eq. 21 (no
Riemann dissipation) and the momentum's Riemann pressure takes beta = 1.
"""

import numpy as np
from numba import njit

from ..materials import ElasticSolid
from ..particles import Field, is_wall
from ..tensors import SYM3, unpack_row
from .fluid import linear_pressure
from .solid import SolidScheme, jaumann_rate, strain_energy, velocity_gradient


@njit(cache=True)
def elastic_pressure(n, kind, rho, rho0, c0, shear, p, stress):
    """p from the equation of state and the total stress sigma = sigma^s - p I."""
    for i in range(n):
        if is_wall(kind[i]):
            continue
        p[i] = linear_pressure(rho[i], rho0, c0)
        for k in range(6):
            stress[i, k] = shear[i, k]
        for a in range(3):
            stress[i, a] -= p[i]


@njit(cache=True)
def shear_stress_update(n, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, beta_max, B, k, G, dt,
                        shear):
    """sigma^s += dt [2 G dev(D) + sigma^s W^T + W sigma^s] (Eqs. 7-8 with Eq. 10's rotation),
    with L of Eq. 23 from ``velocity_gradient`` particle by particle; both stresses packed."""
    L = np.empty((3, 3))
    s_i = np.empty((3, 3))
    rate = np.empty((3, 3))
    for i in range(n):
        if is_wall(kind[i]):
            continue
        velocity_gradient(i, start, nbr, xc, v, mass, rho, kind, normal, wall_distance, beta_max, B, k, L)
        trace = L[0, 0] + L[1, 1] + L[2, 2]
        unpack_row(shear, i, s_i)
        jaumann_rate(L, s_i, G, rate)
        for a in range(3):
            rate[a, a] -= 2.0 * G * trace / 3.0
        for a in range(3):  # the rate is symmetric to the bit: each term is formed symmetrically
            for b in range(a, 3):
                shear[i, SYM3[a, b]] += dt * rate[a, b]


class RiemannElastic(SolidScheme):
    """Elastic solid: beta = 1, Eq. 21 continuity, and by default the corrected shear force
    (solid.py says why). Option ``shear_force``: ``corrected`` or ``as_printed`` (000_ Eq. 22)."""

    name = "riemann_elastic"
    materials = (ElasticSolid,)
    eta = -1.0  # beta = 1 in the Riemann pressure
    riemann_continuity = 0.0  # Eq. 21
    options = {"shear_force": "corrected"}
    SHEAR_FORCES = {"corrected": True, "as_printed": False}  # B on the shear part or not
    carried_fields = ("v", "rho", "shear_stress")
    fields = SolidScheme.base_fields + (
        Field("shear_stress", (6,), np.float64, "shear (deviatoric) stress, packed (tensors.py) [Pa]"),)
    observable_names = ("strain_energy",)

    def __init__(self, case, kernel):
        super().__init__(case, kernel)
        self.corrected_shear_force = self.SHEAR_FORCES[self.option_choice("shear_force", self.SHEAR_FORCES)]

    def state(self, ctx):
        pa, m = ctx.particles, self.material
        elastic_pressure(pa.n_owned, pa.kind, pa.rho, m.rho0, m.c0, pa.shear_stress, pa.p, pa.stress)

    def update_stress(self, ctx, dt):
        pa = ctx.particles
        shear_stress_update(pa.n_owned, *self.gradient_args(ctx), self.material.G, dt, pa.shear_stress)

    def observables(self, pa, n):
        return {"strain_energy": strain_energy(pa, n, pa.shear_stress[:n], self.material)}
