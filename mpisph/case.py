"""Cases: typed parameters, loading case files, and the Case description.

A case file ``cases/NAME.py`` holds a docstring (its first line is the
one-line description), ``PARAMS`` (a dict of ``Param``) and ``setup(p)``,
which receives the validated parameters as attributes and returns a
``Case``. Every case also has the run parameters in ``RUN_PARAMS``.
"""

import dataclasses
import difflib
import importlib.util
import math
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from .barrier_load import check_barrier_loads
from .errors import InputError
from .gauges import check_gauges, gauge_warnings
from .kernels import KERNELS
from .sources import as_points
from .materials import DruckerPrager, ElasticSolid, Fluid, MuIGranular  # noqa: F401  (case files import them from here)
from .physics.fluid import LIMITED_PAIRS
from .stabilisers import SEPARATOR, stabiliser_names
from .stabilisers.artificial_stress import EPSILON
from .stabilisers.shifting import COEFFICIENT
from .stabilisers.transport_velocity import EDGE_NEIGHBOURS, NEAR_SURFACE_NORMALS, SPLASHED

CASES_DIR = Path(__file__).resolve().parent.parent / "cases"
KIND_WORDS = {float: "a number", int: "a whole number", bool: "true or false", str: "a word"}  # in errors


@dataclass(frozen=True)
class Param:
    """A case parameter: default value (its type is the parameter's type), unit, meaning; with
    ``stabilisers``, a value may also be several of the choices but "none" joined by "+", which
    stabilisers.stabiliser_names checks as a combination; with ``bounds`` (low, high), a number
    must lie in [low, high). A float must be finite. With ``applies`` (name, choices), the
    parameter acts only where the parameter ``name`` is one of ``choices`` (a stabiliser
    combination: holds one of them); ``idle_warnings`` says so of a value set where it does not."""

    default: object
    unit: str
    doc: str
    choices: tuple = ()
    positive: bool = False
    stabilisers: bool = False
    bounds: tuple = ()
    applies: tuple = ()

    @property
    def type(self):
        return type(self.default)

    def with_default(self, default):
        """The same parameter with another default (a case's own choice of a shared parameter)."""
        return dataclasses.replace(self, default=default)

    def only_with(self, name, *choices):
        """The same parameter, acting only where the parameter ``name`` is one of ``choices``."""
        return dataclasses.replace(self, applies=(name, choices))

    def parse(self, name, text):
        """Convert command-line text to the parameter's type, or raise InputError."""
        kind = self.type
        try:
            if kind is bool:
                low = text.strip().lower()
                if low not in ("true", "false", "1", "0", "yes", "no", "on", "off"):
                    raise ValueError
                value = low in ("true", "1", "yes", "on")
            else:
                value = kind(text)
        except ValueError:
            raise InputError(f"parameter {name} takes {KIND_WORDS.get(kind, kind.__name__)}, not {text!r}") from None
        return self.check(name, value)

    def check(self, name, value):
        if self.type is float and isinstance(value, int) and not isinstance(value, bool):
            value = float(value)
        if not isinstance(value, self.type):
            raise InputError(f"parameter {name} takes {KIND_WORDS.get(self.type, self.type.__name__)}, not {value!r}")
        if self.choices and value not in self.choices:
            parts = value.split(SEPARATOR) if self.stabilisers else ()
            if not parts or "none" in parts or any(part not in self.choices for part in parts):
                combined = f", or several of them (not none) joined by {SEPARATOR}" if self.stabilisers else ""
                raise InputError(f"parameter {name} must be one of {', '.join(map(str, self.choices))}{combined}, "
                                 f"not {value!r}")
            stabiliser_names(value)
        if self.type is float and not math.isfinite(value):
            raise InputError(f"parameter {name} must be a finite number, not {value!r}")
        if self.positive and not value > 0:
            raise InputError(f"parameter {name} must be positive, not {value!r}")
        if self.bounds and not self.bounds[0] <= value < self.bounds[1]:
            raise InputError(f"parameter {name} must lie in [{self.bounds[0]:g}, {self.bounds[1]:g}), not {value!r}")
        return value


POISSON = (0.0, 0.5)  # bounds of a Poisson's ratio: up to 1/2, where the bulk modulus diverges
ANGLE = (0.0, 90.0)  # bounds of a friction or dilatancy angle [deg]

H_FACTOR = (1.0, 3.0)  # bounds of h / dp (h_factor_param)


def h_factor_param(default=1.3, source=""):
    """The smoothing length in spacings, h_factor = h / dp, in H_FACTOR: below 1 the support (2 h)
    misses the lattice's second ring and the kernel sum of a lattice leaves one (Kernel.lattice_sum,
    Wendland C2 in 2D: 1.010 at 1.3, 1.038 at 1, 1.25 at 0.7); at 3 a 3D particle already has about
    900 neighbours, twelve times the default 1.3's, for a resolution set by h, not dp.
    ``source`` says where the case's default comes from."""
    return Param(default, "-", "smoothing length h = h_factor * dp" + (f" ({source})" if source else ""),
                 bounds=H_FACTOR)


RUN_PARAMS = {
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.1, "s", "simulated time between frames", positive=True),
    "kernel": Param("wendland_c2", "-", "smoothing kernel", choices=tuple(KERNELS)),
    "h_factor": h_factor_param(),
    "time_stepping": Param("dual", "-", "dual: 001_ Eqs. 9-11; single: 000_ Eq. 38",
                           choices=("dual", "single")),
    "max_time_step": Param(0.0, "s", "upper bound of the time step, 0: none (002_ steps at 1e-6 s and 5e-5 s "
                           "in its Tables 2 and 4)", bounds=(0.0, math.inf)),
    "rebalance_threshold": Param(0.1, "-", "rebalance when max/mean work per rank - 1 exceeds this "
                                 "(work: neighbour pairs)", positive=True),
    "diagnostics_every": Param(10, "steps", "advection steps between rows of diagnostics.csv, counted from "
                               "t = 0 across restarts", positive=True),
    "damping": Param(0.0, "1/s", "rate c of the velocity damping -c v that settles a body to rest before a "
                     "restart without it (forces.VelocityDamping); 0: none", bounds=(0.0, math.inf)),
}

# Every case that offers the stabiliser ``shifting`` exposes this.
SHIFTING_PARAMS = {
    "shifting_coefficient": Param(COEFFICIENT, "-", "C of the particle shift (Xu et al. 2009 Eq. 35, who give 0.01-0.1; "
                                  "with stabiliser=shifting)", positive=True, applies=("stabiliser", ("shifting",))),
}

COMBINATION_DOC = (f"; several joined by {SEPARATOR}, as artificial_stress{SEPARATOR}utvf, apply in that order, "
                   "at most one of them a position shift (a transport-velocity correction or shifting)")

# Every case that offers the stabiliser ``artificial_stress`` exposes this.
ARTIFICIAL_STRESS_PARAMS = {
    "artificial_stress_epsilon": Param(EPSILON, "-", "epsilon of the artificial stress (Monaghan 2000; Gray, "
                                       "Monaghan & Swift 2001; with stabiliser=artificial_stress)", positive=True,
                                       applies=("stabiliser", ("artificial_stress",))),
}


def fluid_stabiliser_params(default, also=None):
    """The parameters of a fluid case's stabiliser: ``stabiliser`` with the case's default and, in
    ``also``, {name: source} of the stabilisers the case offers besides the free-surface ones,
    then those of shifting, artificial stress and UTVF (SHIFTING_PARAMS, ARTIFICIAL_STRESS_PARAMS,
    UTVF_PARAMS)."""
    also = also or {}
    return {"stabiliser": Param(default, "-", "particle regularisation: tvf on inner particles, utvf on all "
                                "(000_ Eqs. 30-37); shifting (Xu et al. 2009, Khayyer et al. 2017); "
                                "artificial_stress (Monaghan 2000)"
                                + "".join(f"; {name} ({source})" for name, source in also.items())
                                + COMBINATION_DOC,
                                choices=("none", *also, "tvf", "utvf", "shifting", "artificial_stress"),
                                stabilisers=True),
            **SHIFTING_PARAMS, **ARTIFICIAL_STRESS_PARAMS, **UTVF_PARAMS}


# Case.density_reinit (physics/density_reinit.py): each mode and what it does
DENSITY_REINITS = {"inner": "on every particle",
                   "free_surface": "not below the evolved density's share near a free surface",
                   "none": "continuity alone"}


def density_reinit_param(default, choices=tuple(DENSITY_REINITS), why=""):
    """The parameter choosing the density reinitialisation (Case.density_reinit), with the case's
    default, the modes it offers (its help names those alone) and, in ``why``, the case's reason for
    its default."""
    modes = "; ".join(f"{mode}, {DENSITY_REINITS[mode]}" for mode in DENSITY_REINITS if mode in choices)
    return Param(default, "-", "density by kernel summation (001_ Eq. 8) every configuration (physics/"
                 f"density_reinit.py): {modes}" + (f"; {why}" if why else ""), choices=choices)


def limiter_param(default):
    """The parameter naming the pairs the Riemann dissipation limiter damps (the option ``limiter``
    of the schemes riemann_fluid and riemann_granular), with the case's default."""
    return Param(default, "-", "pairs the Riemann dissipation limiter damps (separating: the authors' code, "
                 "physics/fluid.py; approaching: 000_'s text; none: no dissipation in the momentum)",
                 choices=tuple(LIMITED_PAIRS))


def classic_viscosity_params(alpha, beta, scheme):
    """The alpha and beta of 002_ Eq. 25's artificial viscosity, with the case's defaults, for a
    case that offers the classic scheme ``scheme`` (read by ``scheme_keywords``)."""
    return {
        "av_alpha": Param(alpha, "-", f"alpha of the artificial viscosity (002_ Eq. 25; {scheme})",
                          applies=("scheme", (scheme,))),
        "av_beta": Param(beta, "-", f"beta of the artificial viscosity (002_ Eq. 25; {scheme})",
                         applies=("scheme", (scheme,))),
    }


def scheme_keywords(p, classic_options, riemann_options):
    """The Case keywords for the scheme ``p.scheme``: a classic one (``classic_*``, stepped by its own
    integrator, 002_'s predictor-corrector) with the artificial viscosity of
    ``classic_viscosity_params`` and the options ``classic_options``; a Riemann one with
    ``riemann_options``."""
    if p.scheme.startswith("classic_"):
        return {"scheme": p.scheme, "scheme_options": {"alpha": p.av_alpha, "beta": p.av_beta, **classic_options}}
    return {"scheme": p.scheme, "scheme_options": riemann_options}


# The options of UTVF (stabilisers/transport_velocity.py), on every case that offers utvf.
UTVF_PARAMS = {
    "utvf_edge_neighbours": Param(EDGE_NEIGHBOURS[0], "-", "with stabiliser=utvf, the 3D free-surface particles "
                                  "within h of an edge or corner (div r < 0.6 d): shifted (000_ Eq. 37 as printed) "
                                  "or kept in place, so that a perfect lattice stays regular "
                                  "(stabilisers/transport_velocity.py)", choices=EDGE_NEIGHBOURS,
                                  applies=("stabiliser", ("utvf",))),
    "utvf_near_surface_normal": Param(NEAR_SURFACE_NORMALS[0], "-", "with stabiliser=utvf, the normal on which "
                                      "a near-surface particle's shift is projected (000_ Eq. 36): its own B g "
                                      "(Eq. 35 as printed) or the kernel-weighted mean of the Eq. 35 normals of the "
                                      "outermost particles within h (stabilisers/transport_velocity.py)",
                                      choices=NEAR_SURFACE_NORMALS, applies=("stabiliser", ("utvf",))),
    "utvf_splashed": Param(SPLASHED[0], "-", "with stabiliser=utvf, splashed particles (outermost, no near-surface "
                           "particle within h): kept in place (000_ Sec. 3.3's text) or shifted along their surface "
                           "as the other outermost ones, as the authors' code does (stabilisers/transport_velocity.py)",
                           choices=SPLASHED, applies=("stabiliser", ("utvf",))),
}


# Every solid case (elastic or granular) exposes these, with the paper's integration as default:
# one time step (000_ Eq. 38) and the UTVF shift after each (Sec. 3.4, Eq. 42).
SOLID_PARAMS = {
    "stabiliser": Param("utvf", "-", "particle regularisation (000_ Eqs. 30-37; tvf_limited: tvf with 001_'s "
                        "limiter, Eqs. 15-16; artificial_stress: Gray, Monaghan & Swift 2001; shifting: Xu et al. "
                        "2009; adaptive_kernel: 002_ Sec. 4, with kernel=cubic_spline)" + COMBINATION_DOC,
                        choices=("none", "tvf", "tvf_limited", "utvf", "artificial_stress", "shifting",
                                 "adaptive_kernel"), stabilisers=True),
    **ARTIFICIAL_STRESS_PARAMS,
    **SHIFTING_PARAMS,
    **UTVF_PARAMS,
    "time_stepping": Param("single", "-", "single: 000_ Eq. 38, the shift after every step; "
                           "dual: 001_ Eqs. 9-11, the shift once per advection step",
                           choices=("dual", "single")),
}


@dataclass
class Body:
    """Moving particles of one material with their initial state.

    ``x`` is an array (n, dim) or a source (sources.py) that each rank reads only its slab of.
    Each of the initial fields is None (zero), an array over the rows of an array ``x``, or a
    function of positions (m, dim) -> values (m, ...), which a source's body needs."""

    name: str
    x: object
    velocity: object = None  # (n, dim)
    pressure: object = None  # (n,)
    stress: object = None  # (n, 3, 3) initial Cauchy stress, solids only
    clamped: object = None  # (n,) bool: held in place (solids only)


@dataclass
class Wall:
    """Fixed dummy particles: positions, inward normals, wall velocity, slip condition.

    ``x`` is an array (with ``normal``) or a source (sources.py) that gives the normals itself;
    ``velocity`` is None (at rest), one vector, or an array over the rows of an array ``x``."""

    name: str
    x: object
    normal: np.ndarray | None = None
    velocity: np.ndarray | None = None  # (n, dim) or (dim,); zero if None
    slip: bool = False
    distance: object = None  # (n,) or a function of positions: depth behind the wall surface (Morris, 004_ Eq. 34)

    @property
    def points(self):
        return as_points(self.x, self.normal)


@dataclass(frozen=True)
class Front:
    """The front of a spreading body, recorded in diagnostics.csv as column ``front``: the largest
    distance of a moving particle from ``origin`` measured along ``axes`` only (``(0,)``: x, for a
    planar collapse; ``(0, 1)``: the radius in the x-y plane, for an axisymmetric one)."""

    origin: tuple
    axes: tuple


@dataclass
class Case:
    """Everything the solver needs to know about one simulation."""

    dim: int
    domain: tuple  # (lo, hi) corners; a particle leaving it stops the run
    dp: float
    material: object  # Fluid, ElasticSolid, DruckerPrager or MuIGranular (materials.py)
    scheme: str  # a name of mpisph.schemes.SCHEMES that takes the material
    bodies: list
    walls: list = field(default_factory=list)
    gravity: tuple | None = None
    periodic: tuple | None = None
    slab_axis: int = 0
    density_reinit: str = "none"  # none | inner | free_surface
    stabilisers: tuple | str = ()  # names of mpisph.stabilisers.STABILISERS, in order ("a+b" or "none" too)
    forces: list = field(default_factory=list)  # the case's own force terms (forces.ForceTerm), last in the sum
    integrator: str | None = None  # a name of mpisph.integrators.INTEGRATORS; None: the scheme's own
    scheme_options: dict = field(default_factory=dict)  # the scheme's discretisation options (Scheme.options)
    u_ref: float = 0.0  # reference speed of 001_ Eq. 10 [m/s]
    warnings: list = field(default_factory=list)  # one-line warnings printed when a run starts
    probes: dict = field(default_factory=dict)  # name -> global id (over the bodies' particles, in order) or a
    # position, (x, y[, z]): the nearest body particle; recorded in diagnostics.csv as its displacement
    front: Front | None = None  # recorded in diagnostics.csv when given
    gauges: list = field(default_factory=list)  # gauges.Gauge and gauges.SurfaceGauge, a CSV file each
    wall_forces: dict = field(default_factory=dict)  # wall name -> point of its moment; diagnostics (wall_forces.py)
    barrier_loads: list = field(default_factory=list)  # barrier_load.BarrierLoad: alpha of a barrier in diagnostics

    @property
    def sources(self):
        """The particle sources of the bodies, then the walls (sources.py), in id order."""
        return [as_points(b.x) for b in self.bodies] + [w.points for w in self.walls]

    @property
    def particle_estimate(self):
        """About how many particles its sources hold, walls included, before any is made."""
        return sum(s.estimate for s in self.sources)

    def __post_init__(self):
        if isinstance(self.stabilisers, str):
            self.stabilisers = stabiliser_names(self.stabilisers)
        self.stabilisers = tuple(self.stabilisers)
        self.domain = (np.asarray(self.domain[0], float), np.asarray(self.domain[1], float))
        self.gravity = np.zeros(self.dim) if self.gravity is None else np.asarray(self.gravity, float)
        self.periodic = (False,) * self.dim if self.periodic is None else tuple(self.periodic)
        self._check_countable()
        probes = {name: self._probe(name, where) for name, where in self.probes.items()}
        self.probes = {name: gid for name, (gid, _) in probes.items()}
        self.probe_origins = {name: origin for name, (_, origin) in probes.items()}
        self.id_ranges = []  # set by validate: [(name, (first, last + 1) global id)] of the bodies, then the walls
        self.wall_gids = {}  # set by validate, from the walls

    def _wall_gids(self):
        """{wall name: (first, last + 1) global id} of the walls whose forces are recorded (global ids
        run over the sources of the bodies, then the walls, in order)."""
        names = [w.name for w in self.walls]
        unknown = [name for name in self.wall_forces if name not in names]
        if unknown:
            raise InputError(f"wall_forces names {', '.join(map(repr, unknown))}: the walls are "
                             f"{', '.join(map(repr, names)) or 'none'}")
        return {name: ids for name, ids in self.id_ranges[len(self.bodies):] if name in self.wall_forces}

    def _id_ranges(self):
        """[(name, (first, last + 1) global id)] of the bodies, then the walls, in id order."""
        out, first = [], 0
        for item, source in zip([*self.bodies, *self.walls], self.sources):
            out.append((item.name, (first, first + source.size)))
            first += source.size
        return out

    def name_of(self, gid):
        """The name of the body or wall that the particle of global id ``gid`` belongs to."""
        return next(name for name, (first, stop) in self.id_ranges if first <= gid < stop)

    def _initial_position(self, gid):
        """Initial position of the moving or clamped particle with global id ``gid``; None if no
        body has a particle of that id (a gap of a lattice fill, or beyond the bodies)."""
        if not 0 <= gid:
            return None
        for b in self.bodies:
            points = as_points(b.x)
            if gid < points.size:
                return np.asarray(points.position(gid), float) if points.holds(gid) else None
            gid -= points.size
        return None

    def _check_countable(self):
        """Refuse a case with more particles than global ids (int64) number, before a probe looks
        for its particle among them (memory.check_fits refuses the others too large to run)."""
        from .memory import available_bytes, too_many
        count = self.particle_estimate
        if count >= 2**63:
            available = available_bytes()
            raise InputError(too_many(count, "the case has about", available) if available is not None else
                             f"the case has about {count:.3g} particles, more than 64-bit ids number: choose a "
                             "larger dp")

    def _nearest_body_particle(self, point):
        """The global id of the body particle nearest to ``point`` within 2 dp of it; None if none is."""
        reach, best, first = 2.0 * self.dp, (np.inf, None), 0
        for b in self.bodies:
            points = as_points(b.x)
            index, x = points.near(point, reach)
            if len(index):
                d = np.linalg.norm(x - point, axis=1)
                k = int(np.argmin(d))
                best = min(best, (float(d[k]), first + int(index[k])))
            first += points.size
        return best[1] if best[0] <= reach else None

    def _probe(self, name, where):
        """(global id, initial position) of the probe ``name``, given by global id or by a position
        (the nearest body particle); InputError for an id that is no body particle's."""
        if np.ndim(where) == 0:
            gid = int(where)
            origin = self._initial_position(gid)
            if origin is None:
                raise InputError(f"probe {name!r}: global id {gid} is no body particle's (ids run over each body's "
                                 "lattice, gaps included): give the probe a position instead, as (x, y[, z])")
            return gid, origin
        point = np.asarray(where, float)
        if point.shape != (self.dim,):
            raise InputError(f"probe {name!r}: a position takes {self.dim} coordinates, not {list(where)}")
        gid = self._nearest_body_particle(point)
        if gid is None:
            raise InputError(f"probe {name!r}: no body particle within 2 dp of {point.tolist()}")
        return gid, self._initial_position(gid)

    def forget_particles(self):
        """Drop the bodies and walls (their arrays, or sources with their caches) once the
        particles are made from them (in 3D arrays would stay resident for the whole run, about
        80 bytes per particle); domain, material and probe origins stay."""
        self.bodies, self.walls = [], []

    def validate(self, support):
        """Raise InputError for a case that cannot run; note the global ids of the walls whose forces
        are recorded (``wall_gids``)."""
        self.id_ranges = self._id_ranges()
        self.wall_gids = self._wall_gids()
        check_gauges(self)
        check_barrier_loads(self)
        if not self.dp > 0:
            raise InputError(f"spacing dp must be positive, not {self.dp!r}")
        lo, hi = self.domain
        if np.any(hi <= lo):
            raise InputError("the domain has no volume: every upper corner must exceed the lower one")
        for a in range(self.dim):
            if self.periodic[a] and hi[a] - lo[a] < 2 * support:
                raise InputError(f"periodic axis {'xyz'[a]} is {hi[a] - lo[a]:.4g} m, {(hi[a] - lo[a]) / self.dp:.4g} dp "
                                 f"long, shorter than twice the kernel support, {2 * support:.4g} m = "
                                 f"{2 * support / self.dp:.4g} dp")
        if self.density_reinit not in DENSITY_REINITS:
            raise InputError(f"density_reinit must be one of {', '.join(DENSITY_REINITS)}, not {self.density_reinit!r}")


def closest(name, names):
    """The one of ``names`` nearest to ``name``, letter case ignored (for a "did you mean"), or None."""
    by_lower = {n.lower(): n for n in names}
    close = difflib.get_close_matches(name.lower(), list(by_lower), n=1)
    return by_lower[close[0]] if close else None


def case_names():
    return sorted(p.stem for p in CASES_DIR.glob("*.py") if not p.stem.startswith("_"))


def load_case_module(name):
    """Import ``cases/NAME.py`` (or a case file given by its path).

    Unknown names, a case file that is missing, is not Python or has no PARAMS and setup raise
    InputError (an error raised by the file's own code keeps its traceback).
    """
    path = Path(name) if name.endswith(".py") else CASES_DIR / f"{name}.py"
    if not path.is_file():
        if name.endswith(".py"):
            raise InputError(f"no case file {name!r}")
        close = closest(name, case_names())
        hint = f"; did you mean {close!r}?" if close else "; see 'python -m mpisph list'"
        raise InputError(f"unknown case {name!r}{hint}")
    spec = importlib.util.spec_from_file_location(f"mpisph_case_{path.stem}", path)
    module = importlib.util.module_from_spec(spec)
    try:
        spec.loader.exec_module(module)
    except SyntaxError as e:
        raise InputError(f"case file {name}, line {e.lineno}: {e.msg}") from None
    missing = [attr for attr in ("PARAMS", "setup") if not hasattr(module, attr)]
    if missing:
        raise InputError(f"case file {name} defines no {' and no '.join(missing)} (cases/*.py show the form)")
    return module


def case_key(name):
    """How a frame names its case (parameter ``case``): a file of cases/ by its name, however given,
    another case file by its absolute path, so that a restart from any directory finds it."""
    if not name.endswith(".py"):
        return name
    path = Path(name).resolve()
    return path.stem if path.parent == CASES_DIR.resolve() else str(path)


def all_params(module):
    """Case parameters followed by the run parameters the case does not set itself."""
    params = dict(module.PARAMS)
    for name, p in RUN_PARAMS.items():
        params.setdefault(name, p)
    return params


def describe(module):
    """The first paragraph of the case's docstring, on one line."""
    return " ".join((module.__doc__ or "").strip().split("\n\n")[0].split())


def resolve_params(module, overrides, base=None):
    """Defaults, then ``base`` (the values of an earlier run: a restart), then ``overrides``
    {name: text}; returns {name: value}. A parameter newer than ``base`` takes its default."""
    params = all_params(module)
    values = {k: p.default for k, p in params.items()}
    values.update(base or {})
    for name, text in overrides.items():
        if name not in params:
            close = closest(name, params)
            hint = f"; did you mean {close!r}{_in_degrees(params[close], text)}?" if close else ""
            raise InputError(f"unknown parameter {name!r} for this case{hint}")
        values[name] = params[name].parse(name, text)
    for name, value in values.items():
        if name in params:
            values[name] = params[name].check(name, value)
    return values


def angle_warnings(params, values):
    """A warning for each angle (a parameter in degrees) in (0, pi/2]: a value in radians, likely,
    or for a friction angle a friction coefficient."""
    warnings = []
    for name, p in params.items():
        value = values.get(name, 0.0)
        if p.unit == "deg" and 0.0 < value <= math.pi / 2:
            readings = [f"{value:g} rad would be {math.degrees(value):.4g} deg"]
            readings += [f"{_as_friction(value)} deg"] * _is_friction(p)
            warnings.append(f"{name} = {value:g} deg: angles are in degrees ({', '.join(readings)})")
    return warnings


def _is_friction(param):
    """Whether ``param`` is a friction angle (in degrees, its meaning naming friction)."""
    return param.unit == "deg" and "friction" in param.doc


def _as_friction(value):
    """'a friction coefficient VALUE is ATAN': the angle [deg] that a coefficient typed for it gives."""
    return f"a friction coefficient {value:g} is {math.degrees(math.atan(value)):.4g}"


def _in_degrees(param, text):
    """' (in degrees: a friction coefficient TEXT is ATAN)' where ``param`` is a friction angle and
    ``text`` a number (mu_s=0.38 given for mu_s_deg), else ''."""
    try:
        value = float(text)
    except ValueError:
        return ""
    return f" (in degrees: {_as_friction(value)})" if _is_friction(param) else ""


def idle_warnings(params, values):
    """A warning for each parameter set off its default where it does nothing (``Param.applies``):
    av_alpha with the Riemann scheme, a UTVF option without UTVF."""
    warnings = []
    for name, p in params.items():
        if not p.applies or p.applies[0] not in values or values.get(name, p.default) == p.default:
            continue
        other, choices = p.applies
        chosen = str(values[other])
        if not set(chosen.split(SEPARATOR)) & set(choices):
            value = f"{values[name]:g}" if isinstance(values[name], float) else values[name]
            warnings.append(f"{name} = {value} does nothing with {other} = {chosen}: it acts only with {other} = "
                            + " or ".join(choices))
    return warnings


def build_case(module, values):
    """Call the case's ``setup`` with the parameter values as attributes; its warnings gain those
    of ``angle_warnings``, ``idle_warnings`` and ``gauges.gauge_warnings``."""
    case = module.setup(SimpleNamespace(**values))
    case.warnings = [*case.warnings, *angle_warnings(module.PARAMS, values), *idle_warnings(module.PARAMS, values),
                     *gauge_warnings(case)]
    return case


def case_of_frame(params, module=None):
    """The Case a frame was written with, built again from the frame's parameters (``params`` of
    io.frames.read_frame) by its case's ``module`` (default: the one the frame names); a parameter
    newer than the frame takes its default."""
    module = load_case_module(params["case"]) if module is None else module
    return build_case(module, resolve_params(module, {}, base=params))

