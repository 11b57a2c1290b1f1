"""Recorded drops against the model from Python: `impact.drops` gives the command line's rows bit
for bit (against `impact drops`'s drops.json on the same scene and recording), a recording with a
bad drop is refused naming the key and value, and a scene without "drops" among its analyses is
refused. (The comparison's numbers against recordings made by the full model are tested in
crates/studies/tests/drops.rs.)"""

from __future__ import annotations

import json
import math
import subprocess

import pytest

import impact
from conftest import REPO, impact_binary

SCENE = REPO / "scenes" / "drop-rig.toml"
DROP = {
    "touch_s": 0.01,
    "point_mm": [229.2, 180.0],
    "radius_mm": 25.0,
    "density_kg_m3": 2400.0,
    "youngs_modulus_gpa": 16.0,
    "poisson_ratio": 0.28,
    "cohesion_mpa": 37.68,
    "friction_angle_deg": 37.0,
    "fall_height_m": 0.45,
    "class": "gangue",
}


def recording(folder, drops):
    """400 samples at 10 kHz on two channels (a small sine and silence), with `drops`."""
    lines = ["t_s,a1,a2"] + [f"{k / 1e4!r},{0.01 * math.sin(k)!r},0.0" for k in range(400)]
    (folder / "signal.csv").write_text("\n".join(lines) + "\n")
    side = {"format": "impact-signal/1", "data": "signal.csv", "rate_hz": 1e4, "columns": ["a1", "a2"], "condition": "Con 1", "drops": drops}
    path = folder / "signal.json"
    path.write_text(json.dumps(side))
    return path


def test_rows_are_one_per_drop_and_quantity(tmp_path):
    r = impact.drops(impact.Scene.from_toml(str(SCENE)), recording(tmp_path, [DROP, dict(DROP, touch_s=0.015)]))
    assert len(r.rows["quantity"]) == 8
    assert list(r.rows["drop"]) == [0] * 4 + [1] * 4
    assert r.results["modes"] == [160, 80] and r.results["realisations"] == 16
    # A quiet recording is not a drop: its peaks fall outside their bars.
    assert r.rows["disagrees"].sum() >= 4


def test_bad_drops_and_scenes_are_refused(tmp_path):
    scene = impact.Scene.from_toml(str(SCENE))
    with pytest.raises(ValueError, match=r"drops\[0\]\.radius_mm = -2"):
        impact.drops(scene, recording(tmp_path, [dict(DROP, radius_mm=-2.0)]))
    with pytest.raises(ValueError, match="lists no drops"):
        impact.drops(scene, recording(tmp_path, []))
    with pytest.raises(ValueError, match='add "drops" to its analyses'):
        impact.drops(impact.Scene.from_toml(str(REPO / "scenes" / "paper-table-1.toml")), recording(tmp_path, [DROP]))


BINARY = impact_binary()


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_python_and_the_command_line_agree_bit_for_bit(tmp_path):
    signal = recording(tmp_path, [DROP])
    out = tmp_path / "out"
    subprocess.run([str(BINARY), "drops", "--scene", str(SCENE), "--signal", str(signal), "--out", str(out)], check=True, capture_output=True)
    cli = json.loads((out / "drops.json").read_text())
    r = impact.drops(impact.Scene.from_toml(str(SCENE)), signal)
    assert cli["drops"] == r.results["drops"]
