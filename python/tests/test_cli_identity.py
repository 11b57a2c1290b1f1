"""Python and the command line give identical numbers for the same scene: the scene is written
to a file, run by `impact solve --json --scene FILE --model M` and by `impact.solve`, and every
field of every row is compared for exact equality, under the same keys (JSON carries f64 exactly: shortest
round-trip digits). Both go through impact::run::results, so any difference is a conversion
bug in the bindings."""

from __future__ import annotations

import json
import math
import os
import subprocess
import tomllib

import numpy as np
import pytest

import impact
from conftest import REPO, impact_binary

BINARY = impact_binary()
# In CI the binary must be there (the release build runs before the Python tests); on a
# developer's machine without a build, the comparison is skipped with the reason.
if BINARY is None and os.environ.get("CI"):
    raise RuntimeError("CI: target/release/impact (or $IMPACT_BIN) is missing")
pytestmark = pytest.mark.skipif(BINARY is None, reason="no impact binary: cargo build --release")

def same(a, b) -> bool:
    """Exact equality; NaN (a column's "does not apply") matches a key the JSON row leaves out."""
    if isinstance(b, float) and math.isnan(b):
        return a is None
    if isinstance(b, (bool, np.bool_)):
        return a == bool(b)
    return a == b


def compare(rows: list[dict], cols: dict[str, np.ndarray]) -> int:
    """Compares every field of every row under the one schema's keys (the JSON row holds the
    columns that apply to it; Python has NaN, False or "" elsewhere); returns the number of
    numbers compared."""
    n = 0
    assert all(len(v) == len(rows) for v in cols.values())
    for i, row in enumerate(rows):
        # Every key the command line writes is a Python column of the same name and value.
        for key, value in row.items():
            assert key in cols, (i, key)
            got = cols[key][i]
            got = got.item() if hasattr(got, "item") else got
            assert same(value, got), (i, key, value, got)
            n += isinstance(value, float)
        # And no Python column holds a value the command line left out.
        for key, col in cols.items():
            if key not in row:
                v = col[i]
                assert (isinstance(v, (float, np.floating)) and math.isnan(v)) or v in ("", False), (i, key, v)
    return n


def cli(scene_file, model: str, *extra: str) -> dict:
    out = subprocess.run(
        [str(BINARY), "solve", "--json", "--scene", str(scene_file), "--model", model, *extra],
        check=True,
        capture_output=True,
        text=True,
    )
    return json.loads(out.stdout)


def test_beam_and_plate_identical_on_a_general_support_scene(tmp_path):
    scene = impact.Scene.from_toml(REPO / "scenes" / "clamped-edge-props.toml")
    doc = cli(REPO / "scenes" / "clamped-edge-props.toml", "plate")
    r = impact.solve(scene, model="plate")
    assert r.status == doc["status"]
    n = compare(doc["results"]["responses"], r.responses) + compare(doc["results"]["yields"], r.yields)
    assert n > 50
    doc = cli(REPO / "scenes" / "clamped-edge-props.toml", "beam")
    r = impact.solve(scene, model="beam")
    # The beam does not describe the general set: those rows say why, identically.
    assert not r.responses["applicable"].all()
    compare(doc["results"]["responses"], r.responses)
    compare(doc["results"]["yields"], r.yields)


def test_transient_identical_from_a_dict_scene(tmp_path, paper_dict):
    d = paper_dict
    del d["transient"]
    d["bodies"] = d["bodies"][:1]
    d["conditions"] = d["conditions"][1:2]
    d["points"] = {"pairs_mm": [[114.6, 90.0]]}
    d["velocities"] = {"m_per_s": [0.008]}
    d["analyses"] = ["responses"]
    scene = impact.Scene.from_dict(d)
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml_str())
    # A loose tolerance keeps the test fast and checks that it reaches the model alike.
    # A share of 0 counts every contact as a main one, on both sides alike.
    doc = cli(path, "transient", "--tolerance", "0.01", "--main-contact-share", "0")
    r = impact.solve(scene, model="transient", tolerance=0.01, main_contact_share=0.0)
    assert (r.responses["tolerance"] == 0.01).all()
    assert (r.responses["main_contacts"] == r.responses["contacts"]).all()
    assert (r.responses["micro_contacts"] == 0).all()
    assert r.status == doc["status"]
    assert compare(doc["results"]["responses"], r.responses) >= 25


def test_transient_identical_at_the_default_tolerance(tmp_path):
    """Neither side is given a tolerance: both must take the default (1e-4) and choose the same
    mesh and step for it. The README's example case (clamped + props, coal at the centre at
    0.008 m/s) has an estimate of about 8e-5 on the first level, close to the tolerance, so a
    drift in either side's default or its choice shows here; it runs in about a second."""
    with open(REPO / "scenes" / "clamped-edge-props.toml", "rb") as f:
        d = tomllib.load(f)
    d["conditions"] = [c for c in d["conditions"] if c["name"] == "clamped + props"]
    d["points"] = {"pairs_mm": [[229.2, 180.0]]}
    d["analyses"] = ["responses"]
    scene = impact.Scene.from_dict(d)
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml_str())
    doc = cli(path, "transient")
    r = impact.solve(scene, model="transient")
    assert (r.responses["tolerance"] == 1e-4).all()
    assert r.status == doc["status"]
    assert compare(doc["results"]["responses"], r.responses) >= 25
    row = doc["results"]["responses"][0]
    assert (r.responses["elements"][0], r.responses["steps_per_contact"][0]) == (row["elements"], row["steps_per_contact"])


def test_mindlin_identical_from_a_dict_scene(tmp_path, paper_dict):
    d = paper_dict
    del d["transient"]
    d["bodies"] = d["bodies"][:1]
    d["conditions"] = d["conditions"][:1]
    d["points"] = {"pairs_mm": [[114.6, 90.0]]}
    d["velocities"] = {"m_per_s": [0.008]}
    d["analyses"] = ["responses", "yield-velocity"]
    scene = impact.Scene.from_dict(d)
    path = tmp_path / "scene.toml"
    path.write_text(scene.to_toml_str())
    doc = cli(path, "mindlin")
    r = impact.solve(scene, model="mindlin")
    assert (r.responses["model"] == "mindlin").all()
    assert compare(doc["results"]["responses"], r.responses) + compare(doc["results"]["yields"], r.yields) > 20
