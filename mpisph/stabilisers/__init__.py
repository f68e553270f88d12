"""Corrections that keep particle distributions regular, by name.

``STABILISERS`` maps each name a case may list in ``Case.stabilisers`` to its
class (base.py says what a stabiliser is). ``none`` is the empty list.
"""

from .adaptive_kernel import AdaptiveKernel
from .artificial_stress import ArtificialStress
from .shifting import ParticleShifting
from .transport_velocity import LimitedTransportVelocity, TransportVelocity, UnifiedTransportVelocity

STABILISERS = {c.name: c for c in (LimitedTransportVelocity, TransportVelocity, UnifiedTransportVelocity,
                                   ArtificialStress, ParticleShifting, AdaptiveKernel)}


def stabiliser_names(text):
    """The list of names in ``text``: "none", one name, or names separated by commas."""
    names = [] if text.strip() == "none" else [t.strip() for t in text.split(",")]
    return tuple(names)
