"""Reference solutions and experimental data the validation compares against."""

import numpy as np

from .physics.mu_i_law import regularised_shear_rates


def elliptical_drop_axes(t, A0=100.0, dt_max=1e-7):
    """Semi-axes (a, 1/a) of the stretched drop (Monaghan 1994; 000_ Sec. 4.1).

    dA/dt = A^2 (a^4 - 1)/(a^4 + 1), da/dt = -a A, A(0) = A0, a(0) = 1,
    integrated with classical Runge-Kutta in steps of at most ``dt_max``;
    ``t`` may be an array (any order). Returns an array (len(t), 2).
    """
    def rate(A, a):
        a4 = a**4
        return A * A * (a4 - 1.0) / (a4 + 1.0), -a * A

    t = np.atleast_1d(np.asarray(t, dtype=float))
    out = np.empty((len(t), 2))
    A, a, now = A0, 1.0, 0.0
    for k in np.argsort(t):
        steps = int(np.ceil((t[k] - now) / dt_max))
        h = (t[k] - now) / steps if steps else 0.0
        for _ in range(steps):
            k1 = rate(A, a)
            k2 = rate(A + 0.5 * h * k1[0], a + 0.5 * h * k1[1])
            k3 = rate(A + 0.5 * h * k2[0], a + 0.5 * h * k2[1])
            k4 = rate(A + h * k3[0], a + h * k3[1])
            A += h / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            a += h / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        now = t[k]
        out[k] = a, 1.0 / a
    return out


def taylor_green_energy_rate(Re):
    """Decay rate of the kinetic energy, d ln(KE)/dt = -16 pi^2 / Re (001_ Sec. 4.1)."""
    return -16.0 * np.pi**2 / Re


# The kinetic energy of the authors' own Taylor-Green run (SPHinXsys, Xiangyu-Hu/SPHinXsys, its
# regression data tests/2d_examples/test_2d_taylor_green/regression_test_tool/
# WaterBody_TotalKineticEnergy_Run_0_result.xml at commit 4c3c916dcffccb3eca2ad392e5790528c3380f19),
# written every 0.1 s from t = 0 to 5 (each at the first advection step past it), to 6 digits. The
# test at that commit: unit square, rho0 = 1, U = 1, c0 = 10, Re = 100, a perfect 100 x 100 lattice
# (ParticleGeneratorLattice, no reload), density by summation, the transport-velocity correction
# without a limiter on every particle once per advection step, 001_'s dual time stepping.
SPHINXSYS_TAYLOR_GREEN_DT = 0.1
SPHINXSYS_TAYLOR_GREEN_KE = np.array([
    0.25, 0.206463, 0.104494, 0.0811429, 0.0678611, 0.0579921, 0.0483675, 0.0409469,
    0.0335027, 0.0317613, 0.023462, 0.0198826, 0.0168425, 0.0148062, 0.012009, 0.0103007,
    0.00884408, 0.00766765, 0.00662638, 0.00547755, 0.00469251, 0.0040193, 0.00344552, 0.00329152,
    0.00252773, 0.00237109, 0.00192775, 0.00183381, 0.00162712, 0.00133348, 0.00100603, 0.00122432,
    0.000755985, 0.000893024, 0.00056172, 0.000643051, 0.000442576, 0.00047645, 0.000521788, 0.000288762,
    0.000445653, 0.000357234, 0.000198875, 0.000375696, 0.000180123, 0.000149044, 0.000345227, 0.00011609,
    0.000124743, 0.00047719, 9.25385e-05,
])


# Ghia, Ghia & Shin (1982), Re = 100: u on the vertical centre line, v on the horizontal one.
GHIA_Y = np.array([1, .9766, .9688, .9609, .9531, .8516, .7344, .6172, .5, .4531, .2813, .1719,
                   .1016, .0703, .0625, .0547, 0])
GHIA_U = np.array([1, .84123, .78871, .73722, .68717, .23151, .00332, -.13641, -.20581, -.21090,
                   -.15662, -.10150, -.06434, -.04775, -.04192, -.03717, 0])
GHIA_X = np.array([1, .9688, .9609, .9531, .9453, .9063, .8594, .8047, .5, .2344, .2266, .1563,
                   .0938, .0781, .0703, .0625, 0])
GHIA_V = np.array([0, -.05906, -.07391, -.08864, -.10313, -.16914, -.22445, -.24533, .05454,
                   .17527, .17507, .16077, .12317, .10890, .10091, .09233, 0])
# The same authors' Re = 1000 columns (their Tables I and II), on the same GHIA_Y and GHIA_X.
GHIA_U_RE1000 = np.array([1, .65928, .57492, .51117, .46604, .33304, .18719, .05702, -.06080, -.10648,
                          -.27805, -.38289, -.29730, -.22220, -.20196, -.18109, 0])
GHIA_V_RE1000 = np.array([0, -.21388, -.27669, -.33714, -.39188, -.51550, -.42665, -.31966, .02526,
                          .32235, .33075, .37095, .32627, .30353, .29012, .27485, 0])

# Koshizuka & Oka (1996): surge front z/L against T = t sqrt(2 g / L).
KOSHIZUKA_T = np.array([0, .381, .769, 1.153, 1.537, 1.935, 2.323, 2.719, 3.096])
KOSHIZUKA_Z = np.array([1, 1.111, 1.252, 1.505, 1.892, 2.241, 2.615, 3.003, 3.624])

# Martin & Moyce (1952), Phil. Trans. R. Soc. A 244, run with n^2 = 2, a = 2.25 in: surge front
# Z = z/a against T = t sqrt(2 g / a) (n^2 = 2: T = n t sqrt(g/a)), the points issue 13 quotes.
MARTIN_MOYCE_T = np.array([1.219, 1.997, 2.547, 3.345])
MARTIN_MOYCE_Z = np.array([1.474, 2.292, 2.995, 4.134])


def koshizuka_oka_front(T):
    """Koshizuka & Oka's surge front z/L at T, their points joined by straight lines."""
    return np.interp(T, KOSHIZUKA_T, KOSHIZUKA_Z)


# The span of T over which issue 13 compares the late front speed with Martin & Moyce's.
MARTIN_MOYCE_SPAN = (1.9, 3.1)


def martin_moyce_speed():
    """dZ/dT of Martin & Moyce's front over MARTIN_MOYCE_SPAN, the points joined by straight lines."""
    lo, hi = MARTIN_MOYCE_SPAN
    return (np.interp(hi, MARTIN_MOYCE_T, MARTIN_MOYCE_Z) - np.interp(lo, MARTIN_MOYCE_T, MARTIN_MOYCE_Z)) / (hi - lo)

# Rotating square patch (000_ Eq. 44): centre pressure over rho omega^2 L^2.
ROTATING_SQUARE_CENTRE_PRESSURE = -0.147343


def beam_period(L=0.2, H=0.02, rho0=1000.0, E=2.0e6, nu=0.3975, kL=1.875):
    """First period 2 pi / omega of the cantilever, omega^2 = E H^2 k^4 / (12 rho0 (1 - nu^2)) (000_ Eq. 47)."""
    k = kL / L
    return 2.0 * np.pi / np.sqrt(E * H**2 * k**4 / (12.0 * rho0 * (1.0 - nu**2)))


# 000_ Table 1: the beam's first period T [s] at H/dp = 30 (L = 0.2 m, H = 0.02 m) by v_f, for the
# paper's TVF, UTVF and artificial stress (SPH-AS, Gray et al. 2001); its analytical T is 0.254.
BEAM_TABLE_1_V_F = (0.001, 0.01, 0.03, 0.05)
BEAM_TABLE_1_PERIODS = {"tvf": (0.275, 0.277, 0.283, 0.284), "utvf": (0.274, 0.271, 0.271, 0.271),
                        "artificial_stress": (0.273, 0.273, 0.275, 0.278)}

# 004_ Table 1: constitutive parameters of the mu(I) law (friction angles in degrees, d in m).
# Glass beads and 0.8 mm sand after GDR MiDi (2004); 0.4 mm sand (d = 0.32 mm in the collapses of
# Lube et al. 2004) with I_0 from 004_ Sec. 2.1.
MU_I_MATERIALS = {
    "glass_beads": {"mu_s_deg": 20.90, "mu_2_deg": 32.76, "I_0": 0.279, "d": 0.5e-3},
    "sand_0.8mm": {"mu_s_deg": 27.00, "mu_2_deg": 43.40, "I_0": 1.09, "d": 0.8e-3},
    "sand_0.4mm": {"mu_s_deg": 30.50, "mu_2_deg": 51.30, "I_0": 2.65, "d": 0.32e-3},
}

# 004_ Table 2: the inclined plane run; eta_max is the paper's value of Eq. 53 at tau_0. K_t as
# printed is about 1 / (rho0 c0) with c0 = 10 times the steady surface speed, where Sec. 5.1 asks for
# Mach 0.1; cases/inclined_plane.py takes K_t from that Mach number (granular_flow.mach_compressibility).
INCLINED_PLANE_TABLE_2 = {"H": 0.1, "theta": 25.0, "rho_s0": 800.0, "K_t": 1.5e-5, "tau_0": 190.0, "m_0": 1.0,
                          "eta_max": 190.3, "N": 800, "dp": 5e-3, "h": 6.5e-3}


def inclined_plane_velocity(material, theta_deg, H, g, z):
    """Steady uniform velocity u(z) at height z above the bed of a mu(I) layer of depth H on a
    slope of theta degrees (004_ Sec. 5.1):

        u(z) = (2 I_u / 3 d) sqrt(phi_u g cos(theta)) (H^(3/2) - (H - z)^(3/2)),

    from gamma_dot = I_u sqrt(p / rho_s) / d with the hydrostatic p = phi_u rho_s g cos(theta) (H - z)
    and the uniform I_u of mu(I_u) = tan(theta). Eq. 56 prints squares instead of the 3/2 powers
    that this integration gives. Grains taken incompressible (rho_s = rho_s0, d = d0)."""
    I_u, phi_u = material.uniform_flow(theta_deg)
    scale = 2.0 * I_u / (3.0 * material.d0) * np.sqrt(phi_u * g * np.cos(np.radians(theta_deg)))
    return scale * (H**1.5 - (H - np.asarray(z, dtype=float)) ** 1.5)


def inclined_plane_flow_depth(material, theta_deg, H_rest):
    """Depth of the uniform flow (``inclined_plane_velocity``) of the grains of a layer laid at rest
    ``H_rest`` deep, as cases/inclined_plane.py lays them (mpisph's derivation): the same mass per area
    at the volume fraction phi_u of Eq. 8 instead of phi_max, H_rest phi_max / phi_u. The glass beads
    at 25 deg dilate by 2.3 %, and u ~ H^(3/2) puts their surface 3.4 % faster than at H_rest."""
    _, phi_u = material.uniform_flow(theta_deg)
    return H_rest * material.phi_max / phi_u


def inclined_plane_surface_velocity(material, theta_deg, H, g):
    """u(H) of ``inclined_plane_velocity``."""
    return float(inclined_plane_velocity(material, theta_deg, H, g, H))


def inclined_plane_relaxation_time(material, theta_deg, H, g):
    """Time constant T [s] with which a layer's mean speed U approaches the uniform flow's U_u
    (mpisph's derivation, not 004_'s): the layer's momentum, rho H dU/dt = rho g H (sin(theta) -
    mu(I_b) cos(theta)), linearised about I_u with I proportional to U (the profile keeping its
    shape), gives dU/dt = -(U - U_u) / T with T = U_u / (g cos(theta) I_u mu'(I_u)); U_u is 3/5
    of the surface speed. The flatter mu(I) is at I_u, the slower the approach."""
    I_u, _ = material.uniform_flow(theta_deg)
    a = I_u + material.params.I_s
    slope = (material.mu_2 - material.mu_s) * material.I_0 / (a + material.I_0) ** 2  # mu'(I_u), Eq. 7
    mean = 0.6 * inclined_plane_surface_velocity(material, theta_deg, H, g)
    return mean / (g * np.cos(np.radians(theta_deg)) * I_u * slope)


def pair_viscosity_of_alpha(alpha, h, c0, dim):
    """Kinematic shear viscosity nu = alpha h c0 / (2 (D + 2)) [m^2/s] of 004_ Eq. 38's term
    Pi_ij = -alpha h c0 (v_ij . r_ij) / (rho_bar r^2), applied to every pair: it has the form of
    the viscous pair term of Eq. 27, 2 (D + 2) eta (v_ij . r_ij) / (rho_i rho_j r^2), which
    reproduces div(eta grad v) (physics/mu_i.py), with eta / rho = alpha h c0 / (2 (D + 2))."""
    return alpha * h * c0 / (2.0 * (dim + 2))


def _uniform_flow(material, theta_deg, H, g, nu=0.0, wall_rate=0.0, regularised=False, samples=4001):
    """(height, speed, pressure, inertial number) from the bed up of the steady uniform mu(I) layer
    with a Newtonian kinematic viscosity ``nu`` added (``inclined_plane_velocity_with_viscosity``) or
    between side walls (``wall_rate`` = 2 mu_w / W, ``inclined_plane_velocity_between_walls``), of
    the friction law or, ``regularised``, of the regularised law the solver takes (Eqs. 46-55,
    physics/mu_i_law.py; not with nu). Needs the uniform flow's finite I_u (tan(theta) < mu_2)."""
    if regularised and nu != 0.0:
        raise ValueError("the regularised uniform flow takes no added viscosity")
    m = material.params
    tan, cos = np.tan(np.radians(theta_deg)), np.cos(np.radians(theta_deg))
    I_u, phi_u = material.uniform_flow(theta_deg)
    p = phi_u * material.rho_s0 * g * cos * H * np.linspace(1.0, 0.0, samples) ** 2  # bed to top, finer at the top
    root = np.sqrt(p / material.rho_s0)
    phi = np.full_like(p, phi_u)
    for _ in range(1 if wall_rate == 0.0 else 30):  # the walls' share depends on phi(I) above: a fixed point
        depth_per_pressure = 1.0 / (phi * material.rho_s0 * g * cos)
        # the walls' load per area above each depth: wall_rate times the integral of p over the depth
        held = wall_rate * np.concatenate((np.cumsum((0.5 * (p[1:] * depth_per_pressure[1:] + p[:-1]
                                                             * depth_per_pressure[:-1]) * -np.diff(p))[::-1])[::-1],
                                           [0.0]))
        friction = tan - held / np.maximum(p, 1e-300)
        if regularised:
            I = regularised_shear_rates(friction * p, p, m) * material.d0 / np.maximum(root, 1e-300)
        else:
            lo, hi = np.zeros_like(p), np.full_like(p, I_u)  # nu >= 0, walls: I <= I_u
            for _ in range(100):  # bisection: the left side rises with I
                I = 0.5 * (lo + hi)
                a = I + m.I_s
                excess = m.mu_s + (m.mu_2 - m.mu_s) * a / (a + m.I_0) - friction
                excess += ((m.phi_max - (m.phi_max - m.phi_min) * I) * nu * I
                           / (np.maximum(root, 1e-300) * material.d0))
                lo, hi = np.where(excess < 0.0, I, lo), np.where(excess < 0.0, hi, I)
            I = 0.5 * (lo + hi)
        phi = m.phi_max - (m.phi_max - m.phi_min) * np.minimum(I, 1.0)
    dz_dp = 1.0 / (phi * material.rho_s0 * g * cos)  # height gained per pressure lost upwards
    du_dp = I * root / material.d0 * dz_dp
    lost = -np.diff(p)
    height = np.concatenate(([0.0], np.cumsum(0.5 * (dz_dp[1:] + dz_dp[:-1]) * lost)))
    speed = np.concatenate(([0.0], np.cumsum(0.5 * (du_dp[1:] + du_dp[:-1]) * lost)))
    return height, speed, p, I


def inclined_plane_velocity_with_viscosity(material, theta_deg, H, g, nu, z):
    """Steady uniform velocity u(z) of the mu(I) layer of ``inclined_plane_velocity`` (the same mass
    per area, phi_u rho_s0 H) with a Newtonian kinematic viscosity ``nu`` added to the law
    (mpisph's derivation, for 004_ Fig. 6's alpha = 0.05 with ``pair_viscosity_of_alpha``). In the
    uniform flow the shear stress is p tan(theta) at every depth, so at each pressure p the
    inertial number solves

        mu(I) + phi(I) nu I sqrt(rho_s0 / p) / d = tan(theta),   phi(I) from Eq. 8,

    then gamma_dot = I sqrt(p / rho_s0) / d and dp/dz = -phi(I) rho_s0 g cos(theta); u(z) is
    gamma_dot integrated from the bed. nu = 0 gives ``inclined_plane_velocity``. Heights above the
    layer's top take the top's speed. Grains incompressible, as there."""
    height, speed, _, _ = _uniform_flow(material, theta_deg, H, g, nu=nu)
    return np.interp(np.asarray(z, dtype=float), height, speed)


def inclined_plane_mean_velocity_with_viscosity(material, theta_deg, H, g, nu):
    """The mass-weighted mean of ``inclined_plane_velocity_with_viscosity`` over the layer (the
    mean over its pressure, dp being the mass per area times g cos(theta))."""
    _, speed, p, _ = _uniform_flow(material, theta_deg, H, g, nu=nu)
    return float(np.sum(0.5 * (speed[1:] + speed[:-1]) * -np.diff(p)) / p[0])


def inclined_plane_velocity_between_walls(material, theta_deg, H, g, width, mu_w, z, regularised=False):
    """Steady uniform velocity u(z) of the mu(I) layer of ``inclined_plane_velocity`` (the same mass
    per area, phi_u rho_s0 H) in a channel ``width`` wide whose side walls hold it back with the
    friction coefficient ``mu_w`` (physics/side_walls.py; Jop, Forterre & Pouliquen 2005). The walls
    take 2 mu_w p / W per unit volume, so at depth zeta below the surface the shear stress is
    p tan(theta) - (2 mu_w / W) int_0^zeta p, and the friction the law must carry falls with depth,

        mu(I) = tan(theta) - (2 mu_w / (W p)) int_0^zeta p dzeta'   (= tan(theta) - mu_w zeta / W at constant phi),

    down to the depth where it reaches mu(0): below it the grains rest (mpisph's derivation after Jop
    et al.'s). u(z) is gamma_dot = I sqrt(p / rho_s0) / d integrated from the bed, p the weight above
    at phi(I) of Eq. 8. Grains incompressible, as there. With ``regularised`` the law is the one the
    solver takes, regularised below the yield stress (004_ Eqs. 46-55), under which the grains that
    the walls would hold creep; the walls' friction stays mu_w p there, where the solver's softens
    below its regularising speed (physics/side_walls.py)."""
    height, speed, _, _ = _uniform_flow(material, theta_deg, H, g, wall_rate=2.0 * mu_w / width,
                                        regularised=regularised)
    return np.interp(np.asarray(z, dtype=float), height, speed)


def inclined_plane_mean_velocity_between_walls(material, theta_deg, H, g, width, mu_w, regularised=False):
    """The mass-weighted mean of ``inclined_plane_velocity_between_walls`` over the layer (the mean
    over its pressure, dp being the mass per area times g cos(theta))."""
    _, speed, p, _ = _uniform_flow(material, theta_deg, H, g, wall_rate=2.0 * mu_w / width, regularised=regularised)
    return float(np.sum(0.5 * (speed[1:] + speed[:-1]) * -np.diff(p)) / p[0])


def inclined_plane_inertial_number_between_walls(material, theta_deg, H, g, width, mu_w, z):
    """The inertial number I(z) of ``inclined_plane_velocity_between_walls``: 0 where the grains rest."""
    height, _, _, I = _uniform_flow(material, theta_deg, H, g, wall_rate=2.0 * mu_w / width)
    return np.interp(np.asarray(z, dtype=float), height, I)


def inclined_plane_pressure(material, theta_deg, H, g, z):
    """Hydrostatic pressure phi_u rho_s0 g cos(theta) (H - z) of the steady layer (004_ Fig. 7)."""
    _, phi_u = material.uniform_flow(theta_deg)
    return phi_u * material.rho_s0 * g * np.cos(np.radians(theta_deg)) * (H - np.asarray(z, dtype=float))


# 004_ Table 3: the paper's (2D) runs of Lube's sand columns, r_0 = 9.72 cm, rho_s0 = 2600 kg/m^3,
# d = 0.32 mm, sand of Table 1's third column. Columns: id: (a, H_0 [m], K_t [1/Pa], tau_0 [Pa], m_0 [s],
# eta_max [Pa s], N, dp [m], h [m]). K_t as printed equals 1 / (rho_s0 c) with c = 10 sqrt(g H_0) to
# within 1.5 % (row 6 prints 2.2e-6 where that gives 2.27e-5), which has the units of m^2 s/kg, not
# 1/Pa; tau_0 equals mu_s phi_max rho_s0 g H_0 within 1.2 % (6 % in row 1); eta_max is Eq. 53's at the
# printed tau_0 and an m_0 that the table rounds to one decimal (tests/test_references.py). The cases
# take K_t from the text instead: Mach 0.1 with U = sqrt(g H_0).
LUBE_TABLE_3 = {
    1: (0.19, 0.0185, 9.0e-5, 177.0, 1.2, 215.0, 2500, 1.20e-3, 1.56e-3),
    2: (0.55, 0.0535, 5.3e-5, 483.0, 1.4, 684.0, 2200, 2.20e-3, 2.86e-3),
    3: (0.90, 0.0875, 4.1e-5, 795.0, 1.2, 961.0, 1900, 3.02e-3, 3.93e-3),
    4: (1.60, 0.1555, 3.1e-5, 1414.0, 1.4, 2003.0, 2900, 3.24e-3, 4.21e-3),
    5: (2.75, 0.2673, 2.4e-5, 2415.0, 1.6, 3911.0, 2300, 4.86e-3, 6.32e-3),
    6: (3.00, 0.2916, 2.2e-6, 2660.0, 1.6, 4292.0, 2500, 4.86e-3, 6.32e-3),
}
LUBE_R0 = 0.0972  # m, radius of the columns of Lube et al. (2004) that 004_ reproduces


def axisymmetric_runout(a):
    """(r_inf - r_0) / r_0 of an axisymmetric column of aspect ratio a = H_0 / r_0 (Lube et al. 2004,
    004_ Eq. 58): 1.24 a for a < 1.7, 1.6 a^(1/2) above."""
    a = np.asarray(a, dtype=float)
    return np.where(a < 1.7, 1.24 * a, 1.6 * np.sqrt(a))


def planar_runout(a):
    """(L_inf - L_0) / L_0 of a planar column of aspect ratio a = H_0 / L_0 (Lube et al. 2005,
    Balmforth & Kerswell 2005): 1.2 a for small a, 1.9 a^(2/3) for large a. The experiments place the
    change between a = 2 and 3, where the two laws differ by 26 % (a = 2) to 10 % (a = 3); this returns the smaller, which
    switches at a = (1.9 / 1.2)^3 = 3.97. The validation fits the two regimes separately."""
    a = np.asarray(a, dtype=float)
    return np.minimum(1.2 * a, 1.9 * a ** (2.0 / 3.0))


# Balmforth & Kerswell (2005), J. Fluid Mech. 538, 399-428, abstract: the runout of planar columns,
# (l_inf - L) / L ~ a^n, with n = 0.9 +- 0.1 in wide channels and 0.65 +- 0.05 in narrow slots (where
# the side walls' friction holds the flow back). A plane-strain run has no side walls.
PLANAR_RUNOUT_EXPONENTS = {"wide channels": (0.9, 0.1), "narrow slots": (0.65, 0.05)}


def lateral_earth_force(coefficients, gamma, top, bottom, width):
    """Horizontal force on a vertical wall ``width`` wide spanning the depths ``top`` to ``bottom``
    below a level soil surface of unit weight ``gamma``, under the pressure sigma_h = max(0, k gamma z
    + cohesion_term) at depth z (no tension on the wall), ``coefficients`` = (k, cohesion_term) of
    one state of ``earth_pressure``: Rankine's (1857) active or passive force with Bell's (1915)
    cohesion terms, or Jaky's force at rest."""
    k, cohesion_term = coefficients
    z0 = max(top, -cohesion_term / (k * gamma)) if cohesion_term < 0.0 else top  # the tension crack's depth
    if bottom <= z0:
        return 0.0
    return width * (0.5 * k * gamma * (bottom**2 - z0**2) + cohesion_term * (bottom - z0))


def earth_pressure(phi_deg, cohesion):
    """The coefficients (k, cohesion_term) of sigma_h = k sigma_v + cohesion_term behind a vertical
    wall under a level surface, by state: Rankine's active, k = tan^2(45 - phi/2), with -2 c sqrt(k)
    (Bell 1915); Jaky's (1944) at rest, k = 1 - sin phi, without cohesion term; Rankine's passive,
    k = tan^2(45 + phi/2), with +2 c sqrt(k)."""
    phi = np.radians(phi_deg)
    ka, kp = np.tan(np.pi / 4 - phi / 2) ** 2, np.tan(np.pi / 4 + phi / 2) ** 2
    return {"active": (ka, -2.0 * cohesion * np.sqrt(ka)), "at rest": (1.0 - np.sin(phi), 0.0),
            "passive": (kp, 2.0 * cohesion * np.sqrt(kp))}


# The critical height of a vertical cut in a Mohr-Coulomb soil on a rigid base: Chen (1975), Limit
# Analysis and Soil Plasticity (Elsevier), the upper bound of a log-spiral mechanism through the
# toe, gamma H_c / c = 3.83 tan(45 deg + phi / 2) (Culmann's plane wedge gives 4 for 3.83). Limit
# analysis assumes associated flow. For a dilatancy psi below phi, Drescher & Detournay (1993,
# Geotechnique 43, 443-456) estimate the collapse by an associated soil of c* = eta c and tan phi* =
# eta tan phi, eta = cos psi cos phi / (1 - sin psi sin phi) (exact for their translational mechanisms,
# an estimate otherwise: the lower-bound theorem does not hold without associated flow, while the
# associated height still bounds a non-associated soil from above, Radenkovic's first theorem).
# mpisph's Drucker-Prager cone is fitted to Mohr-Coulomb in plane strain (000_ Eq. 14), so an
# associated soil collapses at the same heights.
VERTICAL_CUT_LOG_SPIRAL = 3.83


def vertical_cut_critical_height(cohesion, phi_deg, gamma, psi_deg=None):
    """H_c of the comment above [m]: associated flow without ``psi_deg``, else Drescher & Detournay's
    reduced strength for that dilatancy (the same as associated for psi = phi, and for phi = 0)."""
    phi = np.radians(phi_deg)
    eta = 1.0
    if psi_deg is not None:
        psi = np.radians(psi_deg)
        eta = np.cos(psi) * np.cos(phi) / (1.0 - np.sin(psi) * np.sin(phi))
    phi_star = np.arctan(eta * np.tan(phi))
    return VERTICAL_CUT_LOG_SPIRAL * eta * cohesion / gamma * np.tan(np.pi / 4 + phi_star / 2)


def vertical_cut_safety_factor(cohesion, phi_deg, gamma, height, psi_deg=0.0):
    """(associated, Drescher & Detournay for ``psi_deg``): the factors F of strength reduction (c / F,
    tan phi / F, tan psi / F) at which ``vertical_cut_critical_height`` falls to ``height``, found by
    bisection (the height falls as F grows)."""
    def reduced_height(factor, dilatant):
        phi = np.degrees(np.arctan(np.tan(np.radians(phi_deg)) / factor))
        psi = np.degrees(np.arctan(np.tan(np.radians(psi_deg)) / factor)) if dilatant else None
        return vertical_cut_critical_height(cohesion / factor, phi, gamma, psi)

    def factor(dilatant):
        low, high = 1e-3, 1e3
        for _ in range(200):
            middle = np.sqrt(low * high)
            low, high = (middle, high) if reduced_height(middle, dilatant) > height else (low, middle)
        return float(np.sqrt(low * high))
    return factor(False), factor(True)
