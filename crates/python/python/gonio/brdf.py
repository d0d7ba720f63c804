"""BRDF tables: compute one from a height map, import a measurement, tabulate a model, open a
``.gbrdf`` file. The tables are :class:`gonio.Table` objects (``eval``, ``albedo``, ``save``,
``export``)."""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Sequence

from . import _gonio
from ._gonio import Surface, Table

__all__ = ["Table", "compute", "import_", "tabulate", "open"]

#: The default nodes of a computed isotropic table (theta_h, theta_d, phi_d).
COMPUTE_RESOLUTION = (32, 90, 180)


def open(path: str | os.PathLike) -> Table:  # noqa: A001 - the name users expect
    """Open a ``.gbrdf`` table (memory-mapped)."""
    return Table.open(os.fspath(path))


def compute(
    surface: Surface | str | os.PathLike,
    method: str = "ray",
    index: float = 1.55,
    *,
    index_imag: float | None = None,
    wavelength_nm: float | Sequence[float] = (550.0,),
    resolution: Sequence[int] = COMPUTE_RESOLUTION,
    incidence_azimuths: int | None = None,
    shadowing: bool = True,
) -> Table:
    """The BRDF table of a height map, as ``gonio brdf compute`` makes it.

    ``method`` ``"ray"`` (geometric optics, one monochrome channel) or ``"kirchhoff"`` (one
    channel per wavelength in ``wavelength_nm``; several give a spectral table). ``resolution``:
    (theta_h, theta_d, phi_d) nodes for an isotropic table, or with phi_h for an anisotropic one.
    ``incidence_azimuths``: turns of the source averaged (isotropic) or interpolated
    (anisotropic); default from the map's texture aspect ratio. ``shadowing`` ``False``: no
    shadowing or masking by the map (the ray method as NIST's original, the Kirchhoff integral
    without Smith's G2), as ``gonio brdf compute --no-shadowing``.
    """
    source = os.fspath(surface) if isinstance(surface, (str, os.PathLike)) else "Surface"
    if not isinstance(surface, Surface):
        surface = _gonio.read_surface(os.fspath(surface))
    wavelengths = [float(wavelength_nm)] if isinstance(wavelength_nm, (int, float)) else [float(w) for w in wavelength_nm]
    return _gonio.compute_table(
        surface,
        method,
        float(index),
        index_imag,
        wavelengths,
        [int(n) for n in resolution],
        incidence_azimuths,
        shadowing,
        source,
    )


def import_(path: str | os.PathLike, resolution: Sequence[int] | None = None) -> Table:
    """Import a measured BRDF by extension: Cornell ``.astm``, MERL ``.binary`` or a ``.csv`` of
    samples; scattered measurements are fitted onto ``resolution`` (default 90 × 90 × 48)."""
    return _gonio.import_table(
        os.fspath(path), None if resolution is None else [int(n) for n in resolution]
    )


def tabulate(
    model: Mapping[str, Any] | str,
    resolution: Sequence[int] = (90, 90, 180),
    mono: bool = False,
) -> Table:
    """Tabulate an analytic model, a dict (or JSON text) of ``docs/brdf-models.md``, e.g.
    ``{"model": "ggx", "alpha": 0.2, "index": 1.5, "diffuse": 0.5}``."""
    text = model if isinstance(model, str) else json.dumps(dict(model))
    return _gonio.tabulate(text, [int(n) for n in resolution], mono)
