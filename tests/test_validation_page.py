"""scripts/validation/page.py: docs/VALIDATION.md's sections behind their markers, so that a run of
some sections (validate.py --only) keeps the others as they were and in the registry's order."""

from repo_script import load_package


def test_a_rerun_section_replaces_its_own_text_and_keeps_the_others(tmp_path):
    page = load_package("validation.page")
    path = tmp_path / "VALIDATION.md"
    rows = [("runout", "0.55", "0.60", "-8%", "15%", True), ("rest", "2e-3", "<= 1e-3", "-", "1e-3", False)]
    first = {"a": page.section("a", "Case A", "mpirun -n 2 python -m mpisph a", rows, "a.png", "A's note."),
             "b": page.section("b", "Case B", "mpirun -n 1 python -m mpisph b", rows[:1], "b.png", "")}
    page.write(path, first, ["b", "a", "c"])
    text = path.read_text()
    assert text.startswith(page.HEAD) and text.index("## Case B") < text.index("## Case A")
    assert "| runout | 0.55 | 0.60 | -8% | 15% |" in text and "True" not in text and "False" not in text
    assert "A's note.\n\n![Case A](img/a.png)" in text and "\n\n\n![Case B]" not in text
    assert page.existing_sections(path) == first

    again = page.existing_sections(path)
    again["a"] = page.section("a", "Case A", "mpirun -n 2 python -m mpisph a", rows[:1], "a.png", "Rerun.")
    page.write(path, again, ["a", "b"])
    kept = page.existing_sections(path)
    assert kept["b"] == first["b"] and "Rerun." in kept["a"] and "| rest |" not in kept["a"]
    assert page.existing_sections(tmp_path / "missing.md") == {}


def test_the_text_above_the_sections_is_read_back_as_written(tmp_path):
    """What a page holds before its first section (production.py --only keeps it, hand-written
    paragraphs included); None for a page that is missing or has no section."""
    page = load_package("validation.page")
    path = tmp_path / "PAGE.md"
    head = "# Page\n\nA paragraph added by hand.\n\n"
    page.write(path, {"a": page.section("a", "Case A", "cmd", [], "a.png", "")}, ["a"], head=head)
    assert page.existing_head(path) == head
    assert page.existing_head(tmp_path / "missing.md") is None
    path.write_text("# No sections\n")
    assert page.existing_head(path) is None
