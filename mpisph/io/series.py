"""``frames.hdf.series``: the frames of a run with their simulated times, in the JSON file-series
format that ParaView reads (open it instead of the frames to see physical time on the time axis)."""

import json
import os

SERIES_NAME = "frames.hdf.series"


def _read(path):
    """The entries of the series file ``path``, none if it is missing or not a series."""
    try:
        with open(path) as f:
            return json.load(f)["files"]
    except (OSError, ValueError, KeyError):
        return []


def _write(path, files):
    """The series file ``path`` with ``files``, written under a temporary name and renamed, so a
    reader never sees half a file."""
    with open(path + ".part", "w") as f:
        json.dump({"file-series-version": "1.0", "files": files}, f, indent=1)
    os.replace(path + ".part", path)


def add_to_series(out_dir, frame, time):
    """Enter ``frame`` (a path in ``out_dir``) at ``time`` in the series file of ``out_dir``, replacing
    an entry of the same name (a restarted run rewriting a frame); entries sorted by time."""
    path = os.path.join(out_dir, SERIES_NAME)
    name = os.path.basename(frame)
    files = [e for e in _read(path) if e.get("name") != name] + [{"name": name, "time": float(time)}]
    files.sort(key=lambda e: (e["time"], e["name"]))
    _write(path, files)


def drop_from_series(out_dir, names):
    """Remove the entries of the frames ``names`` (base names) from the series file of ``out_dir``."""
    path = os.path.join(out_dir, SERIES_NAME)
    files = _read(path)
    kept = [e for e in files if e.get("name") not in set(names)]
    if len(kept) < len(files):
        _write(path, kept)
