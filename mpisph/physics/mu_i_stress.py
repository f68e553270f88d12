"""The Cauchy stress of the mu_i scheme's grains, for frames (physics/mu_i.py).

The scheme steps pressure and viscosity, not a stress; a frame gets the stress whose divergence
its momentum sum tends to, from each particle's pressure p, viscosity eta and strain rate eps:

    sigma = -p I + 2 eta_s eps + zeta tr(eps) I

with the options of physics/mu_i.py (pair_term_factors says where each continuum limit comes from):

    viscous_form       viscous_stress   the momentum tends to          zeta
    corrected_stress   full             div(2 eta eps)                 0
    either             deviatoric       div(2 eta dev(eps))            -2 eta / D
    cleary (Eq. 27)    full             eta (lap v + 2 grad div v)     eta

and eta_s = eta, plus the shear viscosity of 004_ Eq. 38's artificial viscosity where alpha > 0:
applied to every pair it is Eq. 27's pair term with eta_a = rho alpha h c0 / (2 (D + 2))
(references.pair_viscosity_of_alpha), which adds eta_a to eta_s and to zeta. tr and dev are
those of the model's D dimensions. A 2D run is read as plane strain with sigma_zz = -p, since eps
has no zz part and the model's pressure is the mean of its D normal stresses. The stress is packed
as the solids' (tensors.py: 3 x 3, VTK order), tension positive; it is zero on wall particles,
whose strain rate the scheme leaves unset.

What the frame's stress leaves out: with ``pressure_form = isotropic`` or ``law_pressure = carried``
the pairs carry s p of the pressure (s = tr(B^-1) / D, 0.94-0.97 in a flowing layer), and the
particles' jostle carries a stress of its own outside the law (docs/INCLINE.md); the stress here
is the continuum's, -p I with the grains' own pressure of Eq. 41.
"""

import numpy as np
from numba import njit

from ..particles import MOVING
from ..references import pair_viscosity_of_alpha
from ..tensors import SYM3, component


def bulk_factor(dim, corrected, deviatoric):
    """zeta / eta of the module docstring's table for the scheme's options."""
    if deviatoric:
        return -2.0 / dim
    return 0.0 if corrected else 1.0


@njit(cache=True)
def granular_stress(n, kind, p, rho, strain, eta, bulk, nu_alpha, stress):
    """``stress`` [0, n) = the packed 3 x 3 sigma of the module docstring of the moving particles
    (eps packed in the model's D dimensions), zero on the others."""
    dim = 2 if strain.shape[1] == 3 else 3
    for i in range(n):
        for c in range(6):
            stress[i, c] = 0.0
        if kind[i] != MOVING:
            continue
        eta_a = rho[i] * nu_alpha
        shear = 2.0 * (eta[i] + eta_a)
        trace = 0.0
        for a in range(dim):
            trace += strain[i, component(dim, a, a)]
        isotropic = -p[i] + (bulk * eta[i] + eta_a) * trace
        for a in range(dim):
            for b in range(a, dim):
                stress[i, SYM3[a, b]] = shear * strain[i, component(dim, a, b)] + (isotropic if a == b else 0.0)
        if dim == 2:
            stress[i, SYM3[2, 2]] = -p[i]


def granular_stress_of(scheme, pa, n):
    """The packed stress (n, 6) of the owned particles [0, n) of the mu_i ``scheme``."""
    stress = np.empty((n, 6))
    nu_alpha = pair_viscosity_of_alpha(scheme.alpha, scheme.h, scheme.material.c0, scheme.dim)
    granular_stress(n, pa.kind, pa.p, pa.rho, pa.strain, pa.eta,
                    bulk_factor(scheme.dim, scheme.corrected, scheme.deviatoric_stress), nu_alpha, stress)
    return stress
