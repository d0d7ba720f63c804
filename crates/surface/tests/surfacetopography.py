"""Read height-map files with SurfaceTopography (an independent reader, PyPI
`SurfaceTopography`) and print, as JSON, what it reports for each: grid, physical size in
metres, channel names and the one read, valid fraction, and the rms height after removing the
least-squares plane (Sq; Rq along a profile) in metres.

Usage: python3 surfacetopography.py FILE...
Exit status 77 when SurfaceTopography is not installed (the Rust test then skips or, with
GONIO_REQUIRE_ORACLES=1, fails).
"""
import json
import sys
import warnings

try:
    import numpy as np
    from SurfaceTopography import open_topography
except ImportError as e:  # pragma: no cover - depends on the machine
    print(f"SurfaceTopography is not installed: {e}", file=sys.stderr)
    sys.exit(77)

warnings.filterwarnings("ignore")


def describe(path):
    reader = open_topography(path)
    topography = reader.topography()
    if topography.unit is not None and topography.unit != "m":
        topography = topography.to_unit("m")
    heights = topography.heights()
    if np.ma.isMaskedArray(heights):
        invalid = np.ma.getmaskarray(heights) | ~np.isfinite(heights.filled(0.0))
    else:
        invalid = ~np.isfinite(heights)
    levelled = topography.detrend("height")
    if topography.dim == 2:
        sq = levelled.rms_height_from_area()
    else:
        sq = levelled.rms_height_from_profile()
    return {
        "grid": [int(n) for n in topography.nb_grid_pts],
        "size_m": [float(s) for s in np.atleast_1d(topography.physical_sizes)],
        "channels": [c.name for c in reader.channels],
        "default_channel": reader.default_channel.name,
        "valid_fraction": float(1.0 - invalid.sum() / invalid.size),
        "sq_m": float(sq),
    }


out = {}
for path in sys.argv[1:]:
    try:
        out[path] = describe(path)
    except Exception as e:  # SurfaceTopography refuses the file: say so, the test decides
        out[path] = {"error": f"{type(e).__name__}: {e}"}
print(json.dumps(out))
