"""3D cohesive granular flow down a 50-degree flume onto a barrier, built from STL files (000_ Sec. 5.4, Fig. 25).

The geometry is read from cases/flume/ (written by scripts/make_flume_stl.py, sketched in
docs/FLUME.md; the paper gives its dimensions only in a figure, these are ours): a chute 3 m
long at 50 degrees and 1 m wide between side walls 1.5 m high, closed at its top; a level
run-out 3 m long closed at its end; across it, 0.6 m from the foot of the slope, a barrier 0.12 m
thick and 0.8 m high. The soil mass, 1.6 m along the slope, 1 m wide and 1.2 m deep, rests on the
chute against its top wall. It is twice as deep as the infinite-slope limit c / (rho g (sin 50 -
cos 50 tan 25)) = 0.59 m, so it cannot stand on the slope, and deep enough to reach the barrier
(a mass 0.8 m deep stops at the foot of the slope). It starts at rest without stress (the paper
does not give its initial stress); gravity loads it at t = 0.

Material: 000_ Table 2, second column (rho 1850, E 1.8 MPa, nu 0.3, c 5 kPa, phi 25, psi 0); UTVF;
the density by kernel summation every configuration (density_reinit = free_surface, docs/FLUME.md).
Floors, end walls and the barrier are no-slip dummy walls (000_ Sec. 5). The side walls are
free-slip, as the smooth side walls of a laboratory flume: had they no slip, the cohesion on the
mass's two sides (2 c L T) would add to that on its base (c L W), and a mass of length L and depth
T could slide only if rho g L W T (sin 50 - cos 50 tan 25) > c L (W + 2 T), i.e. 8455 W T > 5000
(W + 2 T) with W = 1 m: never, however deep. Every wall's lattice runs along its own floor: the
chute's along the slope (so are the soil's particles), the run-out's and the barrier's level.

Recorded: the force and moment of the soil on the barrier (diagnostics.csv, the moment about the
middle of its upstream foot, x = the barrier's upstream face, z = its foot; about another point r,
M_r = M + (r_foot - r) x F, the downstream toe's r_foot - r = (-0.12, 0, 0) m), the front
(distance along x from the chute's top), the flow top along the centre line upstream of the barrier
(gauge_depth.csv), and the velocity on a vertical line 0.4 m upstream of the barrier
(gauge_approach.csv) with the flow top over it (gauge_approach_top.csv), from which diagnostics.csv
gets the approach speed v and depth h (over the run-out's floor, z = 0) and the dynamic pressure
coefficient alpha = F / (rho v^2 h w) of the same row, w the barrier's width, rho the soil's rho0
(barrier_load.py). After the impact the approach line stands in the deposit or its backwave, where
v is small and alpha large: the impact's alpha is the peak force over the flux rho v^2 h w of the
flow that arrives (scripts/production.py plots both and docs/PRODUCTION_3D.md quotes it). A geometry
of one's own (scripts/make_flume_stl.py) must keep the run-out's floor at z = 0 and the barrier on
it, downstream of the foot (x > 0).
"""

from pathlib import Path

import numpy as np

from mpisph.barrier_load import BarrierLoad
from mpisph.case import Body, Case, Front, Param, Wall, limiter_param
from mpisph.errors import InputError
from mpisph.gauges import Gauge, SurfaceGauge
from mpisph.geometry import support_layers
from mpisph.lattice import Frame
from mpisph.meshes import fill, read_surface, wall_layers
from mpisph.soil import drucker_prager, soil_params, stress_diffusion_param

GEOMETRY = Path(__file__).resolve().parent / "flume"
WALLS = ("chute", "chute_sides", "runout", "runout_sides", "barrier")  # STL files; floors before sides
APPROACH = 0.4  # distance of the approach gauge upstream of the barrier [m]

PARAMS = {
    "geometry": Param("", "-", "directory of the STL files " + ", ".join(WALLS) + " and soil; empty: cases/flume"),
    "dp": Param(0.04, "m", "particle spacing (000_'s cube, Sec. 5.3; Sec. 5.4 gives none)", positive=True),
    # 000_ Table 2, second column; the density by kernel summation, as the authors' code does for soils:
    # evolved by Eq. 16 alone it drifts without bound in the resting deposit (docs/FLUME.md)
    **soil_params(rho0=1850.0, E=1.8e6, nu=0.3, cohesion=5.0e3, phi=25.0, density_reinit="free_surface",
                  at_rest=False),
    "limiter": limiter_param("separating"),
    "stress_diffusion": stress_diffusion_param(),
    "t_end": Param(4.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
}


def slope_frame(chute):
    """The lattice frame of the chute: down the slope, across, and the floor's upward normal, from
    the chute's steepest-up facing triangles (its floor); origin at the floor's top corner at y = 0."""
    n = chute.normals
    floor = n[:, 2] > n[:, 2].max() - 1e-9
    up = n[floor][0]
    across = np.array([0.0, 1.0, 0.0])
    along = np.cross(across, up)
    corners = chute.triangles[floor].reshape(-1, 3)
    top = corners[np.lexsort((corners[:, 1], -corners[:, 2]))[0]]
    return Frame(origin=tuple(top), axes=tuple(map(tuple, np.column_stack([along, across, up]))))


def setup(p):
    geometry = Path(p.geometry) if p.geometry else GEOMETRY
    surfaces = [read_surface(geometry / f"{name}.stl") for name in WALLS]
    chute, barrier = surfaces[0], surfaces[-1]
    slope, level = slope_frame(chute), Frame()
    soil = read_surface(geometry / "soil.stl")
    frames = [slope if name.startswith("chute") else level for name in WALLS]
    layers = support_layers(p.h_factor)
    walls = [Wall(name, points, slip=name.endswith("sides")) for name, points in
             zip(WALLS, wall_layers(surfaces, p.dp, layers, frames))]
    corners = np.concatenate([s.triangles.reshape(-1, 3) for s in [soil] + surfaces])
    lo, hi = corners.min(axis=0) - (layers + 1) * p.dp, corners.max(axis=0) + (layers + 1) * p.dp
    soil_lo, soil_hi = soil.triangles.reshape(-1, 3).min(axis=0), soil.triangles.reshape(-1, 3).max(axis=0)
    b_lo, b_hi = barrier.triangles.reshape(-1, 3).min(axis=0), barrier.triangles.reshape(-1, 3).max(axis=0)
    if b_lo[0] <= APPROACH:
        raise InputError(f"flume_3d: the barrier's upstream face is at x = {b_lo[0]:g} m, where the case needs it "
                         f"on the run-out more than the approach gauge's {APPROACH:g} m downstream of the foot "
                         "of the slope (x = 0)")
    middle = 0.5 * (b_lo[1] + b_hi[1])
    upstream = b_lo[0] - APPROACH
    along = np.arange(0.5 * p.dp, b_lo[0], max(2 * p.dp, b_lo[0] / 100))  # the run-out upstream of the barrier
    stations = np.column_stack([along, np.full_like(along, middle)])
    return Case(
        dim=3,
        domain=(lo, hi),
        dp=p.dp,
        material=drucker_prager(p),
        scheme="riemann_granular",
        scheme_options={"limiter": p.limiter, "stress_diffusion": p.stress_diffusion},
        bodies=[Body("soil", fill(soil, p.dp, slope))],
        walls=walls,
        gravity=(0.0, 0.0, -p.g),
        stabilisers=p.stabiliser,
        density_reinit=p.density_reinit,
        u_ref=float(np.sqrt(2.0 * p.g * (soil_hi[2] - soil_lo[2]))),
        front=Front(origin=(float(slope.origin[0]), 0.0, 0.0), axes=(0,)),  # x from the top corner of the chute floor
        wall_forces={"barrier": (b_lo[0], middle, b_lo[2])},
        barrier_loads=[BarrierLoad("barrier", "approach", "approach_top", width=b_hi[1] - b_lo[1], density=p.rho0,
                                   bed=0.0)],
        gauges=[SurfaceGauge("depth", stations),
                Gauge.line("approach", (upstream, middle, 0.5 * p.dp), (upstream, middle, 1.5), 31, fields=("v",)),
                SurfaceGauge("approach_top", np.array([[upstream, middle]]))],
    )
