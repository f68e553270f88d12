"""Vertical cuts against limit analysis (docs/CUTS.md): below its critical height a cut stands, above
it a wedge slides off its face (Chen 1975; Drescher & Detournay 1993; references.vertical_cut_critical_height);
and the factor of safety of the 2 m cuts by strength reduction (mpisph/strength_reduction.py)."""

import matplotlib.pyplot as plt

from mpisph import measure, references, strength_reduction
from mpisph.arguments import parse_sets
from mpisph.case import load_case_module, resolve_params
from mpisph.io.frames import list_frames, read_frame

from .figures import save
from .runs import run, run_directory
from .soils import deposit_panel


HEIGHTS = (1.30, 1.40, 1.45, 1.60)  # m; the first stands and the last fails by limit analysis
ASSERTED = {1.30: "stands", 1.60: "fails"}
SETTINGS = ("kernel=wendland_c2", "h_factor=1.3", "density_reinit=free_surface")  # docs/CUTS.md says why
PEAK_BY = 0.2  # s: a standing cut's kinetic energy peaks as its face unloads (0.06-0.10 s in docs/CUTS.md)
MOVED = 0.15  # a failed wedge moves by more than this share of H (99th percentile of displacements at 3 s)


def verdict(peak_time, moved):
    """'stands' when the kinetic energy peaked by PEAK_BY and the 99 % displacement stays below MOVED H,
    'fails' when it peaked later and moved further, 'at the edge' when the two signs disagree."""
    early, small = peak_time <= PEAK_BY, moved < MOVED
    return "stands" if early and small else "fails" if not early and not small else "at the edge"


def vertical_cut_critical_height(ranks):
    """vertical_cut (002_'s soil, dp = 0.025 m) at four heights to 3 s: the 1.30 m cut, 0.94 of the
    critical height for psi = 0, stands; the 1.60 m one, 1.06 of Chen's for associated flow, fails."""
    p = resolve_params(load_case_module("vertical_cut"), {})
    gamma = p["rho0"] * p["g"]
    h_c = references.vertical_cut_critical_height(p["cohesion"], p["phi"], gamma)
    h_c_psi = references.vertical_cut_critical_height(p["cohesion"], p["phi"], gamma, p["psi"])
    fig = plt.figure(figsize=(12, 9))
    energy_ax = fig.add_subplot(3, 1, 1)
    rows, cmds, standing, failing = [], [], [], []
    for k, H in enumerate(HEIGHTS):
        frames, diag, cmd = run(f"vertical_cut_H{H:g}", "vertical_cut",
                                ["--set", f"H={H:g}", *SETTINGS, "--t-end", "3", "--output-interval", "0.25"], ranks)
        cmds.append(cmd)
        height = measure.cut_height(frames[0])
        peak, when = measure.kinetic_energy_peak(diag)
        moved = measure.displacement_percentile(frames[0], frames[-1]) / height
        outcome = verdict(when, moved)
        if outcome == "stands":
            standing.append(height)
        elif outcome == "fails":
            failing.append(height)
        row = (f"H = {height:.3f} m ({height / h_c_psi:.2f} H_c for psi = 0, {height / h_c:.2f} H_c associated): "
               f"peak kinetic energy [J] at [s]; 99 % displacement / H at {frames[-1]['t']:g} s",
               f"{peak:.3g} at {when:.2f}; {moved:.3f}: {outcome}", ASSERTED.get(H, "-"), "-",
               ASSERTED.get(H, "-"))
        rows.append(row + ((outcome == ASSERTED[H],) if H in ASSERTED else ()))
        energy_ax.semilogy(diag["t"], diag["kinetic_energy"], label=f"H = {height:.2f} m: {outcome}")
        deposit_panel(fig, fig.add_subplot(3, 2, 3 + k), frames[-1], frames[0], f"H = {height:.2f} m, t = 3 s")
    rows.append(("critical height [m]: the highest cut that stands, the lowest that fails",
                 f"{max(standing, default=float('nan')):.3f}-{min(failing, default=float('nan')):.3f}",
                 f"{h_c_psi:.3f} (psi = 0) - {h_c:.3f} (associated)", "-", "-"))
    energy_ax.set_xlabel("t [s]")
    energy_ax.set_ylabel("kinetic energy [J]")
    energy_ax.axvline(PEAK_BY, color="grey", lw=0.5)
    energy_ax.legend(fontsize=8)
    note = (f"002_'s soil (c = {p['cohesion'] / 1e3:g} kPa, phi = {p['phi']:g} deg, psi = {p['psi']:g}) in cuts "
            f"{p['L']:g} m long, lowered from the case's 2 m. Chen's log-spiral mechanism gives gamma H_c / c = "
            "3.83 tan(45 deg + phi / 2) for associated flow; Drescher & Detournay's reduction of c and tan phi "
            "estimates it for psi = 0 (an estimate; only Chen's height bounds a non-associated soil, from above, by "
            "Radenkovic's theorem). A cut stands "
            f"when its kinetic energy peaks within {PEAK_BY:g} s, as its face unloads elastically, and the 99th "
            f"percentile of its particles' displacements at 3 s stays below {MOVED:g} H; it fails when the energy "
            "peaks later, as a wedge slides off the face, and the wedge moves further. 000_'s Wendland kernel at "
            "h = 1.3 dp keeps the particles regular where the case's cubic spline pairs them, and the kernel "
            "summation keeps a standing cut's density, which with Eq. 16 alone drifts at its face and lets it "
            "creep (docs/CUTS.md, with dp = 0.0125 m beside it).")
    return ("Vertical cuts against their critical height (limit analysis)", "; ".join(cmds), rows,
            save(fig, "vertical_cut_critical_height.png"), note)


SAFETY_FACTOR_RUNS = (  # case, its --set items, the factors climbed; bisected twice after the first slide
    ("vertical_cut", SETTINGS, (0.6, 0.65, 0.7, 0.75, 0.8, 0.85)),
    ("cohesive_failure_2d", ("density_reinit=free_surface",), (0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9)),
)
BISECT = 2
SAFETY_FACTOR_TOLERANCE = 0.05  # the bracket's middle against Drescher & Detournay's factor: mpisph's own bar


def stage_launch(case, ranks):
    """A ``launch`` for strength_reduction.search: each stage a run of runs.run, under a name of its
    case's, so that --reuse reads it again."""
    def launch(name, stage_case, arguments):
        run(f"{case}_srm_{name}", stage_case, arguments, ranks)
        return str(run_directory(f"{case}_srm_{name}"))
    return launch


def shown(factor):
    """A factor of the bracket as the table prints it: 'none' when no stage slid."""
    return "none" if factor is None else f"{factor:g}"


def safety_factor(ranks):
    """The factor of safety by strength reduction of the case's own 2 m cuts, vertical_cut (002_'s soil
    on the Wendland kernel) and cohesive_failure_2d (000_'s), against limit analysis."""
    fig, axes = plt.subplots(2, 2, figsize=(12, 8))
    rows, cmds = [], []
    for k, (case, sets, factors) in enumerate(SAFETY_FACTOR_RUNS):
        soil = resolve_params(load_case_module(case), parse_sets(list(sets)))
        stages = strength_reduction.search(stage_launch(case, ranks), case, list(sets), soil, list(factors),
                                           settle=2.0, stage=1.0, bisect=BISECT)
        cmds.append(f".venv/bin/python scripts/strength_reduction.py {case} --set {' '.join(sets)} --factors "
                    f"{' '.join(f'{f:g}' for f in factors)} --bisect {BISECT} -n {ranks} --out RUN")
        release = strength_reduction.release_frame(stages)
        height = stages[0].height
        associated, dilatant = strength_reduction.limit_factors(height, soil)
        stood, slid = strength_reduction.bracket(stages)
        middle = float("nan") if slid is None else 0.5 * (stood + slid)
        error = abs(middle / dilatant - 1.0)
        label = f"{case}, H = {height:.2f} m, c = {soil['cohesion'] / 1e3:g} kPa, phi = {soil['phi']:g} deg"
        rows.append((f"{label}: factor of safety (last F that stood - first that slid)",
                     f"{stood:g}-{shown(slid)}",
                     f"{dilatant:.3f} (psi = {soil['psi']:g}, Drescher & Detournay)",
                     f"{error * 100:.1f} % (middle)", f"{SAFETY_FACTOR_TOLERANCE * 100:g} %",
                     error <= SAFETY_FACTOR_TOLERANCE))
        rows.append((f"{label}: first F that slid, below the associated factor (Chen; Radenkovic's bound)",
                     shown(slid), f"{associated:.3f}", "-", "below",
                     slid is not None and slid < associated))
        ax = axes[0, k]
        for outcome, marker in (("settling", "s"), ("stood", "o"), ("slid", "x")):
            chosen = [s for s in stages if s.outcome == outcome]
            ax.semilogy([s.factor for s in chosen], [s.moved for s in chosen], marker, ls="none", label=outcome)
        ax.axhline(strength_reduction.SLIDE, color="grey", lw=0.5)
        ax.axvline(dilatant, color="C3", ls="--", lw=0.8, label="Drescher & Detournay (psi = 0)")
        ax.axvline(associated, color="C4", ls=":", lw=0.8, label="Chen (associated)")
        ax.set_xlabel("F")
        ax.set_ylabel("99 % displacement over the stage / H")
        ax.set_title(case)
        ax.legend(fontsize=8)
        first_slid = next((s for s in stages if s.outcome == "slid"), stages[-1])
        deposit_panel(fig, axes[1, k], read_frame(list_frames(first_slid.directory)[-1]), release,
                      f"{case}, the stage at F = {first_slid.factor:g}, t = {first_slid.end:g} s")
    note = ("Strength reduction (mpisph/strength_reduction.py, docs/CUTS.md): the cut is released with c and "
            "tan phi (and tan psi) divided by the first factor and settles for 2 s; each larger factor restarts "
            "the last stage that stood for 1 s, up to the first stage whose 99th percentile of displacements "
            f"passes {strength_reduction.SLIDE:g} H; then two stages halve the bracket. Limit analysis gives the "
            "factor at which the cut's height becomes critical: Chen's log-spiral for associated flow, which "
            "bounds a non-associated soil's factor from above (Radenkovic), and Drescher & Detournay's reduced "
            "strength for psi = 0, an estimate, not a bound; the 5 % bar on it is mpisph's own (no issue gives "
            "one). The bottom row shows the first stage that slid, coloured by accumulated plastic strain over "
            "the released cut's outline.")
    return ("Factor of safety of the 2 m cuts by strength reduction", "; ".join(cmds), rows,
            save(fig, "safety_factor.png"), note)
