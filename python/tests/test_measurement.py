"""The measurement chain (`[measurement]`) from Python: `impact.identify` reads the signals
through it as `impact identify` does, so the features of any index range are those of the
whole run (the backgrounds are drawn per impact), a transparent chain gives the chain-less
features to half an ADC step, the chain's own columns (clean peaks, clipped samples) are
there, and a bad chain is refused with the key named.

The ensemble is scenes/paper-velocities-ensemble.toml made tiny: 6 coal and 6 gangue impacts
on Con 2, a 5 ms window at 20 kHz on 16 modes."""

from __future__ import annotations

import copy
import tomllib

import numpy as np
import pytest

import impact
from conftest import REPO


def tiny() -> dict:
    d = tomllib.loads((REPO / "scenes" / "paper-velocities-ensemble.toml").read_text())
    d["ensemble"]["families"] = d["ensemble"]["families"][:2]
    for f in d["ensemble"]["families"]:
        f["count"] = 6
    d["signals"].update(modes=16, window_ms=5.0, rate_hz=20000.0)
    d["conditions"] = [c for c in d["conditions"] if c["name"] == "Con 2"]
    return d


CHAIN = {
    "rate_hz": 10000.0,
    "seed": 3,
    "sensor": {"resonance_hz": 8000.0, "resonance_damping": 0.05, "high_pass_hz": 1.0},
    "anti_alias": {"order": 6, "corner_hz": 4000.0},
    "acceleration": {"adc_range_m_s2": 50.0, "adc_bits": 16, "noise": "white", "noise_rms_m_s2": 0.01},
    "strain": {"adc_range_microstrain": 100.0, "adc_bits": 16, "noise": "pink", "noise_rms_microstrain": 0.05, "pink_flat_below_hz": 20.0},
}


def with_chain(chain: dict) -> impact.Scene:
    d = tiny()
    d["measurement"] = copy.deepcopy(chain)
    return impact.Scene.from_dict(d)


def features(cols: dict, quantity: str) -> dict:
    return {k: v for k, v in cols.items() if k.startswith(quantity + " at") and ": clean peak" not in k}


def test_a_range_under_a_chain_is_the_whole_runs_rows():
    scene = with_chain(CHAIN)
    whole = impact.identify(scene, "Con 2")
    part = impact.identify(scene, "Con 2", 5, 9)
    for k, v in part.items():
        assert np.array_equal(v, whole[k][5:9], equal_nan=v.dtype.kind == "f"), k
    # The chain records accelerations and strains only, and says what it clipped.
    assert features(whole, "acceleration") and features(whole, "strain")
    assert not features(whole, "velocity") and not features(whole, "displacement")
    assert "clipped_samples" in whole
    assert any(k.endswith(": clean peak (1)") for k in whole)


def test_a_transparent_chain_gives_the_chainless_features():
    d = tiny()
    plain = impact.identify(impact.Scene.from_dict(d), "Con 2")
    ideal = {"rate_hz": 20000.0, "acceleration": {"adc_range_m_s2": 1000.0, "adc_bits": 32}}
    through = impact.identify(with_chain(ideal), "Con 2")
    q = 2000.0 / 2.0**32
    peaks = [k for k in features(plain, "acceleration") if k.endswith(": peak (m/s^2)")]
    assert peaks
    for k in peaks:
        assert np.all(np.abs(plain[k] - through[k]) <= 0.5 * q + 1e-15 * np.abs(plain[k])), k


@pytest.mark.parametrize(
    "path, value, needle",
    [
        (("rate_hz",), 15000.0, "measurement"),
        (("anti_alias", "corner_hz"), 6000.0, "measurement.anti_alias.corner_hz"),
        (("acceleration", "noise"), "brown", "measurement.acceleration.noise"),
        (("strain", "adc_bits"), 40, "measurement.strain.adc_bits"),
    ],
)
def test_a_bad_chain_names_its_key(path, value, needle):
    chain = copy.deepcopy(CHAIN)
    target = chain
    for p in path[:-1]:
        target = target[p]
    target[path[-1]] = value
    with pytest.raises(impact.SceneError, match=needle.replace(".", r"\.")):
        with_chain(chain)


def test_a_pickled_scene_finds_its_psd_file_from_any_folder(tmp_path, monkeypatch):
    """A scene read from a file whose chain names a measured PSD file (relative to the scene's
    folder) unpickles, and is validated again, in a process with another working folder (a
    Dask worker); its text alone, read there, would not find the file."""
    import pickle

    text = (REPO / "scenes" / "caving-stream-measured.toml").read_text()
    text = text.replace('noise = "pink"\nnoise_rms_m_s2 = 2.0\npink_flat_below_hz = 10.0\n', 'noise = "measured"\nnoise_psd_file = "psd/tail-beam.csv"\n')
    assert 'noise_psd_file = "psd/tail-beam.csv"' in text
    (tmp_path / "scene" / "psd").mkdir(parents=True)
    (tmp_path / "scene" / "psd" / "tail-beam.csv").write_text("frequency_hz,psd\n0,1e-2\n100,1e-2\n5000,1e-4\n")
    (tmp_path / "scene" / "s.toml").write_text(text)
    scene = impact.Scene.from_toml(tmp_path / "scene" / "s.toml")
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    back = pickle.loads(pickle.dumps(scene))
    assert back.to_toml_str() == scene.to_toml_str()
    # The text without its folder would look for the file here, and not find it.
    with pytest.raises(impact.SceneError, match="noise_psd_file"):
        impact.Scene.from_str(scene.to_toml_str())
