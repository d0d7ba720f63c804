"""Studies: serial and on a Dask LocalCluster of two workers give the same DataFrame, to the
bit and in the same order; surfaces travel as paths or synthesis parameters."""

from __future__ import annotations

import pandas as pd
import pytest

import gonio
from conftest import SURFACE_DATA

SURFACES = [
    {"label": "sq100", "sq": 100e-9, "corr": 5e-6, "size": 128, "dx": 0.5e-6, "seed": 1},
    {"label": "sq300", "sq": 300e-9, "corr": 5e-6, "size": 128, "dx": 0.5e-6, "seed": 2},
    str(SURFACE_DATA / "al3d-1.al3d"),
]
OPTIONS = dict(incidence_deg=[20, 60], scatter_deg=list(range(-60, 61, 10)))


def test_tasks_and_order():
    tasks = gonio.studies.tasks_of(SURFACES[:2], ["ray", "kirchhoff"], [500.0, 600.0], OPTIONS)
    # Ray once per surface, Kirchhoff once per wavelength.
    assert [(t.label, t.method, t.wavelength_nm) for t in tasks] == [
        ("sq100", "ray", (500.0, 600.0)),
        ("sq100", "kirchhoff", (500.0,)),
        ("sq100", "kirchhoff", (600.0,)),
        ("sq300", "ray", (500.0, 600.0)),
        ("sq300", "kirchhoff", (500.0,)),
        ("sq300", "kirchhoff", (600.0,)),
    ]
    with pytest.raises(TypeError, match="paths or dicts"):
        gonio.study([gonio.synthesize(1e-7, 5e-6, 64, 0.5e-6)])
    with pytest.raises(ValueError, match="wavelength"):
        gonio.study(SURFACES[:1], methods="kirchhoff")


def test_dask_equals_serial():
    distributed = pytest.importorskip("distributed")
    serial = gonio.study(SURFACES, ["ray", "kirchhoff"], [550.0], **OPTIONS)
    assert set(serial.surface) == {"sq100", "sq300", "al3d-1"}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster:
        with distributed.Client(cluster) as client:
            parallel = gonio.study(SURFACES, ["ray", "kirchhoff"], [550.0], client=client, **OPTIONS)
    pd.testing.assert_frame_equal(parallel, serial, check_exact=True)
