"""gonio: predict how a coated surface looks from its measured topography.

Height maps from instrument files or synthesis (:class:`Surface`), in-plane BRDF curves by the
ray method, the scalar Kirchhoff integral and analytic models (:func:`inplane`, a pandas
DataFrame with the columns of ``gonio inplane``'s CSV), gloss, haze and DOI (:func:`gloss`),
BRDF tables (:mod:`gonio.brdf`), coatings from their constituents (:mod:`gonio.coating`),
pictures (:func:`render`), colorimetry (:mod:`gonio.color`), studies over many surfaces that
run on Dask when given a client (:func:`study`) and the demo's report (:mod:`gonio.report`).

Units: lengths in metres unless a name says otherwise (``sq_nm``, ``corr_um``, ``wavelength_nm``),
angles in degrees, BRDFs in 1/sr. The numbers are those of the ``gonio`` command line: both call
the same Rust code (``docs/python.md``).
"""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Sequence

import numpy as np
import pandas as pd

from . import _gonio
from ._gonio import Surface, Table, read_surface, synthesize
from . import brdf, coating, color, report
from . import studies
from .studies import study

__version__ = _gonio.__version__

__all__ = [
    "booth",
    "Surface",
    "Table",
    "read_surface",
    "synthesize",
    "inplane",
    "gloss",
    "multiangle",
    "render",
    "study",
    "brdf",
    "coating",
    "color",
    "report",
    "studies",
    "STARR_INCIDENCES_DEG",
    "COLUMNS",
    "E2194",
    "E2539",
]

#: Incidence angles of the NIST STARR in-plane set-up, degrees.
STARR_INCIDENCES_DEG = (20.0, 45.0, 60.0, 70.0)
#: Columns of :func:`inplane`'s DataFrame (those of ``gonio inplane``'s CSV).
COLUMNS = tuple(_gonio.COLUMNS)
#: The geometries of ASTM E2194 and gonio's ASTM E2539 set, as :func:`multiangle` names them.
E2194 = tuple(_gonio.E2194)
E2539 = tuple(_gonio.E2539)


def _surface(surface: Surface | str | os.PathLike, channel: Any = None) -> Surface:
    if isinstance(surface, Surface):
        return surface
    if isinstance(surface, (str, os.PathLike)):
        return read_surface(os.fspath(surface), channel)
    raise TypeError(
        f"expected a gonio.Surface or the path of a height map, got {type(surface).__name__}"
    )


def _as_list(v: Any) -> list:
    if v is None:
        return []
    if isinstance(v, (str, bytes)) or np.isscalar(v):
        return [v]
    return list(v)


def inplane(
    surface_or_model: Surface | str | os.PathLike | Mapping[str, float] | None,
    method: str | Sequence[str] = "ray",
    incidence_deg: float | Sequence[float] = STARR_INCIDENCES_DEG,
    scatter_deg: Sequence[float] | None = None,
    aperture_deg: float = 1.4,
    index: float = 1.55,
    wavelength_nm: float | Sequence[float] | None = None,
    *,
    index_imag: float | None = None,
    sq_nm: float | None = None,
    corr_um: float | None = None,
    shadowing: bool = True,
    second_bounce: bool = False,
    normals: str = "plane",
    azimuths: int = 1,
    spot_um: float | None = None,
    spots: int = 1,
    channel: Any = None,
    warnings: list | None = None,
) -> pd.DataFrame:
    """In-plane BRDF curves, as a goniometer sweeping the plane of incidence measures them.

    ``surface_or_model``: a :class:`Surface`, the path of a height map, or a Gaussian random
    surface ``{"sq_nm": ..., "corr_um": ...}`` for the analytic models. ``method``: one or several
    of ``"ray"`` (geometric optics on the map's facets), ``"kirchhoff"`` (the scalar Kirchhoff
    integral; needs ``wavelength_nm``) and the models ``"beckmann"``, ``"geometric"``,
    ``"microfacet"``, ``"smooth"`` (need ``sq_nm`` and ``corr_um``, from the model dict or given).
    Angles in degrees: incidences from the normal, signed scattering angles (specular of
    incidence θ at +θ; default −75 to 75 every 1), detector half-angle ``aperture_deg`` (NIST
    STARR: 1.4). ``index`` (+ ``index_imag``) the coating's refractive index.

    Returns a DataFrame with the columns of ``gonio inplane``'s CSV (:data:`COLUMNS`), one row per
    detector; NaN where the CSV leaves a cell empty. The validity warnings are appended to
    ``warnings`` when a list is given, and are in ``df.attrs["warnings"]``.
    """
    surface = None
    if isinstance(surface_or_model, Mapping):
        sq_nm = surface_or_model.get("sq_nm", sq_nm)
        corr_um = surface_or_model.get("corr_um", corr_um)
    elif surface_or_model is not None:
        surface = _surface(surface_or_model, channel)
    if scatter_deg is None:
        scatter_deg = np.arange(-75.0, 76.0, 1.0)
    cols, warns = _gonio.inplane_columns(
        surface,
        [str(m) for m in _as_list(method)],
        [float(t) for t in _as_list(incidence_deg)],
        [float(t) for t in _as_list(scatter_deg)],
        float(aperture_deg),
        float(index),
        index_imag,
        [float(w) for w in _as_list(wavelength_nm)],
        sq_nm,
        corr_um,
        shadowing,
        second_bounce,
        normals,
        int(azimuths),
        spot_um,
        int(spots),
    )
    df = pd.DataFrame(cols, columns=list(COLUMNS))
    df.attrs["warnings"] = list(warns)
    if warnings is not None:
        warnings.extend(warns)
    return df


def gloss(
    surface_or_table: Surface | Table | str | os.PathLike,
    method: str = "ray",
    index: float = 1.55,
    wavelength_nm: float = 550.0,
) -> dict:
    """What a gloss meter (ISO 2813 at 20/60/85°) and an ASTM E430 appearance meter read.

    ``surface_or_table``: a :class:`Surface` (or height-map path), scattering by ``method``
    ``"ray"`` or ``"kirchhoff"`` (at ``wavelength_nm``) over a coating of refractive index
    ``index``; or a :class:`Table` (or ``.gbrdf`` path), read photometrically. Returns the keys
    of ``gonio gloss --json``: ``gu20``, ``gu60``, ``gu85`` (gloss units), ``haze``,
    ``haze_wide``, ``haze_20``, ``haze_20_log``, ``haze_d4039``, ``doi``, ``doi_uncertainty``
    and ``warnings``.
    """
    specimen = surface_or_table
    if isinstance(specimen, (str, os.PathLike)):
        specimen = (
            Table.open(os.fspath(specimen))
            if os.fspath(specimen).lower().endswith(".gbrdf")
            else read_surface(os.fspath(specimen))
        )
    return json.loads(_gonio.gloss_json(specimen, method, float(index), float(wavelength_nm)))


def multiangle(
    table: Table | str | os.PathLike,
    standard: str = "e2194",
    geometries: Sequence[str] | None = None,
    aperture_deg: float = 0.0,
    illuminant: str = "D65",
    observer_deg: int = 10,
) -> pd.DataFrame:
    """What a multi-angle spectrophotometer reads on a spectral table (``gonio multiangle``).

    ``table``: a spectral :class:`Table` or ``.gbrdf`` path. ``standard``: ``"e2194"`` (45°
    illumination, aspecular 15, 25, 45, 75, 110°) or ``"e2539"`` (adds 45as-15 and 15°
    illumination); ``geometries`` names others (``"45as15"``: illumination and aspecular angle in
    degrees, the aspecular angle from the specular direction towards the light).
    ``aperture_deg``: half-angle of the source's and receptor's cones (0: the directions
    themselves). Colour under ``illuminant`` (``"D65"`` or ``"A"``) for the ``observer_deg``
    (10 or 2) observer.

    Returns one row per geometry: ``geometry``, ``illumination_deg``, ``aspecular_deg``,
    ``viewing_deg`` (the detector's signed angle, + on the light's side), CIELAB ``L``, ``a``,
    ``b``, ``C``, ``h_deg``, tristimulus ``X``, ``Y``, ``Z`` (Y = 100 for the perfect diffuser),
    and the reflectance factors (π × BRDF) in columns ``R_400nm``, ... . Alman's flop index is in
    ``df.attrs["flop_index"]`` (None unless 45as15, 45as45 and 45as110 are read).
    """
    if isinstance(table, (str, os.PathLike)):
        table = Table.open(os.fspath(table))
    if geometries is None:
        sets = {"e2194": E2194, "e2539": E2539}
        if standard.lower() not in sets:
            raise ValueError(f"standard {standard!r}: use \"e2194\" or \"e2539\"")
        geometries = sets[standard.lower()]
    return coating._reading_frame(
        *_gonio.multiangle_columns(
            table, [str(g) for g in geometries], float(aperture_deg), illuminant, int(observer_deg)
        )
    )


def booth(
    input: str | os.PathLike,
    output_dir: str | os.PathLike,
    booth: str | os.PathLike | None = None,
    spp: int | None = None,
    seed: int | None = None,
    size: tuple[int, int] | None = None,
    *,
    threads: int | None = None,
) -> dict[str, Any]:
    """The virtual viewing booth (``docs/standard.md``), as ``gonio booth``: render ``input``
    (a booth spec, a coating description ``.toml`` or a ``.gbrdf`` table; a coating or table in
    the standard booth or the spec ``booth``) and write into ``output_dir`` every view's absolute
    CIE XYZ OpenEXR (cd/m²), sRGB and Display P3 PNGs with masks, the specimen's mask and
    ``manifest.json``. ``spp``, ``seed`` and ``size`` (width, height in pixels) override the
    spec's ``[render]``. Returns the summary: per view its name, aspecular angle, the specimen's
    mean luminance ``specimen_luminance_cd_m2``, the files, and per display the fractions of
    pixels out of gamut and over range.
    """
    text = _gonio.booth_json(
        os.fspath(input),
        os.fspath(output_dir),
        os.fspath(booth) if booth is not None else None,
        spp,
        seed,
        tuple(size) if size is not None else None,
        threads,
    )
    return json.loads(text)


def render(
    scene: str | os.PathLike | Mapping[str, Any],
    spp: int | None = None,
    seed: int | None = None,
    *,
    max_bounces: int | None = None,
    denoise: bool | None = None,
    spectral: bool = False,
    threads: int | None = None,
    base_dir: str | os.PathLike | None = None,
) -> np.ndarray:
    """Path-trace a scene and return its picture, shape (height, width, 3), float32 linear sRGB
    radiance (W m⁻² sr⁻¹; a white Lambertian surface under a uniform sky of radiance 1 is 1).

    ``scene``: the path of a TOML scene file (``docs/render.md``) or a dict of the same
    structure, whose relative paths start in ``base_dir`` (default the working directory).
    ``spp``, ``seed``, ``max_bounces`` and ``denoise`` override the scene's ``[render]``;
    ``spectral`` carries four wavelengths per path instead of RGB.
    """
    if isinstance(scene, Mapping):
        path, text = None, json.dumps(scene)
    else:
        path, text = os.fspath(scene), None
    return _gonio.render_scene(
        path,
        text,
        os.fspath(base_dir) if base_dir is not None else os.getcwd(),
        spp,
        seed,
        max_bounces,
        denoise,
        spectral,
        threads,
    )
