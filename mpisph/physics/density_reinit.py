"""Density by kernel summation in place of the integrated one (001_ Eq. 8), at every neighbour
configuration where a case asks for it (``Case.density_reinit``): every scheme's ``configure``
calls ``reinitialise_density``."""

from numba import njit

from ..kernels import pair_w
from ..neighbours import pair_distance
from ..particles import MOVING


@njit(cache=True)
def density_summation(n, start, nbr, xc, kind, mass, rho, rho0, k, lattice_sum, free_surface):
    """Density reinitialisation by kernel summation (001_ Eq. 8).

    rho_i = sum_j m_j W_ij / (V0 sum_j W_ij^0), self term included, with V0 =
    dp^d and sum W^0 the sum over a full lattice (``lattice_sum`` is their
    product). With equal masses m = rho0 V0 this is Eq. 8, rho0 sum W / sum W^0;
    weighting by mass keeps an initial pressure field (masses set from it).
    With ``free_surface`` the summed density only replaces the evolved one
    where it is larger; below it the evolved excess is kept in proportion,
    rho = rho_sum + max(0, rho* - rho_sum) rho0 / rho*, so that particles
    with a truncated kernel near a free surface are not dragged below rho0.
    """
    for i in range(n):
        if kind[i] != MOVING:
            continue
        acc = mass[i] * pair_w(k, 0.0, i, i)
        for s in range(start[i], start[i + 1]):
            j = nbr[s]
            acc += mass[j] * pair_w(k, pair_distance(xc, i, j), i, j)
        rho_sum = acc / lattice_sum
        if free_surface:
            rho[i] = rho_sum + max(0.0, rho[i] - rho_sum) * rho0 / rho[i]
        else:
            rho[i] = rho_sum


def reinitialise_density(ctx, scheme):
    """The density of the owned moving particles by ``density_summation``, in a scheme's
    ``configure``, unless its ``density_reinit`` (Case.density_reinit) is "none"; returns whether
    it did (the caller then sends rho to the ghosts, with whatever it derives from it)."""
    if scheme.density_reinit == "none":
        return False
    pa = ctx.particles
    density_summation(pa.n_owned, ctx.start, ctx.nbr, ctx.xc, pa.kind, pa.mass, pa.rho, scheme.material.rho0,
                      ctx.kernel.params, scheme.lattice_sum, scheme.density_reinit == "free_surface")
    return True
