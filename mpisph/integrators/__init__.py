"""Time integration, apart from the schemes: integrators by name, and the time-step criteria.

``INTEGRATORS`` maps each name a case may give in ``Case.integrator`` to its
class. An integrator is built from the run's scheme and ``Forces`` and
advances one time step with ``step(ctx, dt)``, spelling out the order of its
sub-steps and where ghosts are refreshed; ``fields`` are the per-particle
fields it needs itself.
"""

from .position_verlet import PositionVerlet
from .predictor_corrector import PredictorCorrector
from .symplectic_verlet import SymplecticVerlet

INTEGRATORS = {c.name: c for c in (PositionVerlet, SymplecticVerlet, PredictorCorrector)}
