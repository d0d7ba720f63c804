"""Pictures and colour from Python: the white furnace renders white, a scene dict renders as
its file, and colorimetry agrees with colour-science where it is installed."""

from __future__ import annotations

import numpy as np
import pytest

import gonio
from conftest import ROOT, oracle_missing

FURNACE = ROOT / "examples" / "furnace.toml"


def test_furnace_renders_white_from_a_file_and_from_a_dict():
    img = gonio.render(FURNACE, spp=16, seed=1)
    assert img.dtype == np.float32 and img.shape == (40, 40, 3)
    # A white Lambertian sphere in a uniform sky of radiance 1: every pixel estimates 1. The
    # sky seen past the sphere is 1 exactly; on the sphere Russian roulette and the weighting
    # of light and BRDF samples make each pixel's 16 paths scatter about 1, and the mean of
    # 1600 pixels lies within a few tenths of a per cent of it.
    assert img.min() > 0 and abs(img.mean() - 1.0) < 0.005, img.mean()
    np.testing.assert_array_equal(img[0, 0], [1.0, 1.0, 1.0])
    import tomllib

    scene = tomllib.loads(FURNACE.read_text())
    np.testing.assert_array_equal(gonio.render(scene, spp=16, seed=1), img)
    with pytest.raises(ValueError, match="scene"):
        gonio.render({"camera": {}}, spp=1)
    with pytest.raises(FileNotFoundError):
        gonio.render(ROOT / "nope.toml")


def test_colour_of_a_flat_spectrum_and_against_colour_science():
    w = np.arange(380.0, 781.0, 5.0)
    grey = gonio.color.xyz(w, np.full_like(w, 0.5))
    # A flat reflectance ρ has Y = 100 ρ and the chromaticity of the illuminant.
    assert grey["xyz"][1] == pytest.approx(50.0, rel=1e-4)
    assert grey["cielab"][1] == pytest.approx(0.0, abs=1e-3)
    try:
        import colour
    except ImportError:
        oracle_missing("colour-science is not installed (pip install colour-science)")
    values = 0.2 + 0.6 * np.exp(-((w - 600.0) / 40.0) ** 2)
    sd = colour.SpectralDistribution(dict(zip(w, values)))
    ref = colour.sd_to_XYZ(
        sd,
        cmfs=colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"],
        illuminant=colour.SDS_ILLUMINANTS["D65"],
        method="ASTM E308",
    )
    ours = gonio.color.xyz(sd)
    # Both follow ASTM E308; the CIE tables agree to their printed digits.
    np.testing.assert_allclose(ours["xyz"], ref, rtol=2e-3)


def test_from_lab_gives_the_spectrums_colour_back_and_colour_sciences_xyz():
    # A spectrum's CIELAB taken back through from_lab reports the spectrum's own XYZ and sRGB
    # (D65, 10°: the multi-angle instruments' conditions).
    w = np.arange(400.0, 701.0, 10.0)
    values = 0.1 + 0.5 * np.exp(-((w - 480.0) / 50.0) ** 2)
    spectrum = gonio.color.xyz(w, values, observer=10)
    back = gonio.color.from_lab(spectrum["cielab"], observer=10)
    np.testing.assert_allclose(back["xyz"], spectrum["xyz"], rtol=1e-12)
    assert back["srgb_hex"] == spectrum["srgb_hex"]
    try:
        import colour
    except ImportError:
        oracle_missing("colour-science is not installed (pip install colour-science)")
    white = np.array(spectrum["white_xyz"])
    ref = colour.Lab_to_XYZ(np.array(spectrum["cielab"]), colour.XYZ_to_xy(white / 100.0)) * white[1]
    np.testing.assert_allclose(back["xyz"], ref, rtol=1e-9)


def test_booth_writes_its_files_and_returns_the_summary(tmp_path):
    solid = ROOT / "examples" / "coatings" / "red_solid.toml"
    summary = gonio.booth(solid, tmp_path / "booth", spp=2, seed=5, size=(24, 16))
    assert summary["seed"] == 5
    assert [v["name"] for v in summary["views"]] == ["near-specular", "45", "flank"]
    for view in summary["views"]:
        # A red under a clear coat at 2000 lx: darker than the white (E/pi = 637 cd/m2).
        assert 0 < view["specimen_luminance_cd_m2"] < summary["white_xyz_cd_m2"][1]
        assert (tmp_path / "booth" / f"{view['name']}.exr").is_file()
        assert [d["display"] for d in view["displays"]] == ["srgb", "p3"]
    assert (tmp_path / "booth" / "manifest.json").is_file()
    neither = tmp_path / "neither.toml"
    neither.write_text("[paint]\ncolour = 1\n")
    with pytest.raises(ValueError, match="neither a booth spec nor a coating"):
        gonio.booth(neither, tmp_path / "x")
    with pytest.raises(FileNotFoundError):
        gonio.booth(tmp_path / "missing.gbrdf", tmp_path / "x")
