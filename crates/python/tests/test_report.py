"""The demo's report from Python: ``gonio.report.demo`` writes the same report as ``gonio demo``
(both call gonio_report::demo::run), here the quick run."""

from __future__ import annotations

from pathlib import Path

import pytest

import gonio


def test_quick_demo_writes_a_report_with_every_section(tmp_path: Path) -> None:
    out = tmp_path / "demo"
    report = gonio.report.demo(out, quick=True)
    assert report == out / "report.html"
    assert report.is_file()
    html = report.read_text(encoding="utf-8")
    for title in (
        "Surfaces: the epoxy roughness series",
        "A real instrument file: x3p-2.x3p",
        "Isotropy of x3p-2.x3p",
        "The roughness study",
        "Coatings and multi-angle colour",
        "Formulation: a measured paint matched from the pigment library",
        "Texture: sparkle, graininess and orange peel",
        "Standard of appearance: the viewing booth",
    ):
        assert f"<h2>{title}</h2>" in html, title
    assert (out / "study" / "gloss.csv").is_file()


def test_an_output_folder_that_cannot_be_made_is_an_os_error(tmp_path: Path) -> None:
    taken = tmp_path / "taken"
    taken.write_text("a file")
    with pytest.raises(OSError, match="taken"):
        gonio.report.demo(taken / "out", quick=True)
