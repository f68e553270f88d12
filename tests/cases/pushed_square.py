"""A fluid square at rest in free space, pushed by a body force the case declares itself (tests the force-term route)."""

from mpisph.case import Body, Case, Fluid, Param
from mpisph.forces import UniformAcceleration
from mpisph.geometry import box

PARAMS = {
    "dp": Param(0.01, "m", "particle spacing", positive=True),
    "ax": Param(2.0, "m/s^2", "pushing acceleration along x"),
    "ay": Param(-1.0, "m/s^2", "pushing acceleration along y"),
    "t_end": Param(0.05, "s", "simulated end time", positive=True),
    "output_interval": Param(0.025, "s", "simulated time between frames", positive=True),
    "diagnostics_every": Param(1, "steps", "advection steps between rows of diagnostics.csv", positive=True),
}


class Push(UniformAcceleration):
    """A constant body force, evaluated at every time step (not frozen, unlike gravity)."""

    name = "push"
    frozen = False


def setup(p):
    return Case(
        dim=2,
        domain=((-1.0, -1.0), (1.0, 1.0)),
        dp=p.dp,
        material=Fluid(rho0=1000.0, c0=10.0),
        scheme="riemann_fluid",
        bodies=[Body("square", box((-0.1, -0.1), (0.1, 0.1), p.dp))],
        forces=[Push((p.ax, p.ay))],
        u_ref=1.0,
    )
