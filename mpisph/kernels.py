"""Smoothing kernels: one object per kernel, and the numba functions the pair loops call.

A ``Kernel`` holds everything about one kernel at one smoothing length: its
name, support radius (``SUPPORT_FACTOR`` h), normalisation in 1, 2 or 3
dimensions, value, gradient and the lattice sum that density summation divides
by. ``Kernel(name, h, dim)`` refuses an unknown name.

The pair loops take ``Kernel.params``, a numba-friendly named tuple, and
evaluate the kernel of a pair with ``pair_w(k, r, i, j)`` and
``pair_dw(k, r, i, j)``. A fixed kernel has one shape for all particles: its
``KernelParams`` (kind id, h, sigma_d) give W(r_ij). The adaptive kernel's are
an ``AdaptiveKernelParams`` (the cubic spline's, with the dimension and the
knots); numba compiles every pair loop once per type, so a fixed kernel's loops
carry no test of it, and ``w``/``dw`` given them are the cubic spline (a = 1).

The adaptive cubic B-spline of 002_ (Sec. 4.1, Eq. 31; ``Kernel(...,
adaptive=True)``, only for ``cubic_spline``) is the B-spline over the knots
{-b, -a, 0, a, b}, b = 2, with a knot a per particle (the field ``knot``,
which a stabiliser sets with the factors of ``knot_coefficients``:
stabilisers/adaptive_kernel.py); a = 1 is the cubic spline. With q = r/h,

    W(q; a) = sigma_d(a) / h^d * ((a + b) q^3 - 3 a b q^2 + a^2 b^2) / (a^2 b (a + b))   q < a
            = sigma_d(a) / h^d * (b - q)^3 / (b (b^2 - a^2))                            a <= q < b

(the printed denominator "a^{2b} (a + b)" is a^2 b (a + b): only that makes the
two pieces meet at q = a, and it gives the cubic spline's 1/6 at a = 1), and
int W = 1 gives sigma_1 = 2 / b, sigma_2 = 10 (a + b) / (pi b (a^2 + a b + b^2))
(both as printed) and sigma_3 = 15 / (pi b (a^2 + b^2)) (derived the same way:
int_0^b f(q) q^2 dq = b (a^2 + b^2) / 60). A pair takes the mean of the two
particles' kernels, W_ij = (W(r; a_i) + W(r; a_j)) / 2: the pair weight is
then the same seen from i and from j, grad_i W_ij = -grad_j W_ji, and the pair
forces stay antisymmetric, which conserves linear momentum.

Conventions used throughout mpisph: r_ij = x_i - x_j, e_ij = r_ij / |r_ij|
(pointing from j to i), grad_i W_ij = W'(r_ij) e_ij with W' <= 0. The papers
use Wendland C2 with h = 1.3 dp (000_ Sec. 4, 001_ Sec. 4).
"""

import math
from collections import namedtuple

import numpy as np
from numba import njit, types
from numba.extending import overload

from .errors import InputError
from .particles import Field

WENDLAND_C2 = 0
CUBIC_SPLINE = 1
SUPPORT_FACTOR = 2.0  # support radius = SUPPORT_FACTOR * h for every kernel here
KNOT_SUPPORT = SUPPORT_FACTOR  # b of 002_ Eq. 31, the outer knot: the support in units of h

KernelParams = namedtuple("KernelParams", ("kind", "h", "sigma"))
AdaptiveKernelParams = namedtuple("AdaptiveKernelParams", ("kind", "h", "sigma", "dim", "knot", "coefficients"))
KNOT = Field("knot", (), np.float64, "knot a of the adaptive cubic B-spline (002_ Eq. 31; 1: the cubic spline) [-]")
KNOT_COEFFICIENTS = Field("knot_coefficients", (2,), np.float64,
                          "factors of the two pieces of the adaptive B-spline (kernels.knot_coefficients) [1/m^d]")


class Kernel:
    """One smoothing kernel at smoothing length ``h`` in ``dim`` dimensions; with ``adaptive``, the
    cubic spline with a knot per particle (module docstring), whose pair loops read the particles
    bound by ``bind``; ``value``, ``derivative`` and ``lattice_sum`` are then those of a = 1."""

    def __init__(self, name, h, dim, adaptive=False):
        if name not in KERNELS:
            raise InputError(f"kernel must be one of {', '.join(KERNELS)}, not {name!r}")
        if adaptive and name != "cubic_spline":
            raise InputError(f"the adaptive kernel (002_) adapts the cubic B-spline: set kernel=cubic_spline, "
                             f"not {name!r}")
        self.name = name
        self.kind = KERNELS[name]
        self.h = float(h)
        self.dim = dim
        self.adaptive = adaptive
        self.fields = (KNOT, KNOT_COEFFICIENTS) if adaptive else ()
        self.support = SUPPORT_FACTOR * self.h
        self.sigma = normalisation(self.kind, self.h, dim)
        self.fixed_params = KernelParams(self.kind, self.h, self.sigma)
        self.params = self.fixed_params

    def bind(self, particles):
        """Point the pair loops' parameters at the knots of ``particles`` (owned and ghosts), after
        every rebuild of the halo; nothing to do for a fixed kernel."""
        if self.adaptive:
            self.params = AdaptiveKernelParams(*self.fixed_params, self.dim, particles.arrays["knot"],
                                               particles.arrays["knot_coefficients"])

    def value(self, r):
        """W(r) for an array of distances (any shape)."""
        return self._on_array(r, False)

    def derivative(self, r):
        """dW/dr (non-positive) for an array of distances (any shape)."""
        return self._on_array(r, True)

    def _on_array(self, r, derivative):
        r = np.asarray(r, dtype=float)
        out = np.empty(r.size)
        _values(r.ravel(), self.fixed_params, derivative, out)
        return out.reshape(r.shape)

    def lattice_sum(self, dp):
        """V0 sum_j W_ij (self included) over a full square or cubic lattice of spacing dp, V0 = dp^d."""
        m = int(np.ceil(self.support / dp)) + 1
        axis = np.arange(-m, m + 1) * dp
        grids = np.meshgrid(*([axis] * self.dim), indexing="ij")
        r = np.sqrt(sum(g.ravel() ** 2 for g in grids))
        return dp**self.dim * float(sum(self.value(r)))


KERNELS = {"wendland_c2": WENDLAND_C2, "cubic_spline": CUBIC_SPLINE}


def normalisation(kind, h, dim):
    """Normalisation constant sigma_d of kernel ``kind`` in ``dim`` = 1, 2 or 3 dimensions."""
    if kind == WENDLAND_C2:
        return {1: 3.0 / (4.0 * h), 2: 7.0 / (4.0 * math.pi * h * h), 3: 21.0 / (16.0 * math.pi * h * h * h)}[dim]
    return {1: 2.0 / (3.0 * h), 2: 10.0 / (7.0 * math.pi * h * h), 3: 1.0 / (math.pi * h * h * h)}[dim]


@njit(cache=True)
def w(r, k):
    """Kernel value W(r) of the kernel ``k`` (a ``KernelParams``)."""
    q = r / k.h
    if q >= 2.0:
        return 0.0
    if k.kind == WENDLAND_C2:
        t = 1.0 - 0.5 * q
        return k.sigma * t * t * t * t * (2.0 * q + 1.0)
    if q < 1.0:
        return k.sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q)
    t = 2.0 - q
    return k.sigma * 0.25 * t * t * t


@njit(cache=True)
def dw(r, k):
    """Radial derivative dW/dr (non-positive) of the kernel ``k``."""
    q = r / k.h
    if q >= 2.0:
        return 0.0
    if k.kind == WENDLAND_C2:
        t = 1.0 - 0.5 * q
        return -5.0 * k.sigma / k.h * q * t * t * t
    if q < 1.0:
        return k.sigma / k.h * (-3.0 * q + 2.25 * q * q)
    t = 2.0 - q
    return -0.75 * k.sigma / k.h * t * t


@njit(cache=True)
def knot_normalisation(a, dim):
    """sigma_d(a) of the adaptive cubic B-spline (module docstring), to be divided by h^d."""
    b = KNOT_SUPPORT
    if dim == 1:
        return 2.0 / b
    if dim == 2:
        return 10.0 * (a + b) / (math.pi * b * (a * a + a * b + b * b))
    return 15.0 / (math.pi * b * (a * a + b * b))


@njit(cache=True)
def knot_coefficients(a, h, dim):
    """The factors (inner, outer) of the two pieces of W(q; a) (module docstring), computed once per
    particle and configuration so that a pair evaluation divides nothing: sigma_d(a) / h^d over
    a^2 b (a + b) and over b (b^2 - a^2) (0 for a = b, which has no outer piece)."""
    b = KNOT_SUPPORT
    sigma = knot_normalisation(a, dim) / h**dim
    outer = sigma / (b * (b * b - a * a)) if a < b else 0.0
    return sigma / (a * a * b * (a + b)), outer


@njit(inline="always")
def knot_w(r, h, a, inner, outer):
    """W(r; a) of the adaptive cubic B-spline, with the factors of ``knot_coefficients``."""
    b = KNOT_SUPPORT
    q = r / h
    if q >= b:
        return 0.0
    if q < a:
        return inner * ((a + b) * q * q * q - 3.0 * a * b * q * q + a * a * b * b)
    t = b - q
    return outer * t * t * t


@njit(inline="always")
def knot_dw(r, h, a, inner, outer):
    """dW/dr (non-positive) of the adaptive cubic B-spline, with the factors of ``knot_coefficients``."""
    b = KNOT_SUPPORT
    q = r / h
    if q >= b:
        return 0.0
    if q < a:
        return inner / h * (3.0 * (a + b) * q * q - 6.0 * a * b * q)
    t = b - q
    return -3.0 * outer / h * t * t


@njit(inline="always")
def _fixed_pair_w(k, r, i, j):
    return w(r, k)


@njit(inline="always")
def _fixed_pair_dw(k, r, i, j):
    return dw(r, k)


@njit(inline="always")
def _adaptive_pair_w(k, r, i, j):
    c = k.coefficients
    return 0.5 * (knot_w(r, k.h, k.knot[i], c[i, 0], c[i, 1]) + knot_w(r, k.h, k.knot[j], c[j, 0], c[j, 1]))


@njit(inline="always")
def _adaptive_pair_dw(k, r, i, j):
    c = k.coefficients
    return 0.5 * (knot_dw(r, k.h, k.knot[i], c[i, 0], c[i, 1]) + knot_dw(r, k.h, k.knot[j], c[j, 0], c[j, 1]))


def pair_w(k, r, i, j):
    """W_ij of the pair (i, j) at distance r (module docstring: the same seen from i and j)."""
    return (_adaptive_pair_w if isinstance(k, AdaptiveKernelParams) else _fixed_pair_w)(k, r, i, j)


def pair_dw(k, r, i, j):
    """dW_ij/dr of the pair (i, j) at distance r; grad_i W_ij = pair_dw e_ij."""
    return (_adaptive_pair_dw if isinstance(k, AdaptiveKernelParams) else _fixed_pair_dw)(k, r, i, j)


def _adaptive(k):
    """Whether the numba type ``k`` is that of an AdaptiveKernelParams."""
    return isinstance(k, types.BaseNamedTuple) and k.instance_class is AdaptiveKernelParams


@overload(pair_w, inline="always")
def _pair_w(k, r, i, j):
    pair = _adaptive_pair_w if _adaptive(k) else _fixed_pair_w
    return lambda k, r, i, j: pair(k, r, i, j)


@overload(pair_dw, inline="always")
def _pair_dw(k, r, i, j):
    pair = _adaptive_pair_dw if _adaptive(k) else _fixed_pair_dw
    return lambda k, r, i, j: pair(k, r, i, j)


@njit(cache=True)
def _values(r, k, derivative, out):
    """out = W(r) (or dW/dr) element by element."""
    for m in range(len(r)):
        out[m] = dw(r[m], k) if derivative else w(r[m], k)
