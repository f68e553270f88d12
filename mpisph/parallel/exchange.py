"""Row exchange between ranks: the one MPI pattern migration and halo share."""

import numpy as np
from mpi4py import MPI


def exchange_counts(comm, send_counts):
    """Tell every rank how many rows it receives from each rank."""
    send_counts = np.ascontiguousarray(send_counts, dtype=np.int64)
    recv_counts = np.empty_like(send_counts)
    comm.Alltoall(send_counts, recv_counts)
    return recv_counts


def alltoallv_rows(comm, rows, send_counts, recv_counts):
    """Send consecutive blocks of float64 ``rows`` (grouped by destination rank).

    ``rows`` has shape (sum(send_counts), width); returns the received rows
    ordered by source rank.
    """
    width = rows.shape[1]
    recv = np.empty((int(recv_counts.sum()), width))
    if comm.size == 1:
        recv[:] = rows
        return recv
    sc = send_counts * width
    rc = recv_counts * width
    sd = np.concatenate(([0], np.cumsum(sc)[:-1]))
    rd = np.concatenate(([0], np.cumsum(rc)[:-1]))
    comm.Alltoallv([np.ascontiguousarray(rows), (sc, sd), MPI.DOUBLE],
                   [recv, (rc, rd), MPI.DOUBLE])
    return recv
