"""The caving-stream detection study (`[stream]`) from Python: `impact.stream` gives the
command line's numbers bit for bit (every window's score and every lump against
`impact stream --json`'s files), its columns agree with each other, the recorded signal has
the stream's length at its rate, and a scene without `[stream]` is refused with the key named.

The scene is scenes/paper-velocities-ensemble.toml made tiny: Con 2, 16 modes, a 5 ms follow,
two streams of 4 s at 10 lumps a second."""

from __future__ import annotations

import csv
import json
import subprocess
import tomllib

import numpy as np
import pytest

import impact
import impact.shards
from conftest import REPO, impact_binary

STREAM = {
    "rate_per_s": 10.0,
    "duration_s": 4.0,
    "streams": 2,
    "seed": 5,
    "gangue_before": 0.0,
    "gangue_after": 1.0,
    "onset_s": 2.0,
    "window_s": 0.5,
    "hop_s": 0.25,
    "blocks": 4,
    "write_signal": True,
}


def tiny() -> dict:
    d = tomllib.loads((REPO / "scenes" / "paper-velocities-ensemble.toml").read_text())
    d["ensemble"]["families"] = d["ensemble"]["families"][:2]
    d["signals"].update(modes=16, window_ms=5.0, rate_hz=20000.0)
    d["conditions"] = [c for c in d["conditions"] if c["name"] == "Con 2"]
    d["stream"] = dict(STREAM)
    return d


def test_stream_columns_agree_and_the_signal_has_the_streams_length():
    r = impact.stream(impact.Scene.from_dict(tiny()))
    c = r.conditions["Con 2"]
    w, lumps = c.windows, c.lumps
    assert len(w["start_s"]) == 2 * 15
    # Each window's lump count is that of the lumps column in its span.
    for i in range(len(w["start_s"])):
        inside = (lumps["stream"] == w["stream"][i]) & (lumps["time_s"] >= w["start_s"][i]) & (lumps["time_s"] < w["end_s"][i])
        assert w["lumps"][i] == inside.sum()
        assert w["gangue_lumps"][i] == (inside & lumps["gangue"]).sum()
    assert c.signal_rate_hz == 20000.0
    assert all(len(v) == 80000 for v in c.signal.values())
    every = r.results["conditions"][0]["groups"][0]
    assert every["group"] == "every channel" and 0.0 <= every["auc"] <= 1.0


def test_a_scene_without_a_stream_is_refused():
    d = tiny()
    del d["stream"]
    with pytest.raises(ValueError, match="scene"):
        impact.stream(impact.Scene.from_dict(d))


BINARY = impact_binary()


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_python_and_the_command_line_agree_bit_for_bit(tmp_path):
    """Every window's score, the groups, the baselines and the window-level sensor design
    (two accelerometers among the scene's 7 x 5 candidate points) are the command line's."""
    d = tiny()
    d["stream"]["design_sensors"] = 2
    scene = impact.Scene.from_dict(d)
    path = tmp_path / "stream.toml"
    path.write_text(scene.to_toml_str())
    subprocess.run([str(BINARY), "stream", "--scene", str(path), "--out", str(tmp_path / "out"), "--json"], check=True, capture_output=True)
    r = impact.stream(scene)
    cli = json.loads((tmp_path / "out" / "stream.json").read_text())
    assert cli["conditions"][0]["groups"] == r.results["conditions"][0]["groups"]
    assert cli["conditions"][0]["baselines"] == r.results["conditions"][0]["baselines"]
    design = r.results["conditions"][0]["design"]
    assert cli["conditions"][0]["design"] == design and len(design["steps"]) == 2
    with open(tmp_path / "out" / "con-2" / "windows.csv") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))[1:]
    p = r.conditions["Con 2"].windows["probability_gangue_rich"]
    for row, q in zip(rows, p, strict=True):
        assert (row[7] == "" and np.isnan(q)) or float(row[7]) == q


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_the_detector_scores_the_same_in_python_and_the_command_line(tmp_path):
    """`impact stream`'s detector.json, applied by `impact detect` and by `impact.Detector`
    (to the sidecar, and to the arrays `impact.read_signal` returns), gives every window the
    same probability bit for bit; the detector Python's `impact.stream` fits is the command
    line's (the same model, bit for bit)."""
    scene = impact.Scene.from_dict(tiny())
    path = tmp_path / "stream.toml"
    path.write_text(scene.to_toml_str())
    out = tmp_path / "out"
    subprocess.run([str(BINARY), "stream", "--scene", str(path), "--out", str(out)], check=True, capture_output=True)
    run = out / "con-2"
    subprocess.run(
        [str(BINARY), "detect", "--detector", str(run / "detector.json"), "--signal", str(run / "signal.json"), "--out", str(tmp_path / "d")],
        check=True,
        capture_output=True,
    )
    with open(tmp_path / "d" / "scores.csv") as f:
        rows = list(csv.reader(line for line in f if not line.startswith("#")))
    assert rows[0] == ["start_s", "end_s", "probability_gangue_rich", "alarm"]
    cli = np.array([float(r[2]) for r in rows[1:]])
    detector = impact.Detector.load(run / "detector.json")
    detected = detector.detect(run / "signal.json")
    assert np.array_equal(detected["scores"]["probability_gangue_rich"], cli)
    signal = impact.read_signal(run / "signal.json")
    scored = detector.score(signal["channels"], signal["rate_hz"])
    assert np.array_equal(scored["probability_gangue_rich"], cli)
    assert signal["onset_s"] == STREAM["onset_s"]
    # 4 s in windows of 0.5 s every 0.25 s: 15 of them; 7 end by the onset at 2 s (starts 0
    # to 1.5 s), 7 start from it (2 to 3.5 s), the one from 1.75 s straddles it.
    answer = json.loads((tmp_path / "d" / "detect.json").read_text())["assessment"]
    assert (answer["windows_before"], answer["windows_after"]) == (7, 7)
    assert json.loads(detected["assessment"]) == {k: v for k, v in answer.items() if k != "provenance"}
    fitted = impact.stream(scene).conditions["Con 2"].detector
    assert json.loads(fitted.to_json())["model"] == json.loads(detector.to_json())["model"]
    with pytest.raises(ValueError, match="rate_hz = 1000"):
        detector.score(signal["channels"], 1000.0)
    with pytest.raises(ValueError, match="channels given"):
        detector.score(signal["channels"][:1], signal["rate_hz"])
    (tmp_path / "bad.json").write_text('{"format": "something-else/2"}')
    with pytest.raises(ValueError, match="something-else/2"):
        impact.Detector.load(tmp_path / "bad.json")
    with pytest.raises(FileNotFoundError):
        impact.Detector.load(tmp_path / "missing.json")


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_a_parquet_signal_reads_in_pandas_as_impact_reads_it(tmp_path):
    """`signal_format = "parquet"`: pandas (through pyarrow) reads `signal.parquet` to the same
    bits as `impact.read_signal` and as `impact.stream`'s own arrays; the file carries its
    sidecar in its key-value metadata; a detector scores it as it scores the CSV."""
    pd = pytest.importorskip("pandas")
    pq = pytest.importorskip("pyarrow.parquet")
    d = tiny()
    d["stream"]["signal_format"] = "parquet"
    scene = impact.Scene.from_dict(d)
    path = tmp_path / "stream.toml"
    path.write_text(scene.to_toml_str())
    out = tmp_path / "out"
    subprocess.run([str(BINARY), "stream", "--scene", str(path), "--out", str(out)], check=True, capture_output=True)
    run = out / "con-2"
    sidecar = json.loads((run / "signal.json").read_text())
    assert sidecar["data"] == "signal.parquet"
    frame = pd.read_parquet(run / "signal.parquet")
    assert list(frame.columns) == [sidecar["time_column"], *sidecar["columns"]]
    assert np.array_equal(frame["t_s"].to_numpy(), np.arange(80000) / 20000.0)
    read = impact.read_signal(run / "signal.json")
    own = impact.stream(scene).conditions["Con 2"].signal
    for key, name, mine, theirs in zip(sidecar["columns"], sidecar["channels"], read["channels"], own.values(), strict=True):
        assert np.array_equal(frame[key].to_numpy(), mine), key
        assert np.array_equal(mine, theirs), name
    inside = pq.read_schema(run / "signal.parquet").metadata[b"impact-signal"]
    assert json.loads(inside) == sidecar
    detector = impact.Detector.load(run / "detector.json")
    scored = detector.detect(run / "signal.json")["scores"]["probability_gangue_rich"]
    assert np.array_equal(scored, detector.score(read["channels"], read["rate_hz"])["probability_gangue_rich"])



def test_a_recording_pandas_wrote_as_parquet_is_read_as_written(tmp_path):
    """A recording written by pandas (through pyarrow, not by impact): float32, int64 (an
    ADC's counts) and optional float64 columns read back as their values; a null sample, a
    missing column and a CSV under a .parquet name are refused, naming them."""
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    n = 5000
    frame = pd.DataFrame(
        {
            "a32": (np.sin(np.arange(n) * 0.01) * 3.0).astype(np.float32),
            "counts": np.arange(n, dtype=np.int64) - 2500,
            "a64": pd.array(np.cos(np.arange(n) * 0.02), dtype="Float64"),
        }
    )
    frame.to_parquet(tmp_path / "rec.parquet", index=False)
    sidecar = {"format": "impact-signal/1", "data": "rec.parquet", "rate_hz": 10000.0, "columns": ["counts", "a32", "a64"]}
    (tmp_path / "rec.json").write_text(json.dumps(sidecar))
    r = impact.read_signal(tmp_path / "rec.json")
    assert np.array_equal(r["channels"][0], frame["counts"].to_numpy(dtype=np.float64))
    assert np.array_equal(r["channels"][1], frame["a32"].to_numpy().astype(np.float64))
    assert np.array_equal(r["channels"][2], frame["a64"].to_numpy(dtype=np.float64))
    frame.loc[17, "a64"] = pd.NA
    frame.to_parquet(tmp_path / "rec.parquet", index=False)
    with pytest.raises(ValueError, match='column "a64", row 17: empty'):
        impact.read_signal(tmp_path / "rec.json")
    (tmp_path / "rec.json").write_text(json.dumps({**sidecar, "columns": ["a32", "nope"]}))
    with pytest.raises(ValueError, match='no column "nope"'):
        impact.read_signal(tmp_path / "rec.json")
    (tmp_path / "rec.parquet").write_text("a32\n1.0\n")
    with pytest.raises(ValueError, match="not a Parquet file"):
        impact.read_signal(tmp_path / "rec.json")


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_streams_computed_apart_are_the_studys_streams(tmp_path):
    """`impact.stream_recording` computes one stream alone: stream 0 is the signal `impact
    stream` writes, bit for bit, and every stream's lumps are the study's lumps of that
    stream; streams computed as tasks of a Dask LocalCluster (two worker processes) are the
    same again; a bad stream number or support set is refused, naming it."""
    distributed = pytest.importorskip("distributed")
    scene = impact.Scene.from_dict(tiny())
    path = tmp_path / "stream.toml"
    path.write_text(scene.to_toml_str())
    out = tmp_path / "out"
    subprocess.run([str(BINARY), "stream", "--scene", str(path), "--out", str(out)], check=True, capture_output=True)
    written = impact.read_signal(out / "con-2" / "signal.json")
    alone = [impact.stream_recording(scene, "Con 2", r) for r in range(STREAM["streams"])]
    assert alone[0].rate_hz == written["rate_hz"]
    for mine, theirs in zip(alone[0].signal.values(), written["channels"], strict=True):
        assert np.array_equal(mine, theirs)
    lumps = impact.stream(scene).conditions["Con 2"].lumps
    for r, one in enumerate(alone):
        of_r = lumps["stream"] == r
        for key in ("time_s", "mass_kg", "x_m", "contact_time_s", "force_max_N"):
            assert np.array_equal(one.lumps[key], lumps[key][of_r]), (r, key)
        assert np.all(one.lumps["stream"] == r)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            futures = client.map(impact.stream_recording, [scene] * 2, ["Con 2"] * 2, [0, 1], pure=False)
            remote = client.gather(futures)
    for a, b in zip(alone, remote, strict=True):
        assert all(np.array_equal(x, y) for x, y in zip(a.signal.values(), b.signal.values(), strict=True))
    with pytest.raises(ValueError, match="stream: -1"):
        impact.stream_recording(scene, "Con 2", -1)
    with pytest.raises(ValueError, match="'Con 9' is not in the scene"):
        impact.stream_recording(scene, "Con 9", 0)


def tiny_measured() -> dict:
    """scenes/caving-stream-detect.toml made small (Con 2, 40 modes, two streams of 6 s, no
    sweeps or design) and cut into three segments of 2 s, each warming up (to ε = 1e-2) for about 1.8 s:
    the later segments start after the stream's start."""
    d = tomllib.loads((REPO / "scenes" / "caving-stream-detect.toml").read_text())
    d["signals"]["modes"] = 40
    d["conditions"] = [c for c in d["conditions"] if c["name"] == "Con 2"]
    s = d["stream"]
    s.update(duration_s=6.0, streams=2, onset_s=3.0, ramp_s=0.0, window_s=1.0, blocks=2, write_signal=True)
    s.update(segment_s=2.0, segment_tolerance=1e-2)
    for k in ("rate_sweep_per_s", "noise_sweep", "size_sweep", "law_sweep", "plate_sweep", "design_sensors"):
        s.pop(k, None)
    return d


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_segments_computed_apart_are_the_studys_stream(tmp_path):
    """A stream the scene cuts into segments (``segment_s``), each segment computed alone
    (``impact.stream_recording(..., segment=b)``, and as tasks of a Dask LocalCluster by
    ``impact.shards.run_stream``), put together, is the signal ``impact stream`` writes and
    the study's lumps, bit for bit, through the measurement chain and its background; a
    segment number past the last, or a scene that cuts nothing, is refused naming it."""
    distributed = pytest.importorskip("distributed")
    scene = impact.Scene.from_dict(tiny_measured())
    assert impact.stream_segments(scene) == (3, 2.0)
    path = tmp_path / "stream.toml"
    path.write_text(scene.to_toml_str())
    out = tmp_path / "out"
    subprocess.run([str(BINARY), "stream", "--scene", str(path), "--out", str(out)], check=True, capture_output=True)
    written = impact.read_signal(out / "con-2" / "signal.json")
    cut = json.loads((out / "stream.json").read_text())["conditions"][0]["simulation"]["segments"]
    assert 0.5 < cut["warm_up_s"] < 2.0, cut  # the last segment's warm-up starts after the stream's
    parts = [impact.stream_recording(scene, "Con 2", 0, segment=b) for b in range(3)]
    assert [p.start_s for p in parts] == [0.0, 2.0, 4.0]
    for k, (name, theirs) in enumerate(zip(parts[0].signal, written["channels"], strict=True)):
        mine = np.concatenate([p.signal[name] for p in parts])
        assert np.array_equal(mine, theirs), name
    lumps = impact.stream(scene).conditions["Con 2"].lumps
    lumps = {k: v[lumps["stream"] == 0] for k, v in lumps.items()}
    times = np.concatenate([p.lumps["time_s"] for p in parts if p.lumps])
    assert np.array_equal(times, lumps["time_s"])
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            remote = impact.shards.run_stream(client, scene, "Con 2", 0)
    for mine, theirs in zip(remote.signal.values(), written["channels"], strict=True):
        assert np.array_equal(mine, theirs)
    for key in ("time_s", "force_max_N", "contact_time_s"):
        assert np.array_equal(remote.lumps[key], lumps[key]), key
    with pytest.raises(ValueError, match="segment 3: allowed 0 to 2"):
        impact.stream_recording(scene, "Con 2", 0, segment=3)
    with pytest.raises(ValueError, match="no segment_s"):
        impact.stream_recording(impact.Scene.from_dict(tiny()), "Con 2", 0, segment=0)


def tiny_box() -> dict:
    """scenes/tail-beam-stream.toml made small: 200 mm elements, two streams of 6 s at 3
    lumps a second over the middle of the top plate, no sweeps."""
    d = tomllib.loads((REPO / "scenes" / "tail-beam-stream.toml").read_text())
    d["tail_beam"]["element_mm"] = 200.0
    d["ensemble"]["region"] = {"x_mm": [400.0, 1400.0], "z_mm": [200.0, 1200.0]}
    d["stream"].update(
        rate_per_s=3.0, duration_s=6.0, streams=2, onset_s=3.0, ramp_s=0.0, window_s=1.0, hop_s=0.5, blocks=2,
        rate_sweep_per_s=[], noise_sweep=[], size_sweep=[], law_sweep=[], write_signal=True,
    )
    return d


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_the_tail_beams_stream_is_the_command_lines(tmp_path):
    """A stream on the tail beam from Python: the command line's scores, baselines and box
    bit for bit, its jack and accelerometer channels recorded over the stream's length; one
    stream apart (impact.stream_recording) is refused by name, as is impact.identify."""
    scene = impact.Scene.from_dict(tiny_box())
    path = tmp_path / "box.toml"
    path.write_text(scene.to_toml_str())
    subprocess.run([str(BINARY), "stream", "--scene", str(path), "--out", str(tmp_path / "out")], check=True, capture_output=True)
    cli = json.loads((tmp_path / "out" / "stream.json").read_text())
    r = impact.stream(scene)
    assert cli["conditions"][0]["groups"] == r.results["conditions"][0]["groups"]
    assert cli["conditions"][0]["baselines"] == r.results["conditions"][0]["baselines"]
    assert cli["structure"] == r.results["structure"]
    c = r.conditions["tail beam on its pins and jacks"]
    names = list(c.signal)
    assert [n.split(" at ")[0] for n in names] == ["jack force", "jack force", "acceleration", "acceleration"]
    assert all(len(v) == 6.0 * c.signal_rate_hz for v in c.signal.values())
    with pytest.raises(ValueError, match="tail beam"):
        impact.stream_recording(scene, "Con 1", 0)
    with pytest.raises(ValueError, match="tail beam"):
        impact.identify(scene, "Con 1", 0, 1)
