"""Vertical cuts against limit analysis (docs/CUTS.md): below its critical height a cut stands, above
it a wedge slides off its face (Chen 1975; Drescher & Detournay 1993; references.vertical_cut_critical_height)."""

import matplotlib.pyplot as plt

from mpisph import measure, references
from mpisph.case import load_case_module, resolve_params

from .figures import save
from .runs import run
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
            "estimates it for psi = 0 (neither height bounds a non-associated soil rigorously). A cut stands "
            f"when its kinetic energy peaks within {PEAK_BY:g} s, as its face unloads elastically, and the 99th "
            f"percentile of its particles' displacements at 3 s stays below {MOVED:g} H; it fails when the energy "
            "peaks later, as a wedge slides off the face, and the wedge moves further. 000_'s Wendland kernel at "
            "h = 1.3 dp keeps the particles regular where the case's cubic spline pairs them, and the kernel "
            "summation keeps a standing cut's density, which with Eq. 16 alone drifts at its face and lets it "
            "creep (docs/CUTS.md, with dp = 0.0125 m beside it).")
    return ("Vertical cuts against their critical height (limit analysis)", "; ".join(cmds), rows,
            save(fig, "vertical_cut_critical_height.png"), note)
