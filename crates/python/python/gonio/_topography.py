"""Conversions between gonio's :class:`~gonio.Surface` and SurfaceTopography's topographies
(``Surface.from_topography`` and ``Surface.to_topography`` call these)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ._gonio import Surface


def from_topography(topography: Any) -> Surface:
    """A :class:`Surface` from a SurfaceTopography topography (heights and physical sizes in
    the topography's unit, converted to metres)."""
    scale = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "um": 1e-6, "nm": 1e-9, "Å": 1e-10}
    unit = topography.unit
    if unit not in scale:
        raise ValueError(f"SurfaceTopography unit {unit!r}: gonio knows m, mm, µm, nm, Å")
    k = scale[unit]
    raw = topography.heights()
    heights = np.ma.filled(np.ma.asarray(raw, dtype=float) * k, np.nan)
    nx, ny = topography.nb_grid_pts
    sx, sy = topography.physical_sizes
    # SurfaceTopography indexes heights [x, y]; gonio's rows run along y.
    return Surface.from_array(np.ascontiguousarray(heights.T), sx / nx * k, sy / ny * k)


def to_topography(surface: Surface) -> Any:
    """The surface as a SurfaceTopography ``Topography`` in metres (NaN points masked)."""
    from SurfaceTopography import Topography

    h = surface.heights.T
    ny, nx = surface.shape
    data = np.ma.masked_invalid(h) if np.isnan(h).any() else np.array(h)
    return Topography(data, (nx * surface.dx, ny * surface.dy), unit="m")
