"""What every mu(I) case shares (004_): the scheme's discretisation options as case parameters,
the scheme and integrator they select, the grain compressibility of a chosen Mach number, and side
walls across the plane of a 2D run."""

import math

from .case import ANGLE, Param
from .errors import InputError
from .physics.implicit_viscosity import TOLERANCE
from .physics.mu_i import (LAW_PRESSURES, LAW_STRAIN_RATES, PRESSURE_FORMS, VISCOSITY_MEANS, VISCOUS_FORMS,
                          VISCOUS_STEPS, VISCOUS_STRESSES)
from .physics.side_walls import SideWallFriction

MACH = 0.1  # 004_ Secs. 5.1 and 5.2 choose K_t for this Mach number
WALL_CREEP = 0.01  # the side walls' regularising speed over sqrt(g H) (physics/side_walls.py)

# The corrected viscous stress taken implicitly and the three options that make the friction law see
# the continuum's stresses and strain rate (physics/mu_i.py, docs/INCLINE.md), as --set words: what
# brings the CI-sized incline to its uniform flow (scripts/validate.py, section inclined_plane_steady).
CONSISTENT_MU_I = ("viscous_form=corrected_stress", "viscous_step=implicit", "pressure_form=isotropic",
                   "law_pressure=carried_mean", "law_strain_rate=deviatoric_kernel_mean")

# The corrected viscous stress without its bulk part (Eq. 4 with xi = 0) and a regularisation time
# 33 times 004_'s for the columns, as --set words: deposits that come to rest and columns that still
# fail at once (physics/mu_i.py, docs/COLLAPSES.md, scripts/validate.py).
DEVIATORIC_MU_I = ("viscous_form=corrected_stress", "viscous_step=implicit", "viscous_stress=deviatoric", "m_0=40")


def mach_compressibility(rho0, speed_squared, mach=MACH):
    """K_t [1/Pa] that puts a flow of speed U (``speed_squared`` = U^2 [m^2/s^2]) at Mach number ``mach``
    in grains of bulk density ``rho0`` at rest: the sound speed of Eqs. 9, 41 is c0 = 1/sqrt(K_t rho0),
    so K_t = mach^2/(rho0 U^2). (004_ Tables 2 and 3 print about 1/(rho0 c0) instead, which is not a
    compressibility: Pa^-1 needs c0^2.)"""
    return mach**2 / (rho0 * speed_squared)


def mu_i_params(alpha_doc, viscous_step):
    """Typed parameters of the mu_i scheme's options (physics/mu_i.py) and of 004_'s single time step
    (Eq. 39), with the case's word on alpha and its default viscous step."""
    return {
        "alpha": Param(0.0, "-", f"artificial viscosity (Eq. 38; {alpha_doc})"),
        "beta_max": Param(1.5, "-", "cap of the Morris wall factor (Eq. 36)", positive=True),
        "viscous_form": Param("cleary", "-", "viscous term: Eq. 27's pair term (its 8 as 2 (D + 2)), or the corrected stress divergence",
                              choices=VISCOUS_FORMS),
        "viscous_step": Param(viscous_step, "-", "explicit: Eq. 39's viscous limit bounds the step; implicit: the "
                              "viscous term backward in time (physics/implicit_viscosity.py)",
                              choices=VISCOUS_STEPS),
        "viscous_stress": Param("full", "-", "viscous stress: full, 2 eta eps or Eq. 27's pair term (each with a "
                                "bulk viscosity), or deviatoric, 2 eta dev(eps), Eq. 4 with no bulk viscosity, or "
                                "the pair term that tends to its divergence (physics/mu_i.py)",
                                choices=VISCOUS_STRESSES),
        "viscosity_mean": Param("secant", "-", "viscosity of a particle pair: harmonic (Eq. 37), arithmetic or "
                                "secant (mu_i_law.pair_viscosity)", choices=VISCOSITY_MEANS),
        "pressure_form": Param("symmetric", "-", "pressure term: symmetric (Eq. 27 as printed) or isotropic, whose "
                               "pair sum carries no shear stress (physics/mu_i.py)", choices=PRESSURE_FORMS),
        "law_pressure": Param("state", "-", "pressure of the friction law: state (Eq. 41), carried, the share of it "
                              "the pairs carry, or carried_mean, its kernel mean (physics/mu_i.py)",
                              choices=LAW_PRESSURES),
        "law_strain_rate": Param("own", "-", "strain rate of the friction law: own (each grain's, Eq. 31), "
                                 "kernel_mean, the modulus of its kernel mean, or deviatoric_kernel_mean, that of "
                                 "the mean's deviator (physics/mu_i.py)",
                                 choices=LAW_STRAIN_RATES),
        "viscous_tolerance": Param(TOLERANCE, "-", "where the implicit viscous kick's conjugate gradients stop: "
                                   "the RMS velocity residual over the case's reference speed "
                                   "(physics/implicit_viscosity.py)", positive=True),
        "time_stepping": Param("single", "-", "single: every quantity at the current positions, as 004_; dual "
                               "(001_ Eqs. 9-11) keeps a configuration for 0.25 h/|v|, over which a sheared layer "
                               "dilates and runs away (docs/VALIDATION.md)", choices=("dual", "single")),
    }


def mu_i_scheme(p):
    """Case keywords of the mu_i scheme (stepped by its own integrator, symplectic Verlet) with the
    options of ``mu_i_params``."""
    return dict(scheme="mu_i",
                scheme_options={"alpha": p.alpha, "beta_max": p.beta_max, "viscous_form": p.viscous_form,
                                "viscous_step": p.viscous_step, "viscous_stress": p.viscous_stress,
                                "viscosity_mean": p.viscosity_mean,
                                "pressure_form": p.pressure_form, "law_pressure": p.law_pressure,
                                "law_strain_rate": p.law_strain_rate, "viscous_tolerance": p.viscous_tolerance})


def side_wall_params():
    """Typed parameters of two side walls across the plane of a 2D run (physics/side_walls.py)."""
    return {
        "channel_width": Param(0.0, "m", "gap between two side walls across the plane, whose friction the grains "
                               "feel (physics/side_walls.py); 0: none, plane strain"),
        "wall_friction_deg": Param(0.0, "deg", "friction angle of the side walls on the grains, mu_w = tan",
                                   bounds=ANGLE),
    }


def side_walls(p, height):
    """The case's force terms of the side walls of ``p`` (side_wall_params) on grains of a layer or
    column ``height`` high: none for channel_width = 0, else their friction, regularised below
    WALL_CREEP sqrt(g height)."""
    if p.channel_width == 0 and p.wall_friction_deg != 0:
        raise InputError(f"wall_friction_deg = {p.wall_friction_deg:g} is the friction of side walls, which "
                         "channel_width = 0 leaves out: give channel_width too")
    if p.channel_width == 0:
        return []
    if p.channel_width < 0:
        raise InputError(f"side walls need channel_width > 0, not {p.channel_width} m")
    if p.law_pressure == "carried":
        raise InputError("side walls take the law's pressure, which law_pressure=carried does not keep: use "
                         "carried_mean or state")
    return [SideWallFriction(p.channel_width, math.tan(math.radians(p.wall_friction_deg)),
                             WALL_CREEP * math.sqrt(p.g * height))]
