"""Studies over many surfaces: every (surface × method × wavelength) is one task that computes
in-plane curves; the tasks run here one after another, or on a Dask cluster when given a
``dask.distributed.Client``. Surfaces travel to the workers as file paths or synthesis
parameters, and each worker reads or makes its surface itself, so no height map is pickled.
The result is the same, to the bit and in the same order, wherever the tasks ran."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Mapping, Sequence

import pandas as pd

__all__ = ["study", "Task", "tasks_of", "run_task"]

#: Methods that depend on the wavelength (one task per wavelength); the others run once per
#: surface and write the wavelength only when a single one is given (as ``gonio inplane``).
WAVE_METHODS = ("kirchhoff", "beckmann", "smooth")


@dataclass(frozen=True)
class Task:
    """One unit of a study: a surface (a path, or the keyword arguments of
    :func:`gonio.synthesize`), its label, a method, the wavelengths it computes and the other
    keyword arguments of :func:`gonio.inplane`."""

    label: str
    surface: str | tuple
    method: str
    wavelength_nm: tuple
    options: tuple = field(default=())


def _label(surface: Any, k: int) -> tuple[str, str | tuple]:
    if isinstance(surface, (str, os.PathLike)):
        path = os.fspath(surface)
        return os.path.splitext(os.path.basename(path))[0], path
    if isinstance(surface, Mapping):
        params = dict(surface)
        label = str(params.pop("label", f"synthetic-{k}"))
        return label, tuple(sorted(params.items()))
    raise TypeError(
        "a study takes surfaces as file paths or dicts of gonio.synthesize's arguments "
        f"(sq, corr, size, dx, acf, seed), not {type(surface).__name__}: workers read or make "
        "their own surfaces"
    )


def tasks_of(
    surfaces: Sequence[Any],
    methods: Sequence[str],
    wavelengths_nm: Sequence[float],
    options: Mapping[str, Any],
) -> list[Task]:
    """The tasks of a study, in the order of its rows: surface, then method, then wavelength."""
    tasks = []
    opts = tuple(sorted(options.items()))
    for k, s in enumerate(surfaces):
        label, surface = _label(s, k)
        for m in methods:
            if m in WAVE_METHODS:
                if not wavelengths_nm:
                    raise ValueError(f"method {m!r} depends on the wavelength: give wavelengths_nm")
                for w in wavelengths_nm:
                    tasks.append(Task(label, surface, m, (float(w),), opts))
            else:
                tasks.append(Task(label, surface, m, tuple(map(float, wavelengths_nm)), opts))
    return tasks


def run_task(task: Task) -> pd.DataFrame:
    """Compute one task (on whichever machine runs it): its curves with a ``surface`` column."""
    import gonio

    if isinstance(task.surface, str):
        surface = gonio.read_surface(task.surface)
    else:
        surface = gonio.synthesize(**dict(task.surface))
    df = gonio.inplane(
        surface,
        method=task.method,
        wavelength_nm=list(task.wavelength_nm) or None,
        **dict(task.options),
    )
    df.insert(0, "surface", task.label)
    return df


def study(
    surfaces: Sequence[Any],
    methods: str | Sequence[str] = "ray",
    wavelengths_nm: float | Sequence[float] | None = None,
    *,
    client: Any = None,
    **options: Any,
) -> pd.DataFrame:
    """In-plane curves of many surfaces by several methods, one task per (surface × method ×
    wavelength); a wavelength-independent method (the ray method, the geometric and microfacet
    models) is one task per surface.

    ``surfaces``: file paths, or dicts of :func:`gonio.synthesize`'s arguments (``sq``,
    ``corr``, ``size``, ``dx``, ``acf``, ``seed``; an optional ``label``). ``options``: the
    other keyword arguments of :func:`gonio.inplane` (``incidence_deg``, ``scatter_deg``,
    ``aperture_deg``, ``index``, ...). With ``client`` (a ``dask.distributed.Client``) the tasks
    run on its cluster; every worker needs gonio installed (``pip install ./crates/python``)
    and the surface files at the same paths. Returns one DataFrame, a ``surface`` column then
    :data:`gonio.COLUMNS`, in task order; its ``attrs["tasks"]`` counts the tasks.
    """
    methods = [methods] if isinstance(methods, str) else list(methods)
    if wavelengths_nm is None:
        wavelengths = []
    elif isinstance(wavelengths_nm, (int, float)):
        wavelengths = [float(wavelengths_nm)]
    else:
        wavelengths = [float(w) for w in wavelengths_nm]
    tasks = tasks_of(surfaces, methods, wavelengths, options)
    if client is None:
        frames = [run_task(t) for t in tasks]
    else:
        futures = client.map(run_task, tasks, pure=False)
        frames = client.gather(futures)
    df = pd.concat(frames, ignore_index=True)
    df.attrs["tasks"] = len(tasks)
    return df
