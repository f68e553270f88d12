"""Open a frame of every case in the viewers users have and write docs/PARAVIEW.md.

    .venv/bin/python scripts/paraview_check.py [--ranks 2] [--pvpython pvpython] [--oldest-vtk PYTHON]

Each case of cases/ runs at a coarse spacing for two output intervals (``SMALL``) into
runs/paraview/CASE. Then Debian 12's ParaView (pvpython's OpenDataFile, which picks the reader by the
file's extension, as File > Open does) opens the last frame and the run's series file, and the oldest
VTK mpisph supports (.venv/oldest-vtk, VTK 9.2.6, installed by scripts/bootstrap.sh test) reads the
last frame (scripts/open_frames.py). A case passes when every reader finds every point and every
point array, with its components and values as stored, and the series carries the frames' simulated
times. The script exits non-zero, naming the cases, when one does not.
"""

import argparse
import json
import subprocess
import sys
from pathlib import Path

import h5py

from mpisph.case import case_names
from mpisph.io.frames import list_frames, read_frame
from mpisph.io.series import SERIES_NAME
from mpisph.launch import mpirun_mpisph

ROOT = Path(__file__).resolve().parent.parent
RUNS = ROOT / "runs" / "paraview"
PAGE = ROOT / "docs" / "PARAVIEW.md"
OPEN_FRAMES = ROOT / "scripts" / "open_frames.py"

# a coarse spacing and a short end time (two output intervals) for each case
SMALL = {
    "cohesive_failure_2d": ["dp=0.2", "0.02"],
    "column_collapse_2d": ["dp=0.01", "0.01"],
    "cube_failure_3d": ["dp=0.2", "0.02"],
    "dam_break_2d": ["dp=0.05", "0.02"],
    "dam_break_3d": ["dp=0.1", "0.02"],
    "elliptical_drop": ["dp=0.05", "0.0004"],
    "flume_3d": ["dp=0.1", "0.02"],
    "hydrostatic_tank": ["dp=0.05", "0.02"],
    "inclined_plane": ["H=0.02 dp=0.002 columns=16 m_0=0.2", "0.004"],
    "lid_driven_cavity": ["nx=20", "0.02"],
    "lube_collapse_2d": ["dp=0.01", "0.004"],
    "lube_collapse_3d": ["dp=0.0097", "0.004"],
    "oscillating_beam": ["H_over_dp=5", "0.004"],
    "rotating_square_patch": ["dp=0.05", "0.02"],
    "sliding_sheet": ["dp=0.005", "0.004"],
    "soil_cylinder_impact": ["dp=0.002", "0.0004"],
    "taylor_green": ["nx=20", "0.02"],
    "vertical_cut": ["dp=0.1", "0.02"],
}


def run(case, ranks):
    """Run ``case`` small into runs/paraview/CASE; its frames."""
    settings, t_end = SMALL[case]
    out = RUNS / case
    args = [case, "--set", *settings.split(), "--t-end", t_end, "--output-interval", str(float(t_end) / 2),
            "--out", out, "--quiet"]
    mpirun_mpisph(args, ranks=ranks, timeout=1800, accept=(0,))
    return list_frames(out)


def opened(command, paths, *flags):
    """What scripts/open_frames.py prints for ``paths`` under ``command``, a dict per path."""
    r = subprocess.run([*command, str(OPEN_FRAMES), *flags, *map(str, paths)], capture_output=True, text=True,
                       timeout=600)
    lines = [json.loads(line) for line in r.stdout.splitlines() if line.startswith("{")]
    if r.returncode != 0 or len(lines) != len(paths):
        return [{"path": str(p), "error": (r.stderr.strip().splitlines() or ["no output"])[-1]} for p in paths]
    return lines


def problems(seen, frame, times=None):
    """What ``seen`` (a reader's view of ``frame``) misses of what the frame stores; [] when nothing."""
    if "error" in seen:
        return [seen["error"]]
    with h5py.File(frame, "r") as f:
        data = f["VTKHDF/PointData"]
        stored = {k: (1 if d.ndim == 1 else d.shape[1], float(d[()].astype(float).sum())) for k, d in data.items()}
        n = len(f["VTKHDF/Points"])
    found = [] if seen["type"] == "vtkUnstructuredGrid" else [f"a {seen['type']}"]
    if seen["points"] != n or seen["cells"] != n:
        found.append(f"{seen['points']} points, {seen['cells']} cells of {n}")
    if seen["arrays"] != {k: c for k, (c, _) in stored.items()}:
        found.append(f"arrays {sorted(seen['arrays'])} against {sorted(stored)}")
    else:
        found += [f"{k}: sum {seen['sums'][k]} against {s}" for k, (_, s) in stored.items()
                  if abs(seen["sums"][k] - s) > 1e-12 * max(1.0, abs(s))]
    if times is not None and seen["times"] != times:
        found.append(f"times {seen['times']} against {times}")
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--pvpython", default="pvpython")
    parser.add_argument("--oldest-vtk", default=str(ROOT / ".venv" / "oldest-vtk" / "bin" / "python"))
    args = parser.parse_args()
    missing = sorted(set(case_names()) - set(SMALL))
    if missing:
        raise SystemExit(f"no small setting for {missing}: add them to SMALL")
    pv_version = subprocess.run([args.pvpython, "--version"], capture_output=True, text=True).stdout.strip()
    vtk_version = subprocess.run([args.oldest_vtk, "-c", "import vtk; print(vtk.vtkVersion.GetVTKVersion())"],
                                 capture_output=True, text=True).stdout.strip()
    rows, failed = [], []
    for case in case_names():
        frames = run(case, args.ranks)
        times = [read_frame(f)["t"] for f in frames]
        last, series = frames[-1], RUNS / case / SERIES_NAME
        frame_pv, series_pv = opened([args.pvpython, "--force-offscreen-rendering"], [last, series])
        (frame_vtk,) = opened([args.oldest_vtk], [last], "--vtk")
        issues = (problems(frame_pv, last) + problems(series_pv, last, times) + problems(frame_vtk, last))
        if issues:
            failed.append(case)
        print(f"{case}: {'; '.join(issues) or 'ok'}", flush=True)
        dim = read_frame(last)["dim"]
        rows.append(f"| `{case}` | {dim}D | {frame_pv.get('points', '-')} | {len(frame_pv.get('arrays', {}))} | "
                    f"{frame_pv.get('reader', '-')} | {', '.join(f'{t:g}' for t in series_pv.get('times', []))} | "
                    f"{frame_vtk.get('points', '-')} | "
                    f"{'; '.join(issues) or 'every point and array, values as stored'} |")
    settings = "; ".join(f"`{c}` {' '.join(s.split())}, to {t} s" for c, (s, t) in sorted(SMALL.items()))
    PAGE.write_text(
        "# Frames in ParaView\n\n"
        "Written by `python scripts/paraview_check.py` (each case on "
        f"{args.ranks} ranks; the readers through `scripts/open_frames.py`).\n\n"
        f"ParaView: `{pv_version}` (Debian 12's `paraview` and `python3-paraview`), its `OpenDataFile` on the "
        "last frame and on the run's `frames.hdf.series`; the oldest VTK: vtkHDFReader of VTK "
        f"{vtk_version} on the last frame. A reader passes when it finds every point and every point "
        "array with its components, and each array's sum equals the stored one; the series' times are "
        "the frames' simulated times.\n\n"
        "| case | dim | points (ParaView) | point arrays | ParaView reader | series times [s] | points (VTK "
        f"{vtk_version}) | result |\n|---|---|---|---|---|---|---|---|\n" + "\n".join(rows) +
        f"\n\nThe runs: {settings}, two output intervals each.\n")
    print(f"wrote {PAGE}")
    if failed:
        sys.exit(f"frames that a reader did not open whole: {', '.join(failed)}")


if __name__ == "__main__":
    main()
