"""The scene's coal-gangue ensemble (what `impact identify` runs) in shards on dask.distributed:
index-range shards run as tasks of a LocalCluster with two worker processes merge into exactly
the single-process run of the same scene (every column, bit for bit); a later range alone gives
the same rows; the merge refuses gaps and overlaps.

The ensemble is scenes/paper-velocities-ensemble.toml made tiny for a test: 6 coal and 6
gangue impacts on Con 2, a 5 ms window at 10 kHz on 16 modes."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

import impact
import impact.shards as shards
from conftest import REPO

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def scene() -> impact.Scene:
    d = tomllib.loads((REPO / "scenes" / "paper-velocities-ensemble.toml").read_text())
    d["ensemble"]["families"] = d["ensemble"]["families"][:2]
    for f in d["ensemble"]["families"]:
        f["count"] = 6
    d["signals"].update(modes=16, window_ms=5.0, rate_hz=10000.0)
    d["conditions"] = [c for c in d["conditions"] if c["name"] == "Con 2"]
    return impact.Scene.from_dict(d)


@pytest.fixture(scope="module")
def single(scene) -> dict:
    return impact.identify(scene, "Con 2")


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


def test_merged_shards_equal_the_single_run(scene, single, client):
    assert impact.ensemble_size(scene) == 12 and len(single["index"]) == 12
    assert list(single["class"]) == ["coal"] * 6 + ["gangue"] * 6
    # Two shards on two worker processes (the scene travels pickled as its TOML text).
    merged = shards.run_identify(client, scene, "Con 2", shard_size=6)
    assert_same(single, merged)


def test_a_range_alone_gives_the_same_rows(scene, single):
    tail = impact.identify(scene, "Con 2", start=7, stop=12)
    assert_same({k: v[7:] for k, v in single.items()}, tail)
    # Features of every channel, finite; validity on every row.
    features = [k for k in single if ": " in k]
    # "<channel>: <feature> (<unit>)": every channel has each feature of the registry once.
    names = {k.split(": ", 1)[1].split(" (")[0] for k in features}
    assert len(features) % len(names) == 0 and len(features) >= len(names) * 4
    assert all(np.isfinite(single[k]).all() for k in features)
    assert single["valid"].dtype == bool and np.isfinite(single["elastic_ratio"]).all()


def test_shard_ranges_and_merge_checks(scene, single):
    assert shards.shard_ranges(7, 3) == [(0, 3), (3, 6), (6, 7)]
    assert shards.shard_ranges(0, 3) == []
    parts = {r: {k: v[r[0] : r[1]] for k, v in single.items()} for r in [(0, 2), (2, 3), (3, 5)]}
    empty = impact.identify(scene, "Con 2", start=5, stop=5)
    assert len(empty["index"]) == 0
    with pytest.raises(ValueError, match="gaps or overlaps"):
        shards.merge([parts[(0, 2)], parts[(3, 5)]])
    assert_same(
        shards.merge([parts[(3, 5)], empty, parts[(2, 3)], parts[(0, 2)]]),
        {k: v[:5] for k, v in single.items()},
    )


def test_bad_requests_are_refused(scene):
    with pytest.raises(ValueError) as e:
        impact.identify(scene, "Con 2", start=0, stop=13)
    assert e.value.field == "stop" and e.value.allowed == "[0, 12]"
    with pytest.raises(ValueError, match="'Con 9' is not in the scene"):
        impact.identify(scene, "Con 9", start=0, stop=1)
    with pytest.raises(ValueError, match=r"no \[ensemble\] table"):
        impact.identify(impact.Scene.default(), "Con 1", start=0, stop=1)


def test_sensors_of_one_channel_label_are_refused(scene):
    # 0.04 mm apart: both labelled (229.2, 180) mm, so every feature column of the second
    # would have the first's name (the scene reader refuses them in [signals] sensors_mm).
    with pytest.raises(ValueError) as e:
        impact.identify(scene, "Con 2", 0, 1, sensors_mm=[(229.2, 180.0), (100.0, 90.0), (229.24, 180.0)])
    assert e.value.field == "sensors_mm[2]"
    message = str(e.value)
    assert "(229.2, 180) mm" in message and "sensors_mm[0]" in message and "0.1 mm apart" in message
    # The same sensors as a scene's are refused with the same words.
    with pytest.raises(impact.SceneError) as s:
        d = tomllib.loads((REPO / "scenes" / "paper-velocities-ensemble.toml").read_text())
        d["signals"]["sensors_mm"] = [[229.2, 180.0], [100.0, 90.0], [229.24, 180.0]]
        impact.Scene.from_dict(d)
    assert message in str(s.value).replace("signals.", "")
    # 0.1 mm apart is two channels.
    rows = impact.identify(scene, "Con 2", 0, 1, sensors_mm=[(229.2, 180.0), (229.3, 180.0)])
    assert any("(229.3, 180) mm" in k for k in rows)
