"""Where a 2D soil's lateral stress goes: the change of sum_i V_i sigma_xx split by cause and by band.

    .venv/bin/python scripts/stress_budget.py CASE [--set NAME=VALUE ...] [--t-end 1] [--every 0.1]
                                              [--rows 5] [--out runs/stress_budget]

Runs CASE (a riemann_granular case in 2D, one rank) with its stress update watched. At every update
the change of each grain's sigma_xx is split into
- the stress diffusion's dt D_i (the scheme's own form, from the stress before the update);
- the elastic rate's: the same update rerun on a copy with no diffusion and no yield (Jaumann and
  Hooke terms of 000_ Eq. 10 under the same velocity gradient);
- the plastic rest: the plastic rate of Eq. 10 and the return mapping;
each integrated over the grains (V = m / rho) of three bands: within 2.5 dp of the soil's top, within
2.5 dp of its bottom, and between. Every ``--every`` s it prints the thrust ratio (measure.thrust_ratio)
and the accumulated terms; at the end, for the ``--rows`` lowest and highest rows of grains, each
grain's accumulated elastic and diffusion parts (kPa), left to right. The diffusion conserves
sum V sigma (its pair term is antisymmetric): its three bands sum to zero.
"""

import argparse
import sys

import numpy as np

from mpisph.arguments import parse_sets
from mpisph.case import build_case, load_case_module, resolve_params
from mpisph.errors import InputError
from mpisph.measure import thrust_ratio
from mpisph.particles import WALL, WALL_SLIP
from mpisph.physics import drucker_prager as dp_module

BANDS = ("top", "middle", "bottom")
PARTS = ("diffusion", "elastic", "plastic")


class Budget:
    """Accumulates the split of each grain's sigma_xx change (module docstring); per grain in arrays
    indexed by global id."""

    def __init__(self, every):
        self.every, self.t, self.next_report = every, 0.0, 0.0
        self.bands = {(b, p): 0.0 for b in BANDS for p in PARTS}
        self.grain = {p: np.zeros(0) for p in PARTS[:2]}
        self.position = np.zeros((0, 2))
        self.seen = np.zeros(0, bool)

    def record(self, scheme, ctx, dt, update):
        pa, m = ctx.particles, scheme.material
        n = pa.n_owned
        before = pa.stress[:n].copy()
        diffusion = scheme.diffusion_rate(ctx)
        diffusion = diffusion.copy() if len(diffusion) else np.zeros((n, 6))  # the update reuses its scratch
        elastic = pa.stress.copy()
        dp_module.drucker_prager_update(n, *scheme.gradient_args(ctx), dp_module.NO_DIFFUSION, m.K, m.G, 0.0, 0.0,
                                        np.inf, dt, elastic, pa.plastic_strain.copy())
        update(ctx, dt)
        grains = ~np.isin(pa.kind[:n], (WALL, WALL_SLIP))
        volume = pa.mass[:n] / pa.rho[:n]
        parts = {"diffusion": dt * diffusion[:, 0], "elastic": elastic[:n, 0] - before[:, 0]}
        parts["plastic"] = pa.stress[:n, 0] - before[:, 0] - parts["diffusion"] - parts["elastic"]
        self.dp = float(np.median(volume[grains])) ** (1.0 / pa.x.shape[1])  # the spacing, from the volumes
        for band, mask in self._bands(pa.x[:n], grains, self.dp).items():
            for part, change in parts.items():
                self.bands[band, part] += float(np.sum(volume[mask] * change[mask]))
        self._per_grain(pa.gid[:n][grains], pa.x[:n][grains], {p: parts[p][grains] for p in self.grain})
        self.t += dt
        if self.t >= self.next_report:
            self.next_report += self.every
            self._report(pa, n, grains, volume)

    def _per_grain(self, gid, x, parts):
        """Add this update's parts of the grains ``gid`` (at ``x``) to their accumulated ones."""
        size = int(gid.max()) + 1
        if size > len(self.seen):
            grow = size - len(self.seen)
            self.grain = {p: np.concatenate([v, np.zeros(grow)]) for p, v in self.grain.items()}
            self.position = np.concatenate([self.position, np.zeros((grow, 2))])
            self.seen = np.concatenate([self.seen, np.zeros(grow, bool)])
        for p, change in parts.items():
            self.grain[p][gid] += change
        self.position[gid] = x
        self.seen[gid] = True

    @staticmethod
    def _bands(x, grains, dp):
        y = x[:, -1]
        top, bottom = y[grains].max(), y[grains].min()
        bands = {"top": grains & (y > top - 2.5 * dp), "bottom": grains & (y < bottom + 2.5 * dp)}
        bands["middle"] = grains & ~bands["top"] & ~bands["bottom"]
        return bands

    def _report(self, pa, n, grains, volume):
        frame = {"x": pa.x[:n][grains], "stress": pa.stress[:n][grains], "mass": pa.mass[:n][grains],
                 "rho": pa.rho[:n][grains]}
        terms = " | ".join(f"{b}: " + " ".join(f"{p} {self.bands[b, p]:.0f}" for p in PARTS) for b in BANDS)
        print(f"t {self.t:.3f} s  thrust ratio {thrust_ratio(frame):.3f}  sum V sigma_xx "
              f"{np.sum(volume[grains] * pa.stress[:n, 0][grains]):.0f} N/m  accumulated [N/m]: {terms}", flush=True)

    def rows(self, count):
        """Per row of grains (lowest and highest ``count``), each grain's accumulated parts, left to right."""
        gid = np.flatnonzero(self.seen)
        row = np.rint(self.position[gid, 1] / self.dp - 0.5).astype(int)
        keys = np.unique(row)
        for r in [*keys[:count], *keys[-count:]]:
            in_row = gid[row == r]
            in_row = in_row[np.argsort(self.position[in_row, 0])]
            print(f"row {r}: " + " | ".join(
                f"{p} " + " ".join(f"{v / 1e3:7.2f}" for v in self.grain[p][in_row]) for p in PARTS[:2]) + " [kPa]")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case")
    ap.add_argument("--set", nargs="*", default=[], dest="settings", metavar="NAME=VALUE")
    ap.add_argument("--t-end", type=float, default=1.0)
    ap.add_argument("--every", type=float, default=0.1, help="simulated seconds between printed lines")
    ap.add_argument("--rows", type=int, default=5)
    ap.add_argument("--out", default="runs/stress_budget")
    a = ap.parse_args()
    try:
        module = load_case_module(a.case)
        case = build_case(module, resolve_params(module, parse_sets(a.settings)))
    except InputError as e:
        ap.error(str(e))
    if case.scheme != "riemann_granular" or case.dim != 2:
        ap.error(f"{a.case} runs {case.scheme} in {case.dim}D: this script watches riemann_granular's stress "
                 "update in 2D (column_collapse_2d, cohesive_failure_2d, vertical_cut)")
    budget = Budget(a.every)
    update = dp_module.RiemannGranular.update_stress

    def watched(scheme, ctx, dt):
        budget.record(scheme, ctx, dt, lambda c, t: update(scheme, c, t))

    dp_module.RiemannGranular.update_stress = watched
    from mpisph.__main__ import main as mpisph_main
    code = mpisph_main([a.case, *(["--set", *a.settings] if a.settings else []), "--t-end", str(a.t_end),
                        "--out", a.out])
    if code:
        sys.exit(code)
    budget.rows(a.rows)


if __name__ == "__main__":
    main()
