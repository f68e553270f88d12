"""Where the mu(I) law is well-posed (Barker et al. 2015; Barker & Gray 2017).

The incompressible equations of motion with the friction mu(I) are well-posed
only where

    C(I) = 4 nu^2 - 4 nu + mu^2 (1 - nu / 2)^2 < 0,   nu = I mu'(I) / mu(I)

(Barker, Schaeffer, Bohorquez & Gray 2015, J. Fluid Mech. 779, 794-818; the
form of Barker & Gray 2017, J. Fluid Mech. 828, 5-32, their Eq. 3.9). Where
C > 0 a perturbation of wavenumber k grows at a rate that rises without bound
with k, so a discretisation resolves faster growth the finer it is and its
results depend on the resolution rather than converge. C(0) = mu(0)^2 > 0:
rate-independent friction (nu = 0) is ill-posed. For the law of 004_ Eq. 7 nu
rises from 0 at I = 0 to a largest value near I = I_0 and falls again, and the
law is well-posed in one window of inertial numbers (or nowhere): glass beads
(004_ Table 1, I_0 = 0.279) from I = 0.019 to 0.85, the 0.32 mm sand of
Lube's columns (I_0 = 2.65) from 0.43 to 1.8 (tests/test_well_posedness.py).

The criterion is the incompressible one; 004_'s grains are weakly compressible
(Mach 0.1) and dilate with I (Eq. 8). Heyman, Delannay, Tabuteau & Valance
(2017, J. Fluid Mech. 830; arXiv 1609.01502) show that the compressible
equations are well-posed when enough dissipation goes with volume changes: a
bulk stress mu_b p tr(D) / |D| I beside the shear stress mu p dev(D) / |D|,
|D| = sqrt(D:D / 2) = gamma_dot / 2, with mu_b > 1 - 7 mu / 6 in their model,
where the pressure follows the volume fraction through phi(I) (stiff grains).
For the short waves that decide well-posedness the density is frozen and only
the stress's dependence on the velocity gradient counts; about a simple shear,
with n = d ln p / d ln gamma_dot and nu_b = d ln mu / d ln gamma_dot at fixed
density, a longitudinal wave along the shear's stretching axis, k = (1, 1, 0)
/ sqrt 2, has the stiffness

    p / |D| (2 mu_b - n + mu (n + nu_b + (D - 2) / 3))

(the divergence of the linearised stress projected on k: -n p r from the
pressure, mu p (dev(k k) + (nu_b + n - 1) r D_0) / |D| from the shear term,
r = d|D| / |D| = 1 for this wave, and the bulk term), so the equations are
ill-posed unless mu_b >= n / 2 - mu (n + nu_b + (D - 2) / 3) / 2
(``compressible_bulk_friction_bound``). With stiff grains (n = 2, nu_b = 0)
this is the 1 - 7 mu / 6 of Heyman et al.'s abstract in 3D and 1 - mu in 2D;
their arXiv v1's abstract gives 3 - 7 mu / 2 and 2 - 2 mu, D times each, which
a bulk term written on tr(D) / D gives. tests/test_compressible_well_posedness.py
checks that no other direction of wave or of velocity needs more, by the
eigenvalues of the linearised stress over all directions. 004_'s grains are
softer: at fixed density Eq. 44 gives n and nu_b below 2 and nu
(``rate_exponents``), and both tend to 0 as I does, where the bound falls to
-mu / 6 in 3D and 0 in 2D. The solver's viscous stresses carry the bulk
frictions of ``solver_bulk_friction``. This is the limit of short waves
only: longer waves, for which the grains are as good as incompressible, obey
the incompressible criterion above; where the one hands over to the other,
and how fast the waves grow on either side, is mpisph/shear_stability.py's.
These functions tell in which range of I a flow runs, not how the discrete
scheme behaves.

partially_regularised_friction is Barker & Gray 2017's remedy below the window, kept to measure
what it would do to a material (scripts/well_posedness.py --materials, docs/COLLAPSES.md); the
solver's laws do not use it.
"""

import math

import numpy as np

from .particles import MOVING
from .physics.mu_i_law import MuIParams, friction
from .references import MU_I_MATERIALS


def table_1_law(name, **changes):
    """MuIParams of a material of 004_ Table 1 (references.MU_I_MATERIALS), with ``changes``; the
    fields that the incompressible criterion does not read (phi, rho_s0, K_t, tau_0, m_0) are
    placeholders."""
    m = MU_I_MATERIALS[name]
    mu_s, mu_2 = (math.tan(math.radians(m[k])) for k in ("mu_s_deg", "mu_2_deg"))
    return MuIParams(mu_s, mu_2, m["I_0"], 0.0, 0.6, 0.5, 2500.0, m["d"], 1e-5, 100.0, 1.0)._replace(**changes)


def ill_posedness(I, m):
    """C(I) of the module docstring, for a number or an array of I: negative where the law is
    well-posed. mu is mu_i_law.friction (004_ Eq. 7, Eq. 18 with m.I_s > 0), mu' its derivative
    (mu_2 - mu_s) I_0 / (I + I_s + I_0)^2."""
    I = np.asarray(I, dtype=float)
    return criterion(friction_exponent(I, m), friction(I, m))


def criterion(nu, mu):
    """C of the module docstring from nu = I mu'/mu and mu."""
    return 4.0 * nu * nu - 4.0 * nu + mu * mu * (1.0 - 0.5 * nu) ** 2


def well_posed_window(m, lowest=1e-9, highest=1e3, points=2400):
    """(I_1, I_2): the inertial numbers between which C(I) < 0, each to a relative 1e-10 by
    bisection from a logarithmic scan of [lowest, highest] I_0 (C depends on I / I_0 where I_s = 0);
    an end beyond the scan is 0 or inf (a law of nearly no friction, mu of a tenth of a degree, is
    well-posed up to some 1e4 I_0); None where C >= 0 throughout; ValueError where the scan finds
    more than one window."""
    I = m.I_0 * np.geomspace(lowest, highest, points)
    well = ill_posedness(I, m) < 0.0
    if not well.any():
        return None
    first, last = np.flatnonzero(well)[[0, -1]]
    if not well[first:last + 1].all():
        raise ValueError(f"mu(I) is well-posed in more than one window inside [{lowest:g}, {highest:g}] I_0")
    well_posed = lambda x: ill_posedness(x, m) < 0.0
    return (0.0 if first == 0 else _crossing(well_posed, I[first - 1], I[first]),
            math.inf if last == points - 1 else _crossing(well_posed, I[last], I[last + 1]))


def well_posed_range(lower, upper):
    """'only for lower < I < upper' of a ``well_posed_window``, an end at 0 or inf left out."""
    if lower > 0.0 and upper < math.inf:
        return f"only for {lower:.3g} < I < {upper:.3g}"
    if lower > 0.0 or upper < math.inf:
        return f"only for I > {lower:.3g}" if lower > 0.0 else f"only for I < {upper:.3g}"
    return "for every I"


def _crossing(holds, lo, hi):
    """The point in (lo, hi), both positive, where the predicate ``holds`` changes, by bisection in
    the logarithm."""
    at_lo = holds(lo)
    while hi - lo > 1e-10 * hi:
        mid = math.sqrt(lo * hi)
        if holds(mid) == at_lo:
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)


def partially_regularised_friction(I, m, alpha):
    """Barker & Gray 2017's partial regularisation of the law (their Sec. 6): below the lower end
    I_1 of the window mu = sqrt(alpha / ln(A / I)) with A = I_1 exp(alpha / mu(I_1)^2), so that mu is
    continuous at I_1; 004_'s law (friction) from I_1 up. The form is the one the public OpenFOAM
    module alexjarosch/OpenFOAM-muI (muIreg) codes with the citation of the paper's Eq. 6.4; the
    paper's body was not at hand. Written as mu^2 = mu_1^2 / (1 + (mu_1^2 / alpha) ln(I_1 / I)),
    mu_1 = mu(I_1), the friction falls below I_1 and vanishes as I -> 0: the law loses its yield
    stress. Its nu = I mu'/mu is mu^2 / (2 alpha)."""
    I = np.asarray(I, dtype=float)
    lower = well_posed_window(m)[0]
    mu_1 = friction(lower, m)
    below = mu_1 ** 2 / (1.0 + mu_1 ** 2 / alpha * np.log(lower / np.minimum(I, lower)))
    return np.where(I < lower, np.sqrt(below), friction(I, m))


def partial_regularisation_alphas(m):
    """(alpha_lo, alpha_hi): the alphas for which partially_regularised_friction is well-posed at
    every I below the window. With nu = mu^2 / (2 alpha) the criterion reads
    nu (4 nu - 4 + 2 alpha (1 - nu / 2)^2) < 0, i.e. alpha < 2 (1 - nu) / (1 - nu / 2)^2, whose right
    side falls as nu rises; nu is largest at I_1, so the criterion at I_1 holds it at every I below.
    Each end to a relative 1e-10 by bisection from a scan of (0, 2]."""
    mu_1 = friction(well_posed_window(m)[0], m)
    admissible = lambda alpha: criterion(0.5 * mu_1 ** 2 / alpha, mu_1) < 0.0
    alphas = np.linspace(0.0, 2.0, 2001)[1:]  # inadmissible at both ends
    inside = np.array([admissible(a) for a in alphas])
    if not inside.any():
        return None
    first, last = np.flatnonzero(inside)[[0, -1]]
    return (_crossing(admissible, alphas[first - 1], alphas[first]),
            _crossing(admissible, alphas[last], alphas[last + 1]))


def compressible_bulk_friction_bound(mu, n, nu_b, dim):
    """The least bulk friction mu_b for which the compressible mu(I) equations are well-posed about a
    shear flow of friction ``mu`` whose pressure and friction rise with the strain rate at fixed
    density as gamma_dot^n and gamma_dot^nu_b (module docstring): n / 2 - mu (n + nu_b + (D - 2) / 3) / 2."""
    return 0.5 * n - 0.5 * mu * (n + nu_b + (dim - 2.0) / 3.0)


def rate_exponents(I, grain_ratio, m, dim):
    """(n, nu_b) = d ln (p, mu) / d ln gamma_dot at fixed bulk density of 004_'s grains at inertial
    number ``I`` and grain density ``grain_ratio`` x = rho_s / rho_s0 (arrays or numbers). Eq. 44 ties
    them to gamma_dot^2 through F(x) = (phi_max - phi)^2 (x - 1) x^(2/D - 1), phi = rho / (x rho_s0)
    (mu_i_law.py), so that d ln x / d ln gamma_dot = 2 / (a + b + 2/D - 1), a = 2 phi / (phi_max -
    phi) = d ln (phi_max - phi)^2 / d ln x, b = x / (x - 1); p = (x - 1) / K_t gives n = 2 b / (...)
    and I = (phi_max - phi) / (phi_max - phi_min) gives nu_b = nu a / (...), nu = I mu'(I) / mu.
    Stiff grains (x -> 1): n -> 2, nu_b -> 0; I -> 0: both -> 0."""
    I, x = np.asarray(I, dtype=float), np.asarray(grain_ratio, dtype=float)
    phi = m.phi_max - (m.phi_max - m.phi_min) * I
    with np.errstate(divide="ignore", invalid="ignore"):
        a = 2.0 * phi / ((m.phi_max - m.phi_min) * I)
        b = x / (x - 1.0)
        total = a + b + 2.0 / dim - 1.0
        n = np.where(x > 1.0, np.where(I > 0.0, 2.0 * b / total, 0.0), 2.0)
        nu_b = np.where((x > 1.0) & (I > 0.0), friction_exponent(I, m) * a / total, 0.0)
    return n, nu_b


def friction_exponent(I, m):
    """nu = I mu'(I) / mu(I) of 004_'s law (friction), mu' = (mu_2 - mu_s) I_0 / (I + I_s + I_0)^2."""
    I = np.asarray(I, dtype=float)
    return I * (m.mu_2 - m.mu_s) * m.I_0 / (I + m.I_s + m.I_0) ** 2 / friction(I, m)


def bulk_part(viscous_form, viscous_stress, dim):
    """c_b of the solver's viscous stress 2 eta (dev(eps) + c_b tr(eps) I) (physics/mu_i.py), its bulk
    viscosity over 2 eta: Eq. 27's pair term, eta (lap v + 2 grad div v), (1 + 2 / D) / 2; the
    corrected full stress 2 eta eps, 1 / D; the deviatoric stress and the deviatoric pair term, 0."""
    if viscous_stress == "deviatoric":
        return 0.0
    return 0.5 * (1.0 + 2.0 / dim) if viscous_form == "cleary" else 1.0 / dim


def solver_bulk_friction(mu, viscous_form, viscous_stress, dim):
    """The bulk friction mu_b = xi mu / (2 eta) = c_b mu of the solver's viscous stress (bulk_part)."""
    return bulk_part(viscous_form, viscous_stress, dim) * mu


def compressible_ill_posed_share(frame, case):
    """The share of a frame's viscous dissipation (dissipation_rate) at grains whose solver bulk
    friction lies below compressible_bulk_friction_bound for their state (the frame's I and grain
    density, ``case``'s material and viscous stress); NaN in a frame that dissipates nothing."""
    power = dissipation_rate(frame)
    total = power.sum()
    if not total > 0.0:
        return math.nan
    m, dim = case.material.params, case.dim
    I = frame["inertial_number"]
    mu = friction(I, m)
    n, nu_b = rate_exponents(I, frame["rho_s"] / m.rho_s0, m, dim)
    options = case.scheme_options
    short = solver_bulk_friction(mu, options["viscous_form"], options["viscous_stress"], dim) < \
        compressible_bulk_friction_bound(mu, n, nu_b, dim)
    return float(power[short].sum() / total)


def dissipation_rate(frame):
    """Each particle's viscous dissipation rate eta gamma_dot^2 m / rho [W] (0 for a wall)."""
    return np.where(frame["kind"] == MOVING, frame["eta"] * frame["gamma_dot"] ** 2 * frame["mass"] / frame["rho"],
                    0.0)


def ill_posed_dissipation_share(frame, window):
    """The share of a frame's viscous dissipation (dissipation_rate) that happens at inertial
    numbers outside ``window`` (I_1, I_2) (None: all of it): how much of the flow runs where the law
    is ill-posed. NaN in a frame that dissipates nothing."""
    power = dissipation_rate(frame)
    total = power.sum()
    if not total > 0.0:
        return math.nan
    if window is None:
        return 1.0
    I = frame["inertial_number"]
    return float(power[(I <= window[0]) | (I >= window[1])].sum() / total)


def ill_posed_energy_share(frames, window):
    """The share of the energy a run dissipated at inertial numbers outside ``window``
    (energy_share of ill_posed_dissipation_share)."""
    return energy_share(frames, lambda f: ill_posed_dissipation_share(f, window))


def energy_share(frames, share):
    """The share of the energy a run dissipated, the frames' dissipation rates integrated in time
    by trapezoids, where ``share`` (a frame's share of its dissipation rate) counts it; NaN where
    nothing was dissipated."""
    t = np.array([f["t"] for f in frames])
    rate = np.array([dissipation_rate(f).sum() for f in frames])
    shares = np.nan_to_num(np.array([share(f) for f in frames]))
    energy = np.trapezoid(rate, t)
    return float(np.trapezoid(rate * shares, t) / energy) if energy > 0.0 else math.nan
