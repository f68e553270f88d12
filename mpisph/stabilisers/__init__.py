"""Corrections that keep particle distributions regular, by name.

``STABILISERS`` maps each name a case may list in ``Case.stabilisers`` to its
class (base.py says what a stabiliser is). ``none`` is the empty list; several
remedies combine as names joined by ``+`` ("artificial_stress+utvf"), applied in
that order, each at most once and at most one of them a position shift
(``shifts_positions``: the transport-velocity corrections and particle shifting,
which are rival rules for the same move).
"""

from ..errors import InputError

from .adaptive_kernel import AdaptiveKernel
from .artificial_stress import ArtificialStress
from .shifting import ParticleShifting
from .transport_velocity import LimitedTransportVelocity, TransportVelocity, UnifiedTransportVelocity

STABILISERS = {c.name: c for c in (LimitedTransportVelocity, TransportVelocity, UnifiedTransportVelocity,
                                   ArtificialStress, ParticleShifting, AdaptiveKernel)}


SEPARATOR = "+"  # between the names of a combination


def stabiliser_names(text):
    """The names in ``text``: "none", one name, or names joined by ``SEPARATOR`` in the order they
    apply; InputError for a name given twice or for two position shifts (module docstring). A name
    that is no stabiliser passes here: parts.make_parts refuses it."""
    names = () if text.strip() == "none" else tuple(t.strip() for t in text.split(SEPARATOR))
    twice = [name for k, name in enumerate(names) if name in names[:k]]
    if twice:
        raise InputError(f"stabiliser {twice[0]!r} is listed twice in {text!r}")
    shifts = [name for name in names if name in STABILISERS and STABILISERS[name].shifts_positions]
    if len(shifts) > 1:
        raise InputError(f"stabilisers {shifts[0]} and {shifts[1]} both shift the positions: combine at most one "
                         f"of {', '.join(n for n, c in STABILISERS.items() if c.shifts_positions)} with the others")
    return names
