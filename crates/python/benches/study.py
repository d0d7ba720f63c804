"""Benchmark of a Dask study (docs/performance.md, "Python studies on Dask"): 32 synthetic maps
of 1024² points (the epoxy series' correlation length and spacing, Sq from 50 to 805 nm), ray
and Kirchhoff in-plane curves at the NIST STARR geometry (incidence 20/45/60/70°, −75..75° every
1°, 1.4°, 550 nm), run serially and on a LocalCluster of 2 workers. Prints the wall times, the
mean time per task and the bytes a task moves, and the projected time on N workers.

    python crates/python/benches/study.py [--maps 32] [--size 1024]

Run it on a quiet machine (nothing else building)."""

from __future__ import annotations

import argparse
import pickle
import platform
import time

import numpy as np

import gonio
from gonio.studies import run_task, tasks_of


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--maps", type=int, default=32)
    p.add_argument("--size", type=int, default=1024)
    a = p.parse_args()
    sq = np.geomspace(50e-9, 805e-9, a.maps)
    surfaces = [
        dict(label=f"map{k:02d}", sq=float(s), corr=6e-6, size=a.size, dx=0.5e-6, seed=k + 1)
        for k, s in enumerate(sq)
    ]
    methods, wavelengths = ["ray", "kirchhoff"], [550.0]
    tasks = tasks_of(surfaces, methods, wavelengths, {})
    t0 = time.perf_counter()
    per_task = {}
    frames = []
    for t in tasks:
        s = time.perf_counter()
        frames.append(run_task(t))
        per_task.setdefault(t.method, []).append(time.perf_counter() - s)
    serial = time.perf_counter() - t0
    down = np.mean([len(pickle.dumps(t)) for t in tasks])
    up = np.mean([len(pickle.dumps(f)) for f in frames])
    print(f"serial: {serial:.1f} s for {len(tasks)} tasks", flush=True)

    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        t0 = time.perf_counter()
        df = gonio.study(surfaces, methods, wavelengths, client=client)
        cluster_s = time.perf_counter() - t0
    import pandas as pd

    ser = pd.concat(frames, ignore_index=True)
    ser.insert(0, "surface", ser.pop("surface"))
    same = df.reset_index(drop=True).equals(ser)
    times = [x for ts in per_task.values() for x in ts]
    print(f"machine: {platform.processor() or platform.machine()}, {__import__('os').cpu_count()} cores")
    print(f"{len(tasks)} tasks ({a.maps} maps of {a.size}², methods {methods}, {wavelengths} nm)")
    for m, ts in per_task.items():
        print(f"  {m}: {np.mean(ts):.2f} s per task (min {min(ts):.2f}, max {max(ts):.2f})")
    print(f"serial: {serial:.1f} s; LocalCluster(2 workers): {cluster_s:.1f} s; identical: {same}")
    print(f"moved per task: {down:.0f} B to the worker, {up / 1024:.1f} kB back")
    # N workers like this machine, each task alone on its worker: the work divides until the
    # longest task bounds it (plus the scheduler's few ms per task).
    for n in (1, 2, 8, 32, 64):
        print(f"  projected on {n:>2} workers like this machine: {max(sum(times) / n, max(times)):.0f} s")


if __name__ == "__main__":
    main()
