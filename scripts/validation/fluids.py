"""Fluids: the elliptical drop and the rotating square patch (000_ Secs. 4.1-4.2) with the remedies
beside one another, Taylor-Green and the lid-driven cavity (001_ Sec. 4), and the dam break against
Koshizuka & Oka and Martin & Moyce."""

import matplotlib.pyplot as plt
import numpy as np

from mpisph import measure, pairing, references, surface
from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.compare import measures as compare_measures
from mpisph.instability import tensile_instability
from mpisph.kernels import Kernel

from clustered import shifted_on_the_surface  # scripts/clustered.py (scripts/ is on the import path)
from .figures import clustered_panel, save
from .runs import run, run_directory


def pressure_panel(fig, ax, frame, title):
    """Particles of ``frame`` coloured by pressure."""
    sc = ax.scatter(frame["x"][:, 0], frame["x"][:, 1], c=frame["p"], s=1)
    ax.set_aspect("equal")
    ax.set_title(f"{title}, pressure [Pa]")
    fig.colorbar(sc, ax=ax)


def elliptical_drop(ranks):
    frames, _, cmd = run("elliptical_drop", "elliptical_drop", ["--t-end", "0.008", "--output-interval", "0.0004"], ranks)
    t = np.array([f["t"] for f in frames])
    ab = np.array([measure.semi_axes(f, 0.02) for f in frames])
    tt = np.linspace(0, 0.008, 81)
    ref = references.elliptical_drop_axes(tt)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(tt, ref[:, 0], "k-", label="analytic a")
    ax[0].plot(tt, ref[:, 1], "k--", label="analytic 1/a")
    ax[0].plot(t, ab[:, 0], "o", label="mpisph x semi-axis")
    ax[0].plot(t, ab[:, 1], "s", label="mpisph y semi-axis")
    ax[0].set_xlabel("t [s]")
    ax[0].legend()
    pressure_panel(fig, ax[1], frames[-1], f"t = {frames[-1]['t']:.4f} s")
    image = save(fig, "elliptical_drop.png")
    k = int(np.argmin(np.abs(t - 0.0076)))
    b_ref = references.elliptical_drop_axes(t[k])[0]
    error = ab[k, 1] / b_ref[1] - 1
    rows = [("y semi-axis at t = 0.0076 s", f"{ab[k, 1]:.4f}", f"{b_ref[1]:.4f}", f"{100 * error:+.2f}%", "1.5%",
             abs(error) <= 0.015),
            ("x semi-axis at t = 0.0076 s", f"{ab[k, 0]:.4f}", f"{b_ref[0]:.4f}", f"{100 * (ab[k, 0] / b_ref[0] - 1):+.2f}%", "-")]
    m = tensile_instability(frames[k])
    rows.append(("inner voids / clustering at t = 0.0076 s (`mpisph report`)",
                 f"{100 * m['inner_voids']:.1f}% / {100 * m['clustering']:.2f}%", "0", "-", "-"))
    note = ("Without a particle regularisation the drop's particles, squeezed 2:1 in x and stretched "
            "2:1 in y, end in rows 2 dp apart: the tensile-instability measure counts most particles as "
            "next to a void, and the flanks bulge (x semi-axis). The unified transport-velocity "
            "formulation of 000_ (`--set stabiliser=utvf`, next section) is what removes this.")
    return "Elliptical drop (dp = 0.02)", cmd, rows, image, note


def elliptical_drop_remedies(ranks):
    """000_ Sec. 4.1 with 000_'s own integration: one time step of Eq. 38 and the shift after each
    (Eq. 42), i.e. time_stepping=single; the semi-axes of UTVF at dp = 0.1, 0.05, 0.02 and issue 13's
    0.01 (Fig. 5) and the momenta of TVF, UTVF and shifting at 0.01 (Fig. 6)."""
    dp = 0.01
    module = load_case_module("elliptical_drop")
    common = ["time_stepping=single", "--t-end", "0.008", "--output-interval", "0.0004"]
    b_ref = references.elliptical_drop_axes(0.0076)[0]
    rows, cmds, drift, axes = [], [], {}, {}
    for st, spacing in [("utvf", 0.1), ("utvf", 0.05), ("utvf", 0.02), ("utvf", dp), ("tvf", dp), ("shifting", dp)]:
        name = f"elliptical_drop_{st}_{spacing:g}"
        frames, _, cmd = run(name, "elliptical_drop", ["--set", f"dp={spacing}", f"stabiliser={st}", *common], ranks)
        k = int(np.argmin(np.abs(np.array([f["t"] for f in frames]) - 0.0076)))
        axes[st, spacing] = np.array(measure.semi_axes(frames[k], spacing))
        if spacing == dp:
            cmds.append(cmd)
            case = build_case(module, resolve_params(module, {"dp": str(dp), "stabiliser": st}))
            drift[st] = compare_measures(run_directory(name), case)
    errors = {s: 100 * (axes["utvf", s] / b_ref - 1) for s in (0.1, 0.05, 0.02, dp)}
    for s in (0.1, 0.05, 0.02):
        rows.append((f"UTVF, dp = {s}: x / y semi-axis at t = 0.0076 s",
                     f"{axes['utvf', s][0]:.4f} / {axes['utvf', s][1]:.4f}", f"{b_ref[0]:.4f} / {b_ref[1]:.4f}",
                     f"{errors[s][0]:+.2f}% / {errors[s][1]:+.2f}%", "-"))
    x_err, y_err = errors[dp]
    rows.append((f"UTVF, dp = {dp}: x semi-axis at t = 0.0076 s", f"{axes['utvf', dp][0]:.4f}", f"{b_ref[0]:.4f}",
                 f"{x_err:+.2f}%", "2%", abs(x_err) <= 2.0))
    rows.append((f"UTVF, dp = {dp}: y semi-axis at t = 0.0076 s", f"{axes['utvf', dp][1]:.4f}", f"{b_ref[1]:.4f}",
                 f"{y_err:+.2f}%", "2%", abs(y_err) <= 2.0))
    largest = [np.abs(errors[s]).max() for s in (0.1, 0.05, 0.02, dp)]
    rows.append(("UTVF: the larger semi-axis error at dp = 0.1, 0.05, 0.02 (000_ Fig. 5: it falls)",
                 ", ".join(f"{e:.2f}%" for e in largest[:3]), "falls", "-", "falls",
                 largest[0] > largest[1] > largest[2]))
    rows.append((f"UTVF: the larger semi-axis error at dp = {dp}", f"{largest[3]:.2f}%", "-", "-", "-"))
    for st in ("tvf", "utvf"):
        rows.append((f"{st.upper()}: linear-momentum drift, norm of P - P0 over M v_ref", f"{drift[st]['dP']:.1e}", "0",
                     "-", "1e-12", drift[st]["dP"] <= 1e-12))
    rows.append(("shifting: linear-momentum drift (000_ Fig. 6a: it drifts)", f"{drift['shifting']['dP']:.1e}", "0",
                 "-", "> 1e-12", drift["shifting"]["dP"] > 1e-12))
    rows.append(("angular-momentum drift, norm of L - L0 over M v_ref R: UTVF / TVF / shifting",
                 " / ".join(f"{drift[s]['dL']:.2e}" for s in ("utvf", "tvf", "shifting")), "0", "-",
                 "UTVF < TVF", drift["utvf"]["dL"] < drift["tvf"]["dL"]))
    note = ("000_ integrates every material with one time step (Eq. 38) and the shift after each step "
            "(Eq. 42); the drop's default, the dual criteria of 001_, shifts once per advection step and "
            "leaves the x semi-axis 4.3 % wide with UTVF at dp = 0.01 (docs/REMEDIES.md). Shifting is "
            "Xu et al.'s with Khayyer et al.'s surface treatment (mpisph/stabilisers/shifting.py). The error "
            "falls from dp = 0.1 to 0.02 as in 000_ Fig. 5, but not further: at dp = 0.01 the x semi-axis is "
            "a little wider than at 0.02. Unlike 000_ Fig. 6b, shifting's angular momentum drifts least here.")
    fig, ax = plt.subplots(figsize=(5, 4))
    spacings = [0.1, 0.05, 0.02, dp]
    ax.loglog(spacings, [abs(errors[s][0]) for s in spacings], "o-", label="x semi-axis")
    ax.loglog(spacings, [abs(errors[s][1]) for s in spacings], "s-", label="y semi-axis")
    ax.set_xlabel("dp [m]")
    ax.set_ylabel("|error| at t = 0.0076 s [%]")
    ax.legend()
    return (f"Elliptical drop with TVF, UTVF and shifting (000_ Figs. 5-6, single time step)", "; ".join(cmds), rows,
            save(fig, "elliptical_drop_remedies.png"), note)


def taylor_green(ranks):
    """001_ Sec. 4.1 to t = 5 from a perfect lattice, as issue 13 asks, and from the case's jittered one:
    the limited correction's decay rate over [0, 5] within 3 %; from the lattice the unlimited one
    visibly off, its energy decaying more slowly than the analytic once the start is past (the rate
    over [1, 5] more than 3 % shallower: the overcorrection of 001_ Figs. 1 and 3). The limited
    correction from the lattice is also shown with 000_'s single time step (not 001_'s stepping)."""
    ref = references.taylor_green_energy_rate(100.0)
    rows, curves, cmds = [], [], []
    runs = [(nx, stabiliser, jitter, "dual") for nx in (50, 100) for jitter in (0.0, None)
            for stabiliser in ("tvf_limited", "tvf")]
    runs += [(nx, "tvf_limited", 0.0, "single") for nx in (50, 100)]
    for nx, stabiliser, jitter, stepping in runs:
        single = stepping == "single"
        sets = [f"nx={nx}", f"stabiliser={stabiliser}", "diagnostics_every=1"]
        sets += [] if jitter is None else [f"jitter={jitter:g}"]
        sets += ["time_stepping=single"] if single else []
        name = f"taylor_green_{nx}_{stabiliser}" + ("" if jitter is None else "_lattice") + ("_single" if single else "")
        _, diag, cmd = run(name, "taylor_green", ["--set", *sets, "--t-end", "5", "--output-interval", "1"], ranks)
        cmds.append(cmd)
        t, ke = diag["t"], diag["kinetic_energy"]
        late = t >= 1.0
        rate, late_rate = measure.decay_rate(t, ke), measure.decay_rate(t[late], ke[late])
        start = ("a perfect lattice" if jitter == 0.0 else "the jittered lattice") + (
            ", 000_'s single time step" if single else "")
        limited = stabiliser == "tvf_limited" and not single
        rows.append((f"KE decay rate over [0, 5], {nx} x {nx}, {stabiliser}, from {start}", f"{rate:.4f}", f"{ref:.4f}",
                     f"{100 * (rate / ref - 1):+.1f}%", "3%" if limited else "-",
                     *((abs(rate / ref - 1) <= 0.03,) if limited else ())))
        off = stabiliser == "tvf" and jitter == 0.0  # the unlimited one from the issue's lattice
        rows.append((f"KE decay rate over [1, 5], {nx} x {nx}, {stabiliser}, from {start}", f"{late_rate:.4f}",
                     f"{ref:.4f}", f"{100 * (late_rate / ref - 1):+.1f}%", "below -3%" if off else "-",
                     *((late_rate / ref - 1 < -0.03,) if off else ())))
        analytic = ke[0] * np.exp(ref * t)
        at_1 = np.interp(1.0, t, ke / analytic)
        rows.append((f"KE(1) / analytic and KE(5) / analytic, {nx} x {nx}, {stabiliser}, from {start}",
                     f"{at_1:.3f} / {ke[-1] / analytic[-1]:.3f}", "1", "-", "-"))
        curves.append((f"{nx} x {nx}, {stabiliser}" + (", lattice" if jitter == 0.0 else "")
                       + (", single step" if single else ""), t, ke / ke[0]))
        if (nx, stabiliser, jitter, stepping) == (100, "tvf", 0.0, "dual"):
            ours = (t, ke)
    # the authors' code at the same settings as mpisph's `tvf` from the 100 x 100 lattice (references.py)
    ke_sx = references.SPHINXSYS_TAYLOR_GREEN_KE
    t_sx = references.SPHINXSYS_TAYLOR_GREEN_DT * np.arange(len(ke_sx))
    analytic_sx = ke_sx[0] * np.exp(ref * t_sx)
    late = t_sx >= 1.0
    for span, rate in (("[0, 5]", measure.decay_rate(t_sx, ke_sx)),
                       ("[1, 5]", measure.decay_rate(t_sx[late], ke_sx[late]))):
        rows.append((f"KE decay rate over {span}, the authors' code (SPHinXsys: 100 x 100, TVF without a limiter, "
                     f"from a perfect lattice)", f"{rate:.4f}", f"{ref:.4f}", f"{100 * (rate / ref - 1):+.1f}%", "-"))
    early = np.array([0.1, 0.2, 0.3, 0.5, 1.0])
    t, ke = ours
    ours_early = np.interp(early, t, ke) / (ke[0] * np.exp(ref * early))
    authors_early = np.interp(early, t_sx, ke_sx / analytic_sx)
    rows.append(("KE / analytic at t = " + ", ".join(f"{x:g}" for x in early) + ", 100 x 100 from a perfect lattice: "
                 "mpisph's tvf; the authors' code", " / ".join(f"{x:.3f}" for x in ours_early) + "; "
                 + " / ".join(f"{x:.3f}" for x in authors_early), "1", "-", "-"))
    curves.append(("the authors' code (SPHinXsys), 100 x 100, TVF, lattice", t_sx, ke_sx / ke_sx[0]))
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    tt = np.linspace(0, 5, 100)
    for a, lattice in zip(ax, (True, False)):
        a.semilogy(tt, np.exp(ref * tt), "k-", label="analytic")
        for label, t, ke in curves:
            if ("lattice" in label) == lattice:
                style = ":" if "single" in label else "--" if "tvf_limited" not in label else "-"
                authors = label.startswith("the authors'")
                a.semilogy(t, ke, "k." if authors else style, ms=3, label=label if authors else f"mpisph {label}")
        a.set_xlabel("t [s]")
        a.set_ylabel("KE / KE0")
        a.set_title("from a perfect lattice" if lattice else "from the jittered lattice (0.2 dp)")
        a.legend(fontsize=7)
    note = ("Issue 13 asks for the vortex from a regular lattice without jitter, as 001_ Fig. 2 runs it; the "
            "case's default starts from the lattice perturbed by a seeded 0.2 dp jitter (`jitter`), shown "
            "beside it. From the perfect lattice the symmetric flow carries the lattice in lockstep and "
            "stretches it at the hyperbolic points by exp(2 pi t), 1.9 at t = 0.1 and beyond the kernel support "
            "by t = 0.2. There the kernel sum, hence density and pressure, rises (+10 % at a stretch of 1.9 for "
            "h = 1.3 dp) while sum V grad W stays zero by symmetry, so no transport-velocity correction acts, "
            "and the kinetic energy falls to about half the analytic value by t = 0.2 (docs/REMEDIES.md has the "
            "runs that locate it). That early loss is what puts the rates over [0, 5] from the lattice outside "
            "3 %; over [1, 5] the limited correction's rate is nearer the analytic one. Without the limiter "
            "(001_ Eq. 14 alone, `tvf`) the energy decays more slowly than the analytic after the start: the "
            "correction's overcorrection at low speed, as in 001_ Figs. 1 and 3. With 000_'s single time step "
            "(`time_stepping=single`: a configuration and the limited shift every step, about seven times as "
            "often as 001_'s advection step) the 100 x 100 lattice keeps its energy, while the 50 x 50 one "
            "still loses most of it by t = 1 and then decays too slowly, so its rate over [0, 5] alone "
            "flatters it; neither single-step row is issue 13's run, so neither carries a tolerance. The authors' "
            "own code loses the energy alike: SPHinXsys's regression data for its Taylor-Green test (the same "
            "square, c0, Re, kernel and stepping, a perfect 100 x 100 lattice, the correction without a limiter; "
            f"references.SPHINXSYS_TAYLOR_GREEN_KE, black dots) fall to {authors_early[1]:.2f} of the analytic "
            f"energy by t = 0.2 and {authors_early[4]:.2f} by t = 1, within "
            f"{np.abs(ours_early - authors_early).max():.3f} of mpisph's `tvf` from the same lattice at every "
            "time of the row above; no run of SPHinXsys's test from a lattice with 001_'s limiter is stored.")
    return "Taylor-Green vortex (Re = 100, to t = 5)", "; ".join(cmds), rows, save(fig, "taylor_green.png"), note


def dam_break(ranks):
    """Koshizuka & Oka's front for T <= 1.6 and Martin & Moyce's late front speed (issue 13's
    settlement of the reference), the offset in T that best aligns the front with Martin & Moyce."""
    frames, _, cmd = run("dam_break_2d", "dam_break_2d", ["--t-end", "0.72", "--output-interval", "0.02"], ranks)
    T, z = measure.dam_break_fronts(frames)
    offset = measure.time_offset(T, z, references.MARTIN_MOYCE_T, references.MARTIN_MOYCE_Z)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    ax[0].plot(references.KOSHIZUKA_T, references.KOSHIZUKA_Z, "ks", label="Koshizuka & Oka 1996")
    ax[0].plot(references.MARTIN_MOYCE_T, references.MARTIN_MOYCE_Z, "k^", label="Martin & Moyce 1952")
    ax[0].plot(T, z, "-o", ms=3, label="mpisph dp = 0.02 L")
    ax[0].plot(T - offset, z, ":", label=f"mpisph, T {-offset:+.2f}")
    ax[0].set_xlabel("T = t sqrt(2g/L)")
    ax[0].set_ylabel("front z/L")
    ax[0].legend()
    k = int(np.argmin(np.abs(T - 2.0)))
    pressure_panel(fig, ax[1], frames[k], f"T = {T[k]:.2f}")
    image = save(fig, "dam_break_2d.png")
    rows = []
    for Tk in references.KOSHIZUKA_T[1:]:
        if Tk > T[-1]:
            break
        zk = np.interp(Tk, T, z)
        ref = references.koshizuka_oka_front(Tk)
        error = zk / ref - 1
        rows.append((f"front at T = {Tk:.3f}", f"{zk:.3f}", f"{ref:.3f} (K&O)", f"{100 * error:+.1f}%",
                     *(("10%", bool(abs(error) <= 0.10)) if Tk <= 1.6 else ("-",))))
    speed = measure.front_speed(T, z, *references.MARTIN_MOYCE_SPAN)
    ref_speed = references.martin_moyce_speed()
    rows.append(("front speed dZ/dT over T = {:g}-{:g}".format(*references.MARTIN_MOYCE_SPAN), f"{speed:.3f}",
                 f"{ref_speed:.3f} (M&M)",
                 f"{100 * (speed / ref_speed - 1):+.1f}%", "10%", bool(abs(speed / ref_speed - 1) <= 0.10)))
    rows.append(("offset in T that best aligns the front with M&M", f"{offset:+.2f}", "-", "-", "-"))
    note = ("Issue 13 settles the reference: Koshizuka & Oka's points are held to 10 % up to T = 1.6 only, "
            "and the late front to Martin & Moyce's speed (their n^2 = 2, a = 2.25 in run: the four points of "
            "`references.MARTIN_MOYCE_T/Z`, joined by straight lines). Beyond T ~ 1.9 the front runs ahead of "
            "Koshizuka & Oka's later points, which advance at 0.97 where Martin & Moyce's front does 1.33; they "
            "are evenly spaced in T as video frames would be. The offset is the shift of the computed front in T "
            "that best fits Martin & Moyce's points (dotted line): a release that is not instantaneous in the "
            "experiment delays its front.")
    return "Dam break (Koshizuka & Oka, Martin & Moyce)", cmd, rows, image, note


def cavity_centre_lines(frame, nx, y, x):
    """u on the vertical centre line at heights ``y`` and v on the horizontal one at ``x``, the
    kernel-weighted averages of the particles of ``frame`` (a run at nx x nx)."""
    kernel = Kernel("wendland_c2", 1.3 / nx, 2)
    u = measure.line_average(frame, np.stack([np.full_like(y, 0.5), y], 1), 0, kernel)
    v = measure.line_average(frame, np.stack([x, np.full_like(x, 0.5)], 1), 1, kernel)
    return u, v


def cavity_runs(ranks, Re, t_end, ref_u, ref_v, checked_nx):
    """Runs of the lid-driven cavity at ``Re`` to ``t_end`` for nx = 50 and ``checked_nx``; rows of
    the RMS errors against Ghia et al.'s columns ``ref_u``, ``ref_v`` (at t_end, and for the finest
    run also at t_end - 10 s to show the flow is steady), asserted (<= 0.05 at Re = 1000, 0.03 at
    Re = 100) for nx = ``checked_nx``; the command and the figure."""
    tolerance = 0.03 if Re == 100 else 0.05
    gy, gx = references.GHIA_Y[1:-1], references.GHIA_X[1:-1]
    ys = np.linspace(0, 1, 101)
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(ref_u, references.GHIA_Y, "ks", label="Ghia et al. 1982")
    ax[1].plot(references.GHIA_X, ref_v, "ks", label="Ghia et al. 1982")
    rows, shown = [], []
    for nx in sorted({50, checked_nx}):
        args = ["--set", f"nx={nx}", f"Re={Re:g}", "--t-end", f"{t_end:g}", "--output-interval", "5"]
        frames, _, cmd = run(f"lid_driven_cavity_re{Re:g}_nx{nx}", "lid_driven_cavity", args, ranks)
        shown.append(cmd)
        u, v = cavity_centre_lines(frames[-1], nx, ys, ys)
        ax[0].plot(u, ys, "-", label=f"mpisph, dp = 1/{nx}")
        ax[1].plot(ys, v, "-", label=f"mpisph, dp = 1/{nx}")
        times = [t_end - 10.0, t_end] if nx == checked_nx else [t_end]
        for t in times:
            frame = next(f for f in frames if abs(f["t"] - t) < 1e-9)
            ug, vg = cavity_centre_lines(frame, nx, gy, gx)
            for name, err in (("u", ug - ref_u[1:-1]), ("v", vg - ref_v[1:-1])):
                rms = float(np.sqrt(np.mean(err**2)))
                checked = nx == checked_nx and t == t_end
                rows.append((f"RMS error of {name}, dp = 1/{nx}, t = {t:g} s", f"{rms:.4f}", "0", "-",
                             f"{tolerance:g}" if checked else "-", *((rms <= tolerance,) if checked else ())))
    ax[0].set_xlabel("u on x = 0.5")
    ax[0].set_ylabel("y")
    ax[0].legend()
    ax[1].set_xlabel("x")
    ax[1].set_ylabel("v on y = 0.5")
    return "; ".join(shown), rows, fig


def cavity(ranks):
    cmd, rows, fig = cavity_runs(ranks, 100, 20.0, references.GHIA_U, references.GHIA_V, 50)
    return "Lid-driven cavity (Re = 100, dp = 1/50)", cmd, rows, save(fig, "lid_driven_cavity.png"), ""


def cavity_re1000(ranks):
    cmd, rows, fig = cavity_runs(ranks, 1000, 40.0, references.GHIA_U_RE1000, references.GHIA_V_RE1000, 100)
    note = ("001_ Sec. 4.2, Fig. 5: the same cavity at Re = 1000 with the limited transport-velocity "
            "correction, against Ghia et al.'s Re = 1000 columns (`references.GHIA_U_RE1000`, "
            "`GHIA_V_RE1000`). 001_ does not give an end time; the errors at t = 30 s and 40 s show the "
            "flow has settled.")
    return ("Lid-driven cavity (Re = 1000, dp = 1/50 and 1/100)", cmd, rows,
            save(fig, "lid_driven_cavity_re1000.png"), note)


def rotating_patch(ranks):
    frames, diag, cmd = run("rotating_square_patch", "rotating_square_patch",
                            ["--t-end", "2.04", "--output-interval", "0.12"], ranks)
    p0 = measure.nearest_value(frames[0], "p", (0, 0)) / 1000.0
    ang = diag["angular_momentum_z"]
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(diag["t"], ang / ang[0], label="L(t) / L(0)")
    ax[0].plot(diag["t"], diag["kinetic_energy"] / diag["kinetic_energy"][0], label="KE(t) / KE(0)")
    ax[0].set_xlabel("t omega")
    ax[0].legend()
    pressure_panel(fig, ax[1], frames[-1], f"t omega = {frames[-1]['t']:.2f}")
    image = save(fig, "rotating_square_patch.png")
    ref = references.ROTATING_SQUARE_CENTRE_PRESSURE
    k = int(np.argmin(np.abs(diag["t"] - 2.0)))
    error, drift = p0 / ref - 1, ang[k] / ang[0] - 1
    rows = [("initial centre p / (rho omega^2 L^2)", f"{p0:.5f}", f"{ref:.6f}", f"{100 * error:+.2f}%", "1%",
             abs(error) <= 0.01),
            ("angular momentum drift at t omega = 2", f"{100 * drift:+.3f}%", "0", "-", "1%", abs(drift) <= 0.01),
            ("kinetic energy change at t omega = 2",
             f"{100 * (diag['kinetic_energy'][k] / diag['kinetic_energy'][0] - 1):+.2f}%", "0", "-", "-")]
    return "Rotating square patch (dp = 0.02)", cmd, rows, image, ""


def _unshifted_share(frame):
    """(clustered particles, those of them on the free surface that 000_'s UTVF leaves in place:
    splashed, or outermost / near-surface with div r < 0.6 d, Sec. 3.3) of ``frame``."""
    i, _ = pairing.clustered_pairs(frame)
    kind = frame["surface"][i]
    left = (kind == surface.SPLASHED) | (np.isin(kind, (surface.SURFACE, surface.NEAR_SURFACE))
                                         & ~shifted_on_the_surface(frame)[i])
    return len(i), int(left.sum())


def rotating_patch_remedies(ranks):
    """000_ Figs. 8-9a at dp = L/100 with 000_'s single time step: the kinetic-energy loss at
    t omega = 2 in the order UTVF < TVF < shifting, and UTVF's clustering at the two times of
    Fig. 8 (issue 13: at most 0.1 %); UTVF with the case's dual criteria beside it, not asserted."""
    dp = 0.01  # L/100
    stabilisers = ("utvf", "tvf", "shifting")
    runs, cmds = {}, []
    for st, stepping in [(s, "single") for s in stabilisers] + [("utvf", "dual")]:
        frames, diag, cmd = run(f"rotating_square_patch_{st}_{stepping}_dp{dp:g}", "rotating_square_patch",
                                ["--set", f"dp={dp:g}", f"stabiliser={st}", f"time_stepping={stepping}",
                                 "--t-end", "2.04", "--output-interval", "0.12"], ranks)
        runs[st, stepping] = frames, diag
        cmds.append(cmd)
    fig = plt.figure(figsize=(13, 8))
    ax = fig.add_subplot(2, 3, 1)
    loss, rows = {}, []
    for (st, stepping), (frames, diag) in runs.items():
        ke = diag["kinetic_energy"] / diag["kinetic_energy"][0]
        k = int(np.argmin(np.abs(diag["t"] - 2.0)))
        loss[st, stepping] = 1.0 - ke[k]
        ax.plot(diag["t"], ke - 1.0, "--" if stepping == "dual" else "-", label=f"{st}, {stepping}")
    ax.set_xlabel("t omega")
    ax.set_ylabel("(E_K - E_K0) / E_K0")
    ax.legend(fontsize=8)
    single = [loss[s, "single"] for s in stabilisers]
    rows.append(("kinetic-energy loss at t omega = 2: UTVF / TVF / shifting (000_ Fig. 9a)",
                 " / ".join(f"{100 * x:.2f}%" for x in single), "UTVF < TVF < shifting", "-",
                 "UTVF < TVF < shifting", bool(single[0] < single[1] < single[2])))
    at = {}
    for (st, stepping), (frames, _) in runs.items():
        for t in (1.08, 2.04):
            frame = min(frames, key=lambda f: abs(f["t"] - t))
            at[st, stepping, t] = frame, tensile_instability(frame)
    for t in (1.08, 2.04):
        m = at["utvf", "single", t][1]
        rows.append((f"UTVF: clustering at t omega = {t} (inner voids {100 * m['inner_voids']:.2f}%)",
                     f"{100 * m['clustering']:.2f}%", "0", "-", "0.1%", bool(m["clustering"] <= 0.001)))
    for st, stepping in (("tvf", "single"), ("shifting", "single"), ("utvf", "dual")):
        m = at[st, stepping, 2.04][1]
        rows.append((f"{st}, {stepping} time step: clustering / inner voids at t omega = 2.04",
                     f"{100 * m['clustering']:.2f}% / {100 * m['inner_voids']:.2f}%", "0", "-", "-"))
    rows.append(("UTVF, the case's dual criteria: kinetic-energy loss at t omega = 2",
                 f"{100 * loss['utvf', 'dual']:.2f}%", "-", "-", "-"))
    shown = [("utvf", "single", 2.04), ("tvf", "single", 2.04), ("utvf", "single", 1.08),
             ("shifting", "single", 2.04), ("utvf", "dual", 2.04)]
    for k, (st, stepping, t) in enumerate(shown):
        clustered_panel(fig, fig.add_subplot(2, 3, 2 + k), at[st, stepping, t][0],
                         f"{st}, {stepping}: t omega = {t}, p [Pa]; clustered red", field="p")
    clustered, left = _unshifted_share(at["utvf", "single", 2.04][0])
    note = (f"000_ runs the patch with one time step (Eq. 38) and the shift after each, as here; the case's "
            f"default, the dual criteria of 001_, shifts once per advection step (the dashed curve and the last "
            f"rows). With 000_'s step the energy order of Fig. 9a holds, though shifting's patch breaks up "
            f"(its inner voids). UTVF's clustering misses issue 13's 0.1 %: of its {clustered} clustered "
            f"particles at t omega = 2.04, {left} sit on the free surface where 000_'s UTVF leaves them in place "
            f"(splashed, or div r < 0.6 d: Sec. 3.3), along the thinning arms (red in the pictures; "
            f"docs/REMEDIES.md).")
    return (f"Rotating square patch with TVF, UTVF and shifting (000_ Figs. 8-9a, dp = L/{round(1 / dp)})",
            "; ".join(cmds), rows, save(fig, "rotating_square_patch_remedies.png"), note)
