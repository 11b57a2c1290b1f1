"""The tail beam from Python: the same numbers as `impact compare` writes to
`tail-beam/impacts.csv`, bit for bit (the CSV carries shortest round-trip digits; the struck
points, shown in mm, within two ulps), under the same column keys; and a scene without a
`[tail_beam]` is refused naming it."""

from __future__ import annotations

import csv
import os
import subprocess

import numpy as np
import pytest

import impact
from conftest import REPO, impact_binary

BINARY = impact_binary()
if BINARY is None and os.environ.get("CI"):
    raise RuntimeError("CI: target/release/impact (or $IMPACT_BIN) is missing")

SCENE = REPO / "scenes" / "tail-beam.toml"


@pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")
def test_tail_beam_identical_to_the_command_line(tmp_path):
    out = tmp_path / "out"
    subprocess.run([str(BINARY), "compare", "--scene", str(SCENE), "--out", str(out)], check=True, capture_output=True)
    with open(out / "tail-beam" / "impacts.csv", newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    rows = list(csv.DictReader(lines))
    r = impact.tail_beam(str(SCENE))
    cols = r.rows
    assert len(rows) == len(cols["body"]) == 45
    compared = 0
    for key in rows[0]:
        if key not in cols:
            continue  # a ratio of two columns, shown for reading
        for i, row in enumerate(rows):
            got = cols[key][i]
            if isinstance(got, (str, np.str_)):
                assert row[key] == str(got), (i, key)
            elif key in ("x_m", "z_m"):
                # The report shows positions in mm and its CSV takes them back to m: within
                # two ulps of the scene's value, which Python gives as it is.
                assert abs(float(row[key]) - float(got)) <= 4e-16 * max(1.0, abs(float(got))), (i, key)
            else:
                assert float(row[key]) == float(got), (i, key, row[key], got)
                compared += 1
    assert compared > 400
    # The box in time: its CSV's columns are the rows' too.
    with open(out / "tail-beam" / "impacts-in-time.csv", newline="") as f:
        timed = list(csv.DictReader([line for line in f if not line.startswith("#")]))
    shared = [k for k in timed[0] if k in cols and k not in ("body", "x_m", "z_m", "v_m_per_s")]
    assert {"P_max_in_time_N", "jacks_force_in_time_N", "contacts_in_time", "t_c_in_time_s"} <= set(shared)
    for i, row in enumerate(timed):
        assert row["body"] == str(cols["body"][i])
        for key in shared:
            a, b = float(row[key]), float(cols[key][i])
            if key == "t_c_in_time_s":
                # Shown in ms and taken back to s: within two ulps.
                assert abs(a - b) <= 4e-16 * abs(b), (i, key, a, b)
            else:
                assert a == b, (i, key, a, b)
    assert np.all(cols["P_max_in_time_error_N"] < 1e-2 * cols["P_max_in_time_N"])
    # The structure's statics, read from the JSON: the jacks carry the unit load's moment
    # about the pins on a rigid box, to 0.5 %.
    beam = r.results["scene"]["beam"]
    jack = beam["jacks"][0]
    arm = beam["pin_height"] * np.cos(jack["angle"]) + jack["x"] * np.sin(jack["angle"])
    k = sum(j["stiffness"] for j in beam["jacks"])
    rigid = (cols["x_m"] / arm) ** 2 / k
    assert np.all(np.abs(cols["jacks_share"] * cols["C_m_per_N"] / rigid - 1.0) < 5e-3)


def test_a_scene_without_a_tail_beam_is_refused():
    with pytest.raises(ValueError, match="tail_beam"):
        impact.tail_beam(impact.Scene.default())
