"""How the flume's deposit bears on the barrier: its force against the classical earth pressures.

    .venv/bin/python scripts/deposit_stress.py RUN [RUN ...] [--every 5] [--gap 0.1]

Per frame of each run of ``flume_3d`` (every ``--every``-th and the last): the soil's force on the
barrier (diagnostics.csv), the horizontal force the deposit carries through a vertical section
``--gap`` upstream of the barrier's face (-sum sigma_xx V over the grains within dp of it, over 2 dp),
the deposit's top at the barrier, and the medians of sigma_xx / sigma_zz and sigma_yy / sigma_zz
over the grains in front of the barrier (within 0.3 m of its face, below 0.6 m, 0.1 m clear of the
side walls). Then, for each run's last frame, the forces the classical theories give for a wall of
the barrier's height under a level surface at the deposit's top (mpisph/references.py): Rankine's
active with the cohesion's tension crack, Jaky's at rest, the elastic layer's at rest
(K = nu / (1 - nu)) and Rankine's passive.
"""

import argparse
from pathlib import Path

import numpy as np

from mpisph import references
from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.meshes import read_surface
from run_check import run_params  # (this directory)

FLUME = Path(__file__).resolve().parent.parent / "cases" / "flume"


def barrier_box(geometry):
    """(face x, top z, y range) of the barrier's STL file in ``geometry``."""
    corners = read_surface(Path(geometry) / "barrier.stl").triangles.reshape(-1, 3)
    return corners[:, 0].min(), corners[:, 2].max(), (corners[:, 1].min(), corners[:, 1].max())


def frame_row(frame, face, ys, gap):
    """(section force [N], deposit top at the face [m], median K_x, median K_y) of one frame."""
    x, stress, dp = frame["x"], frame["stress"], float(frame["params"]["dp"])
    volume = frame["mass"] / frame["rho"]
    section = np.abs(x[:, 0] - (face - gap)) < dp
    force = -np.sum(stress[section, 0] * volume[section]) / (2.0 * dp)
    at_face = (x[:, 0] > face - 2.0 * dp) & (x[:, 0] < face)
    top = x[at_face, 2].max() + 0.5 * dp if at_face.any() else np.nan
    front = ((x[:, 0] > face - 0.3) & (x[:, 0] < face) & (x[:, 2] < 0.6)
             & (x[:, 1] > ys[0] + 0.1) & (x[:, 1] < ys[1] - 0.1) & (stress[:, 2] < 0.0))
    if not front.any():
        return force, top, np.nan, np.nan
    return force, top, np.median(stress[front, 0] / stress[front, 2]), np.median(stress[front, 1] / stress[front, 2])


def classical_forces(params, top, height, width):
    """{state: force [N]} on a wall ``height`` high and ``width`` wide under a level surface at ``top``."""
    gamma = float(params["rho0"]) * float(params["g"])
    nu = float(params["nu"])
    wall = (max(top - height, 0.0), top)
    states = references.earth_pressure(float(params["phi"]), float(params["cohesion"]))
    states["elastic at rest"] = (nu / (1.0 - nu), 0.0)
    return {name: references.lateral_earth_force(states[name], gamma, *wall, width)
            for name in ("active", "at rest", "elastic at rest", "passive")}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="flume_3d run directories")
    ap.add_argument("--every", type=int, default=5, help="report every EVERY-th frame (and the last)")
    ap.add_argument("--gap", type=float, default=0.1, help="distance of the section upstream of the face [m]")
    a = ap.parse_args()
    for run in a.runs:
        run_params(ap, run, ("geometry", "cohesion", "phi"), "flume_3d runs")
        paths = list_frames(run)
        last = read_frame(paths[-1])
        face, height, ys = barrier_box(last["params"].get("geometry") or FLUME)
        diag = read_diagnostics(Path(run) / "diagnostics.csv")
        print(f"{run}: barrier face x = {face:.3f} m, {height:.2f} m high, section at x = {face - a.gap:.3f} m")
        print("t [s] | barrier F_x [kN] | section force [kN] | deposit top at the face [m] | "
              "median sigma_xx / sigma_zz | sigma_yy / sigma_zz")
        for k, path in enumerate(paths):
            if k % a.every and k != len(paths) - 1:
                continue
            frame = last if k == len(paths) - 1 else read_frame(path)
            force, top, kx, ky = frame_row(frame, face, ys, a.gap)
            barrier = diag["force_barrier_x"][np.argmin(np.abs(diag["t"] - frame["t"]))]
            print(f"{frame['t']:.2f} | {barrier / 1e3:.2f} | {force / 1e3:.2f} | {top:.3f} | {kx:.3f} | {ky:.3f}")
        # top: the last frame's, with which the loop ends
        forces = classical_forces(last["params"], top, height, ys[1] - ys[0])
        print(f"classical forces on the barrier under a level surface at {top:.3f} m [kN]: "
              + ", ".join(f"{name} {f / 1e3:.2f}" for name, f in forces.items()))


if __name__ == "__main__":
    main()
