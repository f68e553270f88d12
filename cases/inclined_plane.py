"""Uniform granular flow down an inclined plane, mu(I) rheology, periodic along the slope (004_ Sec. 5.1).

A layer of glass beads (004_ Table 1, first column) of depth H rests on a rough
bed tilted by theta and is released from rest; x runs down the slope and is
periodic, y is normal to the bed, and gravity is tilted instead of the
geometry. The defaults are 004_ Table 2 (H = 0.1 m, theta = 25 deg,
rho_s0 = 800 kg/m^3, tau_0 = 190 Pa, m_0 = 1 s, dp = 5 mm, h = 6.5 mm,
40 columns: N = 800) except K_t: 004_ chose it for Mach 0.1 at the steady
surface speed (Sec. 5.1), which is K_t = 1.3e-7 1/Pa here
(granular_flow.mach_compressibility); Table 2 prints 1.5e-5, about
1/(rho0 c0), which puts that flow at Mach 1.1. The steady profile is
references.inclined_plane_velocity; 004_ reached it after about 6.5 s.
With ``channel_width`` > 0 the layer flows in a channel that narrow, whose side
walls hold it back (physics/side_walls.py; Jop et al. 2005): its steady profile
is references.inclined_plane_velocity_between_walls, from which K_t then takes
its Mach number.

The layer's depth-averaged speed down the slope is diagnostics.csv's momentum_x /
mass (the mass-weighted mean); scripts/incline_layers.py RUN_DIR compares its
speeds and its profile, layer by layer, with the uniform flow (docs/INCLINE.md).
"""

import dataclasses
import math

from mpisph.case import ANGLE, Body, Case, MuIGranular, Param, Wall, density_reinit_param
from mpisph.geometry import bed, box, support_layers
from mpisph.granular_flow import mach_compressibility, mu_i_params, mu_i_scheme, side_wall_params, side_walls
from mpisph.references import inclined_plane_surface_velocity, inclined_plane_velocity_between_walls

PARAMS = {
    "H": Param(0.1, "m", "depth of the layer", positive=True),
    "theta": Param(25.0, "deg", "slope angle", bounds=ANGLE),
    "dp": Param(0.005, "m", "particle spacing", positive=True),
    "columns": Param(40, "-", "particles along the periodic slope (its length is columns * dp)", positive=True),
    "g": Param(9.81, "m/s^2", "gravity", positive=True),
    "rho_s0": Param(800.0, "kg/m^3", "grain density unconfined (004_ Table 2)", positive=True),
    "d": Param(0.5e-3, "m", "grain size (glass beads, 004_ Table 1)", positive=True),
    "mu_s_deg": Param(20.90, "deg", "static friction angle, mu_s = tan (004_ Table 1)", bounds=ANGLE),
    "mu_2_deg": Param(32.76, "deg", "limiting friction angle, mu_2 = tan (004_ Table 1)", bounds=ANGLE),
    "I_0": Param(0.279, "-", "reference inertial number (004_ Sec. 2.1)", positive=True),
    "phi_max": Param(0.6, "-", "volume fraction at rest (Eq. 8)", positive=True),
    "phi_min": Param(0.5, "-", "lowest volume fraction of the dense regime (Eq. 8)", positive=True),
    "K_t": Param(0.0, "1/Pa", "grain compressibility (Eq. 41); 0: Mach 0.1 at the steady surface speed (004_ "
                 "Sec. 5.1), or at sqrt(g H) where no steady flow exists"),
    "tau_0": Param(190.0, "Pa", "reference yield stress of the regularisation (Eq. 55): 004_ Table 2's, for its "
                   "layer (rho_s0 = 800, H = 0.1 m); it does not follow rho_s0 or H (lube_collapse_2d's tau_0 = 0 "
                   "takes mu_s phi_max rho_s0 g H_0)", positive=True),
    "m_0": Param(1.0, "s", "regularisation time at tau_0 (Eq. 55)", positive=True),
    **mu_i_params("004_ Fig. 6 also uses 0.05", "explicit"),
    **side_wall_params(),
    "density_reinit": density_reinit_param("none"),
    "t_end": Param(6.5, "s", "simulated end time", positive=True),
    "output_interval": Param(0.5, "s", "simulated time between frames", positive=True),
}


def setup(p):
    material = MuIGranular(rho_s0=p.rho_s0, d0=p.d, mu_s=math.tan(math.radians(p.mu_s_deg)),
                           mu_2=math.tan(math.radians(p.mu_2_deg)), I_0=p.I_0, K_t=p.K_t if p.K_t != 0 else 1.0,
                           tau_0=p.tau_0, m_0=p.m_0, phi_max=p.phi_max, phi_min=p.phi_min)
    slope = math.tan(math.radians(p.theta))
    warnings = []
    if slope >= material.mu_2:
        warnings.append(f"tan(theta) = {slope:.4g} >= mu_2 = {material.mu_2:.4g}: no steady flow exists "
                        f"without side walls, the layer accelerates without bound")
    forces = side_walls(p, p.H)
    try:
        u_ref = inclined_plane_surface_velocity(material, p.theta, p.H, p.g)
        if forces:  # the walls' flow, or sqrt(g H) where they hold the whole layer
            u_ref = float(inclined_plane_velocity_between_walls(
                material, p.theta, p.H, p.g, p.channel_width, math.tan(math.radians(p.wall_friction_deg)), p.H))
            u_ref = u_ref if u_ref > 0 else math.sqrt(p.g * p.H)
    except ValueError:  # no uniform flow: the layer stays at rest or accelerates
        u_ref = math.sqrt(p.g * p.H)
    if p.K_t == 0:  # the steady flow above does not depend on K_t
        material = dataclasses.replace(material, K_t=mach_compressibility(material.rho0, u_ref**2))
    length = p.columns * p.dp
    grains = box((0.0, 0.0), (length, p.H), p.dp, "the layer")
    layers = support_layers(p.h_factor)
    bed_x, bed_normal, bed_depth = bed((0.0,), (length,), p.dp, layers)
    cos, sin = math.cos(math.radians(p.theta)), math.sin(math.radians(p.theta))
    pressure = material.rho0 * p.g * cos * (p.H - grains[:, 1])
    return Case(
        dim=2,
        domain=((0.0, -layers * p.dp), (length, 2.0 * p.H)),
        dp=p.dp,
        material=material,
        **mu_i_scheme(p),
        bodies=[Body("grains", grains, pressure=pressure)],
        walls=[Wall("bed", bed_x, bed_normal, distance=bed_depth)],
        gravity=(p.g * sin, -p.g * cos),
        periodic=(True, False),
        density_reinit=p.density_reinit,
        u_ref=u_ref,
        warnings=warnings,
        forces=forces,
    )
