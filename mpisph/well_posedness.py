"""Where the mu(I) law is well-posed (Barker et al. 2015; Barker & Gray 2017).

The incompressible equations of motion with the friction mu(I) are well-posed
only where

    C(I) = 4 nu^2 - 4 nu + mu^2 (1 - nu / 2)^2 < 0,   nu = I mu'(I) / mu(I)

(Barker, Schaeffer, Bohorquez & Gray 2015, J. Fluid Mech. 779, 794-818; the
form of Barker & Gray 2017, J. Fluid Mech. 828, 5-32, their Eq. 3.9). Where
C > 0 a perturbation of wavenumber k grows at a rate that rises without bound
with k, so a discretisation resolves faster growth the finer it is and its
results depend on the resolution rather than converge. C(0) = mu(0)^2 > 0:
rate-independent friction (nu = 0) is ill-posed. For the law of 004_ Eq. 7 nu
rises from 0 at I = 0 to a largest value near I = I_0 and falls again, and the
law is well-posed in one window of inertial numbers (or nowhere): glass beads
(004_ Table 1, I_0 = 0.279) from I = 0.019 to 0.85, the 0.32 mm sand of
Lube's columns (I_0 = 2.65) from 0.43 to 1.8 (tests/test_well_posedness.py).

The criterion is the incompressible one; 004_'s grains are weakly compressible
(Mach 0.1) and dilate with I (Eq. 8). Barker, Schaeffer, Shearer & Gray (2017,
Proc. R. Soc. A 473) show that compressibility can make the equations
well-posed under conditions on the dilatancy law; whether Eq. 8 meets them is
not established here. These functions tell in which range of I a flow runs,
not how the discrete scheme behaves.
"""

import math

import numpy as np

from .particles import MOVING
from .physics.mu_i_law import friction


def ill_posedness(I, m):
    """C(I) of the module docstring, for a number or an array of I: negative where the law is
    well-posed. mu is mu_i_law.friction (004_ Eq. 7, Eq. 18 with m.I_s > 0), mu' its derivative
    (mu_2 - mu_s) I_0 / (I + I_s + I_0)^2."""
    I = np.asarray(I, dtype=float)
    mu = friction(I, m)
    nu = I * (m.mu_2 - m.mu_s) * m.I_0 / (I + m.I_s + m.I_0) ** 2 / mu
    return 4.0 * nu * nu - 4.0 * nu + mu * mu * (1.0 - 0.5 * nu) ** 2


def well_posed_window(m, lowest=1e-9, highest=1e3, points=2400):
    """(I_1, I_2): the inertial numbers between which C(I) < 0, each to a relative 1e-10 by
    bisection from a logarithmic scan of [lowest, highest] I_0 (C depends on I / I_0 where I_s = 0);
    None where C >= 0 throughout; ValueError where the scan finds more than one window or one
    reaching its ends."""
    I = m.I_0 * np.geomspace(lowest, highest, points)
    well = ill_posedness(I, m) < 0.0
    if not well.any():
        return None
    first, last = np.flatnonzero(well)[[0, -1]]
    if first == 0 or last == points - 1 or not well[first:last + 1].all():
        raise ValueError(f"mu(I) is not well-posed in one window inside [{lowest:g}, {highest:g}] I_0")
    return _crossing(I[first - 1], I[first], m), _crossing(I[last], I[last + 1], m)


def _crossing(lo, hi, m):
    """The I in (lo, hi) where C changes sign, by bisection in log I."""
    sign_lo = ill_posedness(lo, m) < 0.0
    while hi - lo > 1e-10 * hi:
        mid = math.sqrt(lo * hi)
        if (ill_posedness(mid, m) < 0.0) == sign_lo:
            lo = mid
        else:
            hi = mid
    return math.sqrt(lo * hi)


def dissipation_rate(frame):
    """Each particle's viscous dissipation rate eta gamma_dot^2 m / rho [W] (0 for a wall)."""
    return np.where(frame["kind"] == MOVING, frame["eta"] * frame["gamma_dot"] ** 2 * frame["mass"] / frame["rho"],
                    0.0)


def ill_posed_dissipation_share(frame, window):
    """The share of a frame's viscous dissipation (dissipation_rate) that happens at inertial
    numbers outside ``window`` (I_1, I_2) (None: all of it): how much of the flow runs where the law
    is ill-posed. NaN in a frame that dissipates nothing."""
    power = dissipation_rate(frame)
    total = power.sum()
    if not total > 0.0:
        return math.nan
    if window is None:
        return 1.0
    I = frame["inertial_number"]
    return float(power[(I <= window[0]) | (I >= window[1])].sum() / total)


def ill_posed_energy_share(frames, window):
    """The share of the energy a run dissipated, the frames' dissipation rates integrated in time
    by trapezoids, at inertial numbers outside ``window``; NaN where nothing was dissipated."""
    t = np.array([f["t"] for f in frames])
    rate = np.array([dissipation_rate(f).sum() for f in frames])
    share = np.nan_to_num(np.array([ill_posed_dissipation_share(f, window) for f in frames]))
    energy = np.trapezoid(rate, t)
    return float(np.trapezoid(rate * share, t) / energy) if energy > 0.0 else math.nan
