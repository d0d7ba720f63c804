"""Shared set-up of the Python tests: the repository's paths, the CLI binary (built by
``cargo build`` when missing) and the oracle policy of the Rust tests (``GONIO_REQUIRE_ORACLES=1``
turns a missing independent implementation into a failure instead of a skip)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
SURFACE_DATA = ROOT / "crates" / "surface" / "tests" / "data"
BRDF_DATA = ROOT / "crates" / "brdf" / "tests" / "data"


def oracle_missing(why: str) -> None:
    """Skip, or fail when GONIO_REQUIRE_ORACLES=1 demands the oracle."""
    if os.environ.get("GONIO_REQUIRE_ORACLES") == "1":
        pytest.fail(f"GONIO_REQUIRE_ORACLES=1 but {why}")
    pytest.skip(why)


@pytest.fixture(scope="session")
def gonio_cli() -> Path:
    """The ``gonio`` binary of this checkout as ``cargo test --workspace`` builds it (already
    there after the Rust tests, so this build does nothing then; the same command keeps the
    workspace's features, which a build of the CLI alone would change). Rust does not reorder
    floating-point arithmetic at any optimisation level, so its numbers are the release
    build's."""
    subprocess.run(
        ["cargo", "test", "-q", "--workspace", "--no-run"],
        cwd=ROOT,
        check=True,
        capture_output=True,
    )
    return ROOT / "target" / "debug" / "gonio"


def cli_map(gonio_cli: Path, path: Path, sq_nm: float, seed: int) -> Path:
    """A 128² Gaussian map (T = 6 µm, 0.5 µm spacing) written by the CLI's synthesis to
    ``path`` (an X3P file), for tests that give the same file to the CLI and to Python."""
    subprocess.run(
        [gonio_cli, "surface", "gen", "--sq-nm", str(sq_nm), "--corr-um", "6", "--size", "128",
         "--dx-um", "0.5", "--seed", str(seed), "-o", path],
        check=True, capture_output=True,
    )
    return path
