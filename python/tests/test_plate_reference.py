"""The plate model's compliance through the Python package against the committed scikit-fem
reference (reference/data/*.json: Argyris C1 quintic triangles, written by
reference/python/plate_reference.py), as tests/reference_skfem.rs does in Rust.

Tolerance (that of tests/reference_skfem.rs). Each value is a Richardson extrapolation of two
meshes with an error estimate: the plate model's from 20 x 16 and 40 x 32 (its column
`compliance_error_m_per_N`), Argyris's from its two finest meshes (computed here from the data,
|finest - extrapolated| in the asymptotic range, else |finest - previous|). Two estimates of
the same exact value differ by no more than the sum of their error estimates; we allow twice
that sum, plus 1e-9 relative for the round-off of the solves."""

from __future__ import annotations

import json
import math

import pytest

import impact
from conftest import REPO

CORNERS = ["left_near", "right_near", "left_far", "right_far"]


def richardson(values: list[float]) -> tuple[float, float]:
    """(extrapolated, error estimate) at the nominal rate 2 (plate_fem::convergence)."""
    q1, q2 = values[-2], values[-1]
    extrapolated = q2 + (q2 - q1) / 3.0
    asymptotic = True
    if len(values) >= 3:
        r = (values[-3] - q1) / (q1 - q2)
        asymptotic = not (math.isfinite(r) and r > 0) or 1.5 <= math.log2(r) <= 2.5
    error = abs(q2 - extrapolated) if asymptotic else abs(q2 - q1)
    return extrapolated, error


def scene_for(case: dict, paper_dict: dict) -> dict:
    corners = {
        name: (c if isinstance(c, str) else {"spring_n_per_m": c})
        for name, c in zip(CORNERS, case["supports"]["corners"])
    }
    edges = {k: ("simply-supported" if v == "simple" else v) for k, v in case["supports"]["edges"].items()}
    d = paper_dict
    del d["transient"]
    d["analyses"] = ["responses"]
    d["bodies"] = d["bodies"][:1]
    d["velocities"] = {"m_per_s": [0.008]}
    d["conditions"] = [{"name": case["case"], "corners": corners, "edges": edges}]
    d["points"] = {"pairs_mm": [[x * 1e3, z * 1e3] for x, z in case["points"]]}
    p = case["plate"]
    assert (p["length"], p["width"], p["thickness"]) == (0.4584, 0.36, 0.008)
    return d


@pytest.mark.parametrize("name", ["paper-con1", "paper-con2", "paper-con3", "clamped-edge-two-springs"])
def test_plate_compliance_meets_argyris(name, paper_dict):
    case = json.loads((REPO / "reference" / "data" / f"{name}.json").read_text())
    r = impact.solve(scene_for(case, paper_dict), model="plate").responses
    runs = case["results"]["argyris"]
    assert len(r["compliance_m_per_N"]) == len(case["points"])
    for i, (x, z) in enumerate(case["points"]):
        reference, reference_error = richardson([run["compliance"][i] for run in runs])
        c, c_error = r["compliance_m_per_N"][i], r["compliance_error_m_per_N"][i]
        assert (r["x_m"][i], r["z_m"][i]) == pytest.approx((x, z), abs=1e-12)
        tolerance = 2.0 * (reference_error + c_error) + 1e-9 * abs(reference)
        assert abs(c - reference) <= tolerance, f"{name} ({x}, {z}): {c:e} vs Argyris {reference:e}"
        # The error estimate is a real bound here, not a formality: well below 1e-3 of C.
        assert c_error < 1e-3 * c
