"""The parts of a run, made from a case and its parameters.

    kernel       kernels.Kernel of the run's ``kernel`` and h = h_factor dp (adaptive when a
                 stabiliser adapts it)
    scheme       schemes.SCHEMES[case.scheme]
    forces       forces.Forces: gravity, the scheme's terms, the stabilisers', the case's
    stabilisers  stabilisers.STABILISERS[name](case, params) for each of case.stabilisers, in order
    integrator   integrators.INTEGRATORS[case.integrator] of the scheme and the forces
    criteria     integrators.time_step.TimeStepCriteria of the run's ``time_stepping``

and the per-particle fields they need between them.
"""

from dataclasses import dataclass

from . import surface
from .errors import InputError
from .forces import Forces, Gravity, VelocityDamping
from .integrators import INTEGRATORS
from .integrators.time_step import TimeStepCriteria
from .kernels import Kernel
from .particles import CORE_FIELDS
from .schemes import make_scheme
from .stabilisers import STABILISERS


@dataclass
class Parts:
    """Everything a run computes with, besides the particles and the engine."""

    kernel: object
    scheme: object
    forces: object
    stabilisers: tuple
    integrator: object
    criteria: object

    @property
    def needs_surface(self):
        """Whether the free-surface classes are computed every configuration (surface.py)."""
        return self.scheme.needs_surface or any(s.needs_surface for s in self.stabilisers)

    @property
    def fields(self):
        """Core fields, then the kernel's, the integrator's, the scheme's, the forces', the
        stabilisers' and the surface fields when needed; each name once."""
        fields = (CORE_FIELDS + self.kernel.fields + self.integrator.fields + self.scheme.fields
                  + self.forces.fields + sum((s.fields for s in self.stabilisers), ()))
        if self.needs_surface:
            fields += surface.FIELDS
        return tuple({f.name: f for f in fields}.values())

    @property
    def frame_fields(self):
        """The fields a frame holds: ``fields``, then the scheme's output-only ``derived``."""
        return self.fields + self.scheme.derived


def make_parts(case, params):
    """The Parts of ``case`` with the run parameters ``params``; InputError for an unknown name."""
    unknown = [name for name in case.stabilisers if name not in STABILISERS]
    if unknown:
        raise InputError(f"stabiliser must be none or one of {', '.join(STABILISERS)}, not {unknown[0]!r}")
    stabilisers = tuple(STABILISERS[name](case, params) for name in case.stabilisers)
    kernel = Kernel(params["kernel"], params["h_factor"] * case.dp, case.dim,
                    adaptive=any(s.adapts_kernel for s in stabilisers))
    scheme = make_scheme(case, kernel)
    integrator_name = case.integrator or scheme.integrator
    if integrator_name not in INTEGRATORS:
        raise InputError(f"integrator must be one of {', '.join(INTEGRATORS)}, not {integrator_name!r}")
    damping = [VelocityDamping(params["damping"])] if params["damping"] > 0.0 else []
    terms = (Gravity(case.gravity), *scheme.forces(), *(t for s in stabilisers for t in s.forces()), *case.forces,
             *damping)
    forces = Forces(terms)
    integrator = INTEGRATORS[integrator_name](scheme, forces)
    criteria = TimeStepCriteria(params["time_stepping"], kernel.h, case.u_ref, params["max_time_step"])
    return Parts(kernel, scheme, forces, stabilisers, integrator, criteria)
