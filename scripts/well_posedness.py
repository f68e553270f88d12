"""How much of a mu(I) run flows where its friction law is ill-posed (mpisph/well_posedness.py).

    .venv/bin/python scripts/well_posedness.py RUN [RUN ...]
    .venv/bin/python scripts/well_posedness.py --materials
    .venv/bin/python scripts/well_posedness.py --compressible
    .venv/bin/python scripts/well_posedness.py --growth

For each run (any mu(I) case: its material is built again from the frames' parameters): the window
of inertial numbers (I_1, I_2) where the law is well-posed, and for each frame the grains' viscous
dissipation rate (sum of eta gamma_dot^2 m / rho), the share of it at I outside the window, and the
inertial numbers below which a quarter, half and three quarters of it happens. The last line weighs
the frames' shares by their dissipation over the run (trapezoids in time): the share of all the
energy the run dissipated where the law is ill-posed. Beside it, the share at grains whose viscous
stress carries less bulk friction than the compressible equations need to be well-posed for their
state (compressible_bulk_friction_bound: the short-wave limit, after Heyman et al. 2017).

--materials prints, for each material of 004_ Table 1, its window, the alphas for which Barker & Gray
2017's partial regularisation is well-posed below it, and the friction at low I of 004_'s law beside
the regularised law's with the largest of those alphas (the nearest to 004_'s).

--compressible prints, for Lube's planar and axisymmetric columns with their cases' defaults, at the
foot's hydrostatic pressure and a quarter of it, against I: the rate exponents n and nu_b of the
grains at fixed density, the least bulk friction of the compressible equations and the bulk friction
of each of the solver's viscous stresses.

--growth prints, for the same columns at 500 Pa and I = 0.003 to 0.1, the linear growth of waves in
a uniform shear (mpisph/shear_stability.py) with each viscous stress: the rate at 1e6 1/m (its plateau
where it levels off), the wavelength at which half of it is reached, and the rate of the shortest wave
that the validation's spacings resolve, 2 dp.
"""

import argparse
import math

import numpy as np

from mpisph import shear_stability
from mpisph.case import build_case, case_of_frame, load_case_module, resolve_params
from mpisph.io.frames import list_frames, read_frame
from mpisph.measure import weighted_quantile
from mpisph.physics.mu_i_law import friction
from mpisph.references import MU_I_MATERIALS
from mpisph.well_posedness import bulk_part, compressible_bulk_friction_bound, compressible_ill_posed_share, \
    dissipation_rate, energy_share, ill_posed_dissipation_share, ill_posed_energy_share, \
    partial_regularisation_alphas, partially_regularised_friction, rate_exponents, solver_bulk_friction, \
    table_1_law, well_posed_window
from run_check import run_params  # (this directory)

LOW_I = (1e-2, 1e-3, 1e-4)
GROWTH_I = (0.003, 0.01, 0.03, 0.1)
GROWTH_P = 500.0  # Pa
# the spacings of the validation's resolution studies: L_0 / dp and r_0 / dp
SPACINGS = {"lube_collapse_2d": (20, 40, 80), "lube_collapse_3d": (14.5, 29.1, 43.6)}
COLUMN_I = (1e-4, 1e-3, 1e-2, 3e-2, 0.1, 0.3, 1.0)
STRESSES = (("cleary", "full"), ("corrected_stress", "full"), ("corrected_stress", "deviatoric"))


def run_table(run):
    """(window, rows, overall shares): a row per frame (t, dissipation rate, share outside the window,
    share short of the compressible bound, the I quartiles of the dissipation); the overall shares
    (ill_posed_energy_share and energy_share of compressible_ill_posed_share) are NaN where nothing
    dissipated."""
    frames = [read_frame(f) for f in list_frames(run)]
    case = case_of_frame(frames[-1]["params"])
    window = well_posed_window(case.material.params)
    rows = []
    for f in frames:
        power = dissipation_rate(f)
        quartiles = [weighted_quantile(f["inertial_number"], power, q) for q in (0.25, 0.5, 0.75)] if power.sum() > 0 else []
        rows.append((f["t"], float(power.sum()), ill_posed_dissipation_share(f, window),
                     compressible_ill_posed_share(f, case), quartiles))
    return window, rows, (ill_posed_energy_share(frames, window),
                          energy_share(frames, lambda f: compressible_ill_posed_share(f, case)))


def default_column(case_name):
    """(parameters, law, dimension, column length or radius) of the case's default column."""
    module = load_case_module(case_name)
    params = resolve_params(module, {})
    case = build_case(module, params)
    return params, case.material.params, case.dim, params["r_0"] if "r_0" in params else params["L_0"]


def growth_rows(case_name):
    """A row per I of GROWTH_I and viscous stress of STRESSES at GROWTH_P for the case's default
    column: I, the stress, the rate at 1e6 1/m, the hand-over wavelength (None without a plateau) and
    the rates at 2 dp for the case's SPACINGS."""
    params, m, dim, length = default_column(case_name)
    wavenumbers, dirs = np.logspace(0, 6, 61), shear_stability.directions(dim, 721 if dim == 2 else 2000)
    rows = []
    for I in GROWTH_I:
        for form, stress in STRESSES:
            lin = shear_stability.LinearisedShear(I, GROWTH_P, dim, m, bulk_part(form, stress, dim))
            rates = shear_stability.growth_curve(lin, wavenumbers, dirs)
            resolved = [lin.growth(math.pi * n / length, dirs).max() for n in SPACINGS[case_name]]
            rows.append((I, f"{form}, {stress}", rates[-1], shear_stability.handover_wavelength(wavenumbers, rates),
                         resolved))
    return rows


def column_rows(case_name):
    """For the case's default column: (its foot's hydrostatic pressure, rows), a row per pressure (the
    foot's and a quarter of it) and I of COLUMN_I: p, I, mu, n, nu_b, the compressible bound and the
    bulk friction of each of STRESSES."""
    params, m, dim, length = default_column(case_name)
    foot = m.phi_max * m.rho_s0 * params["g"] * params["a"] * length
    rows = []
    for p in (foot, 0.25 * foot):
        for I in COLUMN_I:
            mu = friction(I, m)
            n, nu_b = rate_exponents(I, 1.0 + m.K_t * p, m, dim)
            rows.append((p, I, mu, float(n), float(nu_b), float(compressible_bulk_friction_bound(mu, n, nu_b, dim)),
                         [solver_bulk_friction(mu, form, stress, dim) for form, stress in STRESSES]))
    return foot, rows


def material_rows():
    """A row per 004_ Table 1 material: name, I_0, window, (alpha_lo, alpha_hi), and at each of
    LOW_I the friction of 004_'s law and of the partial regularisation with alpha_hi."""
    rows = []
    for name in MU_I_MATERIALS:
        m = table_1_law(name)
        alphas = partial_regularisation_alphas(m)
        rows.append((name, m.I_0, well_posed_window(m), alphas,
                     [(friction(I, m), float(partially_regularised_friction(I, m, alphas[1]))) for I in LOW_I]))
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="*", help="mu(I) run directories: the share of their dissipation where the law "
                    "is ill-posed")
    ap.add_argument("--materials", action="store_true", help="each material of 004_ Table 1: its well-posed window "
                    "and Barker & Gray's partial regularisation")
    ap.add_argument("--compressible", action="store_true", help="Lube's columns: the bulk friction the compressible "
                    "equations need against each viscous stress's")
    ap.add_argument("--growth", action="store_true", help="Lube's columns: the linear growth of waves in a uniform "
                    "shear with each viscous stress")
    a = ap.parse_args()
    if a.growth:
        for name in SPACINGS:
            print(f"{name} (its defaults) at {GROWTH_P:g} Pa: growth rates of waves in a uniform shear [1/s]")
            print("| I | viscous stress | rate at 1e6 1/m | half of it at a wavelength of | "
                  + " | ".join(f"rate at 2 dp, {'L_0' if '2d' in name else 'r_0'} / dp = {n:g}" for n in SPACINGS[name])
                  + " |")
            print("|---" * (4 + len(SPACINGS[name])) + "|")
            for I, stress, top, handover, resolved in growth_rows(name):
                print(f"| {I:g} | {stress} | {top:.4g} | "
                      + (f"{1e3 * handover:.3g} mm" if handover else "none: it grows as k^2") + " | "
                      + " | ".join(f"{r:.4g}" for r in resolved) + " |")
    if a.compressible:
        for name in ("lube_collapse_2d", "lube_collapse_3d"):
            foot, rows = column_rows(name)
            print(f"{name} (its defaults; the foot's hydrostatic pressure {foot:.0f} Pa): bulk friction mu_b "
                  "needed and carried")
            print("| p [Pa] | I | mu | n | nu_b | least mu_b | "
                  + " | ".join(f"{form}, {stress}" for form, stress in STRESSES) + " |")
            print("|---" * (6 + len(STRESSES)) + "|")
            for p, I, mu, n, nu_b, bound, carried in rows:
                print(f"| {p:.0f} | {I:g} | {mu:.3f} | {n:.3f} | {nu_b:.4f} | {bound:+.3f} | "
                      + " | ".join(f"{c:.3f} ({'well' if c >= bound else 'ill'})" for c in carried) + " |")
    if a.materials:
        print("| material (004_ Table 1) | I_0 | well-posed for | alpha | "
              + " | ".join(f"mu at I = {I:g}: 004_ / regularised" for I in LOW_I) + " |")
        print("|---" * (4 + len(LOW_I)) + "|")
        for name, I_0, (lo, hi), (alpha_lo, alpha_hi), mus in material_rows():
            print(f"| {name} | {I_0:g} | {lo:.3g} < I < {hi:.3g} | {alpha_lo:.3f}-{alpha_hi:.3f} | "
                  + " | ".join(f"{ours:.3f} ({math.degrees(math.atan(ours)):.1f} deg) / {reg:.3f} "
                               f"({math.degrees(math.atan(reg)):.1f} deg)" for ours, reg in mus) + " |")
    for run in a.runs:
        run_params(ap, run, ("I_0",), "mu(I) runs")
    for run in a.runs:
        window, rows, overall = run_table(run)
        where = f"well-posed for {window[0]:.3g} < I < {window[1]:.3g}" if window else "ill-posed at every I"
        print(f"{run}: mu(I) {where}")
        print(f"{'t [s]':>8} {'dissipation [W]':>16} {'ill-posed share':>16} {'compressible':>13}   "
              "I below which 1/4, 1/2, 3/4 of it")
        for t, power, share, short, quartiles in rows:
            print(f"{t:8.4f} {power:16.4g} {share:16.3f} {short:13.3f}   " + " ".join(f"{q:.3g}" for q in quartiles))
        print(f"over the run: {overall[0]:.3f} of the energy dissipated at ill-posed I (incompressible), "
              f"{overall[1]:.3f} at grains short of the compressible bound")


if __name__ == "__main__":
    main()
