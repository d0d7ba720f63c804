"""Coatings from Python give the command line's numbers: the summary, the multi-angle reading,
a formulation study and the table, for a file and for the same formulation given as a dict; the
panel picture is a picture of the panel; bad formulations are errors that say what is wrong."""

from __future__ import annotations

import json
import subprocess
import tomllib

import numpy as np
import pandas as pd
import pytest

import gonio
from conftest import ROOT

EXAMPLES = ROOT / "examples" / "coatings"


def cli_json(gonio_cli, *args) -> dict:
    out = subprocess.run([gonio_cli, *map(str, args)], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def test_info_and_study_equal_the_cli(gonio_cli):
    path = EXAMPLES / "red_rough.toml"
    cli = cli_json(gonio_cli, "coating", "info", path, "--samples", "256", "--json")
    py = gonio.coating.info(path, samples=256)
    assert py == {k: v for k, v in cli.items() if k != "file"}
    df = gonio.coating.multiangle(path, samples=256)
    assert list(df["geometry"]) == list(gonio.E2194)
    assert [m["L"] for m in cli["multiangle"]] == list(df["L"])
    assert df.attrs["flop_index"] == cli["flop_index"]

    cli_study = cli_json(gonio_cli, "coating", "study", path, "--vary", "thickness",
                         "--values", "20,60", "--samples", "128", "--json")
    study = gonio.coating.study(path, "thickness", [20, 60], samples=128)
    assert list(study["value"]) == [20.0, 60.0]
    assert study.attrs["label"] == cli_study["label"]
    for row, r in zip(cli_study["rows"], study.itertuples()):
        assert row["gu60"] == r.gu60 and row["doi"] == r.doi
        assert row["multiangle"][0]["L"] == getattr(r, "L_45as15")


def test_readings_are_the_summary_and_the_multiangle_reading():
    """The lab's readings from Python: at the same walks (and seed 0) the multi-angle colour is
    :func:`multiangle`'s and the albedo :func:`info`'s (16 times the walks), bit for bit; every
    reading is there, with the swatches; a bad standard is a ValueError."""
    path = EXAMPLES / "silver_metallic.toml"
    r = gonio.coating.readings(path, walks=64, brdf_walks=4, gloss_walks=2, albedo_samples=1024)
    df = gonio.coating.multiangle(path, samples=64)
    assert [m["L"] for m in r["multiangle"]] == list(df["L"])
    assert r["flop_index"] == df.attrs["flop_index"]
    assert r["albedo"] == gonio.coating.info(path, samples=64)["albedo"]
    assert all(m["srgb_hex"].startswith("#") for m in r["multiangle"])
    assert len(r["inplane_brdf"]["scatter_deg"]) == len(r["inplane_brdf"]["brdf_per_sr"])
    assert r["gloss"]["doi_uncertainty"] > 0
    assert r["walks"]["per_geometry"] == 64
    with pytest.raises(ValueError, match="e2194"):
        gonio.coating.readings(path, standard="e9999")


def test_a_dict_is_read_as_the_toml_with_its_tables(tmp_path):
    text = (
        "[top]\nroughness = { alpha = 0.1 }\n"
        "[coat]\nindex = 1.5\nthickness_um = 40\n"
        "[base]\nkind = \"diffuse\"\nreflectance = 0.3\n"
        "[flakes]\nkind = \"aluminium\"\ncoverage = 0.4\ntilt_deg = 12\n"
    )
    path = tmp_path / "grey.toml"
    path.write_text(text)
    as_dict = tomllib.loads(text)
    assert gonio.coating.info(as_dict, samples=64) == gonio.coating.info(path, samples=64)
    assert gonio.coating.read(as_dict).source == "dict"


def test_table_equals_the_cli(gonio_cli, tmp_path):
    path = EXAMPLES / "red_solid.toml"
    out = tmp_path / "red.gbrdf"
    subprocess.run([gonio_cli, "coating", "compute", path, "-o", out, "--resolution", "8,8,4"],
                   check=True, capture_output=True)
    cli = gonio.brdf.open(out)
    py = gonio.coating.compute(path, resolution=(8, 8, 4))
    assert py.resolution == cli.resolution == [8, 8, 4]
    wi = np.array([[0.3, 0.0, np.sqrt(1 - 0.09)]])
    wo = np.array([[-0.5, 0.1, np.sqrt(1 - 0.26)]])
    np.testing.assert_array_equal(py.eval(wi, wo), cli.eval(wi, wo))


def test_panel_picture_shows_the_panel():
    red = {"coat": {"index": 1.5, "thickness_um": 40},
           "base": {"kind": "diffuse", "reflectance": {"nm": [400, 550, 600, 700],
                                                       "values": [0.05, 0.05, 0.6, 0.7]}}}
    srgb = gonio.coating.panel_picture(red)
    assert srgb.dtype == np.uint8 and srgb.shape[2] == 3 and srgb.shape[0] == 280
    # The panel is red: where the picture is bright, red dominates green and blue (the softbox's
    # mirror on the smooth coat is white, so compare the mean over the picture's lit pixels).
    lit = srgb.reshape(-1, 3)[srgb.reshape(-1, 3).max(axis=1) > 60].astype(float)
    assert len(lit) > 1000
    r, g, b = lit.mean(axis=0)
    assert r > 1.3 * g and r > 1.3 * b, (r, g, b)


def test_bad_formulations_say_what_is_wrong():
    with pytest.raises(ValueError, match="index"):
        gonio.coating.read({"coat": {"thickness_um": 40}, "base": {"kind": "diffuse", "reflectance": 0.3}})
    with pytest.raises(ValueError, match="vary one of"):
        gonio.coating.study(EXAMPLES / "red_solid.toml", "gloss", [1.0], samples=16)
    with pytest.raises(ValueError, match="e2194"):
        gonio.coating.multiangle(EXAMPLES / "red_solid.toml", standard="e9999")
    with pytest.raises(TypeError):
        gonio.coating.read(42)


def test_sensitivity_on_dask_equals_serial_and_the_cli(gonio_cli):
    distributed = pytest.importorskip("distributed")
    path = EXAMPLES / "red_rough.toml"
    args = dict(vary={"roughness": (0.05, 0.2), "thickness": (20, 60)},
                outputs=["gu60", "L@45as15"], method="morris", samples=3, walks=16)
    serial = gonio.coating.sensitivity(path, **args)
    assert len(serial.design) == 9 and list(serial.readings.columns) == ["gu60", "L@45as15"]
    # The clear coat's thickness changes nothing the instruments read: mu* exactly 0.
    mu_star = serial.indices.set_index(["output", "input"])["mu_star"]
    assert mu_star[("gu60", "thickness")] == 0.0 and mu_star[("gu60", "roughness")] > 0.1
    assert "driven by roughness" in serial.summary
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster:
        with distributed.Client(cluster) as client:
            parallel = gonio.coating.sensitivity(path, client=client, rows_per_task=2, **args)
    pd.testing.assert_frame_equal(parallel.readings, serial.readings, check_exact=True)
    pd.testing.assert_frame_equal(parallel.indices, serial.indices, check_exact=True)
    cli = cli_json(gonio_cli, "coating", "sensitivity", path, "--vary",
                   "roughness=0.05:0.2,thickness=20:60", "--outputs", "gu60,L@45as15",
                   "--method", "morris", "--samples", "3", "--walks", "16", "--json")
    assert {k: v for k, v in cli.items() if k != "file"} == serial.json


def test_match_equals_the_cli_and_recovers_a_concentration(gonio_cli, tmp_path):
    red = EXAMPLES / "red_pigmented.toml"
    variant = tmp_path / "variant.toml"
    variant.write_text(red.read_text().replace("concentration = 1.0", "concentration = 0.3"))
    # The target as a DataFrame of CIELAB (gonio.coating.multiangle's columns), and as the CSV
    # of reflectance factors the CLI writes: the same colours, so the same match.
    target = gonio.coating.multiangle(variant)[["geometry", "L", "a", "b"]]
    subprocess.run([gonio_cli, "multiangle", variant, "--spectra", tmp_path / "target.csv"],
                   check=True, capture_output=True)
    m = gonio.coating.match(red, target, "concentration:red=0.1:2", starts=1)
    assert abs(m.constituents["fitted"][0] - 0.3) < 1e-3, m.constituents
    assert m.mean_de00[0] > 2 and m.mean_de00[1] < 0.05, m.mean_de00
    assert "# Two pigments" in m.toml  # the example's comments are kept
    again = gonio.coating.info(m.fitted)
    assert again["multiangle"][2]["L"] == pytest.approx(target["L"][2], abs=0.05)
    cli = cli_json(gonio_cli, "coating", "match", red, "--target", tmp_path / "target.csv",
                   "--vary", "concentration:red=0.1:2", "--starts", "1", "--objective", "de00",
                   "-o", tmp_path / "fitted.toml", "--json")
    assert cli["constituents"][0]["fitted"] == pytest.approx(m.constituents["fitted"][0], abs=1e-6)
    assert [g["name"] for g in cli["geometries"]] == list(m.geometries["geometry"])
    with pytest.raises(ValueError, match="no geometry"):
        gonio.coating.match(red, target.iloc[:2], "concentration:red=0.1:2")
    # The spectral objective on the reflectance factors (the DataFrame's R_ columns) finds the
    # same concentration; on CIELAB alone it is refused (no spectra to compare).
    spectra = gonio.coating.multiangle(variant).drop(columns=["L", "a", "b", "C", "h_deg", "X", "Y", "Z"])
    s = gonio.coating.match(red, spectra, "concentration:red=0.1:2", starts=1, objective="spectral")
    assert abs(s.constituents["fitted"][0] - 0.3) < 1e-3 and s.json["objective"] == "spectral"
    with pytest.raises(ValueError, match="spectr"):
        gonio.coating.match(red, target, "concentration:red=0.1:2", objective="spectral")


WHITE = """# white
[coat]
index = 1.5
thickness_um = 40

[base]
kind = "kubelka-munk"
thickness_um = 30
substrate = 0.6

[[base.pigment]]
library = "titanium_white"
concentration = 1.0
"""

GREEN = WHITE + """
[[base.pigment]]
library = "phthalo_blue_green_shade"
concentration = 0.04

[[base.pigment]]
library = "hansa_yellow_opaque"
concentration = 0.15
"""

CANDIDATES = ["pyrrole_red", "hansa_yellow_opaque", "phthalo_blue_green_shade", "bone_black"]


def _without_times(j: dict) -> dict:
    j = dict(j, seconds=None)
    j["selection"] = dict(j["selection"], seconds=None, screen_seconds=None)
    return j


def test_select_on_dask_equals_serial_and_the_cli(gonio_cli, tmp_path):
    """A green of two library pigments in a white basecoat, matched from the white by selecting
    up to 2 of 4 candidates: the true pigments chosen; the selection on a LocalCluster of two
    worker processes (the finalists searched there) equals the serial one exactly (the times
    aside); the CLI's selection is the same."""
    distributed = pytest.importorskip("distributed")
    (tmp_path / "white.toml").write_text(WHITE)
    (tmp_path / "green.toml").write_text(GREEN)
    spectra = gonio.coating.multiangle(tmp_path / "green.toml").drop(
        columns=["L", "a", "b", "C", "h_deg", "X", "Y", "Z"])
    args = dict(select=2, candidates=CANDIDATES, finalists=2)
    serial = gonio.coating.match(tmp_path / "white.toml", spectra, **args)
    assert sorted(serial.selection["pigments"]) == ["hansa_yellow_opaque",
                                                    "phthalo_blue_green_shade"]
    assert serial.selection["combinations"] == 10 and len(serial.tried) == 10
    assert len(serial.finalists) == 2 and serial.json["objective"] == "spectral"
    assert serial.mean_de00[1] < 0.05
    assert 'library = "hansa_yellow_opaque"' in serial.toml
    fitted = gonio.coating.info(serial.fitted)["multiangle"]
    truth = gonio.coating.info(tmp_path / "green.toml")["multiangle"]
    assert fitted[2]["L"] == pytest.approx(truth[2]["L"], abs=0.05)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster:
        with distributed.Client(cluster) as client:
            parallel = gonio.coating.match(tmp_path / "white.toml", spectra, client=client,
                                           **args)
    assert _without_times(parallel.json) == _without_times(serial.json)
    assert parallel.toml == serial.toml
    spectra.to_csv(tmp_path / "green.csv", index=False)
    cli = cli_json(gonio_cli, "coating", "match", tmp_path / "white.toml", "--target",
                   tmp_path / "green.csv", "--select", "2", "--from", ",".join(CANDIDATES),
                   "--finalists", "2", "-o", tmp_path / "fitted.toml", "--json")
    assert cli["selection"]["pigments"] == serial.selection["pigments"]
    assert cli["selection"]["finalists"][0]["concentrations"] == pytest.approx(
        serial.selection["finalists"][0]["concentrations"], rel=1e-3)
    with pytest.raises(ValueError, match="at least 1 pigment"):
        gonio.coating.match(tmp_path / "white.toml", spectra, select=0)
    with pytest.raises(ValueError, match="did you mean"):
        gonio.coating.match(tmp_path / "white.toml", spectra, select=1, candidates=["pyrole_red"])
