"""What a scheme is: the interface every discretisation of a material implements.

A scheme is a named part a case selects (``Case.scheme``), registered in
``mpisph.schemes.SCHEMES``. It owns per-particle fields, does its work once
per neighbour configuration, gives its force terms and its rates, and says how
large a time step it allows. It sees the step only through a ``StepContext``
(context.py). The run calls it in this order:

    forces()            once, when the run's parts are made (parts.py): the scheme's
                        force terms, summed with the others every step (forces.py)
    start(ctx)          once, before the first frame of a run from t = 0 (solver.py)
    configure(ctx)      once per configuration, after the neighbour lists (solver.py)

and in each step the integrator (integrators/):

    state(ctx)          what the momentum sum reads (pressure, stress),
                        then the integrator refreshes ``state_fields`` on ghosts
    implicit_kick(ctx, dt)  when ``implicit``: after the explicit kick, the part of the
                        kick the scheme takes backward in time (integrators that support it)
    rates(ctx, dt)      per step, after the kick and the drift: the density rate
                        drho/dt and whatever else the scheme integrates itself, or the
                        rates of its ``integrated_fields``, which the integrator advances
    constrain(ctx)      after each update of the ``integrated_fields``: the scheme's
                        constraint on them (002_: the stress scaled back to the yield surface)
"""

import math

from .errors import InputError


class Scheme:
    """Base of every scheme; the defaults are what a scheme without that part does."""

    name = ""
    integrator = "position_verlet"  # the integrator (integrators/) of a case that names none
    materials = ()  # the material classes (materials.py) this scheme discretises
    fields = ()  # per-particle fields it owns (particles.Field)
    derived = ()  # the output-only fields of ``derived_fields`` (particles.Field)
    state_fields = ()  # fields the momentum sum reads from neighbours
    carried_fields = ("v", "rho")  # what a particle carries: corrected to its new place when shifted
    needs_surface = False  # free-surface classes every configuration (surface.py)
    acoustic_cfl = 0.4  # CFL number of the acoustic time step (integrators/time_step.py)
    observable_names = ()  # its columns of diagnostics.csv that sum over the particles
    counter_names = ()  # its columns of diagnostics.csv that are the same on every rank
    options = {}  # the discretisation options a case may set (Case.scheme_options) and their defaults
    implicit = False  # takes part of the kick implicitly (implicit_kick)
    integrated_fields = {}  # field: its rate field, which ``rates`` fills and the integrator advances
    advances_in_rates = False  # ``rates(ctx, dt)`` advances a field by dt itself (the Riemann solids' stress)

    def __init__(self, case, kernel):
        self.material = case.material
        self.dim = case.dim
        unknown = sorted(set(case.scheme_options) - set(self.options))
        if unknown:
            takes = ", ".join(self.options) or "none"
            raise InputError(f"scheme {self.name} has no option {unknown[0]!r} (it takes: {takes})")
        self._options = {**self.options, **case.scheme_options}
        self.density_reinit = case.density_reinit  # physics/density_reinit.py
        self.lattice_sum = kernel.lattice_sum(case.dp) if case.density_reinit != "none" else None

    def option(self, name):
        """The value of option ``name``: the case's, else the default."""
        return self._options[name]

    def option_choice(self, name, choices):
        """The value of option ``name``, which must be one of ``choices`` (names, or a dict keyed by
        them); InputError otherwise."""
        value = self.option(name)
        if value not in choices:
            raise InputError(f"scheme {self.name}: {name} must be one of {', '.join(choices)}, not {value!r}")
        return value

    def initial_density(self, pressure):
        """Density of the material particles that gives ``pressure``: the material's
        ``density_under``. The schemes that integrate the stress itself start from rho0."""
        return self.material.density_under(pressure)

    @property
    def sound_speed(self):
        """Artificial sound speed c0 of the time-step criteria [m/s]."""
        return self.material.c0

    @property
    def kinematic_viscosity(self):
        """nu of the advection criterion (001_ Eq. 10) [m^2/s]."""
        return 0.0

    def time_step_limit(self, ctx):
        """A further limit on this rank's time step (a viscous or force criterion), inf if none."""
        return math.inf

    def forces(self):
        """The scheme's force terms, in the order they are summed."""
        return ()

    def implicit_kick(self, ctx, dt):
        """Per step, after the explicit kick of the owned particles' ``v`` (sent to ghosts): the
        velocities with the scheme's implicit terms over dt."""
        raise NotImplementedError

    def start(self, ctx):
        """Once, before the first frame of a run from t = 0: the state of the initial particles."""

    def configure(self, ctx):
        """Once per neighbour configuration."""

    def state(self, ctx):
        """Per step, before the momentum sum: the fields it reads (the scheme's ``state_fields``)."""

    def rates(self, ctx, dt):
        """Per step, after the kick and the drift: drho/dt, and any field the scheme integrates."""
        raise NotImplementedError

    def constrain(self, ctx):
        """After each update of the ``integrated_fields`` of the owned particles by the integrator."""

    def observables(self, pa, n):
        """{column: sum over the owned particles [0, n)} for ``observable_names``."""
        return {}

    def counters(self):
        """{column: value, the same on every rank} for ``counter_names``, once per row of
        diagnostics.csv."""
        return {}

    def report(self):
        """Lines for the start of a run: derived constants a user should see."""
        return ()

    def warnings(self):
        """Warnings for the start of a run: settings the scheme runs with but that its model does not hold for."""
        return ()

    def closing_report(self):
        """Lines for the end of a run, after its throughput: what a user should know of its cost."""
        return ()

    def derived_fields(self, pa, n):
        """Output-only fields of the owned particles for frames, {name: array}, one for each Field
        of ``derived``."""
        return {}
