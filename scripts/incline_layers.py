"""Where an inclined-plane run stands against the uniform flow, layer by layer (docs/INCLINE.md).

    .venv/bin/python scripts/incline_layers.py RUN_DIR [--frames 40]

Prints the mean speed and the surface speed over the analytical ones in each of the last five
frames, with the profile's L2 error over dp-thick layers and the layers' mean pressure over the
hydrostatic one (the grains' p, and s p, the share the pairs carry: see below); with alpha > 0, the
speeds over those of the uniform flow with Eq. 38's shear viscosity added (references). Then it
averages the last ``--frames`` frames of a run of the case inclined_plane over dp-thick layers above
the bed and prints, per layer: speed over the analytical u(z) of the flow depth
(incline_measures.flow_depth; between the run's side walls, if it has them, their uniform flow), the
shear rate 2 eps_xy over the analytical I_a sqrt(p_h / rho_s0) / d, pressure over p_h (the weight of
the grains above the layer's mean height, incline_measures.weight_above), the friction mu(I) of the
particles over mu(I_a), I over I_a (I_a the analytical inertial number at the layer's height, I_u
without side walls, where mu(I_u) = tan(theta); means of nonlinear functions of each particle's p,
so biased where p scatters), the alignment 2 eps_xy / gamma_dot of the layer's means, and, where the
frames hold the correction matrix B (000_ Eq. 24), the kernel moment A = B^-1 = -sum_j V_j r_ij (x)
grad W_ij: its share s = tr(A) / 2 of an isotropic stress that the pairs carry, with s p over p_h,
and its shear component A_xy (docs/INCLINE.md). With viscous_form=corrected_stress the frames hold
the viscous stress T = 2 eta eps B that the momentum sum uses (with viscous_step=implicit: the
stress of the velocities predicted to the middle of the step, not of those the kick solved for), and
the script also splits the shear and the normal traction across the planes between the layers into
the pressure pairs (with pressure_form=isotropic, those of the stress T_pressure the frames hold),
the viscous pairs and the momentum the particles carry across (m u' v', m v' v'), each over the
weight's component along the slope (less what side walls hold of the part above) and normal to it:
in a steady layer each three add up to 1. A table of the viscous stress's normal part follows
(bulk_table): the bulk viscosity that 2 eta eps gives the grains carries a mean stress where eta and
the grains' change of volume correlate, and the corrected gradient's trace, unlike the uncorrected
one's and the continuity equation's divergence, has a mean in a sheared layer. Frames must be close
in time (an output interval of about 0.05 s) for the averages to settle.
"""

import argparse
import math

import numpy as np

from mpisph.case import case_of_frame
from mpisph.incline_measures import (analytical_inertial_number, analytical_velocity, carried_pressure, flow_depth,
                                     hydrostatic, kernel_moment, layer_speeds, profile_figures, weight_above,
                                     with_artificial_viscosity)
from mpisph.io.frames import list_frames, read_frame
from mpisph.kernels import Kernel
from mpisph.neighbours import neighbour_lists
from mpisph.physics.mu_i_law import friction
from mpisph.physics.side_walls import SideWallFriction, add_side_wall_friction, friction_pressure
from mpisph.physics.viscous_stress import strain_rate
from run_check import run_params  # (this directory)


def per_layer(frames, dp, of_frame):
    """Per dp-thick layer above the bed, bottom first, the mean over ``frames`` of the tuple that
    ``of_frame(frame)`` (what the frame's layers share, computed once) gives for a layer as
    ``of_layer(s, index)``: s the layer's mask, index its place among the frame's layers."""
    sums = {}
    for f in frames:
        of_layer = of_frame(f)
        layer = np.floor(f["x"][:, 1] / dp).astype(int)
        for index, k in enumerate(np.unique(layer)):
            sums.setdefault(k, []).append(of_layer(layer == k, index))
    return [np.mean(sums[k], axis=0) for k in sorted(sums)]


def layer_table(frames, p, material):
    """Rows (height, u/u_a, shear rate/analytical, p/p_h, s p/p_h, mu/mu_a, I/I_a, s, A_xy, alignment)
    averaged over ``frames``, the analytical ones of the uniform flow at the layer's height
    (incline_measures: without side walls mu_a = tan(theta) and I_a = I_u at every depth); u/u_a is nan
    where u_a = 0, on the bed, and the rate's and I's ratios where I_a = 0, where the walls hold the
    grains at rest; the alignment is the layer's mean 2 eps_xy over its mean gamma_dot, the law's
    strain rate."""
    dp = p["dp"]

    def of_frame(f):
        y = f["x"][:, 1]
        share, A_xy = kernel_moment(f)
        p_h = hydrostatic(f, p)
        return lambda s, index: (y[s].mean(), f["v"][s, 0].mean(), 2.0 * f["strain"][s, 2].mean(), f["p"][s].mean(),
                                 (share[s] * f["p"][s]).mean(), p_h[index], f["friction"][s].mean(),
                                 f["inertial_number"][s].mean(), share[s].mean(), A_xy[s].mean(),
                                 f["gamma_dot"][s].mean())

    layers = per_layer(frames, dp, of_frame)
    centres = [layer[0] for layer in layers]  # the uniform flow solved once for every layer's height
    rows = []
    for (centre, u, rate, pressure, carried, p_h, mu, I, share, A_xy, gamma_dot), u_a, I_a in zip(
            layers, analytical_velocity(p, material, centres), analytical_inertial_number(p, material, centres)):
        rate_a = I_a * math.sqrt(p_h / material.rho_s0) / material.d0
        rows.append((centre, u / u_a if u_a > 0 else np.nan, rate / rate_a if I_a > 0 else np.nan, pressure / p_h,
                     carried / p_h, mu / friction(I_a, material.params), I / I_a if I_a > 0 else np.nan, share, A_xy,
                     rate / gamma_dot))
    return rows


def noise_table(frames, p, material):
    """Rows (height, then over the layer's mean shear rate 2 eps_xy: the rms of the particles' volumetric
    rate tr(eps) and of eps_xx - eps_yy; the alignment of the particles' own strain rates, 2 eps_xy over
    the mean modulus of eps and of its deviator; the scatter of the law's pressure P = s p over its
    layer mean, and its median over that mean (how few particles carry it); the rms of the particles'
    velocity normal to the slope over the layer's shear rate times dp (their jostle as the layers slide
    over each other); the layer's mean shear stress of the law mu(I) P, I = gamma_dot d / sqrt(P / rho_s0),
    over that of the layer's mean P and gamma_dot; the layer's mean viscous shear stress 2 eta eps_xy over
    its mean mu(I) P of the law's own I and P, the alignment the law's stress has in effect) averaged over
    ``frames``: the noise the law's inputs carry and what it costs (physics/mu_i.py, options
    law_strain_rate and law_pressure)."""
    dp, m = p["dp"], material.params

    def of_frame(f):
        eps = f["strain"]
        trace, normal_difference, shear = eps[:, 0] + eps[:, 1], eps[:, 0] - eps[:, 1], 2.0 * eps[:, 2]
        full = np.sqrt(2.0 * (eps[:, 0] ** 2 + eps[:, 1] ** 2 + 2.0 * eps[:, 2] ** 2))
        deviatoric = np.sqrt(normal_difference**2 + shear**2)  # sqrt(2 e':e'), e' = eps - tr(eps) / 2 I
        P = carried_pressure(f)
        law_P = f["law_pressure"] if "law_pressure" in f else P
        gamma_dot = f["gamma_dot"]
        # friction's Python source takes arrays as well as numbers
        tau = friction.py_func(gamma_dot * m.d0 / np.sqrt(np.maximum(P, 1e-300) / m.rho_s0), m) * P
        return lambda s, index: (f["x"][s, 1].mean(), shear[s].mean(), np.mean(trace[s] ** 2),
                                 np.mean(normal_difference[s] ** 2), full[s].mean(), deviatoric[s].mean(),
                                 P[s].mean(), P[s].var(), np.median(P[s]), np.mean(f["v"][s, 1] ** 2),
                                 tau[s].mean(), gamma_dot[s].mean(),
                                 np.mean(2.0 * f["eta"][s] * eps[s, 2]), np.mean(f["friction"][s] * law_P[s]))

    rows = []
    for (y, rate, trace2, difference2, full, deviatoric, P, P_var, P_median, normal2, tau, gamma_dot, stress,
         law) in per_layer(frames, dp, of_frame):
        at_mean = friction(gamma_dot * m.d0 / np.sqrt(P / m.rho_s0), m) * P if P > 0.0 else np.nan
        rows.append((y, np.sqrt(trace2) / rate, np.sqrt(difference2) / rate, rate / full, rate / deviatoric,
                     np.sqrt(P_var) / P, P_median / P, np.sqrt(normal2) / (rate * dp), tau / at_mean, stress / law))
    return rows


def uncorrected_trace(frame, p):
    """tr(M_i) of each particle: the velocity's divergence by the gradient of Eq. 31 without the
    correction B, recomputed with the periodic images along the slope. The frames hold no wall
    particles, so within a kernel support of the bed it lacks the walls' partners."""
    dp, length = p["dp"], p["columns"] * p["dp"]
    kernel = Kernel(p["kernel"], p["h_factor"] * dp, 2)
    x = frame["x"].copy()
    x[:, 0] %= length
    n = len(x)
    x = np.concatenate([x, x + [length, 0.0], x - [length, 0.0]])
    kind, mass, rho, v = (np.concatenate([frame[name]] * 3) for name in ("kind", "mass", "rho", "v"))
    start, nbr = neighbour_lists(x, np.arange(len(x)), kind, n, kernel.support, x.min(axis=0) - dp)
    eps = np.zeros((len(x), 3))
    strain_rate(n, start, nbr, x, v, rho, mass, kind, np.zeros_like(x), np.zeros(len(x)), 0.0, np.zeros((0, 1)),
                kernel.params, eps, np.zeros(len(x)))
    return eps[:n, 0] + eps[:n, 1]


def bulk_table(frames, p):
    """Rows (height, then over the layer's mean s p: the mean normal viscous stress 2 eta eps_yy, the
    mean of its isotropic part eta tr(eps) (2 eta eps's in 2D), and the share of that in the layer's
    mean eta times its mean tr(eps), the rest being their covariance; then over the layer's mean shear
    rate 2 eps_xy: the mean tr(eps) of the corrected gradient, that of the uncorrected one
    (``uncorrected_trace``) and the mean -(drho/dt) / rho of the continuity equation, Eq. 26)
    averaged over ``frames``: the bulk viscosity that the stress 2 eta eps gives the grains, and the
    mean stress it carries in a steady layer (physics/mu_i.py)."""

    def of_frame(f):
        eps, eta = f["strain"], f["eta"]
        trace, uncorrected = eps[:, 0] + eps[:, 1], uncorrected_trace(f, p)
        P = carried_pressure(f)
        continuity = -f["drho_dt"] / f["rho"]
        return lambda s, index: (f["x"][s, 1].mean(), P[s].mean(), 2.0 * eps[s, 2].mean(),
                                 np.mean(2.0 * eta[s] * eps[s, 1]), np.mean(eta[s] * trace[s]),
                                 eta[s].mean() * trace[s].mean(), trace[s].mean(), uncorrected[s].mean(),
                                 continuity[s].mean())

    rows = []
    for y, P, rate, normal, isotropic, means, trace, uncorrected, continuity in per_layer(frames, p["dp"], of_frame):
        rows.append((y, normal / P, isotropic / P, means / P, trace / rate, uncorrected / rate, continuity / rate))
    return rows


def traction_table(frames, p):
    """Rows (plane height, then for the shear and for the normal traction on the part above each plane
    between layers: that of the pressure pairs, of the viscous pairs and of the momentum carried
    across, each over the weight's component along the slope less the side walls' friction on that
    part (physics/side_walls.py on the frame's velocities and the law's pressure), then over the
    weight's component normal to it)."""
    dp, theta, length = p["dp"], math.radians(p["theta"]), p["columns"] * p["dp"]
    kernel = Kernel(p["kernel"], p["h_factor"] * dp, 2)
    walls = [t for t in case_of_frame(p).forces if isinstance(t, SideWallFriction)]
    planes = np.arange(1, int(p["H"] / dp)) * dp
    sums = np.zeros((len(planes), 6))
    for f in frames:
        x, m, rho, pressure, T = f["x"], f["mass"], f["rho"], f["p"], f["T_visc"]
        dx = x[:, None, 0] - x[None, :, 0]
        dx -= length * np.round(dx / length)  # periodic along the slope
        dy = x[:, None, 1] - x[None, :, 1]
        r = np.hypot(dx, dy)
        np.fill_diagonal(r, 1.0)
        f_r = kernel.derivative(r) / r  # grad_i W_ij = f_r r_ij
        np.fill_diagonal(f_r, 0.0)
        mm = m[:, None] * m[None, :] * f_r
        on_i = []  # (pressure, viscous) pair forces on i, along the slope, then normal to it
        for c, d in ((0, dx), (1, dy)):
            if "T_pressure" in f:  # pressure_form = isotropic
                on_p = _stress_pairs(mm, rho, f["T_pressure"], dx, dy, c)
            else:
                on_p = -mm * ((pressure / rho**2)[:, None] + (pressure / rho**2)[None, :]) * d
            on_i.append((on_p, _stress_pairs(mm, rho, T, dx, dy, c)))
        layer = np.floor(x[:, 1] / dp).astype(int)
        layer -= layer.min()
        counts = np.bincount(layer)
        v = f["v"] - np.stack([np.bincount(layer, f["v"][:, c]) / counts for c in (0, 1)], axis=1)[layer]
        normal_weight = weight_above(f, p, planes)
        # what the side walls hold of the part above each plane: their force along the slope
        held = np.zeros(len(planes))
        for term in walls:
            acc = np.zeros_like(f["v"])
            add_side_wall_friction(len(x), f["kind"], f["v"], friction_pressure(f), rho, term.rate, term.v_reg, 0.0,
                                   acc)
            held -= [np.sum((m * acc[:, 0])[x[:, 1] > Y]) / length for Y in planes]
        for n, Y in enumerate(planes):
            above = x[:, 1] > Y
            across = above[:, None] & ~above[None, :]
            band = np.abs(x[:, 1] - Y) < dp
            flux = [(m[band] * v[band, c] * v[band, 1]).sum() / (2.0 * dp * length) for c in (0, 1)]
            # in a steady layer the part above feels -(its weight along the slope) and +(its weight
            # normal to the slope) from below
            shear = [-a[across].sum() / length for a in on_i[0]] + [-flux[0]]
            normal = [a[across].sum() / length for a in on_i[1]] + [flux[1]]
            along = normal_weight[n] * math.tan(theta) - held[n]
            sums[n] += np.array(shear + normal) / np.repeat([along, normal_weight[n]], 3)
    return [(Y, *(sums[n] / len(frames))) for n, Y in enumerate(planes)]


def _stress_pairs(mm, rho, T, dx, dy, c):
    """Component c of the force m_i m_j (T_i + T_j) grad_i W_ij / (rho_i rho_j) on i of every pair
    (physics/viscous_stress.py), mm = m_i m_j W' / r."""
    return mm / (rho[:, None] * rho[None, :]) * ((T[:, None, c, 0] + T[None, :, c, 0]) * dx
                                                 + (T[:, None, c, 1] + T[None, :, c, 1]) * dy)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="an inclined_plane run directory")
    ap.add_argument("--frames", type=int, default=40, help="the last this many frames are averaged")
    a = ap.parse_args()
    run_params(ap, a.run, ("theta", "I_0"), "mu(I) inclined planes (inclined_plane)")
    frames = [read_frame(f) for f in list_frames(a.run)[-a.frames:]]
    p = frames[-1]["params"]
    material = case_of_frame(p).material
    print(f"{a.run}: {len(frames)} frames, t = {frames[0]['t']:.2f} to {frames[-1]['t']:.2f} s")
    print(f"{'t [s]':>6} {'mean':>6} {'surface':>7} {'L2':>6} {'p/p_h':>6} {'sp/p_h':>6}   "
          "(speeds over the analytical)")
    for f in frames[-5:]:
        print(f"{f['t']:6.2f}" + "".join(f" {v:6.3f}" for v in (*layer_speeds(f, p, material),
                                                                 *profile_figures(f, p, material))))
    if p.get("alpha", 0.0) > 0.0:
        nu, mean, surface = with_artificial_viscosity(p, material)
        speeds = np.mean([layer_speeds(f, p, material) for f in frames], axis=0)
        print(f"alpha = {p['alpha']:g} (Eq. 38) is a shear viscosity nu = alpha h c0 / 8 = {nu:.3g} m^2/s; the "
              f"uniform flow with it added has {mean:.3f} of the analytical mean speed and {surface:.3f} of the "
              f"surface speed; the {len(frames)} frames' mean over it {speeds[0] / mean:.3f}, surface "
              f"{speeds[1] / surface:.3f}")
    print(f"{'y [mm]':>7} {'u/u_a':>6} {'rate/a':>6} {'p/p_h':>6} {'sp/p_h':>6} {'mu/mu_a':>7} {'I/I_a':>6} "
          f"{'s':>6} {'A_xy':>6} {'align':>6}")
    for row in layer_table(frames, p, material):
        print(f"{1e3 * row[0]:7.2f}" + "".join(f" {v:6.3f}" for v in row[1:]))
    print(f"{'y [mm]':>7} {'tr/rate':>7} {'dif/rate':>8} {'align':>6} {'dev':>6} {'P scat':>6} {'P med':>6} "
          f"{'v_y/rate dp':>11} {'tau/tau(P)':>10} {'2eta e_xy/muP':>13}   (the law's inputs' noise)")
    for row in noise_table(frames, p, material):
        print(f"{1e3 * row[0]:7.2f} {row[1]:7.3f} {row[2]:8.3f} {row[3]:6.3f} {row[4]:6.3f} {row[5]:6.3f} "
              f"{row[6]:6.3f} {row[7]:11.3f} {row[8]:10.4f} {row[9]:13.4f}")
    if "drho_dt" in frames[-1]:
        print(f"{'y [mm]':>7} {'2eta e_yy':>9} {'eta tr':>7} {'of means':>8} {'tr/rate':>8} {'M tr/rate':>9} "
              f"{'cont/rate':>9}   (the bulk viscosity of 2 eta eps: stresses over s p)")
        for row in bulk_table(frames, p):
            print(f"{1e3 * row[0]:7.2f} {row[1]:+9.4f} {row[2]:+7.4f} {row[3]:+8.4f} {row[4]:+8.4f} {row[5]:+9.4f} "
                  f"{row[6]:+9.4f}")
    if "T_visc" in frames[-1]:
        print(f"{'':7} {'shear traction / weight along the slope':^34}   "
              f"{'normal traction / weight normal to it':^34}")
        print(f"{'plane':>7}" + f" {'pressure':>8} {'viscous':>8} {'carried':>8} {'sum':>6}  " * 2)
        for Y, *split in traction_table(frames, p):
            print(f"{1e3 * Y:7.2f}" + "".join(f" {a:8.3f} {b:8.3f} {c:8.3f} {a + b + c:6.3f}  "
                                              for a, b, c in (split[:3], split[3:])))


if __name__ == "__main__":
    main()
