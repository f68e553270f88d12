"""The step loop, and nothing else.

Per advection step, on every rank:

    1. check       stop on a non-finite value or a particle outside the domain
    2. wrap        periodic positions back into the domain
    3. rebalance   new cuts when the imbalance of the work (neighbour pairs of the
                   last configuration) exceeds the threshold
    4. migrate     owned particles that crossed a cut move to their new rank; every
                   CELL_SORT_EVERY configurations the owned particles are
                   re-sorted by cell in memory (sums do not depend on it)
    5. halo        ghosts within the kernel support of each cut (periodic images too)
    6. neighbours  cell-linked lists over owned + ghosts, in canonical order
    7. surface     free-surface classes from the position divergence (solids, UTVF)
    8. configure   the scheme's per-configuration work (density reinit, viscosity,
                   gravity, kernel-gradient correction)
    9. stabilise   the case's particle-regularising shift (transport velocity), which
                   acts as the shift after the previous Verlet update (000_ Eq. 42)
   10. acoustic    steps of the scheme until the advection step is covered
                   (dt = allreduce(min) of the criteria, clipped to output times)

Every output interval one frame holds the whole global state.
"""

import time as wallclock

import numpy as np
from mpi4py import MPI

from . import integrators, surface, tensors
from .blowup import NON_FINITE, first_bad_particle
from .errors import BlowUp
from .io.frames import frame_path, write_frame
from .kernels import KERNELS, SUPPORT_FACTOR, normalisation
from .neighbours import cell_order, neighbour_lists
from .observables import global_observables
from .parallel.decomposition import SlabDecomposition, migrate, particle_work
from .parallel.halo import Halo
from .physics.solid import correction_matrix
from .stabilisers.transport_velocity import STABILISERS
from .timing import PhaseTimer
from .workspace import Workspace

CELL_SORT_EVERY = 25  # configurations between re-sorting the owned particles by cell (memory locality)


class Simulation:
    """One run of a case on the ranks of ``comm``."""

    def __init__(self, comm, case, params, particles, scheme, *, t=0.0, step=0,
                 out_dir, diagnostics, progress):
        self.comm = comm
        self.case = case
        self.params = params
        self.particles = particles
        self.scheme = scheme
        self.t = t
        self.step = step
        self.out_dir = out_dir
        self.diagnostics = diagnostics
        self.progress = progress
        self.h = params["h_factor"] * case.dp
        self.support = SUPPORT_FACTOR * self.h
        kernel = KERNELS[params["kernel"]]
        self.kernel_args = (self.h, normalisation(kernel, self.h, case.dim), kernel)
        lo, hi = case.domain
        self.decomp = SlabDecomposition(comm, case.slab_axis, lo[case.slab_axis],
                                        hi[case.slab_axis], self.support)
        self.stabiliser = STABILISERS[case.stabiliser]()
        self.halo = Halo(self.decomp, self.support, lo, hi, case.periodic)
        self.frame_index = int(np.floor(t / params["output_interval"] + 1e-9))
        self.advection_steps = 0
        self.dt = 0.0
        self.timer = PhaseTimer()
        self.workspace = Workspace()
        self.start = self.nbr = self.xc = self._B = None

    # -- one advection step -------------------------------------------------

    def _configure(self):
        self._configure_geometry()
        with self.timer("physics"):
            self.scheme.configure(self)
            self.stabiliser.apply(self)

    def _configure_geometry(self):
        """Migration, halo, neighbour lists and free-surface classes of the current positions."""
        pa = self.particles
        self._check()
        with self.timer("exchange"):
            self._wrap_periodic()
            work = particle_work(pa, self.start)  # the rows of the last configuration, before they move
            self.start = self.nbr = self._B = None  # the lists are freed before migration and search
            first = self.advection_steps == 0  # cut once on counts, once on the pairs of the first lists
            if first or self.decomp.imbalance(work.sum()) > self.params["rebalance_threshold"]:
                self.decomp.balance(pa.owned("x")[:, self.decomp.axis], work)
            migrate(pa, self.decomp)
            if self.advection_steps % CELL_SORT_EVERY == 0:
                pa.keep_owned(cell_order(pa.x, pa.n_owned, self.support, self.case.domain[0]), 0)
            self.halo.build(pa)
        with self.timer("neighbours"):
            self.xc = self.workspace.get("configuration", pa.n, (pa.dim,))  # rewritten in place
            self.xc[:] = pa.x
            self.start, self.nbr = neighbour_lists(self.xc, pa.gid, pa.kind, pa.n_owned, self.support,
                                                   self.case.domain[0], self.workspace)
        if "surface" in pa.arrays:
            with self.timer("physics"):
                surface.classify(self)

    def correction_matrices(self):
        """B of 000_ Eq. 24 for the owned particles on this configuration, computed once when first
        asked, into the field ``B`` when the particles have one."""
        if self._B is None:
            pa = self.particles
            n = pa.n_owned
            self._B = pa.B[:n] if "B" in pa.arrays else self.workspace.get("correction_matrix", n, (tensors.size(pa.dim),))
            correction_matrix(n, self.start, self.nbr, self.xc, pa.mass, pa.rho, pa.kind, *self.kernel_args, self._B)
        return self._B

    def _check(self):
        """Stop with step, time, rank and particle id on NaN or a lost particle."""
        pa = self.particles
        lo, hi = self.case.domain
        k, problem = first_bad_particle(pa.n_owned, pa.kind, pa.x, pa.v, pa.rho, np.asarray(lo, float),
                                        np.asarray(hi, float), np.array(self.case.periodic, dtype=np.bool_))
        local = None
        if k >= 0:
            what = "a non-finite value" if problem == NON_FINITE else "a particle left the domain"
            local = (int(pa.gid[k]), what, np.round(pa.x[k], 6).tolist())
        if not self.comm.allreduce(local is not None, op=MPI.LOR):
            return
        for rank, rep in enumerate(self.comm.allgather(local)):
            if rep is not None:
                gid, what, pos = rep
                self.frame_index += 1  # after the last regular frame, not over it
                self.write_frame()
                raise BlowUp(f"blow-up at step {self.step}, t = {self.t:.6g} s: {what} "
                             f"(rank {rank}, particle {gid}, at {pos}); last frame written",
                             step=self.step, time=self.t, rank=rank, gid=gid)

    def _wrap_periodic(self):
        lo, hi = self.case.domain
        x = self.particles.owned("x")
        for a, periodic in enumerate(self.case.periodic):
            if periodic:
                x[:, a] = lo[a] + np.mod(x[:, a] - lo[a], hi[a] - lo[a])

    def _max_speed(self):
        pa = self.particles
        return self.comm.allreduce(integrators.max_speed(pa.n_owned, pa.kind, pa.v), op=MPI.MAX)

    def _advection_dt(self, vmax, c0, nu):
        if self.params["time_stepping"] == "single":
            return integrators.acoustic_dt(self.h, vmax, c0, integrators.CFL_SINGLE)
        return integrators.advection_dt(self.h, vmax, nu, self.case.u_ref)

    # -- the run ------------------------------------------------------------

    def run(self):
        t_end = self.params["t_end"]
        interval = self.params["output_interval"]
        c0, nu = self.scheme.speeds()
        wall0, t0, step0 = wallclock.perf_counter(), self.t, self.step
        if self.step == 0:
            self._configure_geometry()  # the surface classes of the first frame
            self.write_frame()
            self.diagnostics.record(global_observables(self))
        while self.t < t_end:
            self._configure()
            vmax = self._max_speed()
            t_next_frame = min((self.frame_index + 1) * interval, t_end)
            t_stop = min(self.t + self._advection_dt(vmax, c0, nu), t_next_frame)
            while True:
                dt = integrators.acoustic_dt(self.h, vmax, c0, self.scheme.acoustic_cfl)
                if self.params["time_stepping"] == "single" or self.t + dt >= t_stop:
                    dt, last = t_stop - self.t, True
                else:
                    last = False
                with self.timer("physics"):
                    self.scheme.acoustic_step(self, dt)
                self.step += 1
                self.t = t_stop if last else self.t + dt
                self.dt = dt
                if last:
                    break
                vmax = self._max_speed()
            self.advection_steps += 1
            frame_due = self.t >= t_next_frame
            if frame_due or self.advection_steps % self.params["diagnostics_every"] == 0:
                self.diagnostics.record(global_observables(self))
            if frame_due:
                self.frame_index = int(np.floor(self.t / interval + 1e-9))
                if self.t >= t_end:
                    self.frame_index = max(self.frame_index, int(np.ceil(t_end / interval - 1e-9)))
                self.write_frame()
            self.progress(self, wallclock.perf_counter() - wall0, t0, step0, frame_due)
        return self

    def write_frame(self):
        pa = self.particles
        fields = pa.owned_fields()
        if hasattr(self.scheme, "derived_fields"):
            fields.update(self.scheme.derived_fields(pa, pa.n_owned))
        with self.timer("io"):
            write_frame(frame_path(self.out_dir, self.frame_index), self.comm, fields,
                        time=self.t, step=self.step, dim=self.case.dim, params=self.params)
