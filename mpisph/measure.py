"""Quantities measured from frames and diagnostics, for validation against references."""

import numpy as np

from .neighbours import neighbour_lists
from .particles import MOVING
from .physics.kernel_mean import kernel_mean


def semi_axes(frame, dp):
    """Half-extents of a body along x and y: max |coordinate| plus half a spacing."""
    x = frame["x"]
    return np.abs(x[:, 0]).max() + 0.5 * dp, np.abs(x[:, 1]).max() + 0.5 * dp


def surge_front(frame, dp):
    """Largest x reached by the fluid, plus half a spacing (the dam-break toe)."""
    return frame["x"][:, 0].max() + 0.5 * dp


def dam_break_fronts(frames):
    """(T, Z) of a dam break's frames (cases/dam_break_2d.py, read with their walls or without) as
    Koshizuka & Oka and Martin & Moyce plot them: T = t sqrt(2 g / L) and Z = z / L, z the surge
    front of the fluid (``surge_front``) and L the column's width, from the frames' parameters."""
    p = frames[0]["params"]
    L, g, dp = float(p["L"]), float(p["g"]), float(p["dp"])
    T = np.array([f["t"] for f in frames]) * np.sqrt(2 * g / L)
    Z = np.array([surge_front({"x": f["x"][f["kind"] == MOVING]}, dp) / L for f in frames])
    return T, Z


def front_speed(T, z, lo, hi):
    """Least-squares slope dz/dT of a front over lo <= T <= hi."""
    T, z = np.asarray(T), np.asarray(z)
    inside = (T >= lo) & (T <= hi)
    return np.polyfit(T[inside], z[inside], 1)[0]


def time_offset(T, z, T_ref, z_ref, span=1.0, step=0.001):
    """The shift dT within [-span, span] that best aligns the front z(T) with the reference points:
    the least squares of z(T_ref + dT) - z_ref over the points inside the run."""
    T_ref, z_ref = np.asarray(T_ref), np.asarray(z_ref)
    best, offset = np.inf, 0.0
    for dT in np.arange(-span, span + step / 2, step):
        inside = (T_ref + dT >= T[0]) & (T_ref + dT <= T[-1])
        if inside.sum() < 2:
            continue
        err = np.mean((np.interp(T_ref[inside] + dT, T, z) - z_ref[inside]) ** 2)
        if err < best:
            best, offset = err, dT
    return offset


def decay_rate(t, energy):
    """Least-squares slope of ln(energy) against t."""
    return np.polyfit(np.asarray(t), np.log(np.asarray(energy)), 1)[0]


def line_average(frame, points, component, kernel):
    """Velocity ``component`` at ``points`` (k, dim): the ``kernel``-weighted average (a Kernel,
    kernels.py) of the particles within its support."""
    x, v = frame["x"], frame["v"][:, component]
    out = np.full(len(points), np.nan)
    for k, q in enumerate(np.asarray(points, dtype=float)):
        w = kernel.value(np.linalg.norm(x - q, axis=1))
        if w.sum() > 0:
            out[k] = np.sum(w * v) / w.sum()
    return out


def nearest_value(frame, name, point, count=4):
    """Mean of field ``name`` over the ``count`` particles nearest ``point``."""
    d = np.linalg.norm(frame["x"] - np.asarray(point, dtype=float), axis=1)
    return float(np.mean(frame[name][np.argsort(d)[:count]]))


def _surface_profile(x, dp):
    """Bins of width dp along x from the leftmost particle: (left edges, top + dp/2, occupied, each
    particle's bin); the height is the last coordinate (y in 2D, z in 3D, where a slab's bins span
    its width). A column of a lattice starts its bin: the 1e-9 keeps it there when round-off puts it
    just below the bin's edge (without it, half the bins of a column's first frame came out empty)."""
    lo = x[:, 0].min()
    k = np.floor((x[:, 0] - lo) / dp + 1e-9).astype(int)
    top = np.full(k.max() + 1, -np.inf)
    np.maximum.at(top, k, x[:, -1])
    return lo + np.arange(len(top)) * dp, top + 0.5 * dp, np.isfinite(top), k


def layer_means(frame, dp, values):
    """(mean height, mean of ``values``) of the particles in each dp-thick layer above the bed
    {y = 0} that holds any, from the bed up: a layer flowing down a slope, layer by layer."""
    y = frame["x"][:, 1]
    k = np.floor(y / dp).astype(int)
    layers = np.unique(k)
    return np.array([y[k == j].mean() for j in layers]), np.array([values[k == j].mean() for j in layers])


def runout(frame, dp):
    """Right end of the connected deposit: the last dp-wide bin before the first empty one, plus its width.

    Particles beyond a gap (grains thrown ahead of the toe) do not count. The bins start at the
    leftmost particle's centre, so a lattice column L_0 long that has not moved reads L_0 + dp/2
    (runout ratio 0.5 dp / L_0, 0.025 at L_0 / dp = 20), where radial_runout, binned from the axis,
    reads r_0: the planar sections of docs/VALIDATION.md were measured so.
    """
    left, _, occupied, _ = _surface_profile(frame["x"], dp)
    return float(left[_last_connected(occupied)] + dp)


def _last_connected(occupied):
    """Index of the last occupied bin before the first empty one."""
    gap = np.flatnonzero(~occupied)
    return (gap[0] - 1) if len(gap) else len(occupied) - 1


def outward_distance(x, radial=False):
    """Each particle's distance along x, or (``radial``) from the z axis: how far a collapse has
    carried it from its back wall or its axis."""
    return np.hypot(x[:, 0], x[:, 1]) if radial else x[:, 0]


def _polar(x, sectors):
    """Distance from the z axis and azimuthal sector (of ``sectors``) of each particle."""
    sector = ((np.arctan2(x[:, 1], x[:, 0]) + np.pi) / (2 * np.pi) * sectors).astype(int) % sectors
    return outward_distance(x, radial=True), sector


def _sector_runouts(r, sector, dp, sectors):
    """Per azimuthal sector: the outer edge of the connected deposit in dp-wide radial bins from the
    axis. Bins nearer the axis than an arc of 2 dp per sector count as occupied (too narrow to hold
    a particle for sure)."""
    k = np.floor(r / dp).astype(int)
    narrow = int(np.ceil(sectors / np.pi))
    out = np.zeros(sectors)
    for s in range(sectors):
        occupied = np.zeros(k.max() + 2, bool)
        occupied[:narrow] = True
        occupied[k[sector == s]] = True
        out[s] = (_last_connected(occupied) + 1) * dp
    return out


def radial_runout(frame, dp, sectors=16):
    """Mean radius of an axisymmetric deposit: the edge of its connected part (``runout``'s rule,
    on radial bins) averaged over ``sectors`` azimuthal sectors."""
    return float(_sector_runouts(*_polar(frame["x"], sectors), dp, sectors).mean())


def front_position(frame, dp, radial=False, sectors=16):
    """Where the connected deposit ends, to better than a bin: the largest x of the grains in its
    outermost dp-wide bin, or (``radial``) the largest distance from the z axis of those of each
    azimuthal sector, averaged over the sectors."""
    x = frame["x"]
    if not radial:
        _, _, occupied, k = _surface_profile(x, dp)
        return float(x[k == _last_connected(occupied), 0].max())
    r, sector = _polar(x, sectors)
    edges = _sector_runouts(r, sector, dp, sectors)
    at_front = (r >= edges[sector] - dp) & (r < edges[sector])
    farthest = np.full(sectors, -np.inf)
    np.maximum.at(farthest, sector[at_front], r[at_front])
    return float(farthest[np.isfinite(farthest)].mean())


def beyond_the_edge(frame, dp, radial=False, sectors=16):
    """Mask of the grains beyond the connected deposit's edge (``runout``, or per azimuthal sector
    ``radial_runout``'s): those that a gap of a bin or more separates from the deposit."""
    x = frame["x"]
    if not radial:
        _, _, occupied, k = _surface_profile(x, dp)
        return k > _last_connected(occupied)
    r, sector = _polar(x, sectors)
    return r >= _sector_runouts(r, sector, dp, sectors)[sector]


def mass_extent(frame, fraction, radial=False):
    """The distance along x (``radial``: from the z axis) within which ``fraction`` of the mass of
    the frame's particles lies: the centre of the particle at which their cumulative mass, in
    order of distance, reaches it. Unlike the edge of a deposit, it does not follow a sheet of a
    few grains' thickness that a finer spacing resolves further out."""
    return weighted_quantile(outward_distance(frame["x"], radial), frame["mass"], fraction)


def weighted_quantile(values, weights, share):
    """The value at which the cumulative weight, in order of the values, reaches ``share`` of the
    total weight."""
    order = np.argsort(values, kind="stable")
    cumulative = np.cumsum(weights[order])
    return float(values[order][np.searchsorted(cumulative, share * cumulative[-1])])


def planar_runout_fits(a, ratio):
    """Lube et al.'s (2005) two fits of planar runout ratios ``ratio`` at aspect ratios ``a``: the
    slope through the origin of the columns a <= 1 (1.2 for their sand) and the exponent of a power
    law through those a >= 4 (2/3)."""
    a, ratio = np.asarray(a, dtype=float), np.asarray(ratio, dtype=float)
    low, high = a <= 1.0, a >= 4.0
    slope = float(np.sum(a[low] * ratio[low]) / np.sum(a[low] ** 2))
    return slope, float(np.polyfit(np.log(a[high]), np.log(ratio[high]), 1)[0])


AT_REST = 1e-3  # edge_rest_ratio at or below which a deposit is at rest (004_ Sec. 5.2: three orders of magnitude)


def edge_rest_ratio(before, last, t, front, dp, radial=False):
    """How far a collapse's deposit is from rest: the speed of its edge (``front_position``) from
    the frame ``before`` to the frame ``last``, over the peak speed of its front ``front`` (the
    farthest grain, diagnostics.csv) against time ``t``. 004_ Sec. 5.2 finds its deposits' fronts
    at least three orders of magnitude slower than at their peak."""
    edge = [front_position(f, dp, radial=radial) for f in (before, last)]
    speed = abs(edge[1] - edge[0]) / (last["t"] - before["t"])
    return float(speed / np.max(np.diff(front) / np.diff(t)))


def collapse_onset(t, front, length, fraction=0.05):
    """When a collapse starts: the first time ``t`` at which its front ``front`` (the farthest
    grain, diagnostics.csv) has moved ``fraction`` of the column's length or radius ``length`` from
    where it started; nan if it never has."""
    moved = np.asarray(front) - front[0] > fraction * length
    return float(np.asarray(t)[np.argmax(moved)]) if moved.any() else float("nan")


def farthest_edge(frame, dp, radial=False):
    """The farthest grain's outer edge (+ dp/2) from the back wall (x) or, ``radial``, the z axis."""
    return float(outward_distance(frame["x"], radial).max() + 0.5 * dp)


def deposit_height(frame, dp, x_max, radial=False):
    """Highest free surface (top particle + dp/2, height the last coordinate) among particles with x
    (``radial``: the distance from the z axis) below ``x_max``."""
    x = frame["x"]
    return float(x[outward_distance(x, radial) < x_max, -1].max() + 0.5 * dp)


def thrust_ratio(frame):
    """A soil's first horizontal stress over its vertical one (the last axis), each integrated over
    its volume: the thrust on a vertical wall over the one a lateral stress equal to the vertical
    would give; nu / (1 - nu) for an elastic layer at rest in one-dimensional compression."""
    volume = frame["mass"] / frame["rho"]
    vertical = frame["x"].shape[1] - 1
    return float(np.sum(frame["stress"][:, 0] * volume) / np.sum(frame["stress"][:, vertical] * volume))


def crest_crack(first, last, dp, face, drop):
    """Distance behind the face ``face`` (x) of the crest crack: the leftmost particle of the
    initial top layer that has sunk by more than ``drop``."""
    x0, x1 = first["x"], last["x"]
    top = x0[:, 1] > x0[:, 1].max() - 0.5 * dp
    sunk = top & (x0[:, 1] - x1[:, 1] > drop)
    if not sunk.any():
        return 0.0
    return float(face - x0[sunk, 0].min())


def zero_crossings(t, y, rising):
    """Times where ``y`` crosses zero upwards (``rising``) or downwards, by linear interpolation."""
    t, y = np.asarray(t), np.asarray(y)
    sign = (y[:-1] < 0) & (y[1:] >= 0) if rising else (y[:-1] > 0) & (y[1:] <= 0)
    k = np.flatnonzero(sign)
    return t[k] - y[k] * (t[k + 1] - t[k]) / (y[k + 1] - y[k])


def period_ends(t, y):
    """Ends of the whole periods of an oscillation that starts at y = 0 moving up: its upward
    crossings after t > 0."""
    up = zero_crossings(t, y, rising=True)
    return up[up > 0.0]


def first_period(t, y):
    """First period of an oscillation that starts at y = 0 moving up (nan before one ends)."""
    ends = period_ends(t, y)
    return float(ends[0]) if len(ends) else float("nan")


def surface_profile(frame, dp):
    """(bin centres, top of the deposit) over occupied dp-wide bins along x."""
    left, top, occupied, _ = _surface_profile(frame["x"], dp)
    return left[occupied] + 0.5 * dp, top[occupied]


def cut_height(frame):
    """The height of a cut (or of any body on a floor at y = 0): its top particle's centre plus half
    of the frame's spacing ``dp``."""
    return float(frame["x"][:, 1].max()) + 0.5 * float(frame["params"]["dp"])


def displacement_percentile(first, frame, share=99.0):
    """The ``share`` percentile of the particles' displacements from ``first`` to ``frame`` [m], both
    read by gid without walls."""
    return float(np.percentile(np.linalg.norm(frame["x"] - first["x"], axis=1), share))


def kinetic_energy_peak(diag):
    """(peak kinetic energy [J], its time [s]) of a run's diagnostics (io.diagnostics.read_diagnostics)."""
    k = int(np.argmax(diag["kinetic_energy"]))
    return float(diag["kinetic_energy"][k]), float(diag["t"][k])


def max_speed(frame):
    """The largest speed of a moving particle in ``frame`` (read with its walls or without)."""
    return float(np.linalg.norm(frame["v"][frame["kind"] == MOVING], axis=1).max())


def final_over_peak(speeds):
    """The last of a run's largest speeds per frame (``max_speed``) over the largest of them: the
    Drucker-Prager column collapse and the 3D flume count a deposit at rest below 0.01."""
    return speeds[-1] / np.max(speeds)


def final_over_peak_speed(frames):
    """``final_over_peak`` of the ``max_speed`` of each of ``frames``."""
    return final_over_peak([max_speed(f) for f in frames])


def jostle_pressure(frame, kernel):
    """rho |v - <v>|^2 / D of each moving particle of ``frame`` (no periodic images; 0 on walls): the
    momentum flux, as a pressure, of its velocity's departure from its kernel mean <v>
    (physics/kernel_mean.py), which follows a velocity that is smooth on the kernel's scale. In a shear
    it is the particles' jostle as they ride over each other (docs/INCLINE.md, 'The particles' jostle')."""
    x, v, kind = frame["x"], frame["v"], frame["kind"]
    n = len(x)
    start, nbr = neighbour_lists(x, frame["gid"], kind, n, kernel.support, x.min(axis=0) - kernel.support)
    mean = np.zeros_like(v)
    kernel_mean(n, start, nbr, x, frame["rho"], frame["mass"], kind, v, kernel.params, mean)
    return np.where(kind == MOVING, frame["rho"] * ((v - mean) ** 2).sum(axis=1) / x.shape[1], 0.0)
