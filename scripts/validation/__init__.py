"""The validation cases of scripts/validate.py, a module per family of cases; each public function
NAME(ranks) runs its cases and returns the section of docs/VALIDATION.md: title, command, rows, image
and note. runs.py runs a case, figures.py saves a plot, page.py writes the page."""

import matplotlib

matplotlib.use("Agg")  # before any module of the package imports pyplot: the plots are written, never shown
