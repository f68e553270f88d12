"""Where a deposit is not yet at rest: the speeds and densities of a run's moving particles.

    .venv/bin/python scripts/at_rest.py RUN [--every 5] [--fastest 10]

Per frame (every ``--every``-th and the last): the largest speed and its fraction of the run's
peak, the 99.9th and 99th percentiles, the mean, the number of particles above 1 % of the peak,
and the density range over rho0 (for mu(I) grains the bulk density at rest, phi_max rho_s0) with the
number of particles beyond 1.5 rho0; then the
``--fastest`` particles of the last frame with their place, velocity, the speed at which they
moved since the frame before (displacement over the frame interval: a particle whose velocity the
transport-velocity shift cancels has a velocity but does not move), density, pressure and distance
to the nearest other moving particle (the frames are read without their walls).
"""

import argparse

import numpy as np

from mpisph.io.frames import list_frames, read_frame
from mpisph.particles import MOVING
from run_check import run_params  # (this directory)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--every", type=int, default=5)
    ap.add_argument("--fastest", type=int, default=10)
    a = ap.parse_args()
    params = run_params(ap, a.run, (), "runs of a material with a reference density")
    if "rho0" in params:
        rho0 = float(params["rho0"])
    elif "rho_s0" in params and "phi_max" in params:  # mu(I) grains: the bulk density at rest
        rho0 = float(params["phi_max"]) * float(params["rho_s0"])
    else:
        ap.error(f"{a.run} is a run of {params.get('case')!r}, which has neither rho0 nor rho_s0 and phi_max: this "
                 "script reads runs of a material with a reference density")
    rows = []  # per frame: t, the moving particles' speeds, rho / rho0 (least, largest, beyond 1.5)
    last = None
    for path in list_frames(a.run):  # one frame in memory at a time; the last two are kept
        before, last = last, read_frame(path)
        moving = last["kind"] == MOVING
        rho = last["rho"][moving] / rho0
        rows.append((last["t"], np.linalg.norm(last["v"][moving], axis=1), rho.min(), rho.max(), np.sum(rho > 1.5)))
    peak = max(row[1].max() for row in rows)
    print(f"peak speed {peak:.4g} m/s; rho0 {rho0:g} kg/m^3")
    print("t [s] | max speed (of peak) | 99.9 % | 99 % | mean | above 1 % of peak | rho / rho0 | above 1.5 rho0")
    for k, (t, s, rho_min, rho_max, dense) in enumerate(rows):
        if k % a.every and k != len(rows) - 1:
            continue
        print(f"{t:.2f} | {s.max():.3g} ({s.max() / peak:.3f}) | {np.percentile(s, 99.9):.3g} | "
              f"{np.percentile(s, 99):.3g} | {s.mean():.3g} | {np.sum(s > 0.01 * peak)} | "
              f"{rho_min:.3f}-{rho_max:.3f} | {dense}")
    s = rows[-1][1]
    moving = np.flatnonzero(last["kind"] == MOVING)
    print(f"fastest at t = {last['t']:.2f} s: gid, x [m], v [m/s], moved since the frame before [m/s], "
          "rho / rho0, p [Pa], nearest / dp")
    dp = float(last["params"]["dp"])
    for i in moving[np.argsort(s)[::-1][:a.fastest]]:
        d = np.linalg.norm(last["x"] - last["x"][i], axis=1)
        d[i] = np.inf
        print(f"{last['gid'][i]} {np.round(last['x'][i], 3)} {np.round(last['v'][i], 3)} "
              f"{moved(before, last, i):.3g} {last['rho'][i] / rho0:.3f} {last['p'][i]:.4g} {d.min() / dp:.2f}")


def moved(before, last, i):
    """The distance particle i of frame ``last`` moved since frame ``before`` over their interval
    (nan without a frame before)."""
    if before is None:
        return float("nan")
    k = np.flatnonzero(before["gid"] == last["gid"][i])[0]
    return float(np.linalg.norm(last["x"][i] - before["x"][k]) / (last["t"] - before["t"]))


if __name__ == "__main__":
    main()
