"""The scene's coal-gangue ensemble split into independent seeded shards, and a long caving
stream split into its segments, run as dask.distributed tasks.

An ensemble of ``n`` impacts is the index range [0, n). Every impact draws from its own random
stream (ChaCha8 keyed by the ensemble's seed, stream i), so a shard [start, stop) computes
exactly the rows a single run computes for those indices, on any machine and in any order. The
shards run as tasks of a ``dask.distributed.Client`` and :func:`merge` puts them back in index
order: the merged columns equal a single-process :func:`impact.identify` of the same scene,
bit for bit (``python/tests/test_shards.py`` checks it on a ``LocalCluster``).

On one machine::

    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        cols = impact.shards.run_identify(client, "scenes/caving-stream.toml", "Con 2", shard_size=500)

On a Slurm cluster (``pip install dask-jobqueue``; every node sees the same Python environment
with ``impact`` installed, e.g. a venv on a shared file system)::

    from dask_jobqueue import SLURMCluster
    cluster = SLURMCluster(
        queue="compute", account="my-project",       # as your site names them
        cores=1, processes=1, memory="2GB",          # one single-threaded worker per job
        walltime="02:00:00",
        python="/shared/venvs/impact/bin/python",
    )
    cluster.scale(jobs=64)                           # or cluster.adapt(maximum_jobs=64)
    client = Client(cluster)
    cols = impact.shards.run_identify(client, scene, "Con 2", shard_size=2000)

A long stream of a ``[stream]`` study whose scene cuts it (``segment_s``) runs as one task per
segment (:func:`run_stream`): each segment starts from rest after a warm-up long enough for
the plate's and the chain's past to have decayed to ``segment_tolerance``, and draws its
background from its own blocks of the recording's random numbers, so the segments put
together are the study's stream bit for bit.

A worker process builds the reduced model of a support set once (the plate's modes: about two
seconds for the default 80 modes) and keeps it for its next shards; the impacts then cost a
few milliseconds each, and a shard adds the Dask task overhead (milliseconds). The README
gives the measured numbers. A shard that fails (a worker lost) is simply rerun by Dask: it has
no state but its range.
"""

from __future__ import annotations

import hashlib
from typing import Any, Callable, Sequence

import numpy as np

from . import Columns, SceneLike, StreamRecording, ensemble_size, identify, load_scene, stream_recording, stream_segments


def _digest(scene: Any) -> str:
    """The first 12 hex digits of the SHA-256 of the scene's TOML text: its tasks' keys, so
    that runs of different scenes on one cluster never share a key."""
    return hashlib.sha256(scene.to_toml_str().encode()).hexdigest()[:12]


def shard_ranges(n: int, shard_size: int) -> list[tuple[int, int]]:
    """[start, stop) ranges of at most ``shard_size`` covering [0, n) in order."""
    if n < 0 or shard_size < 1:
        raise ValueError(f"n = {n} must be >= 0 and shard_size = {shard_size} >= 1")
    return [(a, min(a + shard_size, n)) for a in range(0, n, shard_size)]


def merge(parts: Sequence[Columns]) -> Columns:
    """Concatenates shards (in any order) into index order, checking that their ``index``
    columns tile one contiguous range with no gap or overlap. Empty shards add no rows."""
    if not parts:
        raise ValueError("no shards to merge")
    # An empty shard has no feature columns (they follow from the data): leave it out.
    parts = [p for p in parts if len(p["index"])] or list(parts[:1])
    names = list(parts[0])
    for p in parts:
        if list(p) != names:
            raise ValueError(f"shards have different columns: {list(p)} against {names}")
    order = sorted(range(len(parts)), key=lambda i: int(parts[i]["index"][0]) if len(parts[i]["index"]) else -1)
    merged = {k: np.concatenate([parts[i][k] for i in order]) for k in names}
    index = merged["index"]
    if len(index) and not np.array_equal(index, np.arange(index[0], index[0] + len(index))):
        raise ValueError("the shards' index ranges have gaps or overlaps")
    return merged


def run_sharded(
    client: Any,
    shard: Callable[..., Columns],
    n: int,
    shard_size: int,
    *args: Any,
    key: str = "impact-shard",
    **kwargs: Any,
) -> Columns:
    """Runs ``shard(*args, start=a, stop=b, **kwargs)`` for every range of
    :func:`shard_ranges` as a task of ``client`` and merges the results.

    ``shard`` must be importable on the workers (a module-level function) and return
    columns with an ``index`` column; its arguments are pickled to the workers (a
    :class:`impact.Scene` travels as its TOML text and is validated again there).
    """
    ranges = shard_ranges(n, shard_size)
    futures = [
        client.submit(shard, *args, start=a, stop=b, key=f"{key}-{a}-{b}", pure=False, **kwargs) for a, b in ranges
    ]
    return merge(client.gather(futures))


def _identify_shard(scene: SceneLike, condition: str, *, start: int, stop: int, sensors_mm: Any = None) -> Columns:
    return identify(scene, condition, start=start, stop=stop, sensors_mm=sensors_mm)


def run_identify(
    client: Any,
    scene: SceneLike,
    condition: str,
    *,
    shard_size: int,
    sensors_mm: Sequence[tuple[float, float]] | None = None,
) -> Columns:
    """:func:`impact.identify` of the scene's whole ensemble on ``condition``, split into
    shards of ``shard_size`` impacts run on ``client``; equal to ``impact.identify(scene,
    condition, sensors_mm=sensors_mm)`` bit for bit."""
    scene = load_scene(scene)
    return run_sharded(
        client,
        _identify_shard,
        ensemble_size(scene),
        shard_size,
        scene,
        condition,
        key=f"impact-identify-{_digest(scene)}-{condition}",
        sensors_mm=sensors_mm,
    )


def run_stream(client: Any, scene: SceneLike, condition: str, stream: int = 0) -> StreamRecording:
    """Stream ``stream`` of the scene's ``[stream]`` study on ``condition``, its segments
    (the scene's ``segment_s``) computed as tasks of ``client`` and put together in order:
    equal to ``impact.stream_recording(scene, condition, stream)``, and to the study's
    stream, bit for bit. Each segment runs alone from rest after its warm-up, so a long
    stream spreads over as many workers as it has segments."""
    scene = load_scene(scene)
    cut = stream_segments(scene)
    if cut is None:
        raise ValueError(f"scene {scene.name!r}: its [stream] has no segment_s, so its streams are not cut")
    tag = _digest(scene)
    futures = [
        client.submit(
            stream_recording, scene, condition, stream, b, key=f"impact-stream-{tag}-{condition}-{stream}-{b}", pure=False
        )
        for b in range(cut[0])
    ]
    parts = client.gather(futures)
    first = parts[0]
    signal = {k: np.concatenate([p.signal[k] for p in parts]) for k in first.signal}
    # A segment no lump touched has no lump columns (they follow from the rows).
    named = [p.lumps for p in parts if p.lumps]
    lumps = {k: np.concatenate([c[k] for c in named]) for k in named[0]} if named else first.lumps
    return StreamRecording(signal=signal, rate_hz=first.rate_hz, lumps=lumps)
