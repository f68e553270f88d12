"""Force terms, and their sum: the acceleration of the moving particles.

A force term adds its acceleration dv/dt into an (n_owned, dim) array, for the
moving particles only. The acceleration is summed in this order:

1. ``Gravity`` (Case.gravity);
2. the scheme's terms (the fluid: viscosity, then the Riemann pressure; the
   Riemann solids: the Riemann stress; the classic schemes: their stress with
   artificial viscosity; mu(I): its momentum);
3. the stabilisers' terms (artificial stress);
4. the case's own terms (``Case.forces``);
5. ``VelocityDamping``, where the run parameter ``damping`` is set;

with the frozen terms first (in that order), then the others (in that order).
A term is ``frozen`` when its value is fixed over one neighbour configuration
(gravity; viscosity, which 001_ Sec. 2.3 evaluates once per advection step from
the velocities of the configuration); the others are evaluated at every time
step. The frozen terms are summed once per configuration into the field
``prior`` when one of them varies from particle to particle; when all are
``uniform`` (the same for every particle: gravity, a body force) they are
re-added at every step instead, which saves the field.

To add a term: subclass ``ForceTerm``, give it ``add(ctx, acc)`` (an njit loop
that adds to ``acc[i]`` for ``kind[i] == MOVING``), and list it in the case's
``forces`` (docs/ARCHITECTURE.md).
"""

import numpy as np
from numba import njit

from .particles import MOVING, Field


class ForceTerm:
    """One term of the acceleration (module docstring)."""

    name = ""
    frozen = False  # fixed over a neighbour configuration: evaluated once per configuration
    uniform = False  # the same acceleration for every particle
    pairwise = True  # a sum over neighbour pairs (the wall forces take these, wall_forces.py)
    ghost_fields = ()  # fields the term reads from neighbours, refreshed before the momentum sum

    def add(self, ctx, acc):
        """Add this term's acceleration of the owned moving particles to ``acc``."""
        raise NotImplementedError

    def add_all(self, ctx, acc):
        """``add`` with every part of the term, including one that an implicit step takes instead
        (what the wall forces sum, wall_forces.py)."""
        self.add(ctx, acc)


@njit(cache=True)
def add_uniform(n, kind, acceleration, acc):
    """acc_i += acceleration for the moving particles in [0, n)."""
    dim = acc.shape[1]
    for i in range(n):
        if kind[i] == MOVING:
            for a in range(dim):
                acc[i, a] += acceleration[a]


class UniformAcceleration(ForceTerm):
    """The same acceleration for every moving particle, constant in time."""

    frozen = True
    uniform = True
    pairwise = False

    def __init__(self, acceleration):
        self.acceleration = np.asarray(acceleration, dtype=float)

    def add(self, ctx, acc):
        pa = ctx.particles
        add_uniform(pa.n_owned, pa.kind, self.acceleration, acc)


class Gravity(UniformAcceleration):
    """The acceleration of gravity, Case.gravity [m/s^2]."""

    name = "gravity"


@njit(cache=True)
def add_damping(n, kind, v, rate, acc):
    """acc_i -= rate v_i for the moving particles in [0, n)."""
    dim = acc.shape[1]
    for i in range(n):
        if kind[i] == MOVING:
            for a in range(dim):
                acc[i, a] -= rate * v[i, a]


class VelocityDamping(ForceTerm):
    """-c v: damping in proportion to each particle's mass, at the rate c [1/s] (the run parameter
    ``damping``), which takes kinetic energy out of the moving particles: a body brought to rest
    under its load this way (dynamic relaxation) is then run on without it by a restart from its
    settled frame. c near the body's lowest angular frequency damps its slowest motion fastest; far
    more slows the settling down, as an overdamped oscillator creeps. Not a wall force."""

    name = "damping"
    pairwise = False

    def __init__(self, rate):
        self.rate = float(rate)

    def add(self, ctx, acc):
        pa = ctx.particles
        add_damping(pa.n_owned, pa.kind, pa.v, self.rate, acc)


class Forces:
    """The ordered force terms of a run and their sum (module docstring)."""

    def __init__(self, terms):
        self.terms = tuple(terms)
        frozen = tuple(t for t in self.terms if t.frozen)
        others = tuple(t for t in self.terms if not t.frozen)
        if any(not t.uniform for t in frozen):
            self.per_configuration, self.per_step = frozen, others
        else:
            self.per_configuration, self.per_step = (), frozen + others
        self.fields = ()  # the sum's own fields: the frozen terms' acceleration, kept over a configuration
        if self.per_configuration:
            self.fields = (Field("prior", ("dim",), np.float64,
                                 "acceleration of the frozen force terms (gravity, viscosity) [m/s^2]"),)
        self.ghost_fields = tuple(dict.fromkeys(f for t in self.per_step for f in t.ghost_fields))

    def configure(self, ctx):
        """Once per configuration: the sum of the frozen terms into ``prior``."""
        if self.per_configuration:
            pa = ctx.particles
            prior = pa.prior[:pa.n_owned]
            prior[:] = 0.0
            for term in self.per_configuration:
                term.add(ctx, prior)

    def acceleration(self, ctx):
        """dv/dt of the owned moving particles at the current state, in the workspace's scratch
        (valid until the next scratch user)."""
        pa = ctx.particles
        n = pa.n_owned
        acc, = ctx.workspace.scratch(((n, pa.dim), np.float64))
        acc[:] = pa.prior[:n] if self.per_configuration else 0.0
        for term in self.per_step:
            term.add(ctx, acc)
        return acc
