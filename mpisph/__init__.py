"""mpisph: MPI-parallel SPH for fluids and geomaterials."""

__version__ = "0.1.0"
