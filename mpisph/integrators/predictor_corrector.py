"""Predictor-corrector (Monaghan 1989, the time stepping of 002_ Sec. 3): the order of the
sub-steps of one time step.

With phi each of v, rho and the scheme's ``integrated_fields`` (the stress) and
F(phi) its rate:

    1. rates at n    the scheme's state; ghosts: its state fields; the
                     acceleration a(n) (forces.py); the scheme's rates drho/dt(n)
                     and those of its integrated fields
    2. predictor     phi* = phi(n) + dt/2 F(n); the scheme's constraint (the
                     stress scaled back); ghosts: v
    3. rates at n + 1/2   as 1, from phi*: a*, drho/dt*, F*
    4. corrector     phi(n + 1/2) = phi(n) + dt/2 F*, and phi(n + 1) =
                     2 phi(n + 1/2) - phi(n) = phi(n) + dt F*;
                     x(n + 1) = x(n) + dt v(n + 1/2) = x(n) + dt v(n) + dt^2/2 a*;
                     the scheme's constraint; ghosts: v

Two evaluations of every rate per step, where the Verlet integrators need one:
a step costs about twice as much. The pair geometry of both evaluations is
the configuration's (``StepContext.xc``), as for every integrator, so the
predicted position x(n) + dt/2 v(n) would enter no rate and is not formed.
A scheme whose ``rates`` advance its stress itself (``Scheme.advances_in_rates``,
the Riemann solids) cannot be stepped twice per step and is refused.
"""

from ..errors import InputError
from .position_verlet import PositionVerlet
from .updates import advance, rows


class PredictorCorrector(PositionVerlet):
    """One time step of a scheme and its force terms (module docstring)."""

    name = "predictor_corrector"

    def __init__(self, scheme, forces):
        super().__init__(scheme, forces)
        if scheme.advances_in_rates:
            raise InputError(f"integrator {self.name} evaluates the rates twice per step; scheme {scheme.name} "
                             f"advances its stress inside them (use position_verlet)")

    def step(self, ctx, dt):
        pa = ctx.particles
        n = pa.n_owned
        kind = pa.kind
        start = self._save(ctx, n)
        # 1. rates at n
        acc = self._rates(ctx, dt)
        # 2. predictor to n + 1/2
        self._update(ctx, n, start, acc, 0.5 * dt)
        # 3. rates at n + 1/2
        acc = self._rates(ctx, dt)
        # 4. corrector to n + 1: x with the corrected mid-step velocity, the others with the mid-step rates
        x = rows(pa.x, n)
        advance(n, kind, x, start["x"], start["v"], dt, True)
        advance(n, kind, x, x, acc, 0.5 * dt * dt, True)
        self._update(ctx, n, start, acc, dt)

    def _save(self, ctx, n):
        """Copies of x, v, rho and the integrated fields at the start of the step (2D rows)."""
        pa = ctx.particles
        start = {}
        for name in ("x", "v", "rho", *self.scheme.integrated_fields):
            f = rows(getattr(pa, name), n)
            start[name] = ctx.workspace.get(f"step_start_{name}", n, f.shape[1:])
            start[name][:] = f
        return start

    def _rates(self, ctx, dt):
        """The scheme's state (sent to ghosts), the acceleration (a copy: the next force sum reuses
        the memory) and the scheme's rates, at the current state."""
        pa = ctx.particles
        self.scheme.state(ctx)
        ctx.refresh(self.ghost_fields)
        acc = ctx.workspace.get("step_acceleration", pa.n_owned, (pa.dim,))
        acc[:] = self.forces.acceleration(ctx)
        self.scheme.rates(ctx, dt)
        return acc

    def _update(self, ctx, n, start, acc, dt):
        """v, rho and the integrated fields = their start values + dt times the current rates, the
        scheme's constraint, and the new velocities on ghosts."""
        pa = ctx.particles
        kind = pa.kind
        advance(n, kind, rows(pa.v, n), start["v"], acc, dt, True)
        advance(n, kind, rows(pa.rho, n), start["rho"], rows(pa.drho_dt, n), dt, False)
        for name, rate in self.scheme.integrated_fields.items():
            advance(n, kind, rows(getattr(pa, name), n), start[name], rows(getattr(pa, rate), n), dt, False)
        self.scheme.constrain(ctx)
        ctx.refresh(["v"])
