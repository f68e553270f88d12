"""Measures of a layer flowing down a periodic slope (the case inclined_plane) against the uniform
flow of 004_ Sec. 5.1 (references.inclined_plane_velocity, or between the run's side walls
references.inclined_plane_velocity_between_walls) of the same grains, whose depth is the layer's at
rest dilated to the uniform flow's volume fraction (``flow_depth``), frame by frame, over dp-thick
layers above the bed {y = 0}: for scripts/incline_layers.py and scripts/validate.py."""

import math

import numpy as np

from . import measure
from .references import (inclined_plane_flow_depth, inclined_plane_mean_velocity_with_viscosity,
                         inclined_plane_inertial_number_between_walls,
                         inclined_plane_mean_velocity_between_walls, inclined_plane_surface_velocity,
                         inclined_plane_velocity, inclined_plane_velocity_between_walls,
                         inclined_plane_velocity_with_viscosity, pair_viscosity_of_alpha)
from .tensors import unpacked


def flow_depth(p, material):
    """The depth of the uniform flow of the run's grains, laid at rest H deep
    (references.inclined_plane_flow_depth) [m]."""
    return inclined_plane_flow_depth(material, p["theta"], p["H"])


def side_walls_of(p):
    """(width, mu_w) of the run's side walls, or None without them."""
    if p.get("channel_width", 0.0) > 0:
        return p["channel_width"], math.tan(math.radians(p["wall_friction_deg"]))
    return None


def analytical_velocity(p, material, z):
    """The uniform flow's u at the heights ``z`` (clipped to the flow depth): between the run's side
    walls when it has them (``channel_width`` > 0), else 004_'s."""
    theta, H, g, walls = p["theta"], flow_depth(p, material), p["g"], side_walls_of(p)
    z = np.clip(np.asarray(z, dtype=float), 0.0, H)
    if walls:
        return inclined_plane_velocity_between_walls(material, theta, H, g, *walls, z)
    return inclined_plane_velocity(material, theta, H, g, z)


def analytical_inertial_number(p, material, z):
    """The uniform flow's I at the heights ``z`` (clipped to the flow depth): I_u of mu(I_u) =
    tan(theta) at every depth without side walls."""
    theta, H, g, walls = p["theta"], flow_depth(p, material), p["g"], side_walls_of(p)
    if walls:
        z = np.clip(np.asarray(z, dtype=float), 0.0, H)
        return inclined_plane_inertial_number_between_walls(material, theta, H, g, *walls, z)
    return np.full(np.shape(z), material.uniform_flow(theta)[0])


def analytical_mean(p, material):
    """The mass-weighted mean of ``analytical_velocity`` over the layer, as the particles' mean speed
    weighs it: 3/5 of the surface speed of 004_'s u(z) ~ H^(3/2) - (H - z)^(3/2) at its uniform phi_u."""
    theta, H, g, walls = p["theta"], flow_depth(p, material), p["g"], side_walls_of(p)
    if walls:
        return inclined_plane_mean_velocity_between_walls(material, theta, H, g, *walls)
    return 0.6 * inclined_plane_surface_velocity(material, theta, H, g)


def layer_speeds(frame, p, material):
    """(mean speed along the slope over the analytical mean, mean speed of the particles within dp/2
    of the top over the analytical surface speed) of one frame."""
    x, u = frame["x"], frame["v"][:, 0]
    surface = float(analytical_velocity(p, material, np.inf))
    top = x[:, 1] > x[:, 1].max() - 0.5 * p["dp"]
    return float(u.mean() / analytical_mean(p, material)), float(u[top].mean() / surface)


def with_artificial_viscosity(p, material):
    """(nu, mean, surface) of the uniform flow with the shear viscosity nu of the run's alpha (004_
    Eq. 38; references.pair_viscosity_of_alpha, c0 the sound speed at rest) added to the law: its
    mean and surface speed over the analytical ones of ``layer_speeds``."""
    theta, H, g = p["theta"], flow_depth(p, material), p["g"]
    nu = pair_viscosity_of_alpha(p["alpha"], p["h_factor"] * p["dp"], material.c0, 2)
    surface = inclined_plane_surface_velocity(material, theta, H, g)
    return (nu, inclined_plane_mean_velocity_with_viscosity(material, theta, H, g, nu) / (0.6 * surface),
            float(inclined_plane_velocity_with_viscosity(material, theta, H, g, nu, 2.0 * H)) / surface)


def kernel_moment(frame):
    """(s, A_xy) of each particle of a 2D frame, A = B^-1; nan where the frame holds no B."""
    if "B" not in frame:
        return np.full(len(frame["x"]), np.nan), np.full(len(frame["x"]), np.nan)
    A = np.linalg.inv(unpacked(frame["B"], 2))
    return 0.5 * (A[:, 0, 0] + A[:, 1, 1]), A[:, 0, 1]


def carried_pressure(frame):
    """s p of each particle of a 2D frame, the share of its pressure the pairs carry (``kernel_moment``);
    the grains' p where the frame holds no B."""
    return kernel_moment(frame)[0] * frame["p"] if "B" in frame else frame["p"]


def weight_above(frame, p, heights):
    """The weight normal to the slope, per unit area, of the grains above each of ``heights``: each
    grain a slab dp thick centred on it, so that a grain within dp/2 of a height counts in part
    (half of a row of a lattice that lies on it)."""
    y, m = frame["x"][:, 1], frame["mass"]
    weight = math.cos(math.radians(p["theta"])) * p["g"] / (p["columns"] * p["dp"])
    above = np.clip((y[None, :] - np.asarray(heights, float)[:, None]) / p["dp"] + 0.5, 0.0, 1.0)
    return above @ m * weight


def hydrostatic(frame, p):
    """The hydrostatic pressure at the mean height of each dp-thick layer (measure.layer_means' order):
    the weight of the grains above it (``weight_above``)."""
    y, _ = measure.layer_means(frame, p["dp"], frame["x"][:, 1])
    return weight_above(frame, p, y)


def profile_figures(frame, p, material):
    """(L2 error of the layers' speed against u(z) at their heights clipped to [0, H], H the flow
    depth, the layers' mean pressure over their mean hydrostatic pressure, the same for s p) of one
    frame, over dp-thick layers (measure.layer_means)."""
    dp = p["dp"]
    y, u = measure.layer_means(frame, dp, frame["v"][:, 0])
    _, pressure = measure.layer_means(frame, dp, frame["p"])
    _, carried = measure.layer_means(frame, dp, kernel_moment(frame)[0] * frame["p"])
    u_a = analytical_velocity(p, material, y)
    p_h = hydrostatic(frame, p).mean()
    return (float(np.sqrt(np.mean((u - u_a) ** 2) / np.mean(u_a**2))), float(pressure.mean() / p_h),
            float(carried.mean() / p_h))
