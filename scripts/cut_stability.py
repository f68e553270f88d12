"""Whether vertical cuts stand or fail, beside the critical height of limit analysis.

    .venv/bin/python -m mpisph vertical_cut --set H=1.2 [density_reinit=free_surface] --t-end 3 --output-interval 0.25 --out RUN
    .venv/bin/python scripts/cut_stability.py RUN [RUN ...] [--at 1 3]

Per run (a ``vertical_cut``, any scheme): the cut's height H (its top particle's centre plus dp / 2)
over the critical height H_c of references.vertical_cut_critical_height, for associated flow and for
the run's dilatancy; the peak kinetic energy and when it came (diagnostics.csv); at each time of
``--at`` the 99th percentile of the particles' displacements from the first frame over H; and the
density range of the last frame over rho0; and whether it stood or failed, by validation/cuts.py's
``verdict`` on the energy's peak and the last frame's displacement. A cut that stands keeps the
displacement of its elastic unloading, a few hundredths of H, and its kinetic energy peaks in the first
tenth of a second; one that fails moves a wedge by tenths of H and its energy peaks when the wedge slides.
A run whose body does not start as a block (its top level over its whole width) is refused: a slope's
height over a vertical cut's critical height says nothing (scripts/strength_reduction.py --height
gives a slope's factor of safety).
"""

import argparse
import os

import numpy as np

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.measure import cut_height, displacement_percentile, kinetic_energy_peak, surface_profile
from mpisph.references import vertical_cut_critical_height
from run_check import run_params  # (this directory)
from validation.cuts import verdict


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--at", type=float, nargs="+", default=[1.0, 3.0], help="times [s] of the displacements")
    a = ap.parse_args()
    firsts = {}
    for run in a.runs:
        run_params(ap, run, ("cohesion", "phi", "psi", "rho0", "g"), "soil runs (vertical_cut)")
        first = firsts[run] = read_frame(list_frames(run)[0])
        dp = float(first["params"]["dp"])
        level = float(np.mean(surface_profile(first, dp)[1] > cut_height(first) - 0.5 * dp))
        if level < 1.0:
            ap.error(f"{run}: its body's top is level over {level:.0%} of its width: not a vertical cut, whose "
                     "critical height this script compares with; a slope's factor of safety: "
                     "scripts/strength_reduction.py CASE --height H (the slope's own height)")
    print("| run | H [m] | H / H_c (associated) | H / H_c (psi) | peak kinetic energy [J] at [s] | "
          + " | ".join(f"99 % displacement / H at {t:g} s" for t in a.at) + " | rho / rho0 at the end | verdict |")
    print("|---" * (7 + len(a.at)) + "|")
    for run in a.runs:
        paths = list_frames(run)
        first = firsts[run]
        p = first["params"]
        height = cut_height(first)
        gamma = float(p["rho0"]) * float(p["g"])
        h_c = vertical_cut_critical_height(float(p["cohesion"]), float(p["phi"]), gamma)
        h_c_psi = vertical_cut_critical_height(float(p["cohesion"]), float(p["phi"]), gamma, float(p["psi"]))
        frames = {}
        for path in paths[1:]:
            frame = read_frame(path)
            for t in a.at:
                if abs(frame["t"] - t) < 1e-9:
                    frames[t] = displacement_percentile(first, frame) / height
            last = frame
        energy, when = kinetic_energy_peak(read_diagnostics(os.path.join(run, "diagnostics.csv")))
        outcome = verdict(when, displacement_percentile(first, last) / height)
        shares = " | ".join(f"{frames[t]:.3f}" if t in frames else "-" for t in a.at)
        rho = last["rho"] / float(p["rho0"])
        print(f"| {run} | {height:.3f} | {height / h_c:.3f} | {height / h_c_psi:.3f} | {energy:.3g} at {when:.2f} | "
              f"{shares} | {rho.min():.2f}-{rho.max():.2f} | {outcome} |")


if __name__ == "__main__":
    main()
