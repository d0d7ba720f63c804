"""Coatings from their constituents: a clear coat (smooth or rough) over a diffuse or
Kubelka-Munk base, with or without effect flakes (``docs/coatings.md``). The same calls as the
``gonio coating`` commands, so the same numbers.

Read a formulation with :func:`read` (a TOML file, or a dict of the same tables), then ask for
its :func:`info`, its spectral table (:func:`compute`), its multi-angle colour
(:func:`multiangle`, a DataFrame), a formulation study (:func:`study`, a DataFrame) or its
picture on the curved panel (:func:`panel_picture`, a numpy RGB array), which constituents
drive which reading (:func:`sensitivity`, on Dask when given a client), and the formulation
that reproduces a target (:func:`match`).

Units: wavelengths in nm, angles in degrees, reflectances as fractions (0-1), CIELAB under D65
for the 10° observer; the walks' counts are per evaluation (per geometry, per table cell).
"""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd

from . import _gonio
from ._gonio import Coating, Table

__all__ = [
    "Coating",
    "read",
    "info",
    "compute",
    "multiangle",
    "readings",
    "study",
    "panel_picture",
    "sensitivity",
    "Sensitivity",
    "match",
    "Match",
    "TABLE_RESOLUTION",
    "DEFAULT_BANDS_NM",
]

#: The nodes (theta_h, theta_d, phi_d) of ``gonio coating compute``'s table.
TABLE_RESOLUTION = (90, 90, 48)
#: The bands of a coating's tables and readings: 400, 410, ..., 700 nm.
DEFAULT_BANDS_NM = tuple(400.0 + 10.0 * i for i in range(31))
#: Random walks per table cell before any are added (``gonio coating compute --samples``).
TABLE_WALKS = _gonio.TABLE_WALKS
#: The standard error of a cell's L* above which walks are added (``--target-dl``).
TARGET_DL = _gonio.TARGET_DL


def read(
    description: str | os.PathLike | Mapping[str, Any], base_dir: str | os.PathLike = "."
) -> Coating:
    """A formulation: the path of a TOML description (``examples/coatings/*.toml``), or a dict
    of the same tables, e.g. ``{"coat": {"index": 1.5, "thickness_um": 40}, "base": {"kind":
    "diffuse", "reflectance": 0.3}}``; file names in a dict (a top's height map) start in
    ``base_dir``. A :class:`Coating` is returned as it is."""
    if isinstance(description, Coating):
        return description
    if isinstance(description, (str, os.PathLike)):
        return _gonio.read_coating(os.fspath(description), None, False, os.fspath(base_dir))
    if isinstance(description, Mapping):
        return _gonio.read_coating(None, json.dumps(dict(description)), True, os.fspath(base_dir))
    raise TypeError(f"a coating: give a path or a dict, not {type(description).__name__}")


def info(coating: Coating | str | os.PathLike | Mapping[str, Any], samples: int = 4096) -> dict:
    """What ``gonio coating info --json`` prints (without ``file``): ``coat_index`` at 400, 550
    and 700 nm, ``base_reflectance`` per band, ``specular`` (the coat's mirror reflectance at
    20/60/85° and 550 nm; 0 for a rough top), ``albedo`` (directional-hemispherical
    reflectance at 0/45/75°, 550 nm), ``multiangle`` (E2194, D65/10°: ``name``, ``L``, ``a``,
    ``b``, ``C``, ``h_deg``) and ``flop_index``. ``samples``: walks per geometry for a rough top
    or flakes (the albedo uses 16 times as many directions)."""
    return json.loads(read(coating).info_json(int(samples)))


def compute(
    coating: Coating | str | os.PathLike | Mapping[str, Any],
    resolution: Sequence[int] = TABLE_RESOLUTION,
    bands_nm: Sequence[float] = DEFAULT_BANDS_NM,
    samples: int = TABLE_WALKS,
    target_dl: float = TARGET_DL,
) -> Table:
    """The coating's spectral :class:`gonio.Table`, as ``gonio coating compute`` makes it: one
    channel per band (nm), ``samples`` random walks per cell for a rough top or flakes, then more
    (up to 16 times) where the cell's L* is less certain than ``target_dl`` (one standard
    deviation; 0 keeps ``samples`` in every cell). A smooth coat over a diffuse base is exact.
    A smooth top's mirror reflection (a delta) is not in the table; a rough top's is."""
    return read(coating).compute(
        [int(n) for n in resolution], [float(b) for b in bands_nm], int(samples), float(target_dl)
    )


def _reading_frame(columns, factors, wavelengths, flop) -> pd.DataFrame:
    """A multi-angle reading's DataFrame: the columns, then ``R_<nm>nm`` per wavelength, the
    flop index in ``attrs`` (shared with :func:`gonio.multiangle`)."""
    df = pd.DataFrame(columns)
    for i, wl in enumerate(wavelengths):
        df[f"R_{wl:g}nm"] = factors[:, i]
    df.attrs["flop_index"] = flop
    return df


def multiangle(
    coating: Coating | str | os.PathLike | Mapping[str, Any],
    standard: str = "e2194",
    samples: int = 4096,
) -> pd.DataFrame:
    """The multi-angle reading (D65/10°) of the coating at ``standard``'s geometries
    (``"e2194"`` or ``"e2539"``), its BRDF evaluated where the instrument looks (no table),
    ``samples`` walks per geometry. The columns of :func:`gonio.multiangle`; Alman's flop index
    in ``df.attrs["flop_index"]``."""
    return _reading_frame(*read(coating).multiangle_columns(standard, int(samples)))


def readings(
    coating: Coating | str | os.PathLike | Mapping[str, Any],
    standard: str = "e2194",
    incidence_deg: float = 45.0,
    walks: int | None = None,
    brdf_walks: int | None = None,
    gloss_walks: int | None = None,
    albedo_samples: int | None = None,
    seed: int = 0,
) -> dict:
    """Every reading ``gonio lab`` shows of the coating, in one call (``docs/instruments.md``,
    "The lab's readings"): ``gloss`` (ISO 2813 gloss, ASTM E430 haze, DOI with its uncertainty),
    ``multiangle`` (CIELAB D65/10° at ``standard``'s geometries with ``srgb_hex`` swatches),
    ``flop_index``, ``albedo`` (550 nm, 0/45/75°), ``inplane_brdf`` (the luminance BRDF at
    ``incidence_deg``, a smooth top's mirror apart) and ``lightness_curve`` (L* against the
    aspecular angle at 45°). The walks default to the lab's (about 0.25 s of CPU per reading);
    the same ``seed`` repeats a reading, and nearby formulations share their random numbers."""
    none_or_int = lambda v: None if v is None else int(v)  # noqa: E731
    return json.loads(
        read(coating).readings_json(
            standard,
            float(incidence_deg),
            none_or_int(walks),
            none_or_int(brdf_walks),
            none_or_int(gloss_walks),
            none_or_int(albedo_samples),
            int(seed),
        )
    )


def study(
    coating: Coating | str | os.PathLike | Mapping[str, Any],
    vary: str,
    values: Sequence[float],
    standard: str = "e2194",
    samples: int = 8192,
) -> pd.DataFrame:
    """A formulation study (``gonio coating study --json``): ``vary`` one constituent
    (``roughness``: the top's α, 0 smooth; ``tilt``: the flakes' rms tilt, °; ``coverage``;
    ``tio2``: interference flakes' TiO2, nm; ``thickness``: the coat's, µm; or
    ``concentration:NAME``) over ``values``; one row per value: ``value``, ``gu20``, ``gu60``,
    ``gu85`` (ISO 2813 gloss units), ``haze``, ``haze_20_log``, ``doi`` (ASTM E430),
    ``flop_index``, and ``L_G``, ``a_G``, ``b_G`` for each geometry G of ``standard``. The
    constituent's label (with its unit) is in ``df.attrs["label"]``."""
    result = json.loads(
        read(coating).study_json(vary, [float(v) for v in values], standard, int(samples))
    )
    rows = []
    for r in result["rows"]:
        row = {k: r[k] for k in ("value", "gu20", "gu60", "gu85", "haze", "haze_20_log", "doi")}
        row["flop_index"] = np.nan if r["flop_index"] is None else r["flop_index"]
        for g in r["multiangle"]:
            for c in ("L", "a", "b"):
                row[f"{c}_{g['name']}"] = g[c]
        rows.append(row)
    df = pd.DataFrame(rows)
    df.attrs["label"] = result["label"]
    return df


def panel_picture(
    coating: Coating | str | os.PathLike | Mapping[str, Any], linear: bool = False
) -> np.ndarray:
    """The coating on a curved, bonnet-like panel in the dark studio, as ``gonio coating
    study`` draws it: its table computed for the picture (45 × 45 × 24 nodes, 32 walks per
    cell), rendered spectrally (D65), 16 samples per pixel, denoised. A (height, width, 3) uint8
    sRGB array (the picture the PNG holds), or with ``linear`` the float32 linear sRGB
    radiance. A few seconds to a minute on two cores."""
    srgb, radiance, _seconds = read(coating).panel_picture()
    return radiance if linear else srgb


class Sensitivity:
    """What :func:`sensitivity` found: ``summary`` (which constituents drive which reading, in
    words), ``indices`` (a DataFrame, one row per output and constituent: Sobol ``s1``,
    ``s1_conf``, ``st``, ``st_conf``, or Morris ``mu``, ``mu_star``, ``sigma``,
    ``mu_star_conf``; the confidences are 95% half-widths), ``design`` (the points, one column
    per constituent, physical units), ``readings`` (the outputs at each point), ``noise`` (each
    output's standard deviation over re-readings of the base formulation) and ``json`` (the
    structure ``gonio coating sensitivity --json`` prints)."""

    def __init__(self, result: dict, design: pd.DataFrame, readings: pd.DataFrame):
        self.json = result
        self.summary: str = result["summary"]
        self.method: str = result["method"]
        self.design = design
        self.readings = readings
        rows = []
        for o in result["outputs"]:
            for name in o["indices"][next(iter(o["indices"]))]:
                row = {"output": o["output"], "input": name}
                row.update({k: v[name] for k, v in o["indices"].items()})
                rows.append(row)
        self.indices = pd.DataFrame(rows)
        self.noise = pd.Series({o["output"]: o["noise"] for o in result["outputs"]})

    def __repr__(self) -> str:
        return f"Sensitivity({self.method}, {len(self.design)} readings)\n{self.summary}"


def _vary(vary: str | Mapping[str, tuple[float, float]] | Sequence[str]) -> str:
    """``--vary``'s text: ``"tilt=4:20,coverage"``, ``{"tilt": (4, 20)}`` or ``["tilt",
    "coverage"]`` (a name without bounds takes its default range, docs/formulation.md)."""
    if isinstance(vary, str):
        return vary
    if isinstance(vary, Mapping):
        return ",".join(f"{k}={float(lo)}:{float(hi)}" for k, (lo, hi) in vary.items())
    return ",".join(str(v) for v in vary)


def _plan(description, base_dir, vary, outputs, method, samples, standard, walks):
    if isinstance(description, tuple):  # ("toml", text): a Coating's own description
        coating = _gonio.read_coating(None, description[1], False, base_dir)
    else:
        coating = read(description, base_dir)
    return _gonio.sensitivity_plan(coating, vary, outputs, method, samples, standard, walks)


def _read_rows(plan_args: tuple, rows: np.ndarray) -> np.ndarray:
    """Read some rows of a sensitivity's design (a Dask task: the plan is rebuilt where it
    runs, from the formulation's path or dict)."""
    return _plan(*plan_args).read_points(rows)


def sensitivity(
    coating: str | os.PathLike | Mapping[str, Any] | Coating,
    vary: str | Mapping[str, tuple[float, float]] | Sequence[str],
    outputs: Sequence[str] | None = None,
    method: str = "sobol",
    samples: int | None = None,
    standard: str = "e2194",
    walks: int = 1024,
    threshold: float = 0.1,
    client: Any = None,
    rows_per_task: int = 8,
    base_dir: str | os.PathLike = ".",
) -> Sensitivity:
    """Which constituents drive which reading (``gonio coating sensitivity``): Sobol first-order
    and total indices (``method="sobol"``, ``samples`` base points N, default 32: N (d + 2)
    readings) or Morris screening (``"morris"``, ``samples`` trajectories, default 20) of
    ``outputs`` (``gu20``, ``gu60``, ``gu85``, ``haze``, ``doi``, ``flop``, ``dE00``, ``L@45as15``,
    ``a@...``, ``b@...``; default all at the standard's geometries) against ``vary``, as
    ``"tilt=4:20,roughness=0.01:0.1"`` or ``{"tilt": (4, 20), ...}``. Each reading uses
    ``walks`` walks per geometry with the same random numbers (docs/formulation.md).

    With ``client`` (a ``dask.distributed.Client``) the design's rows are read on the cluster,
    ``rows_per_task`` per task; each task rebuilds the formulation from its path, dict or (a
    :class:`Coating`) TOML text, so the workers must see a path's file and the files it names.
    The result equals the serial one exactly: every row is read from the same streams wherever
    it runs."""
    vary = _vary(vary)
    if isinstance(coating, Coating):
        description = ("toml", coating.toml)
    elif isinstance(coating, Mapping):
        description = dict(coating)
    else:
        description = os.fspath(coating)
    out = None if outputs is None else ",".join(outputs)
    plan_args = (description, os.fspath(base_dir), vary, out, method, samples, standard, int(walks))
    plan = _plan(*plan_args)
    points = plan.design()
    if client is None:
        values = plan.read_points(points)
    else:
        chunks = [points[i : i + rows_per_task] for i in range(0, len(points), rows_per_task)]
        futures = client.map(_read_rows, [plan_args] * len(chunks), chunks, pure=False)
        values = np.vstack(client.gather(futures))
    noise = plan.noise()
    result = json.loads(plan.analyze_json(points, values, noise, float(threshold)))
    names = [i["name"] for i in result["inputs"]]
    return Sensitivity(
        result,
        pd.DataFrame(points, columns=names),
        pd.DataFrame(values, columns=plan.output_names()),
    )


class Match:
    """What :func:`match` found: ``fitted`` (the fitted :class:`Coating`), ``toml`` (its
    description: the start's text with the fitted values, comments kept), ``constituents`` (a
    DataFrame: ``name``, ``lo``, ``hi``, ``start``, ``fitted``, ``sigma`` (one standard
    deviation, Gauss-Newton; about half the real scatter, docs/formulation.md), ``at_bound``),
    ``geometries`` (a DataFrame: ``geometry``, ``de00_start``, ``de00_fitted`` and CIELAB
    D65/10° of the target, the start and the fitted formulation: ``L_target``, ``a_target``,
    ..., ``b_fitted``), ``mean_de00`` (start, fitted) and ``json`` (``gonio coating match
    --json``'s structure without the file names). A selection (``match(..., select=N)``) adds
    ``selection`` (``json["selection"]``), ``tried`` (a DataFrame of the best combinations
    screened: ``pigments``, ``concentrations``, ``score``) and ``finalists`` (a DataFrame:
    ``pigments``, ``screen_concentrations``, ``screen_score``, ``objective``, ``mean_de00``,
    ``de00`` per geometry, ``concentrations``, ``sigma``, ``evaluations``); ``None`` without."""

    def __init__(self, result: dict, toml: str, fitted: Coating):
        self.json = result
        self.toml = toml
        self.fitted = fitted
        self.constituents = pd.DataFrame(result["constituents"])
        rows = []
        for g in result["geometries"]:
            row = {"geometry": g["name"], "de00_start": g["de00_start"],
                   "de00_fitted": g["de00_fitted"]}
            for which in ("target", "start", "fitted"):
                for c in ("L", "a", "b"):
                    row[f"{c}_{which}"] = g[which][c] if g[which] else np.nan
            rows.append(row)
        self.geometries = pd.DataFrame(rows)
        self.mean_de00 = (result["mean_de00_start"], result["mean_de00_fitted"])
        self.selection = result.get("selection")
        self.tried = self.finalists = None
        if self.selection is not None:
            self.tried = pd.DataFrame(self.selection["tried"])
            self.finalists = pd.DataFrame(self.selection["finalists"])

    def save(self, path: str | os.PathLike) -> None:
        """Write the fitted description (TOML) to ``path``."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.toml)

    def __repr__(self) -> str:
        return (f"Match(mean ΔE00 {self.mean_de00[0]:.2f} -> {self.mean_de00[1]:.2f}, "
                f"{self.json['evaluations']} readings)")


def _selection_search(args: tuple, pigments: list, concentrations: list) -> list:
    """One finalist's search of a selection (a Dask task: the start is rebuilt from its TOML
    where it runs, the target read from its path or CSV text)."""
    text, base_dir, *rest = args
    start = _gonio.read_coating(None, text, False, base_dir)
    return _gonio.selection_search(start, *rest, pigments, concentrations)


def match(
    start: str | os.PathLike | Mapping[str, Any] | Coating,
    target: str | os.PathLike | pd.DataFrame,
    vary: str | Mapping[str, tuple[float, float]] | Sequence[str] = "",
    standard: str = "e2194",
    target_gloss: Mapping[int, float] | None = None,
    gloss_weight: float = 0.1,
    walks: int = 1024,
    starts: int = 4,
    objective: str = "auto",
    select: int | None = None,
    candidates: Sequence[str] | None = None,
    finalists: int = 3,
    shown: int = 20,
    client: Any = None,
    base_dir: str | os.PathLike = ".",
) -> Match:
    """The values of the ``vary``'d constituents (``"tilt=4:20,coverage=0.3:0.8"`` or
    ``{"tilt": (4, 20), ...}``, within the bounds) that make ``start`` look like ``target``
    (``gonio coating match``): the objective over the ``standard``'s geometries is minimised
    by Nelder-Mead from the start formulation and ``starts - 1`` other points, every reading
    with the same random numbers.

    ``target``: a file (``.csv`` of CIELAB or reflectance factors per geometry, a measured BRDF
    ``.astm`` or a spectral ``.gbrdf``) or a DataFrame with a ``geometry`` column and ``L``,
    ``a``, ``b`` (or reflectance-factor columns ``R_400nm`` ... as :func:`multiangle` gives).
    ``objective``: ``"auto"`` (the default) minimises the rms difference of reflectance
    factors where the target gives them (and no ``target_gloss`` is matched), the mean
    CIEDE2000 otherwise; ``"de00"`` (plus ``gloss_weight`` ΔE00 per gloss unit of difference
    from ``target_gloss``, e.g. ``{20: 85, 60: 92}``) and ``"spectral"`` choose
    (docs/formulation.md).

    ``select=N`` chooses up to N pigments of gonio's library (``candidates``: their names;
    default the whole library less the start's pigments; the start's base must be
    ``kind = "kubelka-munk"``) and fits their concentrations with ``vary``: every combination
    is screened, then the full match runs on the best ``finalists`` (``gonio coating match
    --select``); ``json["selection"]`` lists the ``shown`` best combinations tried and the
    finalists, and ``toml`` adds the chosen pigments as ``library = "NAME"`` entries. With
    ``client`` (a ``dask.distributed.Client``) the finalists are searched on its workers, each
    rebuilding the start from its TOML (relative file names in it start in ``base_dir``) and
    reading the target from its path (which the workers must see) or its CSV text; the result
    equals the serial one, every reading being made with the same random numbers."""
    vary = _vary(vary)
    gloss = None
    if target_gloss:
        gloss = ",".join(f"{int(a)}={float(gu)}" for a, gu in target_gloss.items())
    path, csv = None, None
    if isinstance(target, pd.DataFrame):
        csv = target.to_csv(index=False)
    else:
        path = os.fspath(target)
    coating = start if isinstance(start, Coating) else read(start, base_dir)
    rest = (path, csv, vary, standard, gloss, float(gloss_weight), int(walks), int(starts),
            objective)
    if select is None:
        result, toml, fitted = _gonio.match_coating(coating, *rest)
        return Match(json.loads(result), toml, fitted)
    plan = _gonio.selection_plan(
        coating, *rest, int(select), None if candidates is None else list(candidates),
        int(finalists))
    chosen = plan.finalists()
    if client is None:
        runs = [plan.search(k) for k in range(len(chosen))]
    else:
        args = (coating.toml, os.fspath(base_dir), *rest)
        futures = [client.submit(_selection_search, args, p, c, pure=False)
                   for p, c, _ in chosen]
        runs = client.gather(futures)
    result, toml, fitted = plan.conclude(runs, int(shown))
    return Match(json.loads(result), toml, fitted)
