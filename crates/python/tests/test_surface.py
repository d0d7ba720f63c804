"""Surfaces: reading instrument files (against the independent reader SurfaceTopography and
the values the data's README gives), arrays in and out, synthesis, statistics and operations."""

from __future__ import annotations

import numpy as np
import pytest

import gonio
from conftest import SURFACE_DATA, oracle_missing


def test_read_x3p_matches_surfacetopography():
    path = SURFACE_DATA / "x3p-2.x3p"
    s = gonio.read_surface(path)
    try:
        import SurfaceTopography as st
    except ImportError:
        oracle_missing("SurfaceTopography is not installed (pip install SurfaceTopography)")
    t = st.read_topography(str(path))
    ref = gonio.Surface.from_topography(t)
    assert s.shape == ref.shape
    np.testing.assert_allclose(s.heights, ref.heights, rtol=1e-12, atol=0)
    assert s.dx == pytest.approx(ref.dx, rel=1e-12)
    back = s.to_topography()
    np.testing.assert_allclose(np.asarray(back.heights()).T, s.heights, rtol=0, atol=0)


def test_heights_are_a_read_only_view_in_metres():
    h = np.random.default_rng(1).normal(0, 1e-7, (32, 48))
    s = gonio.Surface.from_array(h, 0.5e-6)
    assert s.shape == (32, 48) and s.dx == s.dy == 0.5e-6
    v = s.heights
    np.testing.assert_array_equal(v, h)
    assert not v.flags.writeable
    assert v.base is not None  # a view of the surface's own array, not a copy
    with pytest.raises(ValueError):
        v[0, 0] = 1.0


def test_nan_marks_unmeasured_points():
    h = np.zeros((16, 16))
    h[3, 4] = np.nan
    s = gonio.Surface.from_array(h, 1e-6)
    assert np.isnan(s.heights[3, 4]) and np.isfinite(s.heights).sum() == 255
    assert s.statistics()["valid_fraction"] == pytest.approx(255 / 256)


def test_synthesis_statistics_and_operations():
    s = gonio.synthesize(100e-9, 5e-6, 256, 0.5e-6, seed=3)
    again = gonio.synthesize(100e-9, 5e-6, 256, 0.5e-6, seed=3)
    np.testing.assert_array_equal(s.heights, again.heights)
    st = s.statistics()
    # A synthesis draws Sq exactly (the generator rescales to it).
    assert st["sq_m"] == pytest.approx(100e-9, rel=1e-6)
    # Gaussian ACF exp(-r²/T²): Sdq = √2·Sq·√2/T = 2 Sq / T for both axes together, 0.04;
    # forward differences on 10 points per T read a few per cent low.
    assert st["sdq"] == pytest.approx(0.04, rel=0.08)
    np.testing.assert_allclose(s.statistics()["sq_m"], np.nanstd(s.level().heights), rtol=1e-9)
    c = s.crop(10, 20, 100, 50)
    np.testing.assert_array_equal(c.heights, s.heights[20:70, 10:110])
    r = s.rotate(90.0)
    assert r.shape == s.shape
    with pytest.raises(ValueError, match="acf"):
        gonio.synthesize(1e-7, 1e-6, 64, 1e-7, acf="lorentzian")


def test_bad_inputs_raise_python_exceptions(tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.x3p"):
        gonio.read_surface(tmp_path / "nope.x3p")
    bad = tmp_path / "bad.sdf"
    bad.write_bytes(b"aBCR-1.0\nManufacID = x\nNumPoints = 99999999\n")
    with pytest.raises(ValueError, match="bad.sdf"):
        gonio.read_surface(bad)
    with pytest.raises(ValueError):
        gonio.Surface.from_array(np.zeros((4, 4)), -1.0)
    with pytest.raises(ValueError):
        gonio.Surface.from_array(np.full((4, 4), np.inf), 1e-6)
