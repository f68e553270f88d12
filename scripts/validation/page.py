"""docs/VALIDATION.md: one section per validation, each behind a marker, so that a run of some
sections keeps the others (scripts/production.py writes its page the same way)."""

MARK = "<!-- section: {} -->"
OPENING = MARK.split("{")[0]  # what every marker begins with
HEAD = ("# Validation\n\nWritten by `python scripts/validate.py` (each section's command gives its rank "
        "count; `--only NAME ...` re-runs some and keeps the other sections); the tests in "
        "`tests/test_validation.py`, `tests/test_validation_solids.py` and `tests/test_validation_beam.py` "
        "assert the same comparisons.\n\n")


def existing_sections(page):
    """{name: text} of the sections of an existing page, by their markers."""
    if not page.exists():
        return {}
    out = {}
    for chunk in page.read_text().split(OPENING)[1:]:
        name = chunk.split(" -->", 1)[0]
        out[name] = OPENING + chunk.rstrip("\n") + "\n"
    return out


def existing_head(page):
    """The text of an existing page before its first section marker, or None: a run of some sections
    keeps it (scripts/production.py --only), with what was added to it by hand."""
    if not page.exists():
        return None
    text = page.read_text()
    return text[:text.index(OPENING)] if OPENING in text else None


def section(name, title, cmd, rows, image, note):
    """The Markdown of one validation: its title, command, table of rows (quantity, mpisph, reference,
    error, tolerance; a sixth entry, whether the row meets its tolerance, is not shown), note and plot."""
    table = "\n".join(f"| {' | '.join(r[:5])} |" for r in rows)
    return (f"{MARK.format(name)}\n## {title}\n\n`{cmd}`\n\n"
            f"| quantity | mpisph | reference | error | tolerance |\n"
            f"|---|---|---|---|---|\n{table}\n\n{note + chr(10) + chr(10) if note else ''}"
            f"![{title}](img/{image})\n")


def write(page, sections, order, head=HEAD):
    """Write ``head`` and ``sections`` ({name: text}) to ``page``, in the order of the names in
    ``order``."""
    page.write_text(head + "\n".join(sections[k] for k in order if k in sections))
