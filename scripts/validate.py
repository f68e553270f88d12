"""Run the validation cases and write docs/VALIDATION.md with plots.

    .venv/bin/python scripts/validate.py [--ranks 2] [--only NAME ...] [--beam-h-over-dp 30]
        [--beam-v-f V ...] [--reuse]

Every figure in the page comes from a run made by this script; the command
of each run is printed in the page beside its result. Every row with a numeric
tolerance, and some with a worded one ("SPH-AS larger", "converged"), carries a
sixth entry, whether it meets it; the script exits non-zero, listing them, when
one does not ("runs" and "surface clusters" carry none). The sections live in
scripts/validation/, a module per family of cases; this script names them and
writes the page.
"""

import argparse

from mpisph import references

from validation import (beam, cuts, figures, fluids, incline, lube_axisymmetric, lube_planar, page, runs,
                        soil_remedies, soils)

VALIDATIONS = {"elliptical_drop": fluids.elliptical_drop, "elliptical_drop_remedies": fluids.elliptical_drop_remedies,
               "taylor_green": fluids.taylor_green, "dam_break_2d": fluids.dam_break,
               "lid_driven_cavity": fluids.cavity, "lid_driven_cavity_re1000": fluids.cavity_re1000,
               "rotating_square_patch": fluids.rotating_patch,
               "rotating_square_patch_remedies": fluids.rotating_patch_remedies,
               "oscillating_beam": beam.oscillating_beam, "oscillating_beam_table": beam.oscillating_beam_table,
               "oscillating_beam_sph_as": beam.oscillating_beam_sph_as,
               "column_collapse_2d": soils.column_collapse, "cohesive_failure_2d": soils.cohesive_failure,
               "remedies_cuts": soil_remedies.remedies_cuts, "remedies_cube_3d": soil_remedies.remedies_cube_3d,
               "vertical_cut_critical_height": cuts.vertical_cut_critical_height,
               "safety_factor": cuts.safety_factor,
               "soil_cylinder_impact": soils.soil_cylinder,
               "inclined_plane": incline.inclined_plane, "inclined_plane_steady": incline.inclined_plane_steady,
               "inclined_plane_deep": incline.inclined_plane_deep,
               "inclined_plane_deep_fine": incline.inclined_plane_deep_fine,
               "inclined_plane_walls": incline.inclined_plane_walls,
               "lube_collapse_2d": lube_planar.lube_collapse_2d,
               "lube_collapse_2d_convergence": lube_planar.lube_collapse_2d_convergence,
               "lube_collapse_3d": lube_axisymmetric.lube_collapse_3d,
               "lube_collapse_3d_convergence": lube_axisymmetric.lube_collapse_3d_convergence,
               "lube_collapse_3d_convergence_well_posed": lube_axisymmetric.lube_collapse_3d_convergence_well_posed}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--only", nargs="+", choices=list(VALIDATIONS), help="these sections (default: all)")
    ap.add_argument("--beam-h-over-dp", type=int, default=30,
                    help="resolution of the beam period runs (the paper's Table 1: 30)")
    ap.add_argument("--beam-v-f", type=float, nargs="*", default=list(references.BEAM_TABLE_1_V_F),
                    help="v_f of the oscillating_beam_table and _sph_as runs (the paper's Table 1: all four)")
    ap.add_argument("--reuse", action="store_true",
                    help="read a finished run of the same command, rank count and committed code instead of "
                         "running it again (runs/validation/NAME/validate_run.json), and continue an interrupted "
                         "one from its last frame")
    a = ap.parse_args()
    runs.REUSE = a.reuse
    figures.IMG.mkdir(parents=True, exist_ok=True)
    path = figures.DOCS / "VALIDATION.md"
    sections = page.existing_sections(path)
    misses = []
    for name in a.only or VALIDATIONS:
        beam_table = name in ("oscillating_beam_table", "oscillating_beam_sph_as")
        extra = {"h_over_dp": a.beam_h_over_dp, "v_fs": tuple(a.beam_v_f)} if beam_table else {}
        title, cmd, rows, image, note = VALIDATIONS[name](a.ranks, **extra)
        misses += [f"{title}: {r[0]} = {r[1]} (tolerance {r[4]})" for r in rows if len(r) > 5 and not r[5]]
        sections[name] = page.section(name, title, cmd, rows, image, note)
        print(f"{title}: done")
    page.write(path, sections, VALIDATIONS)
    if misses:
        raise SystemExit("outside tolerance:\n  " + "\n  ".join(misses))

if __name__ == "__main__":
    main()
