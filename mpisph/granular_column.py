"""Columns of sand released on a rough floor, mu(I) scheme (004_ Sec. 5.2): what the planar and the
axisymmetric collapse cases share.

The sand is 004_ Table 1's third column (mu_s = tan 30.5 deg, mu_2 = tan 51.3 deg,
I_0 = 2.65) with d = 0.32 mm and rho_s0 = 2600 kg/m^3, as in Lube et al.
(2004). Two parameters follow from the column height H_0 unless given:

- K_t from the Mach number 0.1 with U = sqrt(g H_0), as 004_ Sec. 5.2 says:
  c0 = 10 sqrt(g H_0) and K_t = 1 / (rho0 c0^2). (Table 3's printed values
  are 1 / (rho_s0 c0), references.LUBE_TABLE_3.)
- tau_0 = mu_s phi_max rho_s0 g H_0, the yield stress at the foot of the
  column, which Table 3's values follow within 1.2 % (6 % in its first row;
  tests/test_references.py).

The column starts at rest with the hydrostatic pressure of its bulk density at
rest; the floor is a bed of Morris ghost particles (no slip, 004_ Eqs. 34-36).
"""

import math

from .case import ANGLE, Body, Case, Front, MuIGranular, Param, Wall, density_reinit_param
from .errors import InputError
from .geometry import along, bed_layers, block, depth, lattice_layers, lattice_mismatch, support_layers
from .granular_flow import mach_compressibility, mu_i_params, mu_i_scheme
from .references import MU_I_MATERIALS, planar_runout

SAND = MU_I_MATERIALS["sand_0.4mm"]


def column_params(a, dp, m_0):
    """Typed parameters of a column of aspect ratio ``a`` at spacing ``dp``, with the regularisation
    time ``m_0`` (004_ Table 3 uses 1.2-1.6 s)."""
    return {
        "a": Param(a, "-", "aspect ratio of the column, height over length (planar) or radius", positive=True),
        "dp": Param(dp, "m", "particle spacing", positive=True),
        "g": Param(9.81, "m/s^2", "gravity", positive=True),
        "rho_s0": Param(2600.0, "kg/m^3", "grain density unconfined (004_ Sec. 5.2)", positive=True),
        "d": Param(SAND["d"], "m", "grain size (004_ Sec. 5.2)", positive=True),
        "mu_s_deg": Param(SAND["mu_s_deg"], "deg", "static friction angle, mu_s = tan (004_ Table 1)", bounds=ANGLE),
        "mu_2_deg": Param(SAND["mu_2_deg"], "deg", "limiting friction angle, mu_2 = tan (004_ Table 1)", bounds=ANGLE),
        "I_0": Param(SAND["I_0"], "-", "reference inertial number (004_ Sec. 2.1)", positive=True),
        "phi_max": Param(0.6, "-", "volume fraction at rest (Eq. 8)", positive=True),
        "phi_min": Param(0.5, "-", "lowest volume fraction of the dense regime (Eq. 8)", positive=True),
        "K_t": Param(0.0, "1/Pa", "grain compressibility (Eq. 41); 0: from Mach 0.1 with U = sqrt(g H_0)"),
        "tau_0": Param(0.0, "Pa", "reference yield stress of the regularisation (Eq. 55); 0: mu_s phi_max "
                       "rho_s0 g H_0"),
        "m_0": Param(m_0, "s", "regularisation time at tau_0 (Eq. 55)", positive=True),
        **mu_i_params("004_ uses none for the collapses", "implicit"),
        "density_reinit": density_reinit_param("none", why="004_ evolves the density by Eq. 26"),
        "diagnostics_every": Param(100, "steps", "steps between rows of diagnostics.csv", positive=True),
    }


def sand(p, H0):
    """The MuIGranular of the parameters ``p`` for a column of height ``H0``."""
    mu_s = math.tan(math.radians(p.mu_s_deg))
    rho0 = p.phi_max * p.rho_s0
    K_t = p.K_t if p.K_t != 0 else mach_compressibility(rho0, p.g * H0)
    if p.tau_0 == 0 and mu_s == 0:
        raise InputError("tau_0 = 0 takes mu_s phi_max rho_s0 g H_0, which mu_s_deg = 0 makes 0: give tau_0 "
                         "in Pa, or mu_s_deg > 0")
    tau_0 = p.tau_0 if p.tau_0 != 0 else mu_s * rho0 * p.g * H0
    return MuIGranular(rho_s0=p.rho_s0, d0=p.d, mu_s=mu_s, mu_2=math.tan(math.radians(p.mu_2_deg)), I_0=p.I_0,
                       K_t=K_t, tau_0=tau_0, m_0=p.m_0, phi_max=p.phi_max, phi_min=p.phi_min)


def column_case_settings(p, material, column, H0, front_axes, sides):
    """Case keywords shared by the collapses: the column body (a lattice source) at rest under the
    hydrostatic pressure of its lattice fill, the mu_i scheme with its options (granular_flow.py),
    the front gauge, the force of the grains on the wall named "floor" (and its moment about the
    origin) into diagnostics.csv, the reference speed sqrt(g H0), and a warning for each of the
    ``sides`` ({symbol: length}) that is not a whole number of dp, as the fill then changes the
    column's aspect ratio."""
    top = lattice_layers(H0, p.dp) * p.dp
    dim = len(column.lattice.frame.origin)
    return dict(
        dim=dim,
        dp=p.dp,
        material=material,
        **mu_i_scheme(p),
        bodies=[Body("column", column, pressure=lambda x: material.rho0 * p.g * (top - x[:, -1]))],
        gravity=(0.0,) * (dim - 1) + (-p.g,),
        front=Front((0.0,) * dim, front_axes),
        wall_forces={"floor": (0.0,) * dim},
        u_ref=math.sqrt(p.g * H0),
        density_reinit=p.density_reinit,
        warnings=[w for w in (lattice_mismatch(k, v, p.dp) for k, v in sides.items()) if w],
    )


def planar_column(p, L0, back_wall_slip, across=None):
    """The planar collapse: a column L0 long and H_0 = a L0 high against a back wall at x = 0 on a
    no-slip floor that reaches L0 (1 + 3 f(a)) (f: references.planar_runout), in 2D, or with
    ``across`` (a width) in 3D as a slab periodic along y."""
    H0 = p.a * L0
    layers = support_layers(p.h_factor)
    margin = layers * p.dp
    floor_end = L0 * (1.0 + 3.0 * float(planar_runout(p.a))) + margin  # room for grains thrown ahead

    def at(x, z, y=0.0):
        """A point (x, z) in 2D, (x, y, z) in 3D."""
        return (x, z) if across is None else (x, y, z)

    column = block(at(0.0, 0.0), at(L0, H0, across), p.dp, "the column")
    floor = bed_layers(at(-margin, 0.0)[:-1], at(floor_end, 0.0, across)[:-1], p.dp, layers)
    back = block(at(-margin, 0.0), at(0.0, H0 + margin, across), p.dp, "the back wall", normal=along(0))
    return Case(
        domain=(at(-margin, -margin), at(floor_end + margin, 1.5 * H0 + margin, across)),
        periodic=(False, True, False) if across else (False, False),
        walls=[Wall("floor", floor, distance=depth),
               Wall("back_wall", back, slip=back_wall_slip, distance=lambda x: -x[:, 0])],
        **column_case_settings(p, sand(p, H0), column, H0, front_axes=(0,), sides={"H_0": H0, "L_0": L0}),
    )
