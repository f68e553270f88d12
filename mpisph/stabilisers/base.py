"""What a stabiliser is: a correction applied once per neighbour configuration.

A case lists its stabilisers in order (``Case.stabilisers``); after the
scheme's configuration work, the frozen force terms and the time-step limits
(``ctx.advection_step``), the solver calls ``apply(ctx)`` of each in that
order; before that, right after the neighbour lists, its ``prepare(ctx)``. A
stabiliser may shift positions (the transport-velocity corrections, particle
shifting) and correct fields, adapt the kernel (``adapts_kernel``: the knots of
002_'s B-spline), declare fields it needs (``fields``), ask
for the free-surface classes (``needs_surface``) and add force terms to the
acceleration (``forces()``, summed after the scheme's; forces.py).
"""


class Stabiliser:
    """Base of every stabiliser; the defaults are what a stabiliser without that part does."""

    name = ""
    needs_surface = False
    shifts_positions = False  # moves the particles in ``apply`` (one such per combination: __init__.py)
    fields = ()
    adapts_kernel = False  # sets the knots of the adaptive kernel (kernels.py) in ``prepare``

    def __init__(self, case, params):
        """A stabiliser is made for one case (``Case``) and its parameter values ``params``; those
        that need the spacing or a parameter of their own keep it."""

    def forces(self):
        """Force terms this stabiliser adds to the acceleration, in order."""
        return ()

    def prepare(self, ctx):
        """Once per configuration, right after the neighbour lists, before any pair sum: what the
        configuration's pair sums depend on (the adaptive kernel's knots)."""

    def apply(self, ctx):
        """Once per configuration, after the scheme's configuration work and the time-step limits."""
