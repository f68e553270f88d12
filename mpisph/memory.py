"""Memory of a rank (Linux): resident now, at its peak, and what the machine has available; the
checks that refuse a case too large for the machine before it is allocated or run."""

import os
import resource

from mpi4py import MPI

from .errors import InputError
from .sources import ArrayPoints


# A case built from arrays has them on every rank (positions, wall normals and depths: about 80
# bytes per particle in 3D); sources (sources.py) are built a slab per rank. The run's peak per
# owned particle was measured with per_rank_line: 1596 bytes in the 3D dam break at 140k particles
# on 2 ranks.
BUILD_BYTES_PER_PARTICLE = 100
RUN_BYTES_PER_PARTICLE = 1600


def too_many(count, what, available, node=""):
    """The one-line refusal of ``count`` particles (``what`` says where they come from, ``node`` what
    the ranks of this node would need together)."""
    return (f"{what} {count:.3g} particles: about {count * RUN_BYTES_PER_PARTICLE / 1e9:.3g} GB to run "
            f"({RUN_BYTES_PER_PARTICLE} bytes per particle){node}, where this machine has "
            f"{available / 1e9:.3g} GB available; choose a larger dp")


def check_fits(comm, sources):
    """Refuse a case whose particle ``sources`` (sources.py, walls included) the ranks on this node
    could not build and run within its available memory (collective), from the sources' estimates
    before any particle is generated."""
    node = comm.Split_type(MPI.COMM_TYPE_SHARED)
    ranks_here = node.size
    node.Free()
    count = sum(s.estimate for s in sources)
    held = sum(s.size for s in sources if isinstance(s, ArrayPoints))  # on every rank
    need = ranks_here * (held * BUILD_BYTES_PER_PARTICLE + count * RUN_BYTES_PER_PARTICLE / comm.size)
    available = available_bytes()
    if available is not None and need > available:
        raise InputError(too_many(count, "the case has about", available,
                                  f" and {need / 1e9:.3g} GB on this node's {ranks_here} "
                                  f"rank{'s' if ranks_here > 1 else ''}"))


def resident_bytes():
    """Resident set size of this process now."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def peak_bytes():
    """Largest resident set size of this process so far."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024


def available_bytes():
    """Memory the machine can give without swapping (MemAvailable), None where unknown."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return None


def per_rank_line(comm, baseline, start, n_owned):
    """The closing line on memory: the largest rank's resident size at start-up (``start``) and at
    its peak, and per owned particle above ``baseline`` (the interpreter and libraries, measured
    before the case was built)."""
    peak = peak_bytes()
    per = [(b - baseline) / max(n_owned, 1) for b in (start, peak)]
    start, peak, per_start, per_peak = (comm.allreduce(v, op=MPI.MAX) for v in (start, peak, *per))
    return (f"memory: largest rank {start / 1e9:.3g} GB at start-up, {peak / 1e9:.3g} GB at the peak; "
            f"above the interpreter and libraries {per_start:.0f} and {per_peak:.0f} bytes per owned particle")

