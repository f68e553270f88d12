"""The runs behind the validation: each case run once under runs/validation/NAME by mpirun, stamped with
its command, rank count and the committed solver code, so that `--reuse` reads a finished run again
and continues an interrupted one."""

import json
import subprocess
from pathlib import Path

from mpisph.io.diagnostics import read_diagnostics
from mpisph.io.frames import list_frames, read_frame
from mpisph.launch import command_line, mpirun_mpisph, stopped_by_signal


ROOT = Path(__file__).resolve().parents[2]
RUNS = ROOT / "runs" / "validation"

REUSE = False  # set by validate.py's --reuse
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


def stamp_of(case, args, ranks):
    """What a run's bits depend on: its case, arguments, rank count and committed code."""
    return {"case": case, "args": [str(a) for a in args], "ranks": ranks, "code": code_version()}


def has_stamp(path, stamp):
    """Whether the stamp file ``path`` records ``stamp``; never for uncommitted code (code None)."""
    return (stamp["code"] is not None and path.exists()
            and {k: json.loads(path.read_text()).get(k) for k in stamp} == stamp)


def run_directory(name):
    """Where the run ``name`` writes its frames: runs/validation/NAME."""
    return RUNS / name


def run(name, case, args, ranks, blow_up_ok=False):
    """Frames, diagnostics and the command of one run; with ``blow_up_ok`` a run that stops on a
    blow-up (exit 3) returns what it wrote, its last frame the one at the blow-up. With --reuse, a
    finished run of the same command, rank count and committed code (its stamp) is read, not re-run,
    and one that was interrupted (its partial stamp, written at its start) continues from its last
    frame (a restart gives the bits of an uninterrupted run: tests/test_stop_on_signal.py)."""
    out = run_directory(name)
    stamp = stamp_of(case, args, ranks)
    done, started = out / STAMP, out / PARTIAL_STAMP
    if REUSE and has_stamp(done, stamp):
        returncode = json.loads(done.read_text())["returncode"]
        print(f"  reusing {out} (same command and code)")
    else:
        restart = []
        if REUSE and has_stamp(started, stamp) and list_frames(out):
            restart = ["--restart", list_frames(out)[-1]]
            print(f"  continuing {out} from {restart[1]} (same command and code)")
        done.unlink(missing_ok=True)
        if stamp["code"] is not None:
            out.mkdir(parents=True, exist_ok=True)
            started.write_text(json.dumps(stamp))
        r = mpirun_mpisph([case, *args, *restart, "--out", out, "--quiet"], ranks=ranks,
                          accept=(0, 3) if blow_up_ok else (0,))
        returncode, stopped = r.returncode, stopped_by_signal(r.stdout)
        if stopped:  # not finished: its partial stamp stays, so that --reuse continues it
            raise SystemExit(f"{case} {' '.join(args)}: {stopped}; run validate.py again with --reuse to go on")
        if stamp["code"] is not None:
            done.write_text(json.dumps(dict(stamp, returncode=returncode)))
            started.unlink()
    if returncode != 0 and not blow_up_ok:  # a reused run that blew up, read where that is not allowed
        raise SystemExit(f"{case} {' '.join(args)}: blew up (exit 3); its frames are in {out}")
    shown = command_line(["-m", "mpisph", case, *args], ranks)
    frames = [read_frame(f) for f in list_frames(out)]
    return frames, read_diagnostics(out / "diagnostics.csv"), shown
