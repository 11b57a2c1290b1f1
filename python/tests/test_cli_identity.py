"""Python and the command line give identical numbers for the same scene: the scene is written
to a file, run by `impact solve --json --scene FILE --model M` and by `impact.solve`, and every
field of every row is compared for exact equality (JSON carries f64 exactly: shortest
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

VALUES = {
    "compliance": "compliance_m_per_n",
    "compliance_error": "compliance_error_m_per_n",
    "contact_force": "contact_force_n",
    "contact_force_error": "contact_force_error_n",
    "compression": "compression_m",
    "compression_error": "compression_error_m",
    "deflection": "deflection_m",
    "rock_total_ratio": "rock_total_ratio",
    "rock_stored_ratio": "rock_stored_ratio",
    "plate_ratio": "plate_ratio",
    "sphere_kinetic_ratio": "sphere_kinetic_ratio",
    "yield_compression": "yield_compression_m",
    "yield_velocity": "yield_velocity_m_per_s",
    "yield_velocity_error": "yield_velocity_error_m_per_s",
}
EVIDENCE = {
    "iterations": "solver_iterations",
    "residual": "solver_residual",
    "steps": "steps",
    "time_step": "time_step_s",
    "peak_force": "peak_force_n",
    "peak_force_error": "peak_force_error_n",
    "contact_time": "contact_time_s",
    "contact_time_error": "contact_time_error_s",
    "apparent_restitution": "apparent_restitution",
    "restitution_error": "restitution_error",
    "steps_per_contact": "steps_per_contact",
    "relative_error": "relative_error",
    "tolerance": "tolerance",
    "total_impulse": "total_impulse_n_s",
    "final_velocity": "final_velocity_m_per_s",
}
CRITERIA = {
    "elastic": "elastic_ratio",
    "quasi_static": "quasi_static_ratio",
    "thin_plate": "thin_plate_ratio",
    "regime": "regime_force_error",
    "recontact": "contacts",
}


def same(a, b) -> bool:
    """Exact equality; None (JSON null) and NaN (a column's "does not apply") match."""
    if a is None or (isinstance(a, float) and math.isnan(a)):
        return b is None or (isinstance(b, float) and math.isnan(b))
    return a == b


def compare(rows: list[dict], cols: dict[str, np.ndarray]) -> int:
    """Compares every field; returns the number of numbers compared."""
    n = 0
    assert all(len(v) == len(rows) for v in cols.values())
    for i, row in enumerate(rows):
        assert cols["model"][i] == row["model"] and cols["body"][i] == row["body"]
        assert cols["condition"][i] == row["condition"]
        assert cols["x_m"][i] == row["x"] and cols["z_m"][i] == row["z"]
        if "velocity" in row:
            assert cols["velocity_m_per_s"][i] == row["velocity"]
        out = row["outcome"]
        assert bool(cols["applicable"][i]) == (out["status"] == "computed")
        if out["status"] != "computed":
            assert cols["reason"][i] == out["reason"]
            continue
        for key, col in VALUES.items():
            if key in out:
                got = float(cols[col][i]) if col in cols else None
                assert same(out[key], got), (i, key, out[key], got)
                n += 1
        for key, col in EVIDENCE.items():
            if key in out.get("evidence", {}):
                got = float(cols[col][i]) if col in cols else None
                assert same(out["evidence"][key], got), (i, key, out["evidence"][key], got)
                n += 1
        if "met_tolerance" in out.get("evidence", {}):
            assert bool(cols["met_tolerance"][i]) == out["evidence"]["met_tolerance"]
        for s in out.get("spring_forces", []):
            assert cols[f"spring_force_n: {s['name']}"][i] == s["force"]
            n += 1
        for key, col in CRITERIA.items():
            c = out["validity"][key]
            if c is not None:
                assert cols[col][i] == c["value"], (i, key)
                n += 1
        assert bool(cols["valid"][i]) == all(c["valid"] for c in out["validity"].values() if c is not None)
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
    doc = cli(path, "transient", "--tolerance", "0.01")
    r = impact.solve(scene, model="transient", tolerance=0.01)
    assert (r.responses["tolerance"] == 0.01).all()
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
    row = doc["results"]["responses"][0]["outcome"]["evidence"]
    assert (r.responses["elements"][0], r.responses["steps_per_contact"][0]) == (row["elements"], row["steps_per_contact"])
