"""Coulomb friction of two side walls a width W apart on a plane-strain granular flow (a channel
narrow across the plane of the run), after Jop, Forterre & Pouliquen (2005; 004_ ref. [25]).

Across the gap the walls carry the shear stress mu_w sigma_w against the grains' velocity, with
sigma_w the normal stress on them taken as the pressure p of the friction law mu(I) p (Jop et al.'s
closure). Averaged over the width, two walls give the body force 2 mu_w p / W per unit volume, so
the acceleration

    a_i = -F_i v_i / max(|v_i|, v_reg, F_i dt_a),   F_i = 2 mu_w p_i / (rho_i W),

p_i is the pressure the mu(I) law takes: the field ``law_pressure`` where the scheme keeps one
(law_pressure = carried_mean: the kernel mean of the pressure s p that the pairs carry, the
continuum's pressure in that discretisation, physics/mu_i.py), else the grains' p of Eq. 41
(law_pressure = state). granular_flow.side_walls refuses law_pressure = carried, whose s p is not
kept.

Above the speed max(v_reg, F_i dt_a) this is Coulomb's law, of constant magnitude F_i against the
motion; below it the friction falls linearly to zero with the speed, a drag, instead of flipping the
velocity's sign at every step where the grains stop. v_reg is a case's choice
(granular_flow.side_walls: sqrt(g H) / 100); F_i dt_a, the speed the friction takes in an advection
step dt_a (the configuration's, StepContext.advection_step, at least the time step dt), keeps the
drag's rate times dt at most one: a kick of dt from the velocity the friction is evaluated at does not
reverse it (symplectic_verlet.py evaluates it at the predicted velocity and kicks from v(n), so there
this bounds the friction's share of the kick, not its sign). A particle at
rest feels none; tension (p < 0) gives no friction.
"""

import numpy as np
from numba import njit

from ..forces import ForceTerm
from ..particles import MOVING


@njit(cache=True)
def add_side_wall_friction(n, kind, v, p, rho, rate, v_reg, dt, acc):
    """acc_i -= F_i v_i / max(|v_i|, v_reg, F_i dt), F_i = rate p_i / rho_i, for the moving particles
    in [0, n) with p_i > 0, rate = 2 mu_w / W (module docstring)."""
    dim = acc.shape[1]
    for i in range(n):
        if kind[i] != MOVING or p[i] <= 0.0:
            continue
        speed = 0.0
        for a in range(dim):
            speed += v[i, a] * v[i, a]
        coulomb = rate * p[i] / rho[i]
        scale = coulomb / max(np.sqrt(speed), v_reg, coulomb * dt)
        for a in range(dim):
            acc[i, a] -= scale * v[i, a]


def friction_pressure(fields):
    """The pressure the walls' friction takes from ``fields`` (a particle or frame field mapping): the
    law's, ``law_pressure``, where there is one, else the grains' p (module docstring)."""
    return fields["law_pressure"] if "law_pressure" in fields else fields["p"]


class SideWallFriction(ForceTerm):
    """The side walls' friction on the grains between them (module docstring): ``width`` W [m], the
    walls' friction coefficient ``mu_w`` and the regularising speed ``v_reg`` [m/s]."""

    name = "side_wall_friction"
    pairwise = False

    def __init__(self, width, mu_w, v_reg):
        self.rate = 2.0 * mu_w / width
        self.v_reg = v_reg

    def add(self, ctx, acc):
        pa = ctx.particles
        add_side_wall_friction(pa.n_owned, pa.kind, pa.v, friction_pressure(pa.arrays), pa.rho, self.rate, self.v_reg,
                               ctx.advection_step, acc)
