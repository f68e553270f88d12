"""Particle-steps per second per core at >= 100k particles, 1 and 2 ranks, the 2-rank efficiency,
and each figure as a fraction of this machine's ceiling.

    .venv/bin/python benchmarks/throughput.py [--cases NAME ...] [--repeat 3]
    .venv/bin/python benchmarks/throughput.py --remedies [--stabilisers NAME ...] [--repeat 3]

``--remedies`` runs the 2D column collapse (103k particles) once per stabiliser of a solid case
(none, tvf, tvf_limited, utvf, artificial_stress, shifting, and adaptive_kernel with its cubic spline) on 1 and 2
ranks and marks a rate below REMEDY_FLOOR (issue 13: 2.5e5 particle-steps/s/core).

Cases: the 2D and 3D dam breaks (fluid, dual time stepping; 140k particles
in 3D, as PySPH's 143k), the 2D column collapse and the 3D cube failure
(Drucker-Prager with UTVF, single time stepping as in 000_ Sec. 3.4), and the
mu(I) incline (004_ Table 2 material, 100 layers of 1000 particles, single
time stepping) and the 3D mu(I) collapse (a = 0.55, 100k grains on 85k floor
particles, implicit viscous kick); all of them by default, ``--cases`` names some
(a key of BENCHMARKS: a case, or a case and other settings, "cube_failure_3d geostatic"). Each
run is timed by the solver itself (wall time of the step loop, numba
compilation excluded by a warm-up run), best of ``--repeat`` runs: on a shared
virtual machine single runs scatter by up to 10 %, the best of three by about 2 %.
The 2-rank parallel efficiency is the 2-rank rate per core over the 1-rank rate.

Ceiling: a step that makes P passes over the neighbours of every particle
cannot beat ceiling / P particle-steps per second, with the ceiling of
benchmarks/ceiling.py (one density summation over a cell-linked list). P
counts the pair loops of the scheme, per step plus per neighbour
configuration times configurations per step:

- fluid: per acoustic step pressure acceleration and continuity (2); per
  configuration the neighbour search and the density reinitialisation (2;
  the dam break has no viscosity, so no viscous pass);
- Drucker-Prager with UTVF: per step stress acceleration, velocity gradient,
  continuity and the linear stress diffusion's two passes, the stress
  gradient and the diffusion (5; Feng's geostatic form has one, 4); per
  configuration the neighbour search, position divergence, surface classes,
  correction matrix and the UTVF shift (5);
- mu(I): per step strain rate, momentum and continuity (3); per
  configuration the neighbour search (1). The implicit viscous kick adds a
  pass for its pair coefficients and one per conjugate-gradient iteration,
  which vary from step to step and are not counted: the implicit collapse's
  fraction of the ceiling is an upper bound.

A key of two words names a case and a variant ("lube_collapse_3d explicit":
the 3D collapse with 004_'s explicit step, Eq. 39's viscous limit, about 130
times shorter steps than the implicit kick's; "cube_failure_3d geostatic":
the cube with 000_'s stress diffusion, the default until session 26).
"""

import argparse

from _run import run_case
from ceiling import ceiling

# case: (settings giving >= 100k moving particles, simulated time per run, warm-up arguments,
#        dimension, pair passes per step, pair passes per neighbour configuration)
BENCHMARKS = {
    "dam_break_2d": (("dp=0.0044",), 0.02, ["--set", "dp=0.05", "--t-end", "0.01"], 2, 2, 2),  # 103k
    "column_collapse_2d": (("dp=0.00044",), 0.0005, ["--set", "dp=0.01", "--t-end", "0.005"], 2, 5, 5),  # 103k
    "column_collapse_2d geostatic": (("dp=0.00044", "stress_diffusion=geostatic"), 0.0005,
                                     ["--set", "dp=0.01", "--set", "stress_diffusion=geostatic", "--t-end", "0.005"],
                                     2, 4, 5),
    "cube_failure_3d": (("dp=0.04",), 0.01, ["--set", "dp=0.2", "--t-end", "0.02"], 3, 5, 5),  # 125k
    "cube_failure_3d geostatic": (("dp=0.04", "stress_diffusion=geostatic"), 0.01,
                                  ["--set", "dp=0.2", "--set", "stress_diffusion=geostatic", "--t-end", "0.02"],
                                  3, 4, 5),
    "dam_break_3d": (("dp=0.0239",), 0.006, ["--set", "dp=0.2", "--t-end", "0.02"], 3, 2, 2),  # 140k
    "inclined_plane": (("dp=0.001", "columns=1000"), 2e-5,
                       ["--set", "dp=0.01", "--set", "columns=20", "--t-end", "2e-4"], 2, 3, 1),  # 100k
    "lube_collapse_3d": (("dp=0.0025",), 2e-3, ["--set", "dp=0.02", "--t-end", "0.02"], 3, 3, 1),  # 100k + floor
    "lube_collapse_3d explicit": (("dp=0.0025", "viscous_step=explicit"), 2e-5,
                                  ["--set", "dp=0.02", "--set", "viscous_step=explicit", "--t-end", "1e-3"], 3, 3, 1),
}


REMEDIES = {"none": (), "tvf": (), "tvf_limited": (), "utvf": (), "artificial_stress": (), "shifting": (),
            "adaptive_kernel": ("kernel=cubic_spline",)}
REMEDY_FLOOR = 2.5e5


def remedies(names, repeat):
    """The column collapse of BENCHMARKS with each stabiliser of ``names``, on 1 and 2 ranks."""
    settings, t_end, warm_up, *_ = BENCHMARKS["column_collapse_2d"]
    for name in names:
        extra = REMEDIES[name]
        sets = [*settings, f"stabiliser={name}", *extra]
        run_case("column_collapse_2d", 1, [*warm_up, "--set", f"stabiliser={name}", *extra])  # compile
        args = [*(w for s in sets for w in ("--set", s)), "--t-end", t_end, "--output-interval", t_end]
        for ranks in (1, 2):
            r = max((run_case("column_collapse_2d", ranks, args) for _ in range(repeat)), key=lambda run: run.rate)
            mark = "" if r.rate >= REMEDY_FLOOR else f"  BELOW {REMEDY_FLOOR:.2g}"
            print(f"column_collapse_2d {name} ranks={ranks}: {r.rate:.4g} particle-steps/s/core (best of {repeat}), "
                  f"{r.particles} particles, {r.steps} steps{mark}  [{r.command}]", flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cases", nargs="*", choices=list(BENCHMARKS), default=list(BENCHMARKS))
    ap.add_argument("--repeat", type=int, default=3, help="runs per rank count; the fastest counts")
    ap.add_argument("--remedies", action="store_true", help="the 2D column with each stabiliser instead")
    ap.add_argument("--stabilisers", nargs="*", choices=list(REMEDIES), default=list(REMEDIES),
                    help="with --remedies: these stabilisers only")
    a = ap.parse_args()
    if a.remedies:
        remedies(a.stabilisers, a.repeat)
        return
    ceilings = {}
    for case in a.cases:
        settings, t_end, warm_up, dim, per_step, per_configuration = BENCHMARKS[case]
        if dim not in ceilings:
            ceilings[dim] = ceiling(dim=dim)[0]
            print(f"ceiling {dim}D: {ceilings[dim]:.4g} particle-passes/s on one core  "
                  f"[.venv/bin/python benchmarks/ceiling.py --dim {dim}]", flush=True)
        name = case.split()[0]
        run_case(name, 1, warm_up)  # compile the numba kernels once
        args = [*(w for s in settings for w in ("--set", s)), "--t-end", t_end, "--output-interval", t_end]
        rates = {}
        for ranks in (1, 2):
            r = max((run_case(name, ranks, args) for _ in range(a.repeat)), key=lambda run: run.rate)
            rates[ranks] = r.rate
            passes = per_step + per_configuration * r.configurations / r.steps
            bound = ceilings[dim] / passes
            phases = ", ".join(f"{k} {v:.0f}%" for k, v in r.shares.items())
            print(f"{case} {' '.join(settings)} ranks={ranks}: {r.rate:.4g} particle-steps/s/core "
                  f"(best of {a.repeat}), "
                  f"{r.particles} particles; "
                  f"{passes:.2f} pair passes/step, {100 * r.rate / bound:.0f}% of the ceiling's "
                  f"{bound:.3g}  ({phases})  [{r.command}]", flush=True)
        print(f"{case} 2-rank parallel efficiency: {100 * rates[2] / rates[1]:.1f}%", flush=True)


if __name__ == "__main__":
    main()
