"""What a scheme, a force term or a stabiliser sees of the current neighbour configuration.

The solver makes one ``StepContext`` per configuration, after the halo and the
neighbour lists are built, and hands it to every part of the step; no part
reads the solver itself. It holds:

- ``particles``: owned particles followed by ghosts (particles.py);
- ``start``, ``nbr``: the neighbour lists of the owned material particles (neighbours.py);
- ``xc``: the positions the lists were built on (frozen for the configuration);
- ``kernel``: the ``Kernel`` (kernels.py), ``kernel.params`` for the numba loops;
- ``workspace``: scratch arrays reused from step to step (workspace.py);
- ``refresh(names)``: send the current values of the named fields to the ghosts;
- ``correction_matrices()``: B of 000_ Eq. 24 on this configuration, computed once;
- ``advection_step``: how long the configuration is kept (the minimum over ranks of the
  time-step criteria), set by the solver before the stabilisers are applied;
- ``max_over_ranks(value)``: the largest of a value over the ranks.
"""

import math
from dataclasses import dataclass, field

import numpy as np
from mpi4py import MPI

from . import tensors
from .correction import correction_matrix


@dataclass
class StepContext:
    """One neighbour configuration and the services the parts of a step share."""

    particles: object
    start: np.ndarray
    nbr: np.ndarray
    xc: np.ndarray
    kernel: object
    halo: object
    workspace: object
    advection_step: float = math.nan
    _B: np.ndarray | None = field(default=None, repr=False)

    def refresh(self, names):
        """Send the current values of the fields ``names`` of the owned particles to their ghosts."""
        self.halo.refresh(self.particles, list(names))

    def max_over_ranks(self, value):
        """The largest of ``value`` over the ranks (exact: a maximum does not round)."""
        return self.halo.comm.allreduce(value, op=MPI.MAX)

    def correction_matrices(self):
        """B of 000_ Eq. 24 for the owned particles on this configuration, computed when first
        asked, into the field ``B`` when the particles have one (else into the workspace)."""
        if self._B is None:
            pa = self.particles
            n = pa.n_owned
            self._B = (pa.B[:n] if "B" in pa.arrays
                       else self.workspace.get("correction_matrix", n, (tensors.size(pa.dim),)))
            correction_matrix(n, self.start, self.nbr, self.xc, pa.mass, pa.rho, pa.kind, self.kernel.params,
                              self._B)
        return self._B
