"""Time-step criteria: each rank's limits, of which the solver takes the minimum over ranks.

Dual criteria (001_ Eqs. 9-11): the neighbour configuration is rebuilt once
per advection step dt_ad = 0.25 h / |v|_ad, |v|_ad = max(|v|max, nu/h, U_ref),
and the time step within it is dt_ac = CFL h / (c0 + |v|max) with the scheme's
CFL number (0.6 for fluids, 001_ Eq. 11; 0.4 for solids; 0.5 for mu(I), 004_
Eq. 39). With a single criterion the configuration is rebuilt every step of
dt = 0.4 h / (c0 + |v|max) (000_ Eq. 38), whatever the scheme. A scheme's own
limit (``Scheme.time_step_limit``: a viscous or force criterion) bounds the
time step; with dual criteria the configuration is still kept for an advection
step, over several of the smaller time steps.
The run parameter ``max_time_step`` (when positive) bounds the time step too,
for a run at a paper's fixed step below the CFL limit.

Every limit decreases with |v|max, and rounding is monotone, so the minimum of
the ranks' limits equals the limit of the largest speed to the bit.
"""

import numpy as np

from .updates import max_speed

CFL_ADVECTION = 0.25
CFL_SINGLE = 0.4


class TimeStepCriteria:
    """The limits of one run: ``single`` or ``dual`` stepping, smoothing length ``h``, reference
    speed ``u_ref`` of 001_ Eq. 10, the largest time step ``max_dt`` (0: none)."""

    def __init__(self, time_stepping, h, u_ref, max_dt=0.0):
        self.single = time_stepping == "single"
        self.h = h
        self.u_ref = u_ref
        self.max_dt = max_dt if max_dt > 0.0 else np.inf

    def local_limits(self, ctx, scheme):
        """[time step, advection step] this rank allows at the current state."""
        pa = ctx.particles
        vmax = max_speed(pa.n_owned, pa.kind, pa.v)
        c0, h = scheme.sound_speed, self.h
        extra = min(scheme.time_step_limit(ctx), self.max_dt)
        if self.single:
            dt = min(CFL_SINGLE * h / (c0 + vmax), extra)
            return np.array([dt, dt])
        advection = CFL_ADVECTION * h / max(vmax, scheme.kinematic_viscosity / h, self.u_ref)
        return np.array([min(scheme.acoustic_cfl * h / (c0 + vmax), extra), advection])
