"""Global diagnostics in ``<out_dir>/diagnostics.csv``, a row every ``diagnostics_every``
advection steps and at each frame (and the gauges' CSV files, gauges.py, written the same
way).

Only rank 0 touches the file; the values passed to :meth:`Diagnostics.record`
are already global.  Floats are written with 17 significant digits, so they
read back bitwise.
"""

import csv
import os

import numpy as np

from mpisph.errors import InputError

FILENAME = "diagnostics.csv"


def _format(value):
    """Exact text of a number: integers as such, floats with 17 digits."""
    if isinstance(value, (int, np.integer)):
        return str(int(value))
    return format(float(value), ".17g")


class Diagnostics:
    """CSV writer for one run, open on rank 0 only (``filename`` in ``out_dir``).

    ``columns`` are the column names.  A new file (header only) is created
    unless ``append`` is true; then the existing file is continued after
    dropping its rows with ``t`` > ``restart_time`` (a restarted run repeats
    those steps), so the CSV stays continuous.  An existing file written by
    an earlier version with fewer columns is widened to ``columns``, its rows
    holding ``nan`` where that version recorded nothing; one with a column
    that ``columns`` lacks is refused.
    """

    def __init__(self, out_dir, comm, columns, append=False, *,
                 restart_time=None, filename=FILENAME):
        self.path = os.path.join(out_dir, filename)
        self.columns = list(columns)
        self._file = None
        err = None
        if comm.rank == 0:
            try:
                self._open(append, restart_time)
            except (InputError, OSError) as e:
                err = str(e)
        err = comm.bcast(err, root=0)
        if err:
            raise InputError(err)

    def _open(self, append, restart_time):
        """Create or continue the file (rank 0)."""
        header = ",".join(self.columns)
        if append and os.path.exists(self.path):
            with open(self.path, newline="") as f:
                rows = list(csv.reader(f))
            rows = _widened(rows, self.columns, self.path)
            if restart_time is not None:
                t = self.columns.index("t")
                rows = [rows[0]] + [r for r in rows[1:]
                                    if float(r[t]) <= restart_time]
            tmp = self.path + ".tmp"
            with open(tmp, "w", newline="") as f:
                f.writelines(",".join(r) + "\n" for r in rows)
            os.replace(tmp, self.path)
            self._file = open(self.path, "a")
        else:
            self._file = open(self.path, "w")
            self._file.write(header + "\n")
            self._file.flush()

    def record(self, values):
        """Append one row (rank 0); ``values`` maps every column to a number."""
        if self._file is not None:
            self._file.write(",".join(_format(values[c])
                                      for c in self.columns) + "\n")
            self._file.flush()

    def close(self):
        """Close the file (no-op on ranks other than 0 or when closed)."""
        if self._file is not None:
            self._file.close()
            self._file = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def _widened(rows, columns, path):
    """The rows of an existing file (header first) in the order of ``columns``, with ``nan``
    in the columns its header lacks; an InputError when it has one that ``columns`` lacks."""
    if not rows:
        raise InputError(f"{path}: no header; this run writes {','.join(columns)}")
    if rows[0] == columns:
        return rows
    extra = [c for c in rows[0] if c not in columns]
    if extra:
        raise InputError(f"{path}: columns differ from this run: it has {','.join(extra)}, "
                         f"which this run does not write ({','.join(columns)})")
    at = {c: i for i, c in enumerate(rows[0])}
    return [columns] + [[r[at[c]] if c in at else "nan" for c in columns] for r in rows[1:]]


def read_diagnostics(path):
    """Read a diagnostics CSV: column name -> float64 array."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    data = np.array(rows[1:], dtype=np.float64).reshape(-1, len(rows[0]))
    return {name: data[:, i].copy() for i, name in enumerate(rows[0])}
