"""Colorimetry of spectra: CIE XYZ, chromaticity, CIELAB and sRGB under a CIE illuminant, for
numpy arrays or colour-science's ``SpectralDistribution``."""

from __future__ import annotations

from typing import Any

import numpy as np

from . import _gonio

__all__ = ["xyz", "lab", "from_lab"]


def _spectrum(wavelengths_nm: Any, values: Any) -> tuple[list, list]:
    if values is None and hasattr(wavelengths_nm, "wavelengths"):
        # colour-science's SpectralDistribution.
        return list(map(float, wavelengths_nm.wavelengths)), list(map(float, wavelengths_nm.values))
    w = np.asarray(wavelengths_nm, dtype=float).ravel()
    v = np.asarray(values, dtype=float).ravel()
    if w.shape != v.shape:
        raise ValueError(f"{w.size} wavelengths but {v.size} values")
    return w.tolist(), v.tolist()


def xyz(wavelengths_nm: Any, values: Any = None, illuminant: str = "D65", observer: int = 2) -> dict:
    """The colour of a reflectance spectrum (0–1) at ``wavelengths_nm`` (increasing, nm) under
    ``illuminant`` ("D65" or "A") for the CIE ``observer`` (2 or 10 degrees). ``wavelengths_nm``
    may also be a colour-science ``SpectralDistribution`` (then leave ``values`` out).

    Returns a dict: ``xyz`` (Y = 100 for the perfect diffuser), ``chromaticity`` (x, y),
    ``white_xyz``, ``cielab`` (L*, a*, b*), ``chroma_ab``, ``hue_ab_deg``, ``linear_srgb``
    (white-balanced to D65 by Bradford; may leave [0, 1]), ``srgb_in_gamut``, ``srgb`` (encoded,
    clipped) and ``srgb_hex``; the keys of ``gonio color xyz --json``.
    """
    w, v = _spectrum(wavelengths_nm, values)
    return _gonio.xyz(w, v, illuminant, int(observer))


def lab(wavelengths_nm: Any, values: Any = None, illuminant: str = "D65", observer: int = 2) -> np.ndarray:
    """CIELAB (L*, a*, b*) of a reflectance spectrum, as :func:`xyz` computes it."""
    return np.array(xyz(wavelengths_nm, values, illuminant, observer)["cielab"])


def from_lab(lab: Any, illuminant: str = "D65", observer: int = 10) -> dict:
    """The colour of CIELAB ``lab`` (L*, a*, b*; relative to the perfect diffuser under
    ``illuminant`` for the ``observer``, 10° by default as multi-angle readings are) with the keys
    of :func:`xyz`: ``srgb_hex`` gives a swatch (clipped where the colour leaves the sRGB gamut
    or is brighter than the white, as a metallic near the specular direction is)."""
    return _gonio.from_lab([float(v) for v in lab], illuminant, int(observer))
