"""The dynamic pressure coefficient of a barrier, recorded in diagnostics.csv while a run goes.

A barrier designer sizes a barrier against the force a flow exerts on it as a multiple of the
momentum flux of the flow arriving: alpha = F / (rho v^2 h w). A case declares it with a
``BarrierLoad`` in ``Case.barrier_loads``; each adds three columns to diagnostics.csv:

- ``approach_speed_<wall>``: v, the mean of the flow-direction velocity over the points of a
  vertical gauge line upstream that are inside the flow (kernel sum >= 1/2: ``depth_averaged``);
- ``approach_depth_<wall>``: h, the top of the material over a surface gauge's first station (above
  the line) less the bed's height there;
- ``alpha_<wall>``: the wall's force along the flow direction (wall_forces.py) over rho v^2 h w;
  nan where nothing arrives yet (v h = 0) or no point of the line is inside the flow.

rho and w are the case's: the material's reference density and the width of the flow across the
barrier. Each row takes the force and the gauges at the same instant; a flow that has come to rest
against the barrier has v near 0, so alpha grows without meaning there: read it while the flow
arrives (docs/PRODUCTION_3D.md draws it while v is at least a tenth of its peak).
"""

from dataclasses import dataclass

import numpy as np

from .errors import InputError


@dataclass(frozen=True)
class BarrierLoad:
    """alpha of the wall ``wall`` (a name of ``Case.wall_forces``) struck by a flow along ``axis``:
    v from the gauge ``approach`` (a ``Gauge`` sampling ``v`` on a vertical line), h from the
    ``SurfaceGauge`` ``top`` (its first station) less ``bed``, the flow ``width`` wide, of
    ``density``."""

    wall: str
    approach: str
    top: str
    width: float
    density: float
    axis: int = 0
    bed: float = 0.0


# each barrier load's diagnostics columns, <kind>_<wall>, with their meaning and unit
LOAD_KINDS = {"approach_speed": "depth-averaged speed on the barrier's approach gauge [m/s]",
              "approach_depth": "flow depth over the bed at the approach gauge [m]",
              "alpha": "dynamic pressure coefficient F / (rho v^2 h w) of this row's force, speed and depth [-]"}


def barrier_load_columns(case):
    """The diagnostics columns of the case's barrier loads."""
    return [f"{kind}_{load.wall}" for load in case.barrier_loads for kind in LOAD_KINDS]


def check_barrier_loads(case):
    """Raise InputError for a barrier load whose wall force or gauges the case does not record."""
    from .gauges import Gauge, SurfaceGauge

    gauges = {g.name: g for g in case.gauges}
    for load in case.barrier_loads:
        approach, top = gauges.get(load.approach), gauges.get(load.top)
        if load.wall not in case.wall_forces:
            raise InputError(f"barrier load on {load.wall!r}: the case records no force on that wall (wall_forces)")
        if not (isinstance(approach, Gauge) and "v" in approach.fields):
            raise InputError(f"barrier load on {load.wall!r}: {load.approach!r} is not a gauge that samples v")
        if not isinstance(top, SurfaceGauge):
            raise InputError(f"barrier load on {load.wall!r}: {load.top!r} is not a surface gauge")
        if not (load.width > 0 and load.density > 0 and 0 <= load.axis < case.dim):
            raise InputError(f"barrier load on {load.wall!r}: width and density must be positive and axis "
                             f"one of 0..{case.dim - 1}")


def barrier_load_values(case, forces, gauges):
    """The values of ``barrier_load_columns`` from this row's wall forces ({column: value}) and gauge
    samples ({gauge name: {column: value}}, gauges.GaugeRecorder.sample)."""
    out = []
    for load in case.barrier_loads:
        line = gauges[load.approach]
        sums = [k for k in line if k.endswith("_kernel_sum")]  # one a point, in the points' order
        component = f"_v{'xyz'[load.axis]}"
        speed = depth_averaged([[line[k.replace("_kernel_sum", component)] for k in sums]],
                               [[line[k] for k in sums]])[0]
        depth = gauges[load.top]["s0_top"] - load.bed
        force = forces[f"force_{load.wall}_{'xyz'[load.axis]}"]
        alpha = barrier_coefficient(force, load.density, speed, depth, load.width)
        out += [float(speed), float(depth), float(alpha)]
    return out


def depth_averaged(values, kernel_sum):
    """Mean over the points of a vertical gauge line inside the material (kernel sum >= 1/2) of
    ``values`` (rows: times, columns: points); nan where no point is inside."""
    inside = np.asarray(kernel_sum) >= 0.5
    total = np.where(inside, np.asarray(values), 0.0).sum(axis=1)
    count = inside.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(count > 0, total / count, np.nan)


def barrier_coefficient(force, density, speed, depth, width):
    """Dynamic pressure coefficient alpha = F / (rho v^2 h w) of a barrier w wide struck by a flow of
    density rho arriving at ``speed`` v with ``depth`` h (arrays over time); nan where v h = 0."""
    with np.errstate(invalid="ignore", divide="ignore"):
        load = density * np.asarray(speed) ** 2 * np.asarray(depth) * width
        return np.where(load > 0, np.asarray(force) / load, np.nan)
