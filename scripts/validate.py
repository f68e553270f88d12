"""Run the validation cases and write docs/VALIDATION.md with plots.

    .venv/bin/python scripts/validate.py [--ranks 2] [--only NAME ...] [--beam-h-over-dp 30] [--reuse]

Every figure in the page comes from a run made by this script; the command
of each run is printed in the page beside its result. A row may carry a sixth
entry, whether it meets its tolerance; the script exits non-zero, listing them,
when one does not (the sections written before that check was added carry none:
their tests assert the same figures).
"""

import argparse
import json
import subprocess
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from mpisph import incline_measures, measure, pairing, references, surface  # noqa: E402
from mpisph.case import build_case, case_of_frame, load_case_module, resolve_params  # noqa: E402
from mpisph.compare import measures as compare_measures  # noqa: E402
from mpisph.io.diagnostics import read_diagnostics  # noqa: E402
from mpisph.granular_flow import CONSISTENT_MU_I, DEVIATORIC_MU_I  # noqa: E402
from mpisph.instability import tensile_instability  # noqa: E402
from mpisph.io.frames import list_frames, read_frame  # noqa: E402
from mpisph.kernels import Kernel  # noqa: E402
from mpisph.launch import mpirun_mpisph  # noqa: E402
from mpisph.particles import MOVING  # noqa: E402
from mpisph.well_posedness import ill_posed_energy_share, well_posed_window  # noqa: E402

from clustered import shifted_on_the_surface  # noqa: E402  (this directory)

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
IMG = DOCS / "img"
RUNS = ROOT / "runs" / "validation"


REUSE = False  # set by --reuse
STAMP = "validate_run.json"
PARTIAL_STAMP = "validate_run.started.json"  # a run under way, or interrupted


def code_version():
    """The git tree ids of mpisph/ and cases/, on which a run's bits depend, or None when either
    holds uncommitted changes."""
    def git(*words):
        return subprocess.run(["git", *words], capture_output=True, text=True, cwd=ROOT, check=True).stdout

    if git("status", "--porcelain", "--", "mpisph", "cases").strip():
        return None
    return git("rev-parse", "HEAD:mpisph", "HEAD:cases").split()


def run(name, case, args, ranks, blow_up_ok=False):
    """Frames, diagnostics and the command of one run; with ``blow_up_ok`` a run that stops on a
    blow-up (exit 3) returns what it wrote, its last frame the one at the blow-up. With --reuse, a
    finished run of the same command, rank count and committed code (its stamp) is read, not re-run,
    and one that was interrupted (its partial stamp, written at its start) continues from its last
    frame (a restart gives the bits of an uninterrupted run: tests/test_stop_on_signal.py)."""
    out = RUNS / name
    stamp = {"case": case, "args": [str(a) for a in args], "ranks": ranks, "code": code_version()}
    done, started = out / STAMP, out / PARTIAL_STAMP

    def same(path):
        return path.exists() and {k: json.loads(path.read_text()).get(k) for k in stamp} == stamp

    if REUSE and stamp["code"] and same(done):
        returncode = json.loads(done.read_text())["returncode"]
        print(f"  reusing {out} (same command and code)")
    else:
        restart = []
        if REUSE and stamp["code"] and same(started) and list_frames(out):
            restart = ["--restart", list_frames(out)[-1]]
            print(f"  continuing {out} from {restart[1]} (same command and code)")
        done.unlink(missing_ok=True)
        if stamp["code"]:
            out.mkdir(parents=True, exist_ok=True)
            started.write_text(json.dumps(stamp))
        r = mpirun_mpisph([case, *args, *restart, "--out", out, "--quiet"], ranks=ranks)
        returncode = r.returncode
        if returncode != 0 and not (blow_up_ok and returncode == 3):
            raise SystemExit(r.stderr)
        if stamp["code"]:
            done.write_text(json.dumps(dict(stamp, returncode=returncode)))
            started.unlink()
    if returncode != 0 and not blow_up_ok:  # a reused run that blew up, read where that is not allowed
        raise SystemExit(f"{case} {' '.join(args)}: blew up (exit 3); its frames are in {out}")
    shown = f"mpirun -n {ranks} python -m mpisph {case} {' '.join(args)}"
    frames = [read_frame(f) for f in list_frames(out)]
    return frames, read_diagnostics(out / "diagnostics.csv"), shown


def pressure_panel(fig, ax, frame, title):
    """Particles of ``frame`` coloured by pressure."""
    sc = ax.scatter(frame["x"][:, 0], frame["x"][:, 1], c=frame["p"], s=1)
    ax.set_aspect("equal")
    ax.set_title(f"{title}, pressure [Pa]")
    fig.colorbar(sc, ax=ax)


def save(fig, image):
    fig.tight_layout()
    fig.savefig(IMG / image, dpi=90)
    return image


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
    rows = [("y semi-axis at t = 0.0076 s", f"{ab[k, 1]:.4f}", f"{b_ref[1]:.4f}", f"{100 * (ab[k, 1] / b_ref[1] - 1):+.2f}%", "1.5%"),
            ("x semi-axis at t = 0.0076 s", f"{ab[k, 0]:.4f}", f"{b_ref[0]:.4f}", f"{100 * (ab[k, 0] / b_ref[0] - 1):+.2f}%", "-")]
    m = tensile_instability(frames[k])
    rows.append(("inner voids / clustering at t = 0.0076 s (`mpisph report`)",
                 f"{100 * m['inner_voids']:.1f}% / {100 * m['clustering']:.2f}%", "0", "-", "-"))
    note = ("Without a particle regularisation the drop's particles, squeezed 2:1 in x and stretched "
            "2:1 in y, end in rows 2 dp apart: the tensile-instability measure counts most particles as "
            "next to a void, and the flanks bulge (x semi-axis). The unified transport-velocity "
            "formulation of 000_ (next issue) is what removes this.")
    return "Elliptical drop (dp = 0.02)", cmd, rows, image, note


def elliptical_drop_remedies(ranks, dp=0.01):
    """000_ Sec. 4.1 with 000_'s own integration: one time step of Eq. 38 and the shift after each
    (Eq. 42), i.e. time_stepping=single; the semi-axes of UTVF at dp = 0.1, 0.05, 0.02 and ``dp``
    (Fig. 5) and the momenta of TVF, UTVF and shifting at ``dp`` (Fig. 6)."""
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
            drift[st] = compare_measures(RUNS / name, case)
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
    T = np.array([f["t"] for f in frames]) * np.sqrt(2 * 9.81)
    z = np.array([measure.surge_front(f, 0.02) for f in frames])
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
        ref = np.interp(Tk, references.KOSHIZUKA_T, references.KOSHIZUKA_Z)
        error = zk / ref - 1
        rows.append((f"front at T = {Tk:.3f}", f"{zk:.3f}", f"{ref:.3f} (K&O)", f"{100 * error:+.1f}%",
                     *(("10%", bool(abs(error) <= 0.10)) if Tk <= 1.6 else ("-",))))
    speed, ref_speed = measure.front_speed(T, z, 1.9, 3.1), references.martin_moyce_speed()
    rows.append(("front speed dZ/dT over T = 1.9-3.1", f"{speed:.3f}", f"{ref_speed:.3f} (M&M)",
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
    rows = [("initial centre p / (rho omega^2 L^2)", f"{p0:.5f}", f"{ref:.6f}", f"{100 * (p0 / ref - 1):+.2f}%", "1%"),
            ("angular momentum drift at t omega = 2", f"{100 * (ang[k] / ang[0] - 1):+.3f}%", "0", "-", "1%"),
            ("kinetic energy change at t omega = 2",
             f"{100 * (diag['kinetic_energy'][k] / diag['kinetic_energy'][0] - 1):+.2f}%", "0", "-", "-")]
    return "Rotating square patch (dp = 0.02)", cmd, rows, image, ""


def _clustered_panel(fig, ax, frame, title, field="plastic_strain", axes=(0, 1)):
    """The material particles of ``frame`` coloured by ``field`` (its colours capped at its 99th
    percentile), the clustered ones red."""
    moving = frame["kind"] == MOVING
    x, c = frame["x"][moving], frame[field][moving]
    sc = ax.scatter(x[:, axes[0]], x[:, axes[1]], c=c, s=0.3, cmap="viridis",
                    vmax=max(np.percentile(c, 99), c.min() + 1e-12))
    i, _ = pairing.clustered_pairs(frame)
    ax.plot(frame["x"][i, axes[0]], frame["x"][i, axes[1]], "r.", ms=1.5)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=7)
    fig.colorbar(sc, ax=ax, shrink=0.6)


def _unshifted_share(frame):
    """(clustered particles, those of them on the free surface that 000_'s UTVF leaves in place:
    splashed, or outermost / near-surface with div r < 0.6 d, Sec. 3.3) of ``frame``."""
    i, _ = pairing.clustered_pairs(frame)
    kind = frame["surface"][i]
    left = (kind == surface.SPLASHED) | (np.isin(kind, (surface.SURFACE, surface.NEAR_SURFACE))
                                         & ~shifted_on_the_surface(frame)[i])
    return len(i), int(left.sum())


def rotating_patch_remedies(ranks, dp=0.01):
    """000_ Figs. 8-9a at dp = L/100 with 000_'s single time step: the kinetic-energy loss at
    t omega = 2 in the order UTVF < TVF < shifting, and UTVF's clustering at the two times of
    Fig. 8 (issue 13: at most 0.1 %); UTVF with the case's dual criteria beside it, not asserted."""
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
        _clustered_panel(fig, fig.add_subplot(2, 3, 2 + k), at[st, stepping, t][0],
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


def deposit_panel(fig, ax, frame, first, title):
    """Particles of ``frame`` coloured by plastic strain over the outline of ``first``."""
    sc = ax.scatter(frame["x"][:, 0], frame["x"][:, 1], c=frame["plastic_strain"], s=1, cmap="viridis",
                    vmax=np.percentile(frame["plastic_strain"], 99))
    lo, hi = first["x"].min(axis=0), first["x"].max(axis=0)
    ax.plot([lo[0], hi[0], hi[0], lo[0], lo[0]], [lo[1], lo[1], hi[1], hi[1], lo[1]], "k--", lw=0.8)
    ax.set_aspect("equal")
    ax.set_title(f"{title}, plastic strain")
    fig.colorbar(sc, ax=ax)


def column_collapse(ranks):
    """L = 0.2 against the issue's references; L = 0.1 (aspect 1) runs beside it. Profiles every 0.1 s."""
    dp = 0.002  # the case's default, 000_ Sec. 5.1
    fig, ax = plt.subplots(4, 1, figsize=(10, 12))
    rows = []
    for k, L in enumerate((0.2, 0.1)):
        frames, diag, shown = run(f"column_collapse_2d_L{L}", "column_collapse_2d",
                                  ["--set", f"dp={dp}", "--set", f"L={L}"], ranks)
        last = frames[-1]
        for f in frames:
            tenth = abs(f["t"] * 10 - round(f["t"] * 10)) < 1e-6
            if (tenth and f["t"] <= 0.6) or f is last:
                ax[2 * k].plot(*measure.surface_profile(f, dp), lw=1, label=f"t = {f['t']:.1f} s")
        ax[2 * k].set_xlabel("x [m]")
        ax[2 * k].set_ylabel("surface height [m]")
        ax[2 * k].set_title(f"L = {L} m, H = 0.1 m: profiles")
        ax[2 * k].legend(fontsize=7, ncol=4)
        deposit_panel(fig, ax[2 * k + 1], last, frames[0], f"L = {L} m, t = {last['t']:.1f} s")
        energy = diag["kinetic_energy"] + diag["potential_energy"]
        speeds = [np.linalg.norm(f["v"], axis=1).max() for f in frames]
        runout, top = measure.runout(last, dp), measure.deposit_height(last, dp, 0.05)
        ratio = energy[-1] / energy[0]
        if L == 0.2:
            cmd = shown
            settled, _, _ = run("column_collapse_2d_settled", "column_collapse_2d",
                                ["--restart", str(list_frames(RUNS / f"column_collapse_2d_L{L}")[-1]),
                                 "--set", "stabiliser=none", "--t-end", "1.15"], ranks)
            still = np.linalg.norm(settled[-1]["v"], axis=1).max() / max(speeds)
            # 000_'s stress diffusion (Feng et al.'s geostatic form) beside the default
            feng, feng_diag, _ = run("column_collapse_2d_geostatic_diffusion", "column_collapse_2d",
                                     ["--set", f"dp={dp}", f"L={L}", "stress_diffusion=geostatic"], ranks)
            feng_energy = feng_diag["kinetic_energy"] + feng_diag["potential_energy"]
            rows += [("L = 0.2: runout [m]", f"{runout:.3f}", "0.32-0.38", "-", "[0.30, 0.40]"),
                     ("L = 0.2: column top [m]", f"{top:.4f}", "0.1", f"{100 * (top / 0.1 - 1):+.1f}%", "5%"),
                     ("L = 0.2: final / peak max speed", f"{speeds[-1] / max(speeds):.4f}", "0", "-", "< 0.01"),
                     ("L = 0.2: the same, 0.15 s later without the UTVF shift", f"{still:.4f}", "0", "-", "< 0.01"),
                     ("L = 0.2: final / initial mechanical energy", f"{ratio:.3f}", "0.69 +- 0.03",
                      f"{ratio - 0.69:+.3f}", "+- 0.05"),
                     ("L = 0.2, stress_diffusion=geostatic (000_): runout [m] / top [m] / final / peak max speed "
                      "/ energy ratio", f"{measure.runout(feng[-1], dp):.3f} / "
                      f"{measure.deposit_height(feng[-1], dp, 0.05):.4f} / {final_over_peak_speed(feng):.4f} / "
                      f"{feng_energy[-1] / feng_energy[0]:.3f}", "0.32-0.38 / 0.1 / 0 / 0.69 +- 0.03", "-", "-")]
        else:
            rows += [("L = 0.1: runout [m] / top [m]", f"{runout:.3f} / {top:.4f}", "-", "-", "runs"),
                     ("L = 0.1: final / peak max speed, energy ratio",
                      f"{speeds[-1] / max(speeds):.4f}, {ratio:.3f}", "-", "-", "-")]
    image = save(fig, "column_collapse_2d.png")
    note = ("Runout: the right end of the connected deposit (grains thrown ahead of a gap do not count); "
            "profiles are the highest particle per dp-wide bin. The paper's text does not give the times of "
            "its Figs. 15-16 nor the experimental profiles, so profiles are drawn every 0.1 s without an "
            "experimental overlay. L = 0.1 is the same command with `--set L=0.1`; the last L = 0.2 row with "
            "`--set stress_diffusion=geostatic`, the stress diffusion 000_ uses (Feng et al.'s; the default "
            "diffuses each stress component less its local linear part, mpisph/physics/drucker_prager.py). "
            "The granular Riemann limiter damps pairs that move apart, as the paper's code does "
            "(mpisph/physics/solid.py says why); damping approaching pairs instead, as the text of the printed "
            "Eq. 20 suggests, gave a runout of 0.413 m here (0.401 m without a stabiliser), with grains sliding "
            "ahead of the deposit. The thin toe still creeps under UTVF in the L = 0.1 run (row above) and at "
            "coarser spacings (1.5-3 % of the peak speed at t = 1 s for L = 0.2, dp = 0.005), driven by the "
            "tangential shift of the toe's surface particles; "
            "the row 'without the UTVF shift' continues the last frame for 0.15 s with "
            "`--set stabiliser=none`.")
    return "Granular column collapse, L = 0.2 m and 0.1 m (dp = 0.002)", cmd, rows, image, note


def final_over_peak_speed(frames):
    """The largest particle speed of the last frame over its largest value over the frames."""
    speeds = [np.linalg.norm(f["v"], axis=1).max() for f in frames]
    return speeds[-1] / max(speeds)


def cohesive_failure(ranks):
    # none's clustering against utvf's is asserted by remedies_cuts, on the same runs
    tolerance = {"utvf": "<= 0.1% / 0 / - / 1", "tvf": "surface clusters", "none": "-"}
    dp = 0.04
    runs = {st: run(f"cohesive_failure_2d_{st}", "cohesive_failure_2d", ["--set", f"stabiliser={st}"], ranks)
            for st in ("utvf", "tvf", "none")}
    fig, ax = plt.subplots(3, 1, figsize=(10, 9))
    rows = []
    for a, (st, (frames, _, cmd)) in zip(ax, runs.items()):
        deposit_panel(fig, a, frames[-1], frames[0], f"{st}, t = {frames[-1]['t']:.1f} s")
        a.set_xlim(-0.1, 6.0)
        last = list_frames(RUNS / f"cohesive_failure_2d_{st}")[-1]
        m = tensile_instability(read_frame(last, walls=True))
        row = (f"{st}: clustering / inner voids / closest pair / fragments (outside the largest) at 2 s",
               f"{100 * m['clustering']:.2f}% / {100 * m['inner_voids']:.2f}% / {m['min_spacing']:.2f} dp / "
               f"{m['fragments']} ({100 * m['detached']:.2f}%)", "0 / 0 / 1 dp / 1", "-", tolerance[st])
        if st == "utvf":
            row += (m["clustering"] <= 0.001 and m["inner_voids"] == 0.0 and m["fragments"] == 1,)
        rows.append(row)
        if st == "utvf":
            crack = measure.crest_crack(frames[0], frames[-1], dp, 4.0, 0.05 * 2.0)
            rows.insert(0, ("crest crack behind the face [m]", f"{crack:.2f}", "1.2-1.5", "-", "[1.0, 1.7]"))
            rows.insert(1, ("final / peak max speed", f"{final_over_peak_speed(frames):.3f}", "0", "-", "-"))
            shown = cmd
    # 000_'s stress diffusion, Feng et al.'s geostatic form (physics/drucker_prager.py)
    feng, _, _ = run("cohesive_failure_2d_utvf_geostatic_diffusion", "cohesive_failure_2d",
                     ["--set", "stabiliser=utvf", "stress_diffusion=geostatic"], ranks)
    crack = measure.crest_crack(feng[0], feng[-1], dp, 4.0, 0.05 * 2.0)
    m = tensile_instability(read_frame(list_frames(RUNS / "cohesive_failure_2d_utvf_geostatic_diffusion")[-1],
                                       walls=True))
    rows.append(("utvf, stress_diffusion=geostatic (000_): crest crack [m] / final / peak max speed / clustering "
                 "at 2 s", f"{crack:.2f} / {final_over_peak_speed(feng):.3f} / {100 * m['clustering']:.2f}%",
                 "1.2-1.5 / 0 / 0", "-", "-"))
    image = save(fig, "cohesive_failure_2d.png")
    note = ("Crest crack: the leftmost particle of the initial top layer that sank by more than 0.05 H. "
            "The same command with `--set stabiliser=tvf` and `none` gives the other rows, and with "
            "`--set stabiliser=utvf stress_diffusion=geostatic` the last one (the stress diffusion 000_ uses, "
            "Feng et al.'s: sigma less its geostatic part, where the default takes each component's local "
            "linear part; docs/FLUME.md). The section `remedies_cuts` holds none's clustering against the "
            "remedies'.")
    return "Cohesive soil cut (dp = L/100)", shown, rows, image, note


WENDLAND = ("wendland_c2", 1.3)  # 000_'s kernel and h / dp
CUBIC = ("cubic_spline", 1.5)  # 002_'s, which its adaptive kernel adapts
CUT_RUNS = (("none", WENDLAND, 0.3), ("utvf", WENDLAND, 0.3), ("artificial_stress", WENDLAND, 0.3),
            ("artificial_stress", WENDLAND, 0.1), ("none", CUBIC, 0.3), ("adaptive_kernel", CUBIC, 0.3))


def _cut_run(case, stabiliser, kernel, epsilon, ranks):
    """One run of a cut (or the cube) with ``stabiliser`` on ``kernel`` (name, h / dp): the case's own
    settings are not repeated, so that cohesive_failure's runs are read again; its label, first and
    last frames (the last with walls), the last one's tensile-instability measures and the command."""
    defaults = resolve_params(load_case_module(case), {})
    sets = [f"stabiliser={stabiliser}"]
    if (defaults["kernel"], defaults["h_factor"]) != kernel:
        sets += [f"kernel={kernel[0]}", f"h_factor={kernel[1]:g}"]
    if stabiliser == "artificial_stress" and epsilon != defaults["artificial_stress_epsilon"]:
        sets.append(f"artificial_stress_epsilon={epsilon:g}")
    name = "_".join([case, *(s.split("=")[1] for s in sets)])
    frames, _, cmd = run(name, case, ["--set", *sets], ranks)
    last = read_frame(list_frames(RUNS / name)[-1], walls=True)  # run's frames hold no walls
    first = frames[0]
    label = stabiliser + (f" (epsilon = {epsilon:g})" if stabiliser == "artificial_stress" else "")
    return f"{label}, {kernel[0]} h = {kernel[1]:g} dp", first, last, tensile_instability(last), cmd


def _instability_cells(m):
    return (f"{100 * m['clustering']:.3f}% / {100 * m['inner_voids']:.2f}% / {m['fragments']} "
            f"({100 * m['detached']:.2f}%)")


def _clean(m):
    """No clustering beyond issue 13's 0.1 %, no inner void, one piece."""
    return bool(m["clustering"] <= 0.001 and m["inner_voids"] == 0.0 and m["fragments"] == 1)


def remedies_cuts(ranks):
    """Issue 13 on the two cuts at 2 s: UTVF and artificial stress (epsilon = 0.3) on 000_'s kernel, the
    adaptive kernel on 002_'s cubic spline, each without clustering (<= 0.1 %), inner voids or
    fractures, with none on the same kernel ten times as clustered at least; epsilon = 0.1 fails
    (002_ Fig. 13)."""
    rows, cmds = [], []
    fig = plt.figure(figsize=(15, 10))
    for c, case in enumerate(("cohesive_failure_2d", "vertical_cut")):
        results = {}
        for k, (stabiliser, kernel, epsilon) in enumerate(CUT_RUNS):
            label, _, last, m, cmd = _cut_run(case, stabiliser, kernel, epsilon, ranks)
            results[stabiliser, kernel, epsilon] = m
            cmds.append(cmd)
            _clustered_panel(fig, fig.add_subplot(4, 3, 6 * c + k + 1), last, f"{case}: {label}, t = {last['t']:.1f} s")
        for stabiliser, kernel, epsilon in CUT_RUNS:
            m = results[stabiliser, kernel, epsilon]
            remedy = stabiliser != "none" and epsilon == 0.3
            if stabiliser == "none":
                tolerance, ok = "-", ()
            elif remedy:
                tolerance, ok = "<= 0.1% / 0 / 1", (_clean(m),)
            else:
                tolerance, ok = "fails: > 0.1%, a void or a fracture", (not _clean(m),)
            rows.append((f"{case}, {stabiliser}" + (f" epsilon = {epsilon:g}" if stabiliser == "artificial_stress"
                                                    else "") + f", {kernel[0]}: clustering / inner voids / "
                         "fragments (outside the largest) at 2 s", _instability_cells(m), "0 / 0 / 1", "-",
                         tolerance, *ok))
            if remedy:
                none = results["none", kernel, 0.3]["clustering"]
                ratio = none / m["clustering"] if m["clustering"] > 0 else np.inf
                rows.append((f"{case}: none's clustering over {stabiliser}'s, {kernel[0]}",
                             f"{ratio:.1f} ({100 * none:.3f}% / {100 * m['clustering']:.3f}%)", ">= 10", "-",
                             ">= 10", bool(ratio >= 10)))
    note = ("Each remedy on the kernel of the paper that proposes it: UTVF and artificial stress (Gray, Monaghan & "
            "Swift 2001, epsilon = 0.3, n = 4) on 000_'s Wendland C2 at h = 1.3 dp, the adaptive kernel on 002_'s "
            "cubic spline at h = 1.5 dp, each beside a run without a remedy on the same kernel; all with the "
            "Riemann granular scheme of 000_ at each case's spacing (cohesive_failure_2d: dp = 0.04 m, 000_ "
            "Sec. 5.2; vertical_cut: dp = 0.025 m, 002_ Sec. 6). Clustering: particles nearer than dp / 2 to "
            "another; inner voids: surrounded particles with a low position divergence; fragments: the pieces "
            "the body has broken into (mpisph/instability.py, `mpisph report`). docs/REMEDIES.md compares them "
            "further, with 002_'s classic scheme too.")
    return ("Tensile-instability remedies on the cuts (issue 13)", "; ".join(cmds), rows,
            save(fig, "remedies_cuts.png"), note)


def remedies_cube_3d(ranks):
    """Issue 13: the 3D artificial stress and the 3D adaptive kernel run the 3D cube (000_ Sec. 5.3 at its
    dp = 0.04 m, to 1 s) on 2 ranks without clustering (<= 0.1 %); UTVF's run of docs/PRODUCTION_3D.md is
    the same case's default."""
    rows, cmds = [], []
    fig = plt.figure(figsize=(12, 3.4))
    for k, (stabiliser, kernel) in enumerate((("artificial_stress", WENDLAND), ("adaptive_kernel", CUBIC))):
        label, first, last, m, cmd = _cut_run("cube_failure_3d", stabiliser, kernel, 0.3, ranks)
        cmds.append(cmd)
        rows.append((f"cube_failure_3d, {label}: clustering / inner voids / fragments (outside the largest) at 1 s",
                     _instability_cells(m), "0 / - / 1", "-", "<= 0.1%",
                     bool(m["clustering"] <= 0.001)))
        rows.append((f"cube_failure_3d, {label}: paired share at 1 s (the clustered that the flow's squeeze "
                     "does not explain, mpisph/pairing.py)", f"{100 * pairing.paired_share(last, first):.3f}%",
                     "0", "-", "-"))
        _clustered_panel(fig, fig.add_subplot(1, 2, k + 1), last, f"{label}, t = {last['t']:.1f} s (x-z)",
                         axes=(0, 2))
    note = ("The cube's particles projected on the x-z plane, the clustered ones red. Issue 13 holds the "
            "clustering to 0.1 %. The paired share leaves out the clustered particles that the flow's own "
            "squeeze of the lattice brought that close (docs/REMEDIES.md, 'What the cube's clustering is').")
    return ("Artificial stress and the adaptive kernel on the 3D cube (issue 13)", "; ".join(cmds), rows,
            save(fig, "remedies_cube_3d.png"), note)


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
        files = list_frames(RUNS / name)  # in the order of ``frames``; re-read with the clamp for the panels
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


def _incline_panels(material, theta, H, g):
    """A figure of three panels for a layer down a slope: the speed profile with the analytical one of
    the flow depth H (references.inclined_plane_flow_depth), the pressure profile, the mean speed
    against time with the analytical mean."""
    fig, ax = plt.subplots(1, 3, figsize=(15, 5))
    z = np.linspace(0.0, H, 101)
    ax[0].plot(references.inclined_plane_velocity(material, theta, H, g, z), z, "k--", label="analytical")
    ax[2].axhline(0.6 * references.inclined_plane_surface_velocity(material, theta, H, g), color="k", ls="--",
                  lw=0.8, label="analytical mean")
    return fig, ax


def _finish_incline_panels(ax, pressure):
    """Axis labels (``pressure``: the middle panel's) and legends of ``_incline_panels``."""
    ax[0].set_xlabel("u [m/s]")
    ax[0].set_ylabel("height above the bed [m]")
    ax[1].set_xlabel(pressure)
    ax[2].set_xlabel("t [s]")
    ax[2].set_ylabel("mean velocity down the slope [m/s]")
    for a in ax:
        a.legend(fontsize=7)


def inclined_plane(ranks):
    """004_ Sec. 5.1 with 004_ Table 2 (H = 0.1 m, dp = 5 mm, 40 columns, m_0 = 1 s) to 6.5 s: the
    viscous form, the pair-viscosity mean and alpha against the analytical profile; a layer on a
    level bed against hydrostatic pressure."""
    from mpisph.case import build_case, load_case_module, resolve_params

    module = load_case_module("inclined_plane")
    params = resolve_params(module, {})
    H, dp, theta, g, columns, t_end = params["H"], params["dp"], params["theta"], params["g"], params["columns"], 6.5
    material = build_case(module, params).material
    depth = references.inclined_plane_flow_depth(material, theta, H)
    u_s = references.inclined_plane_surface_velocity(material, theta, depth, g)
    fig, ax = _incline_panels(material, theta, depth, g)
    z = np.linspace(0.0, depth, 101)
    ax[1].plot(references.inclined_plane_pressure(material, theta, depth, g, z), z, "k--", label="hydrostatic")
    rows, cmd = [], None
    for form, alpha, mean in (("cleary", 0.0, "harmonic"), ("cleary", 0.05, "harmonic"), ("cleary", 0.0, "secant"),
                              ("cleary", 0.05, "secant"), ("corrected_stress", 0.0, "-")):
        label = f"{form}, alpha = {alpha}" + (f", {mean} mean" if mean != "-" else "")
        means = ["--set", f"viscosity_mean={mean}"] if mean != "-" else []
        frames, diag, shown = run(f"inclined_plane_{form}_{alpha}_{mean}", "inclined_plane",
                                  ["--set", f"viscous_form={form}", "--set", f"alpha={alpha}", *means,
                                   "--t-end", f"{t_end}", "--output-interval", "0.5"], ranks, blow_up_ok=True)
        cmd = cmd or shown
        last = frames[-1]
        if last["t"] < t_end - 1e-9:
            rows.append((f"{label}: blew up (a particle left the domain) at t [s]", f"{last['t']:.2f}",
                         f"{t_end:g} (end)", "-", f"runs to {t_end:g} s", False))
            last = frames[-2]  # the last regular frame
        y, u = measure.layer_means(last, dp, last["v"][:, 0])
        _, p = measure.layer_means(last, dp, last["p"])
        top = last["x"][:, 1] > last["x"][:, 1].max() - 0.5 * dp
        surface = last["v"][top, 0].mean()
        ua = references.inclined_plane_velocity(material, theta, depth, g, np.clip(y, 0.0, depth))
        l2 = np.sqrt(np.mean((u - ua) ** 2) / np.mean(ua**2))
        ph = references.inclined_plane_pressure(material, theta, depth, g, np.clip(y, 0.0, depth))
        mean_u = diag["momentum_x"] / diag["mass"]
        late = (diag["t"] >= last["t"] - 1.0) & (diag["t"] <= last["t"])
        trend = np.polyfit(diag["t"][late], mean_u[late], 1)[0]
        ax[0].plot(u, y, "o-", ms=3, label=label)
        ax[1].plot(p, y, "o-", ms=3, label=label)
        ax[2].plot(diag["t"], mean_u, label=label)
        at = f"{last['t']:g} s"
        rows += [(f"{label}: surface velocity at {at} [m/s]", f"{surface:.3f}", f"{u_s:.3f}",
                  f"{100 * (surface / u_s - 1):+.1f}%", "3%", abs(surface / u_s - 1) <= 0.03),
                 (f"{label}: profile L2 error at {at}", f"{100 * l2:.1f}%", "0", "-", "5%", l2 <= 0.05),
                 (f"{label}: layer pressure / hydrostatic at {at}", f"{np.mean(p) / np.mean(ph):.3f}", "1",
                  f"{100 * (np.mean(p) / np.mean(ph) - 1):+.1f}%", "2%", abs(np.mean(p) / np.mean(ph) - 1) <= 0.02),
                 (f"{label}: mean velocity trend over the last second [m/s^2]", f"{trend:+.3f}", "0 (steady)",
                  "-", "-")]
    frames, _, _ = run("inclined_plane_level", "inclined_plane",
                       ["--set", "theta=0", "--t-end", "1", "--output-interval", "0.5"], ranks)
    last = frames[-1]
    y, p = measure.layer_means(last, dp, last["p"])
    rho = last["mass"].sum() / (columns * dp * H)
    ratio = np.mean(p) / np.mean(rho * g * (H - y))
    rows += [("level bed, 1 s: layer pressure / hydrostatic", f"{ratio:.3f}", "1", f"{100 * (ratio - 1):+.1f}%",
              "2%", abs(ratio - 1) <= 0.02),
             ("level bed, 1 s: largest speed [m/s]", f"{np.linalg.norm(last['v'], axis=1).max():.1e}", "0", "-", "-")]
    _finish_incline_panels(ax, "p [Pa]")
    image = save(fig, "inclined_plane.png")
    note = ("004_ Table 2: H = 0.1 m, dp = 5 mm, 40 columns (800 grains), m_0 = 1 s, the explicit step of "
            "Eq. 39, to 6.5 s, where 004_ reports its steady state; K_t for Mach 0.1 at the analytical surface "
            "speed as 004_ Sec. 5.1 says (1.3e-7 1/Pa; Table 2 prints 1.5e-5, which puts that flow at Mach 1.1). Layers are dp-thick bins of the last "
            "frame; the surface velocity is the mean of the top layer; the analytical profile takes "
            "incompressible grains and no regularisation, and the depth of the uniform flow of the same grains, "
            "H phi_max / phi_u (references.inclined_plane_flow_depth: 2.3 % deeper than at rest). An open gap "
            "(issue 14): no variant reaches the "
            "analytical flow. Without artificial viscosity the layers still accelerate at 6.5 s (the trend rows); "
            "with Eq. 37's harmonic mean a grain leaves the layer at 6.03 s (the grains at the free surface have "
            "no friction, mu_i_law.pair_viscosity), and the rows for it are read at the frame before. With "
            "004_'s alpha = 0.05 the layers are nearly steady, at a fifth of the analytical surface speed or less. "
            "From rest no layer can be steady by 6.5 s: under the unregularised law (friction at least mu_s "
            "everywhere) the mean speed grows by at most g (sin theta - mu_s cos theta) = 0.75 m/s^2, so it "
            "needs at least 10 s to reach the analytical mean of 7.9 m/s. Near the uniform flow the layer "
            "relaxes with a time of 15 s at H = 0.1 m (references.inclined_plane_relaxation_time). docs/INCLINE.md "
            "has the CI-sized layer (H = 0.02 m) that does reach a steady state, and where it falls short: "
            "Eq. 27's pair viscosity delivers 81-92 % of div(eta grad v) on lattices (tests/test_mu_i_law.py), "
            "which the law magnifies about eightfold near I_u.")
    return "Inclined plane (004_ Sec. 5.1)", cmd, rows, image, note


def _steady_incline(ranks, name, sets, t_end, steady, interval, alphas):
    """Runs of the layer down the slope with the --set words ``sets`` to ``t_end``, one per alpha of
    Eq. 38, and their figures averaged over the frames from ``steady``: (command, rows, image)."""
    module = load_case_module("inclined_plane")
    params = resolve_params(module, dict(a.split("=") for a in sets))
    material = build_case(module, params).material
    H, theta, g = params["H"], params["theta"], params["g"]
    depth = incline_measures.flow_depth(params, material)
    T = references.inclined_plane_relaxation_time(material, theta, depth, g)
    span = f"{steady:g}-{t_end:g} s"
    fig, ax = _incline_panels(material, theta, depth, g)
    rows, cmd = [], None
    for alpha in alphas:
        frames, diag, shown = run(name + (f"_alpha{alpha:g}" if alpha else ""), "inclined_plane",
                                  ["--set", *sets, f"alpha={alpha:g}", "--t-end", f"{t_end:g}", "--output-interval",
                                   f"{interval:g}"], ranks)
        cmd = cmd or shown
        late = [f for f in frames if f["t"] >= steady - 1e-9]
        figures = np.array([(*incline_measures.layer_speeds(f, params, material),
                             *incline_measures.profile_figures(f, params, material)) for f in late])
        mean, surface, l2, grains, carried = figures.mean(axis=0)
        speed = diag["momentum_x"] / diag["mass"]
        window = diag["t"] >= steady
        trend = np.polyfit(diag["t"][window], speed[window], 1)[0] * (t_end - steady) / speed[window].mean()
        label = f"alpha = {alpha:g}"
        rows += [(f"{label}: mean speed / analytical mean, {span}", f"{mean:.3f}", "1",
                  f"{100 * (mean - 1):+.1f}%", "-"),
                 (f"{label}: surface speed / analytical, {span}", f"{surface:.3f}", "1",
                  f"{100 * (surface - 1):+.1f}%", "3%", abs(surface - 1) <= 0.03),
                 (f"{label}: profile L2 error, {span}", f"{100 * l2:.1f}%", "0", "-", "5%", l2 <= 0.05),
                 (f"{label}: pressure the pairs carry, s p / weight above, {span}", f"{carried:.3f}", "1",
                  f"{100 * (carried - 1):+.1f}%", "2%", abs(carried - 1) <= 0.02),
                 (f"{label}: the grains' pressure p / weight above, {span}", f"{grains:.3f}", "1",
                  f"{100 * (grains - 1):+.1f}%", "-"),
                 (f"{label}: change of the mean speed over {span}, relative", f"{trend:+.3f}", "0 (steady)", "-",
                  "-")]
        if alpha:
            nu, mean_nu, surface_nu = incline_measures.with_artificial_viscosity(dict(params, alpha=alpha), material)
            rows += [(f"{label}: mean speed / that of the uniform flow with Eq. 38's viscosity "
                      f"nu = alpha h c0 / 8 = {nu:.2e} m^2/s added, {span}", f"{mean / mean_nu:.3f}", "1",
                      f"{100 * (mean / mean_nu - 1):+.1f}%", "-"),
                     (f"{label}: surface speed / that of the same flow, {span}", f"{surface / surface_nu:.3f}", "1",
                      f"{100 * (surface / surface_nu - 1):+.1f}%", "-")]
            z = np.linspace(0.0, depth, 101)
            ax[0].plot(references.inclined_plane_velocity_with_viscosity(material, theta, depth, g, nu, z), z, "k:",
                       label=f"uniform flow with nu = alpha h c0 / 8 added, {label}")
        layers = [measure.layer_means(f, params["dp"], f["v"][:, 0]) for f in late]
        kept = min(len(y) for y, _ in layers)  # the layers every frame has
        height = np.mean([y[:kept] for y, _ in layers], axis=0)
        ax[0].plot(np.mean([u[:kept] for _, u in layers], axis=0), height, "o-", ms=3,
                   label=f"mpisph, {label}, mean of the frames {span}")
        share = [measure.layer_means(f, params["dp"], incline_measures.carried_pressure(f))[1][:kept]
                 for f in late]
        weight = [incline_measures.hydrostatic(f, params)[:kept] for f in late]
        ax[1].plot(np.mean(weight, axis=0), height, "--", label=f"weight of the grains above, {label}")
        ax[1].plot(np.mean(share, axis=0), height, "o-", ms=3, label=f"s p, the pressure the pairs carry, {label}")
        ax[2].plot(diag["t"], speed, label=f"mpisph, {label}")
    rows.append((f"relaxation time T at H = {H:g} m [s] (references.inclined_plane_relaxation_time)", f"{T:.2f}",
                 "-", "-", "-"))
    _finish_incline_panels(ax, "pressure [Pa]")
    return cmd, rows, save(fig, f"{name}.png")


OPTIONS_NOTE = ("The options are departures from 004_, each with a derivation and a test of its own "
                "(physics/mu_i.py; docs/INCLINE.md): the pressure as the isotropic stress -p s B (no shear from a "
                "pressure); the law's pressure the kernel mean of s p, the share the pairs carry (the law's shear "
                "stress is concave in the pressure, so the grains' scattered pressures would carry less shear than "
                "their mean); and the law's strain rate the modulus of the deviator of the kernel mean of eps (the "
                "particles' jostle biases the modulus of each particle's own, and the grains' volumetric rate is "
                "acoustic noise, not shear: 004_ Eq. 4 puts the shear viscosity on the deviator). The analytical "
                "flow is that of the same grains, whose depth is the layer's at rest dilated from phi_max to phi_u "
                "(references.inclined_plane_flow_depth: 2.3 % deeper, its surface 3.4 % faster). The pressures "
                "are against the weight of the grains above each layer's mean height, each "
                "grain a slab dp thick (incline_measures.weight_above), as the layer dilates above H. ")


def inclined_plane_steady(ranks):
    """The CI-sized layer of docs/INCLINE.md (H = 0.02 m, H/dp = 20, m_0 = 0.2 s, summation density)
    with the corrected stress and the three options that make the law see the continuum's stresses
    and strain rate, to its steady state, without and with 004_'s alpha = 0.05 (Fig. 6): speeds, profile and
    pressure averaged over the frames from 8 s."""
    sets = ["H=0.02", "dp=0.001", "columns=32", "m_0=0.2", "density_reinit=inner", *CONSISTENT_MU_I]
    cmd, rows, image = _steady_incline(ranks, "inclined_plane_steady", sets, 12.0, 8.0, 0.05, (0.0, 0.05))
    note = (OPTIONS_NOTE +
            "The as-printed scheme on this layer is 0.58 of the analytical mean speed (docs/INCLINE.md) and the "
            "section 'Inclined plane' runs it at 004_'s H = 0.1 m. The second run adds 004_'s artificial "
            "viscosity alpha = 0.05 (Eq. 38), which 004_ Sec. 5.1 found to reduce its overestimated velocities. "
            "Applied to every pair, Eq. 38 has the form of Eq. 27's viscous pair term: it is a shear viscosity "
            "nu = alpha h c0 / 8 (references.pair_viscosity_of_alpha), here about an eighth of the law's "
            "eta / rho in the bulk (c0 for Mach 0.1), and the law's flat mu(I) near I_u turns that into a "
            "much slower flow: the uniform flow with nu added (references.inclined_plane_velocity_with_"
            "viscosity) is the dotted line and its rows; the pair form delivers about 81 % of it on a "
            "lattice at h = 1.3 dp (tests/test_mu_i_law.py). Figures are means over the frames from 8 s (about "
            "6 T), every 0.05 s: the layers' mean pressure swings by about 7 % from frame to frame with the "
            "layer's acoustic modes (docs/INCLINE.md), so a few frames cannot tell its mean to 2 %. Without "
            "alpha the layer's profile follows the analytical one within about 1 % from the second "
            "spacing above the bed up to the top two (docs/INCLINE.md); the first spacing slides on the bed at "
            "about 1.5 times the analytical speed there, which lifts the mean speed by about 1 %. The grains' "
            "pressure sits above the weight by the share 1 - s that the pairs do not carry. The agreement leans on "
            "a bias of the corrected gradient: in the sheared layer its trace holds about 1.5 % of the shear "
            "rate (the uncorrected gradient's and the continuity equation's divergence average to zero; "
            "incline_layers.py's bulk table), so the bulk part of the viscous stress, 2 eta tr(eps) / D, carries a "
            "tension of 0.6-0.9 % of the pressure, which the law turns into a slower flow; with that bulk part "
            "taken on the continuity equation's divergence instead (a patch not kept, docs/INCLINE.md) the "
            "layer runs 7 % fast at 10 s and still gains.")
    return "Inclined plane at its steady state, H = 0.02 m (004_ Sec. 5.1)", cmd, rows, image, note


def inclined_plane_deep(ranks):
    """004_'s layer (Table 2: H = 0.1 m, dp = 5 mm, 40 columns, m_0 = 1 s) with the corrected stress
    and the three options of ``inclined_plane_steady``, to its steady state: about 6 T = 90 s, some
    eight hours on two ranks; with --reuse an interrupted run continues from its last frame."""
    sets = ["density_reinit=inner", *CONSISTENT_MU_I]
    cmd, rows, image = _steady_incline(ranks, "inclined_plane_deep", sets, 100.0, 90.0, 2.0, (0.0,))
    note = (OPTIONS_NOTE +
            "The case's defaults are 004_ Table 2's layer, K_t for Mach 0.1 at the analytical surface speed. The "
            "layer relaxes to its uniform flow with T = 15 s (references.inclined_plane_relaxation_time), so the "
            "figures are means over the frames from 90 s (6 T), as the CI-sized layer's are from 6 T.")
    return "Inclined plane at its steady state, H = 0.1 m (004_ Sec. 5.1, Table 2)", cmd, rows, image, note


REST = 1e-3  # 004_ Sec. 5.2: a deposit's front moves at least three orders of magnitude slower than at its peak


def _collapse(case, a, length, dp, ranks, radial, variant=(), t_end=None, n_frames=20):
    """One mu(I) collapse of aspect ratio ``a`` (column length or radius ``length``) to ``t_end``,
    by default 6 sqrt(H_0/g) (at least 0.6 s), with ``n_frames`` frames: its diagnostics, last frame,
    command, runout ratio, how far from rest it is between its last two frames
    (measure.edge_rest_ratio), and its onset (measure.collapse_onset)."""
    H0 = a * length
    default_end = max(0.6, 6.0 * np.sqrt(H0 / 9.81))
    settings = [f"a={a}", f"dp={dp:.12g}", *variant]
    name = f"{case}_" + "_".join(s.replace("=", "") for s in settings)
    if t_end is None:
        t_end = default_end
    else:
        name += f"_to{t_end:g}"
    if n_frames != 20:
        name += f"_frames{n_frames}"
    frames, diag, shown = run(name, case, ["--set", *settings, "--t-end", f"{t_end:.3g}", "--output-interval",
                                           f"{t_end / n_frames:.3g}"], ranks)
    last = frames[-1]
    extent = measure.radial_runout(last, dp) if radial else measure.runout(last, dp)
    rest = measure.edge_rest_ratio(frames[-2], last, diag["t"], diag["front"], dp, radial=radial)
    window = well_posed_window(case_of_frame(last["params"]).material.params)
    return {"a": a, "H0": H0, "dp": dp, "length": length, "radial": radial, "diag": diag, "last": last,
            "cmd": shown, "ratio": (extent - length) / length, "rest": rest, "t_end": last["t"],
            "onset": measure.collapse_onset(diag["t"], diag["front"], length), "window": window,
            "ill_posed": ill_posed_energy_share(frames, window)}


def _ill_posed_row(runs, label):
    """The share of each run's dissipated energy at inertial numbers where its mu(I) is ill-posed
    (mpisph/well_posedness.py; docs/COLLAPSES.md)."""
    window = runs[0]["window"]
    where = f"outside {window[0]:.3g} < I < {window[1]:.3g}" if window else "at every I"
    return (f"share of the energy dissipated where the law is ill-posed ({where}; Barker et al. 2015) at {label}",
            " / ".join(f"{r['ill_posed']:.3f}" for r in runs), "-", "-", "-")


def _centre(r):
    """The deposit's top within 0.3 of the column's length (radius) from its back wall (axis), over
    H_0: 1 where the top stays undisturbed (scripts/collapse_deposit.py's centre)."""
    return measure.deposit_height(r["last"], r["dp"], 0.3 * r["length"], radial=r["radial"]) / r["H0"]


def _farthest(r):
    """The farthest grain's edge beyond the column, over its length (radius)."""
    return measure.farthest_edge(r["last"], r["dp"], r["radial"]) / r["length"] - 1.0


def _front_panel(ax, runs, length, symbol):
    for r in runs:
        scale = np.sqrt(r["H0"] / 9.81)
        ax.plot(r["diag"]["t"] / scale, (r["diag"]["front"] - r["diag"]["front"][0]) / length, label=f"a = {r['a']:g}")
    ax.set_xlabel("t / sqrt(H_0 / g)")
    ax.set_ylabel(f"front advance / {symbol}_0")
    ax.legend(fontsize=7)


def _rest_row(r, what):
    return (f"a = {r['a']:g}: speed of {what} over the last frame interval / peak front speed", f"{r['rest']:.1e}",
            f"<= {REST:g}", "-", f"{REST:g}", r["rest"] <= REST)


def lube_collapse_2d(ranks):
    """Planar mu(I) collapses (Lube et al. 2005) for a = 0.5-6 at L_0 / dp = 20: runout against
    the two scalings and their fitted slope and exponent, the deposit height, rest."""
    L0 = references.LUBE_R0
    dp = L0 / 20
    runs = [_collapse("lube_collapse_2d", a, L0, dp, ranks, radial=False) for a in (0.5, 1.0, 2.0, 4.0, 6.0)]
    fig, ax = plt.subplots(1, 3, figsize=(16, 4.5))
    _front_panel(ax[0], runs, L0, "L")
    a = np.array([r["a"] for r in runs])
    ratio = np.array([r["ratio"] for r in runs])
    aa = np.geomspace(0.3, 8, 50)
    ax[1].loglog(aa, 1.2 * aa, "k--", label="1.2 a")
    ax[1].loglog(aa, 1.9 * aa ** (2 / 3), "k:", label="1.9 a^(2/3)")
    ax[1].loglog(a, ratio, "o", label="defaults")
    ax[1].set_xlabel("a = H_0 / L_0")
    ax[1].set_ylabel("(L_inf - L_0) / L_0")
    ax[1].legend(fontsize=7)
    rows = []
    for r in runs:
        x, top = measure.surface_profile(r["last"], dp)
        ax[2].plot(x / L0, top / L0, label=f"a = {r['a']:g}")
        laws = [("1.2 a", 1.2 * r["a"])] if r["a"] <= 1 else [("1.9 a^(2/3)", 1.9 * r["a"] ** (2 / 3))]
        if r["a"] == 2.0:
            laws.insert(0, ("1.2 a", 1.2 * r["a"]))
        for name, ref in laws:
            rows.append((f"a = {r['a']:g}: (L_inf - L_0) / L_0 against {name}", f"{r['ratio']:.2f}", f"{ref:.2f}",
                         f"{100 * (r['ratio'] / ref - 1):+.0f}%", "-"))
        if r["a"] < 1.15:
            height = measure.deposit_height(r["last"], dp, 0.25 * L0) / L0
            rows.append((f"a = {r['a']:g}: final height H_inf / L_0 (undisturbed top)", f"{height:.3f}",
                         f"{r['a']:g}", f"{100 * (height / r['a'] - 1):+.0f}%", "-"))
        rows.append(_rest_row(r, "the connected deposit's edge"))
    ax[2].set_xlabel("x / L_0")
    ax[2].set_ylabel("deposit height / L_0")
    ax[2].legend(fontsize=7)
    rows.append(("onset [s] (the front 0.05 L_0 out) at a = " + ", ".join(f"{r['a']:g}" for r in runs),
                 " / ".join(f"{r['onset']:.3f}" for r in runs), "-", "-", "-"))
    rows.append(_ill_posed_row(runs, "a = " + ", ".join(f"{r['a']:g}" for r in runs)))
    more = {}  # the runs below by (a, variant, t_end)
    for a_k, variant, what, t_end in ((1.0, (), "the defaults", 3.0), (0.5, (), "the defaults", 3.0),
                                      (1.0, ("viscosity_mean=harmonic",), "Eq. 37's harmonic mean as printed", None),
                                      (1.0, ("viscosity_mean=arithmetic",), "the arithmetic mean", None),
                                      (0.5, ("viscous_step=explicit",), "the explicit step of Eq. 39", None),
                                      (0.5, ("m_0=40",), "m_0 = 40 s", None)):
        r = _collapse("lube_collapse_2d", a_k, L0, dp, ranks, radial=False, variant=variant, t_end=t_end)
        more[(a_k, variant, t_end)] = r
        height = measure.deposit_height(r["last"], dp, 0.25 * L0) / L0
        what += "" if t_end is None else f", to {t_end:g} s"
        rows += [(f"a = {a_k:g} with {what}: (L_inf - L_0) / L_0", f"{r['ratio']:.2f}", f"{1.2 * a_k:.2f}",
                  f"{100 * (r['ratio'] / (1.2 * a_k) - 1):+.0f}%", "-"),
                 (f"a = {a_k:g} with {what}: H_inf / L_0; edge speed / peak; onset [s]",
                  f"{height:.3f}; {r['rest']:.1e}; {r['onset']:.3f}", f"{a_k:g}; <= {REST:g}; -", "-", "-")]
    exponent, fits = _planar_fits(a, ratio)
    rows += fits + _fit_spread("", (), runs, L0, dp, ranks)
    for channel, (n, spread) in references.PLANAR_RUNOUT_EXPONENTS.items():
        rows.append((f"high-a exponent against Balmforth & Kerswell's {channel} ({n:g} +- {spread:g})",
                     f"{exponent:.2f}", f"{n:g}", f"{exponent - n:+.2f}", "-"))
    rows += _variant_collapses("CONSISTENT_MU_I", CONSISTENT_MU_I, a, L0, dp, ranks, ax[1], "s")
    rows += _variant_collapses("DEVIATORIC_MU_I", DEVIATORIC_MU_I, a, L0, dp, ranks, ax[1], "^")
    ax[1].legend(fontsize=7)
    image = save(fig, "lube_collapse_2d.png")
    default = {r["a"]: r for r in runs}
    growth = " and ".join(f"{100 * (more[(a_k, (), 3.0)]['ratio'] / default[a_k]['ratio'] - 1):.0f} %"
                          for a_k in (0.5, 1.0))
    onsets = f"{more[(0.5, ('m_0=40',), None)]['onset']:.2f} s against {default[0.5]['onset']:.2f} s at a = 0.5"
    note = ("Runs with the cases' defaults: the implicit viscous kick (`viscous_step=explicit` is the paper's "
            "scheme) and the secant pair viscosity (`viscosity_mean=harmonic` is Eq. 37 as printed; "
            "mu_i_law.pair_viscosity says why it fails), L_0 = 9.72 cm, dp = L_0 / 20 (004_ Table 3 uses "
            "1.2-4.9 mm), m_0 = 1.2 s, to 6 sqrt(H_0 / g). The runout is the edge of the connected deposit "
            "(measure.runout); the front in the left panel is the farthest grain (diagnostics.csv). With the "
            "harmonic mean the grains at the free surface (p = 0, so eta = 0) are decoupled from the pile and "
            "keep sliding over it: the deposit spreads to nearly twice Lube's runout. An open gap of issue 14: "
            "(0) the columns dissipate their energy where the sand's friction law is ill-posed (the row of "
            "shares), so the runouts at this spacing need not converge with the resolution, and they do not "
            "(docs/COLLAPSES.md, 'Why the runouts do not converge'); (1) the runouts follow 1.2 a up to a = 6, "
            "with too little bend to a^(2/3) (004_ also found no agreement above a = 3); Balmforth & Kerswell "
            "(2005) measured a^(0.9 +- 0.1) in wide channels and "
            "a^(0.65 +- 0.05) only in narrow slots, whose side walls a plane-strain run lacks "
            "(docs/COLLAPSES.md); (2) the deposits creep on, as the regularisation lets a grain below yield "
            "strain at about (tau / tau_y) / m_0 (Eq. 53: eta_max ~ tau_y m_0), which at m_0 = 1.2 s is above "
            "1e-3 of the collapse's speed: run on to 3 s, the runouts of a = 0.5 and 1 grow by "
            + growth + " and their tops sink further (the rows 'to 3 s'; the edge speed at the end is also "
            "sensitive to round-off: runs that differ by 1e-5 m early give 4.7e-4 and 2.3e-3 at a = 2, 0.37 "
            "and 3.1e-3 at a = 4, where a grain at the edge still moves); m_0 = 40 s stops the a = 0.5 "
            "deposit and keeps its top, but with the pair term of Eq. 27 the collapse starts later (onset, the "
            "front 0.05 L_0 out, " + onsets + "): below yield the pair term's bulk viscosity, about tau_y m_0, "
            "resists the expansion by which the released face sheds its pressure, so the column creeps before it "
            "fails (docs/COLLAPSES.md, 'The regularisation time m_0'). The rows 'DEVIATORIC_MU_I' run the five "
            "columns with granular_flow.DEVIATORIC_MU_I: the corrected stress without its bulk part (Eq. 4 with "
            "xi = 0, the fluid 'with no bulk viscosity' 004_ says Eq. 10 is) and m_0 = 40 s, whose columns start "
            "as soon as the defaults' and whose deposits stop, the a = 0.5 one with its top in place; they run out "
            "less at small a, where part of the defaults' agreement with 1.2 a is the creep; "
            "(3) the top of the a = 1 column sinks by a fifth, where "
            "Lube's stays put below a = 1.15. The explicit step of Eq. 39 gives the implicit kick's runout. "
            "The rows 'CONSISTENT_MU_I' run the same five columns with granular_flow.CONSISTENT_MU_I, the options "
            "that bring the CI-sized incline to its uniform flow (the corrected stress taken implicitly, the "
            "isotropic pressure, the law's kernel means of s p and of the strain rate's deviator; "
            "docs/INCLINE.md); they come to rest no better than the defaults. The collapses magnify round-off: "
            "a run whose frames fall at other times takes another sequence of time steps, and its runouts "
            "differ from the first's by a few per cent, which moves an exponent fitted to two columns (a = 4 "
            "and 6) by up to about 0.15. So the slope and the exponent are asserted on their means over "
            f"{len(STEP_SEQUENCES)} step sequences (frames every T / n, n = "
            + ", ".join(f"{n}" for n in STEP_SEQUENCES) + "; the rows 'mean over', with their spread), "
            "and the rows of one sequence (n = 20, the runs drawn) are shown beside them.")
    return "Planar collapses of sand columns, mu(I) (004_ Sec. 5.2, Lube et al. 2005)", runs[0]["cmd"], rows, image, note


def _variant_collapses(label, variant, aspects, L0, dp, ranks, ax, marker):
    """Rows of the planar collapses of ``aspects`` with the options ``variant`` (--set words of
    granular_flow), named ``label``: runout ratios, rest, onsets, the fitted slope and exponent; the
    runouts drawn into ``ax`` with ``marker``."""
    runs = [_collapse("lube_collapse_2d", a, L0, dp, ranks, radial=False, variant=variant) for a in aspects]
    a = np.array([r["a"] for r in runs])
    ratio = np.array([r["ratio"] for r in runs])
    ax.loglog(a, ratio, marker, mfc="none", label=label)
    rows = [(f"{label}: (L_inf - L_0) / L_0 at a = " + ", ".join(f"{x:g}" for x in a),
             " / ".join(f"{x:.2f}" for x in ratio),
             " / ".join(f"{1.2 * x if x <= 1 else 1.9 * x ** (2 / 3):.2f}" for x in a), "-", "-"),
            (f"{label}: edge speed / peak front speed at the end", " / ".join(f"{r['rest']:.1e}" for r in runs),
             f"<= {REST:g}", "-", f"{REST:g}", all(r["rest"] <= REST for r in runs)),
            (f"{label}: onset [s]", " / ".join(f"{r['onset']:.3f}" for r in runs), "-", "-", "-")]
    return rows + _planar_fits(a, ratio, f"{label}: ")[1] + _fit_spread(f"{label}: ", variant, runs, L0, dp, ranks)


SLOPE, EXPONENT = (1.2, 0.25), (0.67, 0.1)  # issue 14: the planar runouts' low-a slope and high-a exponent
# Frames per planar run: the time steps land on the frame times, so each number gives its own sequence of
# steps. The runs differ by round-off at first, which the collapses magnify to a few per cent of a runout
# (docs/COLLAPSES.md): the fits are asserted on their means over these sequences, the first validate's runs'.
STEP_SEQUENCES = (20, 17, 18, 19, 21, 22)


def _slope_and_exponent(a, ratio):
    """The slope through the origin of the runout ratios ``ratio`` of the columns a <= 1 and the
    exponent of those a >= 4."""
    low, high = a <= 1.0, a >= 4.0
    slope = float(np.sum(a[low] * ratio[low]) / np.sum(a[low] ** 2))
    return slope, float(np.polyfit(np.log(a[high]), np.log(ratio[high]), 1)[0])


def _planar_fits(a, ratio, label=""):
    """(exponent, rows) of planar runout ratios ``ratio`` at aspect ratios ``a``, one sequence of
    time steps: the slope of the columns a <= 1 through the origin and the exponent of those a >= 4,
    beside issue 14's values (asserted over the step sequences, ``_fit_spread``); ``label`` starts
    the rows' names."""
    slope, exponent = _slope_and_exponent(a, ratio)
    return exponent, [(f"{label}low-a slope (a = 0.5, 1; through the origin)", f"{slope:.2f}", f"{SLOPE[0]:g}",
                       f"{slope - SLOPE[0]:+.2f}", "-"),
                      (f"{label}high-a exponent (a = 4, 6)", f"{exponent:.2f}", f"{EXPONENT[0]:g}",
                       f"{exponent - EXPONENT[0]:+.2f}", "-")]


def _fit_spread(label, variant, runs, L0, dp, ranks):
    """Rows of the planar fits over STEP_SEQUENCES: ``runs`` (of the first) and the columns a = 0.5,
    1, 4 and 6 with ``variant`` for each other number of frames; the mean slope and exponent asserted
    with issue 14's tolerances, beside their spread (standard deviation, least and greatest)."""
    fits = []
    for n_frames in STEP_SEQUENCES:
        members = runs if n_frames == STEP_SEQUENCES[0] else [
            _collapse("lube_collapse_2d", a, L0, dp, ranks, radial=False, variant=variant, n_frames=n_frames)
            for a in (0.5, 1.0, 4.0, 6.0)]
        fits.append(_slope_and_exponent(np.array([r["a"] for r in members]), np.array([r["ratio"] for r in members])))
    rows = []
    sequences = ", ".join(f"{n}" for n in STEP_SEQUENCES)
    for name, values, (ref, tolerance) in (("low-a slope", [f[0] for f in fits], SLOPE),
                                           ("high-a exponent", [f[1] for f in fits], EXPONENT)):
        mean = float(np.mean(values))
        rows.append((f"{label}{name}, mean over {len(values)} step sequences (frames: {sequences}); sd, least, greatest",
                     f"{mean:.2f}; {np.std(values, ddof=1):.2f}, {min(values):.2f}, {max(values):.2f}", f"{ref:g}",
                     f"{mean - ref:+.2f}", f"{tolerance:g}", abs(mean - ref) <= tolerance))
    return rows


# H_0 / dp of each column, a whole number of layers: r_0 / dp = 29.1, 30, 30 and 16 (a = 2.75 at 30 would
# be 82 layers, about 12 times the 44 layers' run)
LAYERS_3D = {0.55: 16, 0.9: 27, 1.6: 48, 2.75: 44}
LUBE_UNDISTURBED_3D = 0.74  # Lube et al. 2004: below this a the column's top stays undisturbed
# the resolution study: a, and its columns' layers (16: LAYERS_3D's run; 24: 004_'s dp)
STUDY_3D = (0.55, (8, 11, 14, 16, 20, 24))


def lube_collapse_3d(ranks):
    """Axisymmetric mu(I) collapses in 3D (Lube et al. 2004) for 004_'s a = 0.55-2.75 (H_0 / dp of
    LAYERS_3D), and the planar collapse run by the 3D code as a slab beside the 2D run: runout against
    Eq. 58, rest, the deposits' tops. The resolution study is lube_collapse_3d_convergence."""
    r0 = references.LUBE_R0
    runs = [_collapse("lube_collapse_3d", a, r0, a * r0 / n, ranks, radial=True) for a, n in LAYERS_3D.items()]
    slab = _collapse("lube_collapse_3d", 0.5, r0, r0 / 20, ranks, radial=False, variant=("shape=slab",))
    planar = _collapse("lube_collapse_2d", 0.5, r0, r0 / 20, ranks, radial=False)
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    _front_panel(ax[0], runs, r0, "r")
    finest = ", ".join(f"{n / a:.3g}" for a, n in LAYERS_3D.items())  # r_0 / dp of each column
    aa = np.linspace(0.3, 3.2, 60)
    ax[1].plot(aa, references.axisymmetric_runout(aa), "k--", label="Lube et al. 2004 (Eq. 58)")
    ax[1].plot([r["a"] for r in runs], [r["ratio"] for r in runs], "o",
               label=f"mpisph, r_0 / dp = {finest}")
    ax[1].set_xlabel("a = H_0 / r_0")
    ax[1].set_ylabel("(r_inf - r_0) / r_0")
    ax[1].legend(fontsize=7)
    rows, short = [], []
    for (a, n), r in zip(LAYERS_3D.items(), runs):
        ref = float(references.axisymmetric_runout(a))
        error = r["ratio"] / ref - 1
        if abs(error) > 0.15:
            short.append(f"a = {a:g} ({100 * error:+.1f}%)")
        rows += [(f"a = {a:g}, r_0 / dp = {n / a:.3g}: (r_inf - r_0) / r_0", f"{r['ratio']:.3f}", f"{ref:.2f}",
                  f"{100 * error:+.1f}%", "15%", abs(error) <= 0.15),
                 _rest_row(r, "the connected deposit's edge, per sector")]
    centres = [_centre(r) for r in runs]
    undisturbed = [(r["a"], c) for r, c in zip(runs, centres) if r["a"] < LUBE_UNDISTURBED_3D]
    aspects = ", ".join(f"{r['a']:g}" for r in runs)
    rows += [(f"the deposit's top within 0.3 r_0 of the axis, over H_0, at a = {aspects}",
              " / ".join(f"{c:.2f}" for c in centres),
              f"1 below a = {LUBE_UNDISTURBED_3D:g}",
              "; ".join(f"{100 * (c - 1):+.0f}% at a = {a:g}" for a, c in undisturbed), "-"),
             _ill_posed_row(runs, f"a = {aspects}"),
             ("planar a = 0.5, L_0 / dp = 20: (L_inf - L_0) / L_0 of the 3D slab; of the 2D run",
              f"{slab['ratio']:.2f}; {planar['ratio']:.2f}", "0.60 (1.2 a)",
              f"{100 * (slab['ratio'] / planar['ratio'] - 1):+.0f}% (3D against 2D)", "-")]
    image = save(fig, "lube_collapse_3d.png")
    short_text = f"the runout of {', '.join(short)} misses Lube's law by more than 15 %; " if short else ""
    note = ("A cylinder of radius r_0 = 9.72 cm on a round no-slip floor, the cases' defaults (implicit "
            "viscous kick, secant pair viscosity, m_0 = 1.4 s), to 6 sqrt(H_0 / g); runout: the connected "
            "deposit's edge averaged over 16 azimuthal sectors (measure.radial_runout). Each column is a "
            "whole number of layers high (the lattice fills floor(H_0 / dp) layers; the case warns "
            f"otherwise): {', '.join(str(n) for n in LAYERS_3D.values())} layers, r_0 / dp = "
            f"{finest} for a = {', '.join(f'{a:g}' for a in LAYERS_3D)} (004_ Table 3 ran its 2D "
            "columns at r_0 / dp = 44, 32, 30 and 20; a = 2.75 at 55 layers, 004_'s spacing, would take about "
            "(55 / 44)^4 = 2.4 times as long as 44 layers: particles as the cube of the inverse spacing and "
            "steps as the inverse spacing). Each runout is one run at one spacing: the next section, "
            "lube_collapse_3d_convergence, refines a = 0.55. The slab row runs "
            "lube_collapse_2d's planar column with the 3D code "
            "(`--set shape=slab`, 8 particles across, periodic, m_0 = 1.4 s as the 3D default; the 2D run "
            f"has its own default, 1.2 s) beside the 2D run: the slab's farthest grain lies {_farthest(slab):.2f} "
            f"L_0 beyond the column, {measure.beyond_the_edge(slab['last'], slab['dp']).sum()} of its grains "
            f"beyond its connected deposit's edge (the 2D run's farthest: {_farthest(planar):.2f} L_0). Open gaps "
            f"of issue 14: {short_text}"
            "the columns dissipate their energy where the sand's friction law is ill-posed (the row of shares), "
            "so their runouts need not converge with the resolution (docs/COLLAPSES.md, 'Why the runouts do not "
            "converge'); the deposits' edges creep as in the planar "
            "runs (the rest rows); the deposits' centres sink (the row of tops), where Lube's top stays "
            f"undisturbed below a = {LUBE_UNDISTURBED_3D:g}.")
    return "Axisymmetric collapses of sand columns in 3D, mu(I) (004_ Sec. 5.2, Lube et al. 2004)", runs[0]["cmd"], \
        rows, image, note


def _study_3d(ranks, layers, variant, image_name, label):
    """The axisymmetric column a = STUDY_3D[0] at ``layers`` (H_0 / dp), the case's defaults and
    ``variant``: its runs, the runout by the connected deposit's edge and by its grains' front at
    each spacing, their changes at each refinement, the rows common to both studies and the plot."""
    r0 = references.LUBE_R0
    a_study = STUDY_3D[0]
    study = [_collapse("lube_collapse_3d", a_study, r0, a_study * r0 / n, ranks, radial=True, variant=variant)
             for n in layers]
    spacing = a_study / np.array(layers)  # dp / r_0
    ratios = np.array([r["ratio"] for r in study])
    fronts = np.array([(measure.front_position(r["last"], h * r0, radial=True) + 0.5 * h * r0 - r0) / r0
                       for r, h in zip(study, spacing)])  # the grains' front within the outermost bin, + dp/2
    changes, front_changes = ratios[1:] / ratios[:-1] - 1, fronts[1:] / fronts[:-1] - 1
    converged = abs(changes[-1]) <= 0.05
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.plot(spacing, ratios, "o-", label=f"mpisph, a = {a_study:g}{label}: connected deposit's edge (bins)")
    ax.plot(spacing, fronts, "s--", label="its grains' front + dp / 2")
    ax.axhline(float(references.axisymmetric_runout(a_study)), color="k", ls="--",
               label="Lube et al. 2004 (Eq. 58), for the sand")
    ax.set_xlabel("dp / r_0")
    ax.set_ylabel("(r_inf - r_0) / r_0")
    ax.set_xlim(left=0.0)
    ax.legend(fontsize=7)
    image = save(fig, image_name)
    at = ", ".join(f"{1 / h:.3g}" for h in spacing)
    last_step = f"({1 / spacing[-2]:.3g} -> {1 / spacing[-1]:.3g})"
    rows = [(f"a = {a_study:g}{label}: runout ratio at r_0 / dp = {at}", " / ".join(f"{x:.3f}" for x in ratios),
             "converged", f"{100 * changes[-1]:+.1f}% {last_step}", "5%", converged),
            (f"a = {a_study:g}{label}: the grains' front + dp / 2 (measure.front_position), over r_0, at r_0 / dp = "
             f"{at}", " / ".join(f"{x:.3f}" for x in fronts), "converged",
             f"{100 * front_changes[-1]:+.1f}% {last_step}", "-"),
            _rest_row(study[-1], f"the connected deposit's edge at r_0 / dp = {1 / spacing[-1]:.3g}"),
            _ill_posed_row(study, f"r_0 / dp = {at}")]
    text = (f"The column a = {a_study:g} of lube_collapse_3d at {', '.join(str(n) for n in layers)} layers. "
            f"Each refinement moves the runout by {', '.join(f'{100 * c:+.1f}%' for c in changes)} and the grains' "
            f"front by {', '.join(f'{100 * c:+.1f}%' for c in front_changes)}: the last refinement "
            f"{'meets' if converged else 'misses'} the row's 5 %. The edge of the connected deposit is a bin's outer "
            f"edge, so it jumps by up to dp / r_0 per sector ({spacing[0]:.2f} at r_0 / dp = {1 / spacing[0]:.3g}), "
            "where the grains' front within the outermost bin "
            f"{'grows at every refinement' if (front_changes > 0).all() else 'does not grow at every refinement'}.")
    return study, rows, image, text, converged


def lube_collapse_3d_convergence(ranks):
    """The resolution study of the axisymmetric column a = 0.55 (H_0 / dp of STUDY_3D, the case's
    defaults as in lube_collapse_3d): its runout by the connected deposit's edge and by its grains'
    front, converged when the last refinement moves the edge by at most 5 %."""
    study, rows, image, text, converged = _study_3d(ranks, STUDY_3D[1], (), "lube_collapse_3d_convergence.png", "")
    unconverged = (" So the runouts of lube_collapse_3d, each at a single spacing, are likely short of what "
                   "this model gives at finer spacings (the planar runs grow by 11-18 % from L_0 / dp = 20 to "
                   "40: docs/COLLAPSES.md). The columns dissipate their energy where the sand's friction law is "
                   "ill-posed (the last row), where results need not converge with the resolution (docs/COLLAPSES.md, "
                   "'Why the runouts do not converge'); the next section refines the same column with a law that is "
                   "well-posed where it flows.")
    return (f"Resolution study of the axisymmetric collapse a = {STUDY_3D[0]:g} in 3D, mu(I) (issue 14)",
            study[-1]["cmd"], rows, image, text + ("" if converged else unconverged))


# the same column with the friction law's I_0 lowered until the law is well-posed where about half of the
# column's dissipation happens (docs/COLLAPSES.md: in the plane its runout moved by 0.6 % at its last halving)
WELL_POSED_STUDY_3D = (("I_0=0.05",), (8, 11, 14, 16, 20))


def lube_collapse_3d_convergence_well_posed(ranks):
    """The column of lube_collapse_3d_convergence with I_0 = 0.05 in place of the sand's 2.65: a law that is
    well-posed (Barker et al. 2015) where about half of the column's dissipation happens, as the test of
    docs/COLLAPSES.md ran in the plane; converged, as issue 14 asks of the sand, when the last refinement
    moves the runout by at most 5 %."""
    variant, layers = WELL_POSED_STUDY_3D
    study, rows, image, text, converged = _study_3d(ranks, layers, variant,
                                                    "lube_collapse_3d_convergence_well_posed.png", ", I_0 = 0.05")
    window = study[0]["window"]
    note = (f"{text} Not the sand: its I_0 = 2.65 becomes 0.05, which moves the window where the law is well-posed "
            f"to {window[0]:.3g} < I < {window[1]:.3g}, among the inertial numbers of a collapse (the last row: the "
            "share of the dissipation outside it; docs/COLLAPSES.md, 'Why the runouts do not converge'), and every "
            "other setting is the sand's and the case's. Its runout is "
            "not Lube's (the friction at a given I is larger); the section asks only whether the 3D discretisation "
            "converges when the law it discretises is well-posed, beside the sand's study above.")
    return (f"Resolution study of the axisymmetric collapse a = {STUDY_3D[0]:g} in 3D with a well-posed mu(I) "
            "(I_0 = 0.05; issue 14)", study[-1]["cmd"], rows, image, note)


def soil_cylinder(ranks, dp=0.0005):
    """002_ Sec. 5 (Tables 1-2, dp = 0.5 mm, to 10 ms) with its classic scheme, the Riemann scheme
    beside it: the width against time (2 x the front: the case is symmetric about x = 0) and the
    deformed cylinder at 1-4 ms (002_ Figs. 9-10)."""
    D, impact = 0.05, 0.0015 / 5.0
    runs = {scheme: run(f"soil_cylinder_{scheme}", "soil_cylinder_impact", ["--set", f"dp={dp}", f"scheme={scheme}"],
                        ranks) for scheme in ("classic_granular", "riemann_granular")}
    fig = plt.figure(figsize=(11, 7))
    ax = fig.add_subplot(2, 1, 1)
    rows = []
    for scheme, (frames, diag, cmd) in runs.items():
        t, spread = diag["t"], 2.0 * diag["front"]
        ax.plot(1e3 * t, spread / D, label=scheme)
        last = spread[t >= t[-1] - 0.003]
        rose = spread.max() - spread[t <= impact].max()
        level = last.max() - last.min()
        ok = bool(rose > 0.1 * D and level < 0.01 * D)
        rows.append((f"{scheme}: spread at {1e3 * t[-1]:.0f} ms / D; its rise since the impact; its change over "
                     "the last 3 ms", f"{spread[-1] / D:.3f}; {rose / D:.3f} D; {level / D:.4f} D",
                     "rises, then levels off (Fig. 10)", "-", "rise > 0.1 D, last 3 ms < 0.01 D", ok))
        if scheme == "classic_granular":
            shown = cmd
            for k, when in enumerate((0.001, 0.002, 0.003, 0.004)):
                frame = min(frames, key=lambda f: abs(f["t"] - when))
                a = fig.add_subplot(2, 4, 5 + k)
                sc = a.scatter(1e3 * frame["x"][:, 0], 1e3 * frame["x"][:, 1], c=frame["p"] / 1e3, s=0.3,
                               cmap="viridis")
                a.set_aspect("equal")
                a.set_title(f"t = {1e3 * frame['t']:.0f} ms, p [kPa]", fontsize=9)
                fig.colorbar(sc, ax=a, shrink=0.6)
    ax.axvline(1e3 * impact, color="grey", lw=0.5)
    ax.set_xlabel("t [ms]")
    ax.set_ylabel("maximum spread / D")
    ax.legend()
    image = save(fig, "soil_cylinder_impact.png")
    note = ("002_ prints Fig. 10 as a plot only (SPH against Abaqus), so the shape is the reference: flat "
            "until the impact at 0.3 ms, a fast rise, then a plateau. The second run is the same command "
            "with `scheme=riemann_granular` (000_'s scheme, mirrored walls, no artificial viscosity).")
    return "Soil cylinder impact (002_ Sec. 5, dp = 0.5 mm)", shown, rows, image, note


VALIDATIONS = {"elliptical_drop": elliptical_drop, "elliptical_drop_remedies": elliptical_drop_remedies,
               "taylor_green": taylor_green, "dam_break_2d": dam_break,
               "lid_driven_cavity": cavity, "lid_driven_cavity_re1000": cavity_re1000,
               "rotating_square_patch": rotating_patch, "rotating_square_patch_remedies": rotating_patch_remedies,
               "oscillating_beam": oscillating_beam, "oscillating_beam_table": oscillating_beam_table,
               "oscillating_beam_sph_as": oscillating_beam_sph_as,
               "column_collapse_2d": column_collapse, "cohesive_failure_2d": cohesive_failure,
               "remedies_cuts": remedies_cuts, "remedies_cube_3d": remedies_cube_3d,
               "soil_cylinder_impact": soil_cylinder,
               "inclined_plane": inclined_plane, "inclined_plane_steady": inclined_plane_steady,
               "inclined_plane_deep": inclined_plane_deep,
               "lube_collapse_2d": lube_collapse_2d,
               "lube_collapse_3d": lube_collapse_3d,
               "lube_collapse_3d_convergence": lube_collapse_3d_convergence,
               "lube_collapse_3d_convergence_well_posed": lube_collapse_3d_convergence_well_posed}
MARK = "<!-- section: {} -->"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--only", nargs="*", choices=list(VALIDATIONS))
    ap.add_argument("--beam-h-over-dp", type=int, default=30,
                    help="resolution of the beam period runs (the paper's Table 1: 30)")
    ap.add_argument("--beam-v-f", type=float, nargs="*", default=list(references.BEAM_TABLE_1_V_F),
                    help="v_f of the oscillating_beam_table and _sph_as runs (the paper's Table 1: all four)")
    ap.add_argument("--reuse", action="store_true",
                    help="read a finished run of the same command, rank count and committed code instead of "
                         "running it again (runs/validation/NAME/validate_run.json), and continue an interrupted "
                         "one from its last frame")
    a = ap.parse_args()
    global REUSE
    REUSE = a.reuse
    IMG.mkdir(parents=True, exist_ok=True)
    page = DOCS / "VALIDATION.md"
    sections = existing_sections(page)
    misses = []
    for name in a.only or VALIDATIONS:
        beam_table = name in ("oscillating_beam_table", "oscillating_beam_sph_as")
        extra = {"h_over_dp": a.beam_h_over_dp, "v_fs": tuple(a.beam_v_f)} if beam_table else {}
        title, cmd, rows, image, note = VALIDATIONS[name](a.ranks, **extra)
        misses += [f"{title}: {r[0]} = {r[1]} (tolerance {r[4]})" for r in rows if len(r) > 5 and not r[5]]
        table = "\n".join(f"| {' | '.join(r[:5])} |" for r in rows)
        sections[name] = (f"{MARK.format(name)}\n## {title}\n\n`{cmd}`\n\n"
                          f"| quantity | mpisph | reference | error | tolerance |\n"
                          f"|---|---|---|---|---|\n{table}\n\n{note + chr(10) + chr(10) if note else ''}"
                          f"![{title}](img/{image})\n")
        print(f"{title}: done")
    head = ("# Validation\n\nWritten by `python scripts/validate.py` (each section's command gives its rank "
            "count; `--only NAME ...` re-runs some and keeps the other sections); the tests in "
            "`tests/test_validation.py`, `tests/test_validation_solids.py` and `tests/test_validation_beam.py` "
            "assert the same comparisons.\n\n")
    page.write_text(head + "\n".join(sections[k] for k in VALIDATIONS if k in sections))
    if misses:
        raise SystemExit("outside tolerance:\n  " + "\n  ".join(misses))


def existing_sections(page):
    """{name: text} of the sections of an existing page, by their markers."""
    if not page.exists():
        return {}
    out = {}
    for chunk in page.read_text().split("<!-- section: ")[1:]:
        name = chunk.split(" -->", 1)[0]
        out[name] = "<!-- section: " + chunk.rstrip("\n") + "\n"
    return out


if __name__ == "__main__":
    main()
