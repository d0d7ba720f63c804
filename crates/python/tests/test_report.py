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


def test_conformance_on_gonio_returns_the_results_and_writes_the_report(tmp_path: Path) -> None:
    out = tmp_path / "conformance"
    results = gonio.report.conformance(out, renderers=["gonio"], spp=16)
    assert results["report"] == out / "report.html"
    html = results["report"].read_text(encoding="utf-8")
    assert (out / "results.json").is_file()
    names = [s["scene"]["id"] for s in results["scenes"]]
    assert "white_furnace" in names and "metamer_a" in names
    for scene in results["scenes"]:
        (run,) = scene["runs"]
        assert run["renderer"] == "gonio"
        assert run["verdict"] == "pass", scene["scene"]["id"]
        assert f"<h2>{scene['scene']['id']}</h2>" in html


def test_conformance_refuses_an_unknown_renderer_and_a_bad_spp(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="unknown renderer 'povray'"):
        gonio.report.conformance(tmp_path, renderers=["povray"])
    with pytest.raises(ValueError, match="not between 1 and 65536"):
        gonio.report.conformance(tmp_path, renderers=["gonio"], spp=0)
