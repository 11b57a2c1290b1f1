"""Measures the Dask scale-out of an ensemble: the overhead per shard and the speed-up from one
to two workers, against a single-process run of the same ensemble in the same run.

    python python/examples/dask_scaling.py [--n 256] [--shard-size 16]

Prints:
- the single-process time per impact (impact.ensemble, no Dask);
- the task overhead per shard: empty shards through the cluster (scheduling, pickling the
  scene and the result, the round trip);
- the whole overhead per shard with work: (one worker's time - the single-process time) /
  shards, which adds what a shard repeats (reading the scene, building the plate mesh);
- the time on one and on two workers (LocalCluster, one single-threaded process each) and
  the speed-up, and that the merged result equals the single-process one.

Times are wall-clock on whatever else the machine is doing: read the speed-up beside the
load average printed with it.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import impact
import impact.shards as shards

KW = dict(
    condition="Con 2",
    families=["coal", "gangue 1"],
    seed=7,
    velocity_m_per_s=(0.005, 0.02),
    radius_spread=0.2,
    elements=12,
    steps_per_contact=100.0,
)


def timed(f):
    t = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=256, help="impacts in the ensemble")
    ap.add_argument("--shard-size", type=int, default=16, help="impacts per shard")
    ap.add_argument("--empty", type=int, default=200, help="empty shards for the task overhead")
    a = ap.parse_args()
    scene = impact.Scene.default()
    single, t_single = timed(lambda: impact.ensemble(scene, start=0, stop=a.n, **KW))
    shards_n = len(shards.shard_ranges(a.n, a.shard_size))
    print(f"ensemble: {a.n} impacts (transient model, {KW['elements']} elements, {KW['steps_per_contact']:g} steps per contact), {shards_n} shards of {a.shard_size}")
    print(f"single process: {t_single:.3f} s, {1e3 * t_single / a.n:.2f} ms per impact")
    times = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as c, Client(c) as client:
            client.run(lambda: None)  # workers up and connected before timing
            if workers == 1:
                _, t_empty = timed(
                    lambda: client.gather(
                        [
                            client.submit(impact.ensemble, scene, start=0, stop=0, key=f"empty-{i}", pure=False, **KW)
                            for i in range(a.empty)
                        ]
                    )
                )
                print(f"task overhead per shard (empty shards, 1 worker): {1e3 * t_empty / a.empty:.2f} ms")
            merged, t = timed(lambda: shards.run_ensemble(client, scene, n=a.n, shard_size=a.shard_size, **KW))
            times[workers] = t
            same = all(np.array_equal(single[k], merged[k], equal_nan=single[k].dtype.kind == "f") for k in single)
            print(f"{workers} worker(s): {t:.3f} s; merged result identical to the single process: {same}")
            if workers == 1:
                print(f"whole overhead per shard with work (1 worker - single process) / shards: {1e3 * (t - t_single) / shards_n:.2f} ms")
    print(f"speed-up 1 -> 2 workers: {times[1] / times[2]:.2f}x (load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores)")


if __name__ == "__main__":
    main()
