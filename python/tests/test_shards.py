"""Sharded ensembles on dask.distributed: shards of an index range, run as tasks of a
LocalCluster with two worker processes, merge into exactly the single-process ensemble of
the same seed (every column, bit for bit); the merge refuses gaps and overlaps."""

from __future__ import annotations

import numpy as np
import pytest

import impact
import impact.shards as shards

distributed = pytest.importorskip("distributed")

KW = dict(
    condition="Con 2",
    families=["coal", "gangue 1"],
    seed=20261122,
    velocity_m_per_s=(0.005, 0.02),
    radius_spread=0.2,
    elements=8,
    steps_per_contact=60.0,
)


def assert_same(a: dict, b: dict) -> None:
    assert list(a) == list(b)
    for k in a:
        assert a[k].dtype == b[k].dtype, k
        assert np.array_equal(a[k], b[k], equal_nan=a[k].dtype.kind == "f"), k


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as c:
        yield c


def test_merged_shards_equal_the_single_run(client):
    scene = impact.Scene.default()
    single = impact.ensemble(scene, start=0, stop=10, **KW)
    assert len(single["index"]) == 10
    # Shards of 3 (the last one short) on two worker processes.
    merged = shards.run_ensemble(client, scene, n=10, shard_size=3, **KW)
    assert_same(single, merged)
    # Families in turn, and each impact its own draw: a later start gives the same rows.
    assert list(single["family"][:4]) == ["coal", "gangue 1", "coal", "gangue 1"]
    tail = impact.ensemble(scene, start=7, stop=10, **KW)
    assert_same({k: v[7:] for k, v in single.items()}, tail)
    # Another seed is another ensemble.
    other = impact.ensemble(scene, start=0, stop=2, **dict(KW, seed=1))
    assert not np.array_equal(other["x_m"], single["x_m"][:2])


def test_shard_ranges_and_merge_checks():
    assert shards.shard_ranges(7, 3) == [(0, 3), (3, 6), (6, 7)]
    assert shards.shard_ranges(0, 3) == []
    scene = impact.Scene.default()
    a = impact.ensemble(scene, start=0, stop=2, **KW)
    b = impact.ensemble(scene, start=3, stop=4, **KW)
    empty = impact.ensemble(scene, start=4, stop=4, **KW)
    assert list(empty) == list(a) and len(empty["index"]) == 0
    with pytest.raises(ValueError, match="gaps or overlaps"):
        shards.merge([a, b])
    assert_same(shards.merge([b, empty, impact.ensemble(scene, start=2, stop=3, **KW), a]),
                impact.ensemble(scene, start=0, stop=4, **KW))


def test_ensemble_rows_carry_validity_and_bad_arguments_are_refused():
    scene = impact.Scene.default()
    cols = impact.ensemble(scene, start=0, stop=2, **KW)
    assert cols["valid"].dtype == bool and np.isfinite(cols["elastic_ratio"]).all()
    with pytest.raises(impact.SceneError, match="'slate' is not a body"):
        impact.ensemble(scene, start=0, stop=1, **dict(KW, families=["slate"]))
    with pytest.raises(impact.SceneError) as e:
        impact.ensemble(scene, start=0, stop=1, **dict(KW, radius_spread=0.9))
    assert e.value.field == "radius_spread" and e.value.allowed == "[0, 0.5]"
