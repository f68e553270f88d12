"""Symplectic Verlet with a velocity predictor (004_ Sec. 3.5, after Monaghan and Kajtar):
the order of the sub-steps of one time step.

    1. first half    x += dt/2 v ; rho += dt/2 drho/dt ; the velocity
                     predicted to n + 1/2, v* = v + dt/2 a(n - 1/2), with the
                     acceleration of the previous step; ghosts: v*, rho
    2. state         the scheme's state at n + 1/2 from v* (strain rate,
                     pressure, viscosity); ghosts: its state fields
    3. kick          v = v(n) + dt a(n + 1/2), a the sum of the force terms
                     (forces.py) at n + 1/2; ghosts: v. A scheme with an
                     implicit part (``Scheme.implicit``) then takes it from
                     these velocities (the mu(I) viscosity backward in time,
                     physics/implicit_viscosity.py), a becomes (v - v(n))/dt,
                     and the ghosts get v again
    4. second half   x += dt/2 v
    5. rates         the scheme's drho/dt from the new velocities
    6. density       rho += dt/2 drho/dt; the scheme's ``integrated_fields`` as
                     in position_verlet.py

The forces of the mu(I) scheme depend on the velocity (viscosity, artificial
viscosity), so 004_ evaluates them at the midpoint with the predicted
velocity v*; positions follow drift-kick-drift, as in position_verlet.py,
which is symplectic for forces of the positions alone. The first step has no
previous acceleration and predicts v* = v(n).

The density's second half uses the rate at n + 1 (from the new velocities,
also serving the next step's first half): a trapezoidal rule, second-order
like the rest of the step. A literal reading of 004_'s list ("a half Euler
step based on drho/dt(n + 1/2)") would give rho(n + 1) = rho(n) + dt/2
(drho/dt(n) + drho/dt(n + 1/2)), whose local error is of order dt^2 (first
order over a run), and would cost a second continuity pass per step.
"""

import numpy as np

from ..particles import Field
from .position_verlet import PositionVerlet
from .updates import advance_integrated, density_half, drift_half, kick


class SymplecticVerlet(PositionVerlet):
    """One time step of a scheme and its force terms (module docstring)."""

    name = "symplectic_verlet"
    fields = PositionVerlet.fields + (
        Field("dv_dt", ("dim",), np.float64, "acceleration of the last step, at its midpoint [m/s^2]"),
        Field("v_start", ("dim",), np.float64, "velocity at the start of the step [m/s]"))
    takes_implicit = True

    def step(self, ctx, dt):
        pa = ctx.particles
        n = pa.n_owned
        v_start, dv_dt = pa.v_start[:n], pa.dv_dt[:n]
        # 1. first half: positions and density to n + 1/2, the predicted velocity v*
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, True)
        v_start[:] = pa.v[:n]
        kick(n, pa.kind, pa.v, dv_dt, 0.5 * dt)
        ctx.refresh(["v", "rho"])
        # 2. the state at n + 1/2, on owned particles and then on ghosts
        self.scheme.state(ctx)
        ctx.refresh(self.ghost_fields)
        # 3. momentum at n + 1/2 and the kick from v(n), then the new velocities of ghosts
        dv_dt[:] = self.forces.acceleration(ctx)
        pa.v[:n] = v_start
        kick(n, pa.kind, pa.v, dv_dt, dt)
        ctx.refresh(["v"])
        if self.scheme.implicit:
            self.scheme.implicit_kick(ctx, dt)
            dv_dt[:] = (pa.v[:n] - v_start) / dt
            ctx.refresh(["v"])
        # 4. second half: positions
        drift_half(n, pa.kind, pa.x, pa.v, pa.rho, pa.drho_dt, dt, False)
        # 5. rates from the new velocities
        self.scheme.rates(ctx, dt)
        # 6. second half: density; the fields the scheme leaves to the integrator, and its constraint
        density_half(n, pa.kind, pa.rho, pa.drho_dt, dt)
        advance_integrated(ctx, self.scheme, dt)
