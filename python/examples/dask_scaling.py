"""Measures the Dask scale-out of the scene's coal-gangue ensemble (impact.identify): the
overhead per shard and the speed-up from one to two workers, against a single-process run of
the same ensemble in the same run.

    python python/examples/dask_scaling.py [--scene scenes/caving-stream.toml]
        [--condition "Con 2"] [--shard-size 250] [--empty 200]

Prints:
- the single-process time of the whole ensemble (impact.identify, no Dask), and the reduced
  model's set-up (the first call in a process; later calls reuse the model);
- the task overhead per shard: empty shards through the cluster (scheduling, pickling the
  scene and the result, the round trip);
- the whole overhead per shard with work: (one worker's time - the single-process time) /
  shards (it includes the worker's one model set-up);
- the time on one and on two workers (LocalCluster, one single-threaded process each), the
  speed-up, and whether the merged result equals the single-process one bit for bit.

Times are wall-clock on whatever else the machine is doing: read the speed-up beside the load
average printed with it.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from dask.distributed import Client, LocalCluster

import impact
import impact.shards as shards


def timed(f):
    t = time.perf_counter()
    out = f()
    return out, time.perf_counter() - t


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--scene", default="scenes/caving-stream.toml")
    ap.add_argument("--condition", default="Con 2")
    ap.add_argument("--shard-size", type=int, default=250, help="impacts per shard")
    ap.add_argument("--empty", type=int, default=200, help="empty shards for the task overhead")
    a = ap.parse_args()
    scene = impact.Scene.from_toml(a.scene)
    n = impact.ensemble_size(scene)
    ranges = shards.shard_ranges(n, a.shard_size)
    print(f"{scene.name}: {n} impacts on {a.condition}, {len(ranges)} shards of {a.shard_size}")
    _, t_one = timed(lambda: impact.identify(scene, a.condition, 0, 1))
    single, t_single = timed(lambda: impact.identify(scene, a.condition))
    # The first call built the reduced model and kept it (one per process and support set), so
    # the whole-ensemble call that follows is impacts only.
    print(f"single process: {t_single:.2f} s ({1e3 * t_single / n:.2f} ms per impact); "
          f"reduced model set-up (first call, one impact): {t_one:.2f} s")
    times = {}
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as c, Client(c) as client:
            client.run(lambda: None)  # workers up and connected before timing
            if workers == 1:
                def empties():
                    fs = [client.submit(impact.identify, scene, a.condition, 0, 0, key=f"empty-{i}", pure=False) for i in range(a.empty)]
                    return client.gather(fs)
                _, t_empty = timed(empties)
                print(f"task overhead per shard (empty shards, 1 worker): {1e3 * t_empty / a.empty:.2f} ms")
            merged, t = timed(lambda: shards.run_identify(client, scene, a.condition, shard_size=a.shard_size))
            times[workers] = t
            same = list(single) == list(merged) and all(
                np.array_equal(single[k], merged[k], equal_nan=single[k].dtype.kind == "f") for k in single
            )
            print(f"{workers} worker(s): {t:.2f} s; merged result identical to the single process: {same}")
            if workers == 1:
                print(f"whole overhead per shard (1 worker - single process) / shards: {(t - t_single) / len(ranges):.2f} s")
    print(f"speed-up 1 -> 2 workers: {times[1] / times[2]:.2f}x (load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores)")


if __name__ == "__main__":
    main()
