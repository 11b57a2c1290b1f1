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
    d = tiny()
    scene = impact.Scene.from_dict(d)
    path = tmp_path / "stream.toml"
    path.write_text(scene.to_toml_str())
    subprocess.run([str(BINARY), "stream", "--scene", str(path), "--out", str(tmp_path / "out"), "--json"], check=True, capture_output=True)
    r = impact.stream(scene)
    cli = json.loads((tmp_path / "out" / "stream.json").read_text())
    assert cli["conditions"][0]["groups"] == r.results["conditions"][0]["groups"]
    assert cli["conditions"][0]["baselines"] == r.results["conditions"][0]["baselines"]
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
