"""The reports gonio composes (``docs/python.md``, "Reports"): :func:`demo` runs the whole
pipeline on the data built into gonio and writes it up as one HTML page, the same call as
``gonio demo``, so the same report; :func:`conformance` runs the appearance conformance suite
(``docs/conformance.md``) and writes its report, the same call as ``gonio conformance``.
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from . import _gonio

__all__ = ["conformance", "demo"]


def demo(output_dir: str | os.PathLike, quick: bool = False) -> Path:
    """Run the demo into the folder ``output_dir`` (created if missing) and return the path of
    its report, ``report.html``; every file the report shows, and those its commands read, are
    written beside it. ``quick`` is the small run the tests use (seconds instead of minutes:
    128 × 128 maps, two samples, one wavelength, no path-traced pictures)."""
    return Path(_gonio.report_demo(os.fspath(output_dir), bool(quick)))


def conformance(
    output_dir: str | os.PathLike,
    renderers: list[str] | None = None,
    spp: int | None = None,
) -> dict[str, Any]:
    """Run the conformance suite into the folder ``output_dir`` (created if missing) and write
    its report, ``report.html``, with the pictures and ``results.json`` beside it; return the
    results (``results.json``'s dict: ``spp``, ``size`` and ``scenes``, each with its ``runs``,
    their ``verdict``, ``checks``, ``regions``, ``loss``, ``flip_mean``) with ``"report"`` the
    report's path. ``renderers``: names among ``"gonio"``, ``"mitsuba"``, ``"radiance"`` (all
    three when ``None``); a peer whose Python module is missing is ``"unavailable"``.
    ``spp``: samples per pixel of gonio and Mitsuba, 1 to 65536 (64 when ``None``). Raises
    ``ValueError`` for an unknown renderer or an ``spp`` out of range."""
    text, report = _gonio.report_conformance(
        os.fspath(output_dir),
        None if renderers is None else [str(r) for r in renderers],
        None if spp is None else int(spp),
    )
    results: dict[str, Any] = json.loads(text)
    results["report"] = Path(report)
    return results
