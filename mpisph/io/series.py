"""``frames.vtkhdf.series``: the frames of a run with their simulated times, in the JSON file-series
format that ParaView reads (open it instead of the frames to see physical time on the time axis)."""

import json
import os

SERIES_NAME = "frames.vtkhdf.series"


def add_to_series(out_dir, frame, time):
    """Enter ``frame`` (a path in ``out_dir``) at ``time`` in the series file of ``out_dir``, replacing
    an entry of the same name (a restarted run rewriting a frame); entries sorted by time. Written
    under a temporary name and renamed, so a reader never sees half a file."""
    path = os.path.join(out_dir, SERIES_NAME)
    try:
        with open(path) as f:
            files = json.load(f)["files"]
    except (OSError, ValueError, KeyError):
        files = []
    name = os.path.basename(frame)
    files = [e for e in files if e.get("name") != name] + [{"name": name, "time": float(time)}]
    files.sort(key=lambda e: (e["time"], e["name"]))
    with open(path + ".part", "w") as f:
        json.dump({"file-series-version": "1.0", "files": files}, f, indent=1)
    os.replace(path + ".part", path)
