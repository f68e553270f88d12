"""The validation cases of scripts/validate.py, a module per family of cases. The sections are the
functions that validate.py's VALIDATIONS names, each called with the rank count (the beam tables also
with h_over_dp and v_fs) and returning the section of docs/VALIDATION.md: title, command, rows, image
and note. runs.py runs a case, figures.py saves a plot, page.py writes the page."""

import matplotlib

matplotlib.use("Agg")  # before any module of the package imports pyplot: the plots are written, never shown
