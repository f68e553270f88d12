"""Position-based Verlet (000_ Eqs. 39-41): the order of the sub-steps of one time step.

    1. first half    x += dt/2 v ; rho += dt/2 drho/dt                 (Eq. 39)
    2. state         the scheme's state (pressure, total stress) from the
                     half-step density or stress; ghosts: its state fields
    3. kick          v += dt dv/dt, dv/dt the sum of the force terms    (Eq. 40)
                     (forces.py); ghosts: v
    4. second half   x += dt/2 v                                        (Eq. 41)
    5. rates         the scheme's drho/dt from the new velocities (and the
                     stress it integrates itself)
    6. density       rho += dt/2 drho/dt; the scheme's ``integrated_fields`` (if
                     any) by dt from the rates of step 5, then ``scheme.constrain``

The density rate of step 5 serves the second half of this step and the first
half of the next one.
"""

import numpy as np

from ..errors import InputError
from ..particles import Field
from .updates import advance_integrated, density_half, drift_half, kick


class PositionVerlet:
    """One time step of a scheme and its force terms (module docstring)."""

    name = "position_verlet"
    fields = (Field("drho_dt", (), np.float64, "density rate [kg/m^3/s]"),)
    takes_implicit = False  # calls Scheme.implicit_kick

    def __init__(self, scheme, forces):
        if scheme.implicit and not self.takes_implicit:
            raise InputError(f"integrator {self.name} has no implicit kick, which scheme {scheme.name} asks for "
                             f"with these options")
        self.scheme = scheme
        self.forces = forces
        self.ghost_fields = list(dict.fromkeys(scheme.state_fields + forces.ghost_fields))

    def step(self, ctx, dt):
        pa = ctx.particles
        n = pa.n_owned
        # 1. first half: positions and density to n + 1/2
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, True)
        # 2. what the momentum sum reads, on owned particles and then on ghosts
        self.scheme.state(ctx)
        ctx.refresh(self.ghost_fields)
        # 3. momentum and kick, then the new velocities of ghosts
        kick(n, pa.kind, pa.v, self.forces.acceleration(ctx), dt)
        ctx.refresh(["v"])
        # 4. second half: positions
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, False)
        # 5. rates from the new velocities (reads neighbours' density at n + 1/2)
        self.scheme.rates(ctx, dt)
        # 6. second half: density; the fields the scheme leaves to the integrator, and its constraint
        density_half(n, pa.kind, pa.rho, pa.drho_dt, dt)
        advance_integrated(ctx, self.scheme, dt)
