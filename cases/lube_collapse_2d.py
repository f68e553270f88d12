"""Planar collapse of a sand column on a rough floor, mu(I) rheology (Lube et al. 2005; 004_ Sec. 5.2).

A column L_0 long and H_0 = a L_0 high stands against a back wall at x = 0 and
is released at t = 0; it spreads along +x over a no-slip floor. The back wall
is free-slip by default, which makes the run the right half of a symmetric
column 2 L_0 wide. The sand and its defaults are granular_column.py's. The
front (largest x of a grain) is a column of diagnostics.csv; the deposit's
runout L_inf is measure.runout of the last frame, compared with
references.planar_runout.
"""

from mpisph.case import Case, Param, Wall
from mpisph.geometry import bed, box, support_layers
from mpisph.granular_column import column_case_settings, column_params, sand
from mpisph.references import planar_runout

PARAMS = {
    "L_0": Param(0.0972, "m", "length of the column from the back wall", positive=True),
    **column_params(a=0.9, dp=0.003, m_0=1.2),  # 004_ Table 3, row 3
    "back_wall": Param("free_slip", "-", "the wall behind the column", choices=("free_slip", "no_slip")),
    "t_end": Param(1.0, "s", "simulated end time", positive=True),
    "output_interval": Param(0.05, "s", "simulated time between frames", positive=True),
}


def setup(p):
    H0 = p.a * p.L_0
    material = sand(p, H0)
    column = box((0.0, 0.0), (p.L_0, H0), p.dp, "the column")
    layers = support_layers(p.h_factor)
    margin = layers * p.dp
    floor_end = p.L_0 * (1.0 + 3.0 * float(planar_runout(p.a))) + margin  # room for grains thrown ahead
    floor_x, floor_n, floor_d = bed((-margin,), (floor_end,), p.dp, layers)
    back = box((-margin, 0.0), (0.0, H0 + margin), p.dp, "the back wall")
    back_n = back * 0.0
    back_n[:, 0] = 1.0
    return Case(
        domain=((-margin, -margin), (floor_end + margin, 1.5 * H0 + margin)),
        walls=[Wall("floor", floor_x, floor_n, distance=floor_d),
               Wall("back_wall", back, back_n, slip=p.back_wall == "free_slip", distance=-back[:, 0])],
        **column_case_settings(p, material, column, H0, front_axes=(0,)),
    )
