"""Axisymmetric collapse of a sand column on a rough floor in true 3D, mu(I) rheology (Lube et al. 2004; 004_ Sec. 5.2).

A cylinder of radius r_0 and height H_0 = a r_0 stands on the middle of a
round no-slip floor and is released at t = 0 (the lifted tube is not
modelled). The sand and its defaults are granular_column.py's; 004_ Table 3
(references.LUBE_TABLE_3) lists the paper's 2D runs of these columns. The
front (largest distance of a grain from the axis) and the grains' force
on the floor (force_floor_x, _y, _z) are columns of
diagnostics.csv; the deposit's runout r_inf is measure.radial_runout of the
last frame, compared with references.axisymmetric_runout.

``shape=slab`` runs lube_collapse_2d's planar column (length r_0 against a
free-slip back wall) with the 3D code instead: a slab ``width`` particles
across, periodic across, so that its runout (measure.runout of the x-z
positions) can be set beside the 2D one and Lube's planar law.
"""

from mpisph.case import Case, Param, Wall
from mpisph.geometry import bed_layers, depth, support_layers, upright_cylinder
from mpisph.granular_column import column_case_settings, column_params, planar_column, sand
from mpisph.references import LUBE_R0, axisymmetric_runout

PARAMS = {
    "r_0": Param(LUBE_R0, "m", "radius of the column (Lube et al. 2004); the slab's length", positive=True),
    **column_params(a=0.55, dp=0.00486, m_0=1.4),  # 004_ Table 3, row 2 (2D, dp 2.2 mm); dp = r_0 / 20, H_0 = 11 dp
    "shape": Param("cylinder", "-", "cylinder: axisymmetric; slab: the planar column, periodic across",
                   choices=("cylinder", "slab")),
    "width": Param(8, "-", "particles across the slab (shape=slab)", positive=True),
    "t_end": Param(0.6, "s", "simulated end time", positive=True),
    "output_interval": Param(0.05, "s", "simulated time between frames", positive=True),
}


def setup(p):
    if p.shape == "slab":
        return planar_column(p, p.r_0, back_wall_slip=True, across=p.width * p.dp)
    H0 = p.a * p.r_0
    layers = support_layers(p.h_factor)
    margin = layers * p.dp
    column = upright_cylinder((0.0, 0.0, 0.0), p.r_0, H0, p.dp, "the column")
    radius = p.r_0 * (1.0 + 2.0 * float(axisymmetric_runout(p.a))) + margin  # room for grains thrown ahead
    floor = bed_layers((-radius, -radius), (radius, radius), p.dp, layers,
                       keep=lambda x: x[:, 0] ** 2 + x[:, 1] ** 2 < radius**2)
    edge = radius + margin
    return Case(
        domain=((-edge, -edge, -margin), (edge, edge, 1.5 * H0 + margin)),
        walls=[Wall("floor", floor, distance=depth)],
        **column_case_settings(p, sand(p, H0), column, H0, front_axes=(0, 1), sides={"H_0": H0}),
    )
