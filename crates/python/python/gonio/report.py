"""The reports gonio composes (``docs/python.md``, "Reports"): :func:`demo` runs the whole
pipeline on the data built into gonio and writes it up as one HTML page, the same call as
``gonio demo``, so the same report.
"""

from __future__ import annotations

import os
from pathlib import Path

from . import _gonio

__all__ = ["demo"]


def demo(output_dir: str | os.PathLike, quick: bool = False) -> Path:
    """Run the demo into the folder ``output_dir`` (created if missing) and return the path of
    its report, ``report.html``; every file the report shows, and those its commands read, are
    written beside it. ``quick`` is the small run the tests use (seconds instead of minutes:
    128 × 128 maps, two samples, one wavelength, no path-traced pictures)."""
    return Path(_gonio.report_demo(os.fspath(output_dir), bool(quick)))
