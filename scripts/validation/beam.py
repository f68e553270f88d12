"""The oscillating elastic beam (000_ Sec. 4.3): its deflection and first period beside 000_ Table 1 for
each remedy."""

import matplotlib.pyplot as plt
import numpy as np

from mpisph import measure, references
from mpisph.instability import tensile_instability
from mpisph.io.frames import list_frames, read_frame

from .figures import save
from .runs import run, run_directory


def beam_panel(fig, ax, frame, title):
    """Particles of ``frame`` (clamp included) coloured by von Mises stress."""
    sc = ax.scatter(frame["x"][:, 0], frame["x"][:, 1], c=frame["von_mises"], s=2, cmap="viridis")
    ax.set_aspect("equal")
    ax.set_title(f"{title}, von Mises [Pa]")
    fig.colorbar(sc, ax=ax)


def beam_period_run(h_over_dp, v_f, stabiliser, shear_force, ranks, scheme="riemann_elastic", t_end=0.32):
    """Diagnostics and command of a beam run to ``t_end``, past its first period (000_ Table 1), on
    the Riemann scheme with the shear force ``shear_force`` or on the classic scheme (``scheme``
    classic_elastic, which has no such option); a run that breaks up returns what it reached."""
    if scheme == "riemann_elastic":
        variant, chosen = shear_force, f"shear_force={shear_force}"
    else:
        variant, chosen = scheme, f"scheme={scheme}"
    name = f"oscillating_beam_table_{h_over_dp}_{stabiliser}_{variant}_{v_f:g}"
    args = ["--set", f"H_over_dp={h_over_dp}", f"v_f={v_f:g}", f"stabiliser={stabiliser}", chosen,
            "--t-end", f"{t_end:g}", "--output-interval", "0.04"]
    _, diag, cmd = run(name, "oscillating_beam", args, ranks, blow_up_ok=True)
    return diag, cmd


def period_cells(period):
    """The (value, error) cells of a beam's first period against Eq. 47; a run whose tip never
    swung back up says so."""
    if np.isnan(period):
        return "no upward crossing", "-"
    return f"{period:.4f}", f"{100 * (period / references.beam_period() - 1):+.1f}%"


def beam_table_rows(diag, label, v_f, paper, tolerance=None):
    """The rows of one beam period run: its first period beside Eq. 47 and ``paper`` (000_ Table 1's
    value, or None), asserted within ``tolerance`` (a fraction) when one is given, and the energy
    where the beam is straight again; and the period."""
    T = references.beam_period()
    period = measure.first_period(diag["t"], diag["tip_uy"])
    shown = f"{paper:.3f} (000_ Table 1)" if paper is not None else "-"
    value, error = period_cells(period)
    row = (f"first period, {label}, v_f = {v_f:g} [s]", value, f"{T:.4f}; {shown}", error, "-")
    if tolerance is not None:
        row = row[:4] + (f"{100 * tolerance:g}%", abs(period / T - 1) <= tolerance)
    energy = diag["kinetic_energy"] + diag["strain_energy"]
    at = diag["t"][-1] if np.isnan(period) else period  # the beam is straight again at its period
    ratio = np.interp(at, diag["t"], energy) / energy[0]
    return [row, (f"(kinetic + strain energy) at {at:.3f} s / initial, {label}, v_f = {v_f:g}",
                  f"{ratio:.3f}", "1", f"{ratio - 1:+.3f}", "-")], period


def table_1_period(stabiliser, v_f):
    """000_ Table 1's first period with ``stabiliser`` at ``v_f``; None where the table has none."""
    periods = references.BEAM_TABLE_1_PERIODS.get(stabiliser)
    if periods is None or v_f not in references.BEAM_TABLE_1_V_F:
        return None
    return periods[references.BEAM_TABLE_1_V_F.index(v_f)]


def finish_period_axes(ax):
    """Eq. 47's period, log v_f and the labels on an axes of first periods against v_f."""
    ax.axhline(references.beam_period(), color="k", lw=0.8, label="theory (Eq. 47)")
    ax.set_xscale("log")
    ax.set_xlabel("v_f")
    ax.set_ylabel("first period [s]")
    ax.legend(fontsize=7)


def oscillating_beam(ranks):
    """000_ Figs. 11 and 13: the stabilisers at H/dp = 10, v_f = 0.05 to 1 s, and the SPH-AS that
    000_ compares with, Gray et al.'s classic SPH with artificial stress (scheme classic_elastic)."""
    runs = (("utvf", "riemann_elastic"), ("tvf", "riemann_elastic"), ("none", "riemann_elastic"),
            ("artificial_stress", "riemann_elastic"), ("artificial_stress", "classic_elastic"))
    fig, ax = plt.subplots(2 + len(runs), 1, figsize=(10, 20))
    rows, at_crossing, cmds = [], {}, []
    for k, (st, scheme) in enumerate(runs):
        label = st if scheme == "riemann_elastic" else f"SPH-AS ({scheme}, Gray et al. 2001)"
        if scheme == "classic_elastic":
            sph_as = label
        name = f"oscillating_beam_10_{st}" + ("" if scheme == "riemann_elastic" else f"_{scheme}")
        frames, diag, shown = run(name, "oscillating_beam", ["--set", "H_over_dp=10", "--set", "v_f=0.05",
                                                             "--set", f"stabiliser={st}", "--set", f"scheme={scheme}",
                                                             "--t-end", "1.0", "--output-interval", "0.05"], ranks)
        cmds.append(shown)
        energy = diag["kinetic_energy"] + diag["strain_energy"]
        ax[0].plot(diag["t"], diag["tip_uy"], label=label)
        ax[1].plot(diag["t"], energy / energy[0], label=label)
        files = list_frames(run_directory(name))  # in the order of ``frames``; re-read with the clamp for the panels
        at = int(np.argmin([abs(f["t"] - 0.35) for f in frames]))
        beam_panel(fig, ax[2 + k], read_frame(files[at], walls=True), f"{label}, t = 0.35 s")
        ax[2 + k].set_xlim(-0.01, 0.22)
        m = tensile_instability(read_frame(files[-1], walls=True))
        period = measure.first_period(diag["t"], diag["tip_uy"])
        value, error = period_cells(period)
        rows.append((f"{label}: first period [s]", value, f"{references.beam_period():.4f} (Eq. 47)", error, "-"))
        up = measure.period_ends(diag["t"], diag["tip_uy"])
        if len(up):
            at_crossing[label] = np.interp(up[-1], diag["t"], energy) / energy[0]
            rows.append((f"{label}: energy at the last upward crossing of the tip ({up[-1]:.3f} s) / initial",
                         f"{at_crossing[label]:.3f}", "1", f"{at_crossing[label] - 1:+.3f}", "-"))
        rows.append((f"{label}: energy at 1 s / initial", f"{energy[-1] / energy[0]:.3f}", "1",
                     f"{energy[-1] / energy[0] - 1:+.3f}", "-"))
        rows.append((f"{label}: clustering / inner voids / closest pair / fragments (outside the largest) at 1 s",
                     f"{100 * m['clustering']:.2f}% / {100 * m['inner_voids']:.2f}% / {m['min_spacing']:.2f} dp / "
                     f"{m['fragments']} ({100 * m['detached']:.2f}%)", "0 / 0 / 1 dp / 1", "-", "-"))
    if "utvf" in at_crossing and sph_as in at_crossing:
        decay = {st: 1.0 - at_crossing[st] for st in ("utvf", sph_as)}
        rows.append(("energy lost by the last upward crossing: SPH-AS / utvf",
                     f"{decay[sph_as]:.4f} / {decay['utvf']:.4f}", "SPH-AS larger (000_ Fig. 13)", "-",
                     "SPH-AS larger", decay[sph_as] > decay["utvf"]))
    ax[0].set_ylabel("tip deflection [m]")
    ax[1].set_xlabel("t [s]")
    ax[1].set_ylabel("(kinetic + strain energy) / initial")
    for a in ax[:2]:
        a.legend(fontsize=8)
    image = save(fig, "oscillating_beam.png")
    note = ("000_ Fig. 13 compares UTVF with the SPH-AS of Gray et al. 2001: classic SPH (artificial viscosity "
            "alpha = beta = 1, plain gradients, predictor-corrector) with artificial stress "
            "(`--set scheme=classic_elastic stabiliser=artificial_stress`). mpisph's artificial stress on the "
            "Riemann scheme with the corrected gradient is the fourth run. At an upward crossing the beam is "
            "straight, so the energy there compares the runs at one phase: artificial stress does work that "
            "kinetic and strain energy do not hold, and between the crossings the sum swings with the "
            "deflection. The first periods at 000_'s H/dp = 30 are in the next section.")
    return "Oscillating beam (000_ Sec. 4.3, Fig. 13)", "; ".join(cmds), rows, image, note


def oscillating_beam_table(ranks, h_over_dp=30, v_fs=references.BEAM_TABLE_1_V_F):
    """000_ Table 1: the first period at H/dp = 30 for each stabiliser and v_f, and UTVF with Eq. 22
    as printed (no B on the shear part) beside the corrected form, mpisph's default, at v_f = 0.05
    (the largest strains of the table) when it is among ``v_fs``."""
    rows, cmds = [], []
    fig, ax = plt.subplots(figsize=(7, 4.5))
    stabilisers = ("none", "tvf", "utvf", "artificial_stress")
    colour = {st: f"C{k}" for k, st in enumerate(stabilisers)}
    runs = [(st, "corrected", v_fs) for st in stabilisers]
    if 0.05 in v_fs:
        runs.append(("utvf", "as_printed", (0.05,)))
    for st, form, v_f_runs in runs:
        periods = []
        label = st + (", Eq. 22 as printed" if form == "as_printed" else "")
        for v_f in v_f_runs:
            diag, cmd = beam_period_run(h_over_dp, v_f, st, form, ranks)
            cmds.append(cmd)
            paper = table_1_period(st, v_f) if form == "corrected" else None
            run_rows, period = beam_table_rows(diag, label, v_f, paper,
                                               0.08 if (st, form) == ("utvf", "corrected") else None)
            rows += run_rows
            periods.append(period)
        ax.plot(v_f_runs, periods, "o-" if form == "corrected" else "D:", color=colour[st], label=f"mpisph {label}")
    for st, periods in references.BEAM_TABLE_1_PERIODS.items():
        ax.plot(references.BEAM_TABLE_1_V_F, periods, "s--", color=colour[st], alpha=0.5,
                label=f"000_ Table 1, {st}")
    finish_period_axes(ax)
    note = ("Periods: the first upward zero crossing of the tip deflection, runs to 0.32 s (past one period); "
            "UTVF's are asserted within 8 % of Eq. 47, as issue 3 asks. "
            "Without a stabiliser the beam may break up before its period ends (the run then stops with "
            "a blow-up and its row reports what it reached). The energy is kinetic plus elastic strain "
            "energy at the first period, where the beam is straight again (at the run's end without one): "
            "artificial stress does work that neither holds, so with it the sum swings with the deflection "
            "between the crossings, and Eq. 22 as printed gains energy (physics/solid.py says why). 000_ "
            "Table 1's analytical period "
            "is 0.254 s and its SPH periods 6.7-11.8 % above it.")
    return (f"Oscillating beam, first periods at H/dp = {h_over_dp} (000_ Table 1)", "; ".join(cmds[:1]) + " (and the "
            "same with each stabiliser, v_f and shear_force)", rows, save(fig, "oscillating_beam_table.png"), note)


def oscillating_beam_sph_as(ranks, h_over_dp=30, v_fs=references.BEAM_TABLE_1_V_F):
    """000_ Table 1's AS column: Gray et al.'s SPH-AS (the classic scheme with artificial stress,
    scheme classic_elastic) at H/dp = 30 and each v_f of ``v_fs``, runs to 0.36 s."""
    rows, cmds, periods = [], [], []
    for v_f in v_fs:
        diag, cmd = beam_period_run(h_over_dp, v_f, "artificial_stress", None, ranks, scheme="classic_elastic",
                                    t_end=0.36)
        cmds.append(cmd)
        run_rows, period = beam_table_rows(diag, "SPH-AS", v_f, table_1_period("artificial_stress", v_f))
        rows += run_rows
        periods.append(period)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    ax.plot(v_fs, periods, "o-", color="C3", label="mpisph SPH-AS (classic_elastic, artificial_stress)")
    ax.plot(references.BEAM_TABLE_1_V_F, references.BEAM_TABLE_1_PERIODS["artificial_stress"], "s--", color="C3",
            alpha=0.5, label="000_ Table 1, AS")
    finish_period_axes(ax)
    note = ("000_'s AS column is cited as Gray et al. 2001's SPH-AS: classic SPH with artificial stress "
            "(epsilon = 0.3, n = 4) and Monaghan's artificial viscosity, predictor-corrector; the papers do not "
            "give Gray et al.'s viscosity, so these runs take 002_'s alpha = beta = 1. The previous section's "
            "artificial_stress rows are the same repulsion on the Riemann scheme. Periods and energies are "
            "measured as there; these runs go to 0.36 s, as the classic scheme's period at H/dp = 10 is "
            "0.309 s (section oscillating_beam). No tolerance: issue 13 asks for the column beside UTVF, "
            "not for a bound on it.")
    return (f"Oscillating beam, SPH-AS at H/dp = {h_over_dp} (000_ Table 1, AS column)", "; ".join(cmds[:1]) +
            " (and the same with each v_f)", rows, save(fig, "oscillating_beam_sph_as.png"), note)
