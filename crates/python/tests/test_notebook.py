"""The example notebook runs from top to bottom (nbclient): a failing cell fails the test."""

from __future__ import annotations

import nbformat
from nbclient import NotebookClient
import pytest

from conftest import ROOT

NOTEBOOKS = ROOT / "examples" / "python"


@pytest.mark.parametrize("name", ["roughness_study.ipynb", "cayman_match.ipynb"])
def test_notebook_runs(name):
    notebook = NOTEBOOKS / name
    nb = nbformat.read(notebook, as_version=4)
    client = NotebookClient(
        nb,
        timeout=900,
        kernel_name="python3",
        resources={"metadata": {"path": str(notebook.parent)}},
    )
    client.execute()
    errors = [
        o
        for cell in nb.cells
        if cell.cell_type == "code"
        for o in cell.get("outputs", [])
        if o.get("output_type") == "error"
    ]
    assert not errors, errors
