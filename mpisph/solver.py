"""The step loop: the order of an advection step, frames and diagnostics.

A run from t = 0 first takes steps 1-7 below on the initial particles, refusing
a body that starts behind a wall's surface or on another particle (overlap.py),
then the scheme's ``start`` (the state of the initial particles) and frame 0. Then per
advection step (one neighbour configuration), on every rank:

    1. check       stop on a non-finite value, a non-positive density or a particle
                   outside the domain (also when a time-step limit comes out <= 0)
    2. wrap        periodic positions back into the domain
    3. rebalance   new cuts when the imbalance of the work (neighbour pairs of the
                   last configuration) exceeds the threshold
    4. migrate     owned particles that crossed a cut move to their new rank; every
                   CELL_SORT_EVERY configurations the owned particles are
                   re-sorted by cell in memory (sums do not depend on it)
    5. halo        ghosts within the kernel support of each cut (periodic images too)
    6. neighbours  cell-linked lists over owned + ghosts, in canonical order; stop
                   on two particles at the same place (every pair sum divides by
                   their distance); a StepContext (context.py) of this
                   configuration; the kernel bound to the particles (the adaptive
                   kernel's knots)
    7. prepare     each stabiliser's work before any pair sum (the adaptive
                   kernel's knots); the free-surface classes from the position
                   divergence, when the scheme or a stabiliser needs them
    8. configure   the scheme's per-configuration work (density reinitialisation,
                   kernel-gradient correction)
    9. frozen      the force terms fixed over the configuration (gravity, viscosity;
                   forces.py)
   10. limits      each rank's time step and advection step (integrators/time_step.py),
                   the minimum over ranks
   11. stabilise   the case's stabilisers in order (the transport-velocity shift
                   acts as the shift after the previous Verlet update, 000_ Eq. 42)
   12. steps       time steps of the integrator (integrators/) until the advection
                   step is covered, the first with the limits of 10, each later one
                   with its own; clipped to output times
   13. stop        a SIGTERM or SIGUSR1 received on any rank (parallel/stop.py) ends
                   the run after this step with a frame to restart from

Every output interval one frame holds the whole global state. The physics is
in the parts of the run (parts.py): this module knows none of it.
"""

import time as wallclock

import numpy as np
from mpi4py import MPI

from . import surface
from .blowup import COINCIDENT, PROBLEMS, first_bad_particle, first_coincident_pair
from .context import StepContext
from .errors import BlowUp, InputError, NoConvergence, Stopped
from .io.frames import frame_path, regular_frame_number, write_frame
from .io.series import add_to_series
from .neighbours import cell_order, neighbour_lists
from .observables import global_observables
from .overlap import check_start, outside_domain_warnings, thin_wall_warnings
from .parallel.decomposition import SlabDecomposition, migrate, particle_work
from .parallel.halo import Halo
from .timing import PhaseTimer
from .workspace import Workspace

CELL_SORT_EVERY = 25  # configurations between re-sorting the owned particles by cell (memory locality)


class Simulation:
    """One run of a case on the ranks of ``comm``."""

    def __init__(self, comm, case, params, particles, parts, *, t=0.0, step=0, configurations=0,
                 out_dir, diagnostics, progress, stop=None):
        self.comm = comm
        self.case = case
        self.params = params
        self.particles = particles
        self.parts = parts
        self.t = t
        self.step = step
        self.out_dir = out_dir
        self.diagnostics = diagnostics
        self.progress = progress
        self.stop = stop  # a parallel.stop.StopOnSignal, or None: run to the end
        self.gauges = None  # a gauges.GaugeRecorder, or None: the case has no gauges
        self.support = parts.kernel.support
        lo, hi = case.domain
        self.decomp = SlabDecomposition(comm, case.slab_axis, lo[case.slab_axis],
                                        hi[case.slab_axis], self.support)
        self.halo = Halo(self.decomp, self.support, lo, hi, case.periodic)
        self.frame_index = regular_frame_number(t, params["output_interval"])
        self.advection_steps = 0  # of this process: the first cut, the cell sort
        self.configurations = configurations  # advection steps since t = 0: diagnostics.csv's rows
        self.rebalances = 0  # new cuts after the first ones (diagnostics.csv)
        self.dt = 0.0  # the last step taken (cut to an output time at a frame)
        self.time_step = 0.0  # the last time-step limit, before such a cut (the progress lines')
        self.timer = PhaseTimer()
        self.workspace = Workspace()
        self.ctx = None

    # -- one advection step -------------------------------------------------

    def configure_start(self):
        """Steps 1-7 on the initial particles, which refuse (InputError, overlap.py) a body that
        starts behind a wall's surface or on another particle, and warn of walls too thin for the
        kernel or outside the domain; the surface classes of the first frame. ``run`` takes it unless it was taken before,
        as __main__ does before it writes anything."""
        self._configure_geometry()
        case, pa = self.case, self.particles
        for line in (*outside_domain_warnings(self.comm, pa, case.domain, case.periodic, case.dp, case.id_ranges),
                     *thin_wall_warnings(self.comm, pa, case.dp, self.params["h_factor"], self.support,
                                         case.domain[0], case.id_ranges)):
            self.progress.warn(line)

    def _configure(self):
        """Steps 1-11 of the module docstring; the limits [time step, advection step] of 10."""
        ctx = self._configure_geometry()
        with self.timer("physics"):
            self.parts.scheme.configure(ctx)
            self.parts.forces.configure(ctx)
            limits = self._time_steps()
            ctx.advection_step = limits[1]
            for stabiliser in self.parts.stabilisers:
                stabiliser.apply(ctx)
        return limits

    def _configure_geometry(self):
        """Migration, halo, neighbour lists, the stabilisers' preparation and the free-surface classes of
        the current positions."""
        pa = self.particles
        self._check()
        with self.timer("exchange"):
            self._wrap_periodic()
            work = particle_work(pa, self.ctx.start if self.ctx else None)  # the last configuration's rows
            self.ctx = None  # the lists are freed before migration and search
            first = self.advection_steps == 0  # cut once on counts, once on the pairs of the first lists
            if first or self.decomp.imbalance(work.sum()) > self.params["rebalance_threshold"]:
                self.decomp.balance(pa.owned("x")[:, self.decomp.axis], work)
                self.rebalances += not first
            migrate(pa, self.decomp)
            if self.advection_steps % CELL_SORT_EVERY == 0:
                pa.keep_owned(cell_order(pa.x, pa.n_owned, self.support, self.case.domain[0]), 0)
            self.halo.build(pa)
        with self.timer("neighbours"):
            xc = self.workspace.get("configuration", pa.n, (pa.dim,))  # rewritten in place
            xc[:] = pa.x
            start, nbr = neighbour_lists(xc, pa.gid, pa.kind, pa.n_owned, self.support, self.case.domain[0],
                                         self.workspace)
            i, j = first_coincident_pair(pa.n_owned, start, nbr, xc)
        if self.step == 0 and self.advection_steps == 0:  # the particles as the case placed them
            check_start(self.comm, pa, start, nbr, xc, self.case.dp, (i, j), self.case.name_of)
        self._stop_if_bad(None if i < 0 else (f"particles {int(pa.gid[i])} and {int(pa.gid[j])}",
                                              PROBLEMS[COINCIDENT], np.round(pa.x[i], 6).tolist()))
        self.parts.kernel.bind(pa)
        self.ctx = StepContext(pa, start, nbr, xc, self.parts.kernel, self.halo, self.workspace)
        with self.timer("physics"):
            for stabiliser in self.parts.stabilisers:
                stabiliser.prepare(self.ctx)
            if self.parts.needs_surface:
                surface.classify(self.ctx)
        return self.ctx

    def _check(self):
        """Stop with step, time, rank and particle id on NaN, a non-positive density or a lost particle."""
        pa = self.particles
        lo, hi = self.case.domain
        k, problem = first_bad_particle(pa.n_owned, pa.kind, pa.x, pa.v, pa.rho, np.asarray(lo, float),
                                        np.asarray(hi, float), np.array(self.case.periodic, dtype=np.bool_))
        self._stop_if_bad(None if k < 0 else (f"particle {int(pa.gid[k])}", PROBLEMS[problem],
                                              np.round(pa.x[k], 6).tolist()))

    def _stop_if_bad(self, local):
        """Collective: if any rank found a problem, ``local`` = (which particles, what, position), write
        a frame and raise BlowUp with the first such rank's report."""
        if not self.comm.allreduce(local is not None, op=MPI.LOR):
            return
        for rank, rep in enumerate(self.comm.allgather(local)):
            if rep is not None:
                which, what, pos = rep
                if self.step == 0 and self.advection_steps == 0:
                    raise InputError(f"the case's initial particles: {what} (rank {rank}, {which}, at {pos})")
                self._write_unscheduled_frame()
                raise BlowUp(f"blow-up at step {self.step}, t = {self.t:.6g} s: {what} "
                             f"(rank {rank}, {which}, at {pos}); last frame written")

    def _wrap_periodic(self):
        lo, hi = self.case.domain
        x = self.particles.owned("x")
        for a, periodic in enumerate(self.case.periodic):
            if periodic:
                x[:, a] = lo[a] + np.mod(x[:, a] - lo[a], hi[a] - lo[a])

    def _time_steps(self):
        """[time step, advection step]: the minimum over ranks of each rank's limits."""
        local = self.parts.criteria.local_limits(self.ctx, self.parts.scheme)
        limits = np.empty_like(local)
        self.comm.Allreduce(local, limits, op=MPI.MIN)
        return limits

    # -- the run ------------------------------------------------------------

    def run(self):
        t_end = self.params["t_end"]
        interval = self.params["output_interval"]
        single = self.parts.criteria.single
        wall0, t0, step0 = wallclock.perf_counter(), self.t, self.step
        if self.step == 0:
            if self.ctx is None:
                self.configure_start()
            with self.timer("physics"):
                self.parts.scheme.start(self.ctx)
            self.write_frame()
            self._record()
        first = True
        while self.t < t_end:
            dt, dt_advection = self._configure()
            self.time_step = dt
            if first and interval < dt:
                self.progress.warn(f"output_interval = {interval:g} s is shorter than the time step, {dt:.3g} s: "
                                   "each step ends at a frame and is cut to the interval")
            first = False
            t_next_frame = min((self.frame_index + 1) * interval, t_end)
            t_stop = min(self.t + dt_advection, t_next_frame)
            while True:
                if single or self.t + dt >= t_stop:
                    dt, last = t_stop - self.t, True
                else:
                    last = False
                with self.timer("physics"):
                    try:
                        self.parts.integrator.step(self.ctx, dt)
                    except NoConvergence as e:
                        self._write_unscheduled_frame()
                        raise BlowUp(f"blow-up at step {self.step}, t = {self.t:.6g} s: {e}; "
                                     "last frame written") from None
                self.step += 1
                self.t = t_stop if last else self.t + dt
                self.dt = dt
                if last:
                    break
                dt = self.time_step = self._time_steps()[0]
                if not dt > 0.0:  # a limit proportional to the density (the viscous one) went <= 0
                    self._check()
            self.advection_steps += 1
            self.configurations += 1
            frame_due = self.t >= t_next_frame
            if frame_due or self.configurations % self.params["diagnostics_every"] == 0:
                self._record()
            if frame_due:
                self.frame_index = regular_frame_number(self.t, interval)
                if self.t >= t_end:
                    self.frame_index = max(self.frame_index, int(np.ceil(t_end / interval - 1e-9)))
                self.write_frame()
            self.progress(self, wallclock.perf_counter() - wall0, t0, step0, frame_due)
            signal_name = self.stop.requested(self.comm) if self.stop is not None else None
            if signal_name:
                if not frame_due:
                    self._write_unscheduled_frame()
                raise Stopped(signal_name, step=self.step, time=self.t,
                              frame=frame_path(self.out_dir, self.frame_index))
        return self

    def _record(self):
        """A row of diagnostics.csv and of every gauge's file."""
        samples = self.gauges.sample(self) if self.gauges is not None else {}
        self.diagnostics.record(global_observables(self, samples))
        if self.gauges is not None:
            self.gauges.write(self.t, samples)

    def _write_unscheduled_frame(self):
        """A frame of the current state between two output times, numbered after the last regular
        frame (not over it); the regular frame of that number replaces it when a restarted run
        reaches its time."""
        self.frame_index += 1
        self.write_frame()

    def write_frame(self):
        pa = self.particles
        fields = pa.owned_fields()
        fields.update(self.parts.scheme.derived_fields(pa, pa.n_owned))
        symmetric = [f.name for f in (*pa.fields, *self.parts.scheme.derived) if f.shape == ("sym",)]
        with self.timer("io"):
            path = frame_path(self.out_dir, self.frame_index)
            write_frame(path, self.comm, fields, time=self.t, step=self.step, dim=self.case.dim, params=self.params,
                        symmetric=symmetric, configurations=self.configurations)
            if self.comm.rank == 0:
                add_to_series(self.out_dir, path, self.t)
