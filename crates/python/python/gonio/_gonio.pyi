"""Type stubs of gonio's compiled module (crates/python/src). Lengths in metres unless a name
says otherwise, angles in degrees, BRDFs in 1/sr."""

from os import PathLike
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

__version__: str
#: The columns of gonio inplane's CSV, in order.
COLUMNS: list[str]
E2194: list[str]
E2539: list[str]
#: Random walks per coating table cell before any are added.
TABLE_WALKS: int
#: The standard error of a coating table cell's L* above which walks are added.
TARGET_DL: float

class Surface:
    """A height map: heights in metres on a grid of spacings dx, dy (m), NaN where not measured."""

    @staticmethod
    def from_array(heights: npt.ArrayLike, dx: float, dy: float | None = None) -> Surface: ...
    @staticmethod
    def from_topography(topography: Any) -> Surface: ...
    def to_topography(self) -> Any: ...
    @property
    def heights(self) -> npt.NDArray[np.float64]: ...
    @property
    def dx(self) -> float: ...
    @property
    def dy(self) -> float: ...
    @property
    def shape(self) -> tuple[int, int]: ...
    @property
    def metadata(self) -> dict[str, Any]: ...
    def statistics(self) -> dict[str, Any]: ...
    def level(self) -> Surface: ...
    def crop(self, x0: int, y0: int, nx: int, ny: int) -> Surface: ...
    def rotate(self, deg: float) -> Surface: ...

def read_surface(path: str | PathLike[str], channel: str | int | None = None) -> Surface: ...
def synthesize(
    sq: float, corr: float, size: int, dx: float, acf: str = "gaussian", seed: int = 1
) -> Surface: ...

class Table:
    """A tabulated BRDF (mono, rgb, xyz or spectral channels)."""

    @staticmethod
    def open(path: str | PathLike[str]) -> Table: ...
    def eval(
        self, wi: npt.ArrayLike, wo: npt.ArrayLike, channels: bool = False
    ) -> npt.NDArray[np.float64]: ...
    def albedo(self, theta_i_deg: float, phi_i_deg: float = 0.0) -> npt.NDArray[np.float64]: ...
    @property
    def channels(self) -> str: ...
    @property
    def wavelengths_nm(self) -> list[float] | None: ...
    @property
    def resolution(self) -> list[int]: ...
    def save(self, path: str | PathLike[str]) -> None: ...
    def export(self, format: str, path: str | PathLike[str], step_deg: float = 1.0) -> None: ...

def import_table(path: str | PathLike[str], resolution: list[int] | None = None) -> Table: ...
def tabulate(model_json: str, resolution: list[int], mono: bool = False) -> Table: ...
def compute_table(
    surface: Surface,
    method: str,
    index: float,
    index_imag: float | None,
    wavelength_nm: list[float],
    resolution: list[int],
    incidence_azimuths: int | None,
    shadowing: bool,
    source: str,
) -> Table: ...
def inplane_columns(
    surface: Surface | None,
    methods: list[str],
    incidence_deg: list[float],
    scatter_deg: list[float],
    aperture_deg: float,
    index: float,
    index_imag: float | None,
    wavelength_nm: list[float],
    sq_nm: float | None,
    corr_um: float | None,
    shadowing: bool,
    second_bounce: bool,
    normals: str,
    azimuths: int,
    spot_um: float | None,
    spots: int,
) -> tuple[dict[str, Any], list[str]]: ...
def gloss_json(specimen: Surface | Table, method: str, index: float, wavelength_nm: float) -> str: ...
def multiangle_columns(
    table: Table, geometries: list[str], aperture_deg: float, illuminant: str, observer_deg: int
) -> tuple[dict[str, Any], npt.NDArray[np.float64], npt.NDArray[np.float64], float | None]: ...
def booth_json(
    input: str,
    output_dir: str,
    booth: str | None,
    spp: int | None,
    seed: int | None,
    size: tuple[int, int] | None,
    threads: int | None,
) -> str: ...
def render_scene(
    path: str | None,
    json: str | None,
    base_dir: str,
    spp: int | None,
    seed: int | None,
    max_bounces: int | None,
    denoise: bool | None,
    spectral: bool,
    threads: int | None,
) -> npt.NDArray[np.float32]: ...
def report_demo(output_dir: str, quick: bool) -> Path: ...
def xyz(
    wavelengths_nm: list[float], values: list[float], illuminant: str = "D65", observer: int = 2
) -> dict[str, Any]: ...

class Coating:
    """A coating's formulation (docs/coatings.md), read over 400-700 nm in 10 nm bands."""

    @property
    def source(self) -> str: ...
    @property
    def toml(self) -> str: ...
    def info_json(self, samples: int) -> str: ...
    def compute(
        self, resolution: list[int], bands: list[float], samples: int, target_dl: float
    ) -> Table: ...
    def multiangle_columns(
        self, standard: str, samples: int
    ) -> tuple[dict[str, Any], npt.NDArray[np.float64], npt.NDArray[np.float64], float | None]: ...
    def study_json(self, vary: str, values: list[float], standard: str, samples: int) -> str: ...
    def panel_picture(
        self,
    ) -> tuple[npt.NDArray[np.uint8], npt.NDArray[np.float32], float]: ...

def read_coating(
    path: str | PathLike[str] | None, text: str | None, json: bool, base_dir: str | PathLike[str]
) -> Coating: ...

class SensitivityPlan:
    """A coating's sensitivity taken apart: design, readings of rows, noise, analysis."""

    def design(self) -> npt.NDArray[np.float64]: ...
    def output_names(self) -> list[str]: ...
    def read_points(self, points: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]: ...
    def noise(self) -> list[float]: ...
    def analyze_json(
        self,
        points: npt.NDArray[np.float64],
        values: npt.NDArray[np.float64],
        noise: list[float],
        threshold: float,
    ) -> str: ...

def sensitivity_plan(
    coating: Coating,
    vary: str,
    outputs: str | None,
    method: str,
    samples: int | None,
    standard: str,
    walks: int,
) -> SensitivityPlan: ...

def match_coating(
    start: Coating,
    target: str | PathLike[str] | None,
    target_csv: str | None,
    vary: str,
    standard: str,
    target_gloss: str | None,
    gloss_weight: float,
    walks: int,
    starts: int,
    objective: str,
) -> tuple[str, str, Coating]: ...

def from_lab(lab: list[float], illuminant: str = "D65", observer: int = 10) -> dict[str, Any]: ...
